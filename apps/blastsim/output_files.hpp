//! \file output_files.hpp
//! \brief Crash-safe output files: every file is written under a temporary name and renamed into place; the
//! output folder; the output series' part of a checkpoint.
#pragma once

#include "blastsim/core/checkpoint.hpp"

#include <cmath>
#include <filesystem>
#include <cstdint>
#include <fstream>
#include <functional>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

namespace blastsim::app {

//! Advances a schedule time `next` [s] by whole `interval`s until it exceeds `limit`: by repeated addition
//! (the exact sums a run's output times are made of) and, when `limit` lies more than a million intervals
//! ahead, first by one jump, so the loop is bounded whatever the interval and the step (the input refuses
//! intervals below 1e-9 x time.end, which could not advance the time).
inline void advance_schedule(double& next, double interval, double limit) {
  const double ahead = (limit - next) / interval;
  if (ahead > 1e6) next += std::floor(ahead - 1e3) * interval;
  while (next <= limit) next += interval;
}

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

//! Creates the output folder; returns its path. OutputError when it cannot.
std::filesystem::path make_output_dir(const std::string& d);

//! A .pvd collection's entries in a checkpoint (times, then the file names one per line), and back.
void write_pvd_checkpoint(CheckpointWriter& w, const std::string& name, const PvdSeries& pvd);
void read_pvd_checkpoint(CheckpointReader& r, const std::string& name, PvdSeries& pvd);

}  // namespace blastsim::app
