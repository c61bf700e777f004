//! \file output_files.cpp
//! \brief Temporary-name-then-rename file writing and the .pvd series index.
#include "output_files.hpp"

#include <fmt/format.h>

#include <cstdio>
#include <fstream>
#include <stdexcept>

namespace blastsim::app {

void commit_file(const std::string& tmp_path, const std::string& path) {
  if (std::rename(tmp_path.c_str(), path.c_str()) != 0)
    throw std::runtime_error(fmt::format("cannot rename '{}' to '{}'", tmp_path, path));
}

void write_atomically(const std::string& path, const std::function<void(std::ostream&)>& fill) {
  const std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) throw std::runtime_error(fmt::format("cannot open '{}' for writing", tmp));
    fill(out);
    out.flush();
    if (!out) throw std::runtime_error(fmt::format("error while writing '{}'", tmp));
  }
  commit_file(tmp, path);
}

void PvdSeries::add(double time, const std::string& file_name) {
  entries_.emplace_back(time, file_name);
  write_atomically(path_, [&](std::ostream& out) {
    out << "<?xml version=\"1.0\"?>\n"
        << "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n  <Collection>\n";
    for (const auto& [t, f] : entries_)
      out << fmt::format("    <DataSet timestep=\"{:.9e}\" group=\"\" part=\"0\" file=\"{}\"/>\n", t, f);
    out << "  </Collection>\n</VTKFile>\n";
  });
}

}  // namespace blastsim::app
