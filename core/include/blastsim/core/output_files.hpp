//! \file output_files.hpp
//! \brief Crash-safe output files, as the checkpoint (checkpoint.hpp) is: a file is written under a temporary
//! name and renamed into place, a ParaView collection (.pvd) is valid after every snapshot, a CSV series is
//! flushed row by row and cut back on a restart to the size its checkpoint recorded. Host code, header only.
#pragma once

#include "blastsim/core/checkpoint.hpp"
#include "blastsim/core/error.hpp"

#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

namespace blastsim {

//! Advances a schedule time `next` [s] by whole `interval`s until it exceeds `limit`: by repeated addition
//! (the exact sums a run's output times are made of) and, when `limit` lies more than a million intervals
//! ahead, first by one jump, so the loop is bounded whatever the interval and the step (a caller refuses
//! intervals too small to advance the time).
inline void advance_schedule(double& next, double interval, double limit) {
  const double ahead = (limit - next) / interval;
  if (ahead > 1e6) next += std::floor(ahead - 1e3) * interval;
  while (next <= limit) next += interval;
}

//! Renames a file written under a temporary name into place (atomic on POSIX). OutputError on failure.
inline void commit_file(const std::string& tmp_path, const std::string& path) {
  if (std::rename(tmp_path.c_str(), path.c_str()) != 0)
    throw OutputError("cannot rename '" + tmp_path + "' to '" + path + "': " + std::strerror(errno));
}

//! Writes `path` through `fill` into "path.tmp", then renames it over `path`: a crash leaves either the old or
//! the new file, never a partial one. OutputError on I/O failure.
inline void write_atomically(const std::string& path, const std::function<void(std::ostream&)>& fill) {
  const std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) throw OutputError("cannot open '" + tmp + "' for writing: " + std::strerror(errno));
    fill(out);
    out.flush();
    out.close();
    if (!out) throw OutputError("error while writing '" + tmp + "': " + std::strerror(errno));
  }
  commit_file(tmp, path);
}

//! Writes a VTK XML file (`writer`: a vtkXML*Writer with its input set) under "path.tmp" in appended raw
//! binary, then renames it into place. VTK reports a full disk through its error code, not always through
//! Write()'s result: both are checked, and a failed file is never renamed into place. OutputError on failure.
template <class VtkWriter>
void write_vtk_atomically(VtkWriter* writer, const std::string& path) {
  const std::string tmp = path + ".tmp";
  writer->SetFileName(tmp.c_str());
  writer->SetDataModeToAppended();
  writer->EncodeAppendedDataOff();
  if (writer->Write() != 1 || writer->GetErrorCode() != 0)
    throw OutputError("VTK could not write '" + tmp + "' (VTK error code " + std::to_string(writer->GetErrorCode()) +
                      "; " + std::strerror(errno) + ")");
  commit_file(tmp, path);
}

