//! \file output_checkpoint.hpp
//! \brief The output folder and the output series' part of a checkpoint (.pvd entries). Include only from
//! kernel sources (checkpoint.hpp knows the backend).
#pragma once

#include "blastsim/core/checkpoint.hpp"
#include "output_files.hpp"

#include <filesystem>
#include <string>
#include <vector>

namespace blastsim::app {

//! Creates the output folder; returns its path.
inline std::filesystem::path make_output_dir(const std::string& d) {
  std::filesystem::create_directories(d);
  return d;
}

//! A .pvd collection's entries in a checkpoint (times, then the file names one per line), and back.
inline void write_pvd_checkpoint(CheckpointWriter& w, const std::string& name, const PvdSeries& pvd) {
  std::vector<double> times;
  std::string files;
  for (const auto& [t, f] : pvd.entries()) times.push_back(t), files += f + "\n";
  w.host_array(name + ".times", times);
  w.text(name + ".files", files);
}
inline void read_pvd_checkpoint(CheckpointReader& r, const std::string& name, PvdSeries& pvd) {
  const std::vector<double> times = r.host_array<double>(name + ".times");
  const std::string files = r.text(name + ".files");
  PvdSeries::Entries e;
  size_t at = 0;
  for (double t : times) {
    const size_t end = files.find('\n', at);
    e.emplace_back(t, files.substr(at, end - at));
    at = end + 1;
  }
  pvd.restore(e);
}

}  // namespace blastsim::app
