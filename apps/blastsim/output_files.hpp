//! \file output_files.hpp
//! \brief Crash-safe output files: every file is written under a temporary name and renamed into place.
#pragma once

#include <functional>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

namespace blastsim::app {

//! Writes `path` through `fill` into "path.tmp", then renames it over `path` (atomic on POSIX): a crash
//! leaves either the old or the new file, never a partial one. Throws std::runtime_error on I/O failure.
void write_atomically(const std::string& path, const std::function<void(std::ostream&)>& fill);

//! Renames a file that a library wrote under a temporary name into place (same guarantee).
void commit_file(const std::string& tmp_path, const std::string& path);

//! A ParaView collection (.pvd) of snapshots; rewritten atomically after every added snapshot, so it is
//! valid at every moment of a run.
class PvdSeries {
 public:
  explicit PvdSeries(std::string path) : path_(std::move(path)) {}
  void add(double time, const std::string& file_name);

 private:
  std::string path_;
  std::vector<std::pair<double, std::string>> entries_;
};

}  // namespace blastsim::app