//! A ParaView collection (.pvd) of snapshots; rewritten atomically after every added snapshot, so it is
//! valid at every moment of a run.
class PvdSeries {
 public:
  using Entries = std::vector<std::pair<double, std::string>>;
  explicit PvdSeries(std::string path) : path_(std::move(path)) {}
  void add(double time, const std::string& file_name) {
    entries_.emplace_back(time, file_name);
    write();
  }
  const Entries& entries() const { return entries_; }
  //! Replaces the entries (a restart: those of the checkpoint) and rewrites the file.
  void restore(const Entries& entries) {
    entries_ = entries;
    write();
  }
  //! The entries in a checkpoint (times, then the file names one per line), and back: read_checkpoint()
  //! refuses names that are not plain file names of the output folder.
  void write_checkpoint(CheckpointWriter& w, const std::string& name) const {
    std::vector<double> times;
    std::string files;
    for (const auto& [t, f] : entries_) times.push_back(t), files += f + "\n";
    w.host_array(name + ".times", times);
    w.text(name + ".files", files);
  }
  //! Every snapshot it names must exist beside the collection; the file is rewritten once the whole
  //! checkpoint is accepted (CheckpointReader::on_accept()).
  void read_checkpoint(CheckpointReader& r, const std::string& name) {
    const std::vector<double> times = r.host_array<double>(name + ".times");
    const std::string files = r.text(name + ".files");
    Entries e;
    size_t at = 0;
    for (double t : times) {
      const size_t end = files.find('\n', at);
      if (end == std::string::npos) r.fail(name + ".files", "fewer file names than snapshot times");
      const std::string file = files.substr(at, end - at);
      if (file.empty() || file.size() > 255 || file.find_first_of("/\\\"<>&") != std::string::npos || !std::isfinite(t))
        r.fail(name + ".files", "holds a name that is not a snapshot file of the output folder");
      const std::filesystem::path snapshot = std::filesystem::path(path_).parent_path() / file;
      std::error_code ec;
      if (!std::filesystem::is_regular_file(snapshot, ec))
        throw InputError("--restart: " + snapshot.string() + ", a snapshot that " + path_ + " lists, is missing; a "
                         "restart continues the outputs of the run that wrote the checkpoint (start the run anew "
                         "without --restart)");
      e.emplace_back(t, file);
      at = end + 1;
    }
    if (at != files.size()) r.fail(name + ".files", "more file names than snapshot times");
    r.on_accept([this, e] { restore(e); });
  }

 private:
  void write() const {
    write_atomically(path_, [&](std::ostream& out) {
      out << "<?xml version=\"1.0\"?>\n"
          << "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n  <Collection>\n";
      char line[64];
      for (const auto& [t, f] : entries_) {
        std::snprintf(line, sizeof line, "%.9e", t);
        out << "    <DataSet timestep=\"" << line << "\" group=\"\" part=\"0\" file=\"" << f << "\"/>\n";
      }
      out << "  </Collection>\n</VTKFile>\n";
    });
  }
  std::string path_;
  Entries entries_;
};

//! One row of a CSV file with each column named where its value is given: a writer lists its columns once,
//! in a function that fills a CsvRecord, and takes both its header (Mode::header: the names) and its rows
//! (Mode::row: the values) from that list, so the two cannot drift apart (csv_text()).
class CsvRecord {
 public:
  enum class Mode { header, row };
  explicit CsvRecord(Mode mode) : header_(mode == Mode::header) {}
  //! True while collecting the header: the values are not read, so a caller may pass zeros.
  bool header() const { return header_; }
  //! A real column, in scientific notation with `digits` after the point (printf's %.*e). NonFiniteValue,
  //! naming the column, when the value is not finite: no file holds a NaN or an infinity.
  CsvRecord& real(const std::string& name, double value, int digits = 9) {
    if (!header_ && !std::isfinite(value))
      throw NonFiniteValue("column " + name + " = " + std::to_string(value) + " is not finite");
    char text[64];
    return add(name, [&] { return std::string(text, std::snprintf(text, sizeof text, "%.*e", digits, value)); });
  }
  //! real() when `valid`, else an empty field (a quantity that cannot be computed, such as a fit to too few
  //! points; the file's documentation says when).
  CsvRecord& real_if(bool valid, const std::string& name, double value, int digits = 9) {
    return valid ? real(name, value, digits) : add(name, [] { return std::string(); });
  }
  //! An integer column.
  CsvRecord& integer(const std::string& name, long long value) {
    return add(name, [&] { return std::to_string(value); });
  }
  const std::string& text() const { return text_; }

 private:
  template <class Value>
  CsvRecord& add(const std::string& name, const Value& value) {
    if (!first_) text_ += ',';
    first_ = false;
    text_ += header_ ? name : value();
    return *this;
  }
  bool header_;
  bool first_ = true;
  std::string text_;
};

