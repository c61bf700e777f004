//! \file output_files.hpp
//! \brief Crash-safe output files: every file is written under a temporary name and renamed into place.
#pragma once

#include <cstdint>
#include <fstream>
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
  using Entries = std::vector<std::pair<double, std::string>>;
  explicit PvdSeries(std::string path) : path_(std::move(path)) {}
  void add(double time, const std::string& file_name);
  const Entries& entries() const { return entries_; }
  //! Replaces the entries (a restart: those of the checkpoint) and rewrites the file.
  void restore(const Entries& entries);

 private:
  void write() const;
  std::string path_;
  Entries entries_;
};

//! A CSV time series that grows by rows. Rows are flushed as written; on a restart the file is cut back to
//! the size it had at the checkpoint and grows from there, so it reads as if the run had never stopped.
class CsvSeries {
 public:
  //! Opens `path`: a new run truncates it and writes `header`; `resume` keeps it (see truncate_to()).
  CsvSeries(std::string path, const std::string& header, bool resume);
  CsvSeries(CsvSeries&&) = default;
  void row(const std::string& line);  //!< appends one line (with its newline) and flushes
  std::uint64_t size();               //!< bytes written so far
  void truncate_to(std::uint64_t bytes);

 private:
  std::string path_;
  std::ofstream out_;
};

}  // namespace blastsim::app
