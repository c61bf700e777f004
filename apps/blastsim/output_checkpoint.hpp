//! \file output_checkpoint.hpp
//! \brief The output folder and the output series' part of a checkpoint (.pvd entries). Include only from
//! kernel sources (checkpoint.hpp knows the backend).
#pragma once

#include "blastsim/core/checkpoint.hpp"
#include "output_files.hpp"

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

namespace blastsim::app {

//! Creates the output folder; returns its path.
inline std::filesystem::path make_output_dir(const std::string& d) {
  std::error_code ec;
  std::filesystem::create_directories(d, ec);
  if (ec || !std::filesystem::is_directory(d))
    throw OutputError("output.directory = \"" + d + "\": cannot be created (" +
                      (ec ? ec.message() : std::string("a file of that name is in the way")) + ")");
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
    if (end == std::string::npos) r.fail(name + ".files", "fewer file names than snapshot times");
    const std::string file = files.substr(at, end - at);
    // Plain names of files in the output folder, as the run wrote them.
    if (file.empty() || file.size() > 255 || file.find_first_of("/\\\"<>&") != std::string::npos || !std::isfinite(t))
      r.fail(name + ".files", "holds a name that is not a snapshot file of the output folder");
    e.emplace_back(t, file);
    at = end + 1;
  }
  if (at != files.size()) r.fail(name + ".files", "more file names than snapshot times");
  pvd.restore(e);
}

}  // namespace blastsim::app