//! The header, or one row, of a CSV file whose columns `fill(CsvRecord&)` adds.
template <class Fill>
std::string csv_text(CsvRecord::Mode mode, Fill&& fill) {
  CsvRecord r(mode);
  fill(r);
  return r.text();
}

//! A CSV time series that grows by rows. Rows are flushed as written; on a restart the file is cut back to
//! the size it had at the checkpoint and grows from there, so it reads as if the run had never stopped.
class CsvSeries {
 public:
  //! Opens `path`: a new run truncates it and writes `header`; `resume` (a restart) keeps it, and refuses
  //! (InputError) a file that is missing or starts with another header.
  CsvSeries(std::string path, const std::string& header, bool resume)
      : path_(std::move(path)), header_bytes_(header.size() + 1) {
    if (resume) {
      std::ifstream in(path_);
      std::string first;
      if (!in || !std::getline(in, first))
        throw InputError("--restart: " + path_ + " is missing or empty; a restart continues the outputs of the run that "
                         "wrote the checkpoint (start the run anew without --restart)");
      if (first != header)
        throw InputError("--restart: " + path_ + " does not start with this case's header; it belongs to another run");
    }
    out_.open(path_, resume ? std::ios::app : std::ios::trunc);
    if (!out_) throw OutputError("cannot open '" + path_ + "' for writing: " + std::strerror(errno));
    if (!resume) row(header);
  }
  CsvSeries(CsvSeries&&) = default;
  //! Appends the row whose columns `fill(CsvRecord&)` adds; InstabilityError naming the file and the column
  //! when a value is not finite, before anything is written.
  template <class Fill>
  void row_of(Fill&& fill) {
    std::string line;
    try {
      line = csv_text(CsvRecord::Mode::row, fill);
    } catch (const NonFiniteValue& e) {
      throw InstabilityError(path_ + ": " + e.what() + "; the run stops before writing it (the files written so far "
                             "and the last checkpoint are kept)");
    }
    row(line);
  }
  //! Appends one line (with its newline) and flushes.
  void row(const std::string& line) {
    out_ << line << '\n';
    out_.flush();
    if (!out_) throw OutputError("error while writing '" + path_ + "': " + std::strerror(errno));
  }
  //! Bytes written so far.
  std::uint64_t size() {
    out_.flush();
    return std::filesystem::file_size(path_);
  }
  //! The size in a checkpoint record `name`, and back: read_checkpoint() cuts the file to it (truncate_to()).
  void write_checkpoint(CheckpointWriter& w, const std::string& name) { w.value(name, size()); }
  //! The size is checked at once (it must hold at least the header line and at most the file's bytes); the
  //! file is cut back once the whole checkpoint is accepted (CheckpointReader::on_accept()).
  void read_checkpoint(CheckpointReader& r, const std::string& name) {
    const std::uint64_t bytes = r.value<std::uint64_t>(name);
    if (bytes < header_bytes_) r.fail(name, "smaller than the file's header line");
    check_holds(bytes);
    r.on_accept([this, bytes] { truncate_to(bytes); });
  }
  //! Cuts the file back to `bytes` (a restart: the size its checkpoint recorded); InputError when it is shorter.
  void truncate_to(std::uint64_t bytes) {
    check_holds(bytes);
    out_.close();
    std::filesystem::resize_file(path_, bytes);
    out_.open(path_, std::ios::app);
    if (!out_) throw OutputError("cannot reopen '" + path_ + "': " + std::strerror(errno));
  }

 private:
  void check_holds(std::uint64_t bytes) {
    const std::uint64_t now = size();
    if (bytes > now)
      throw InputError("--restart: " + path_ + " holds " + std::to_string(now) + " bytes, fewer than the " +
                       std::to_string(bytes) + " the checkpoint recorded; its rows were removed since (start the run "
                       "anew without --restart)");
  }
  std::string path_;
  std::ofstream out_;
  std::uint64_t header_bytes_ = 0;  // the header line with its newline
};

}  // namespace blastsim
