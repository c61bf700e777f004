//! \file output_files.cpp
//! \brief Temporary-name-then-rename file writing and the .pvd series index.
#include "output_files.hpp"

#include "blastsim/core/error.hpp"

#include <fmt/format.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>

namespace blastsim::app {

void commit_file(const std::string& tmp_path, const std::string& path) {
  if (std::rename(tmp_path.c_str(), path.c_str()) != 0)
    throw OutputError(fmt::format("cannot rename '{}' to '{}': {}", tmp_path, path, std::strerror(errno)));
}

void write_atomically(const std::string& path, const std::function<void(std::ostream&)>& fill) {
  const std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) throw OutputError(fmt::format("cannot open '{}' for writing: {}", tmp, std::strerror(errno)));
    fill(out);
    out.flush();
    out.close();
    if (!out) throw OutputError(fmt::format("error while writing '{}': {}", tmp, std::strerror(errno)));
  }
  commit_file(tmp, path);
}

void PvdSeries::add(double time, const std::string& file_name) {
  entries_.emplace_back(time, file_name);
  write();
}

void PvdSeries::restore(const Entries& entries) {
  entries_ = entries;
  write();
}

void PvdSeries::write() const {
  write_atomically(path_, [&](std::ostream& out) {
    out << "<?xml version=\"1.0\"?>\n"
        << "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n  <Collection>\n";
    for (const auto& [t, f] : entries_)
      out << fmt::format("    <DataSet timestep=\"{:.9e}\" group=\"\" part=\"0\" file=\"{}\"/>\n", t, f);
    out << "  </Collection>\n</VTKFile>\n";
  });
}

CsvSeries::CsvSeries(std::string path, const std::string& header, bool resume) : path_(std::move(path)) {
  if (resume) {  // a restart continues this run's file: it must be there, with this series' header
    std::ifstream in(path_);
    std::string first;
    if (!in || !std::getline(in, first))
      throw InputError(fmt::format("--restart: {} is missing or empty; a restart continues the outputs of the run "
                                   "that wrote the checkpoint (start the run anew without --restart)", path_));
    if (first != header)
      throw InputError(fmt::format("--restart: {} does not start with this case's header; it belongs to another run",
                                   path_));
  }
  out_.open(path_, resume ? std::ios::app : std::ios::trunc);
  if (!out_) throw OutputError(fmt::format("cannot open '{}' for writing: {}", path_, std::strerror(errno)));
  if (!resume) row(header);
}

void CsvSeries::row(const std::string& line) {
  out_ << line << '\n';
  out_.flush();
  if (!out_) throw OutputError(fmt::format("error while writing '{}': {}", path_, std::strerror(errno)));
}

std::uint64_t CsvSeries::size() {
  out_.flush();
  return std::filesystem::file_size(path_);
}

void CsvSeries::truncate_to(std::uint64_t bytes) {
  const std::uint64_t now = size();
  if (bytes > now)
    throw InputError(fmt::format("--restart: {} holds {} bytes, fewer than the {} the checkpoint recorded; its rows "
                                 "were removed since (start the run anew without --restart)", path_, now, bytes));
  out_.close();
  std::filesystem::resize_file(path_, bytes);
  out_.open(path_, std::ios::app);
  if (!out_) throw OutputError(fmt::format("cannot reopen '{}': {}", path_, std::strerror(errno)));
}

std::filesystem::path make_output_dir(const std::string& d) {
  std::error_code ec;
  std::filesystem::create_directories(d, ec);
  if (ec || !std::filesystem::is_directory(d))
    throw OutputError("output.directory = \"" + d + "\": cannot be created (" +
                      (ec ? ec.message() : std::string("a file of that name is in the way")) + ")");
  return d;
}

void write_pvd_checkpoint(CheckpointWriter& w, const std::string& name, const PvdSeries& pvd) {
  std::vector<double> times;
  std::string files;
  for (const auto& [t, f] : pvd.entries()) times.push_back(t), files += f + "\n";
  w.host_array(name + ".times", times);
  w.text(name + ".files", files);
}
void read_pvd_checkpoint(CheckpointReader& r, const std::string& name, PvdSeries& pvd) {
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
