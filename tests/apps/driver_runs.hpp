//! \file driver_runs.hpp
//! \brief Helpers of the driver tests that run the executable: small cases, a run with its exit status and
//! standard error, file bytes, and the checkpoint format's records (to forge them).
#pragma once

#include "catch.hpp"
#include "temp_files.hpp"

#include <zlib.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <utility>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <vector>

namespace blastsim::testing {

namespace fs = std::filesystem;


//! A small coupled case (ring mesh, so no Gmsh is needed): 48 x 48 cells, a 20 mm hole in a 60 mm disc.
inline std::string coupled_text(const fs::path& out, double end) {
  std::ostringstream s;
  s << "[domain]\nnx = 48\nny = 48\nx_min = -0.075\nx_max = 0.075\ny_min = -0.075\ny_max = 0.075\n"
    << "[gas.ambient]\ndensity = 1.20\ninternal_energy = 2.09e5\n"
    << "[[gas.region]]\nshape = \"circle\"\ncenter = [0.0, 0.0]\nradius = 0.024\ndensity = 163.0\ninternal_energy = 4.29e5\n"
    << "[rock]\npreset = \"paper_table2\"\n"
    << "[rock.mesh]\nshape = \"disc_with_hole\"\nmesher = \"rings\"\ncenter = [0.0, 0.0]\nradius = 0.06\n"
    << "hole_radius = 0.02\nelement_size = 0.008\n"
    << "[time]\nend = " << end << "\n"
    << "[output]\ndirectory = \"" << out.string() << "\"\ninterval = 5e-6\nmonitor_interval = 3\nvtk = false\n"
    << "progress_interval = 0.0\n"
    << "[monitor.blasthole]\ncenter = [0.0, 0.0]\nhole_radius = 0.02\nouter_radius = 0.06\ninterval = 1e-6\n"
    << "[[probe.point]]\nname = \"hole\"\nposition = [0.0, 0.0]\ninterval = 1e-6\n";
  return s.str();
}

//! A small gas case.
inline std::string gas_text(const fs::path& out) {
  std::ostringstream s;
  s << "[domain]\nnx = 24\nny = 20\nx_min = -0.2\nx_max = 0.2\ny_min = -0.15\ny_max = 0.15\n"
    << "[gas]\n[gas.ambient]\ndensity = 1.20\ninternal_energy = 2.09e5\n"
    << "[[gas.region]]\nshape = \"circle\"\ncenter = [0.0, 0.0]\nradius = 0.05\ndensity = 163.0\n"
    << "internal_energy = 4.29e5\n[time]\nend = 1.0e-5\n"
    << "[output]\ndirectory = \"" << out.string() << "\"\ninterval = 5.0e-6\nvtk = false\nprogress_interval = 0.0\n"
    << "[[probe.point]]\nname = \"centre\"\nposition = [0.0, 0.0]\ninterval = 1.0e-6\n";
  return s.str();
}

struct Run {
  int status = -1;  //!< exit status (-1: killed by a signal or the time limit)
  std::string err;  //!< standard error
};

//! Runs the driver on `input` with overrides, at most 60 s, and returns its exit status and standard error.
inline Run run_driver(const fs::path& input, const std::vector<std::string>& args, const std::string& tag) {
  const fs::path err = fs::temp_directory_path() / ("blastsim_robust_" + tag + ".err");
  std::string cmd = "timeout 60 " + std::string(BLASTSIM_DRIVER) + " -q '" + input.string() + "'";
  for (const std::string& a : args) cmd += " '" + a + "'";
  cmd += " > /dev/null 2> '" + err.string() + "'";
  const int raw = std::system(cmd.c_str());
  Run r;
  r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  if (r.status == 124) r.status = -1;  // timeout's code: it hung
  std::ifstream in(err);
  std::stringstream ss;
  ss << in.rdbuf();
  r.err = ss.str();
  return r;
}

inline fs::path write_input(const fs::path& dir, const std::string& name, const std::string& text) {
  fs::create_directories(dir);
  const fs::path p = dir / name;
  std::ofstream(p) << text;
  return p;
}

inline std::vector<char> read_bytes(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::vector<char>(std::istreambuf_iterator<char>(in), {});
}
inline void write_bytes(const fs::path& p, const std::vector<char>& b) {
  std::ofstream(p, std::ios::binary | std::ios::trunc).write(b.data(), static_cast<std::streamsize>(b.size()));
}

//! The checkpoint format (core/checkpoint.hpp): 12-byte header, records, 20-byte trailer whose last 4 bytes
//! are the CRC-32 of everything before the trailer. Finds record `name`; returns the offset of its data.
inline std::size_t record_data(const std::vector<char>& b, const std::string& name, std::uint64_t* element = nullptr) {
  std::size_t at = 12;
  const std::size_t body_end = b.size() - 20;
  while (at < body_end) {
    std::uint64_t n, e, c;
    std::memcpy(&n, &b[at], 8);
    const std::string found(&b[at + 8], n);
    std::memcpy(&e, &b[at + 8 + n], 8);
    std::memcpy(&c, &b[at + 16 + n], 8);
    const std::size_t data = at + 24 + n;
    if (found == name) {
      if (element) *element = e;
      return data;
    }
    at = data + e * c;
  }
  FAIL("record " << name << " not found");
  return 0;
}
//! Recomputes the trailer's CRC-32 (a forged file: valid checksum, edited content).
inline void reseal(std::vector<char>& b) {
  const std::size_t body_end = b.size() - 20;
  const std::uint32_t crc = static_cast<std::uint32_t>(crc32(0, reinterpret_cast<const Bytef*>(b.data()), static_cast<uInt>(body_end)));
  std::memcpy(&b[b.size() - 4], &crc, 4);
}

inline bool same_file(const fs::path& a, const fs::path& b) { return read_bytes(a) == read_bytes(b); }

//! A CSV that reads back: a header line, then rows of numbers.
inline bool csv_reads_back(const fs::path& p) {
  std::ifstream in(p);
  std::string line;
  if (!std::getline(in, line) || line.empty()) return false;
  while (std::getline(in, line)) {
    std::stringstream row(line);
    std::string cell;
    while (std::getline(row, cell, ',')) {
      char* end = nullptr;
      std::strtod(cell.c_str(), &end);
      if (cell.empty() || *end != '\0') return false;
    }
  }
  return true;
}

//! One to three random "key=value" overrides drawn from `keys` and `values` (a seeded fuzz), and the same
//! joined by spaces for the test's message.
template <class Rng>
std::pair<std::vector<std::string>, std::string> random_overrides(Rng& rng, const std::vector<std::string>& keys,
                                                                  const std::vector<std::string>& values) {
  std::vector<std::string> args;
  std::string joined;
  const int n = 1 + static_cast<int>(rng() % 3);
  for (int m = 0; m < n; ++m) {
    args.push_back(keys[rng() % keys.size()] + "=" + values[rng() % values.size()]);
    joined += args.back() + " ";
  }
  return {args, joined};
}

//! Every file of a folder and its bytes (to compare the folder before and after a run).
inline std::map<std::string, std::vector<char>> folder_bytes(const fs::path& dir) {
  std::map<std::string, std::vector<char>> files;
  for (const fs::directory_entry& e : fs::directory_iterator(dir))
    if (e.is_regular_file()) files[e.path().filename().string()] = read_bytes(e.path());
  return files;
}

//! True when no CSV of the folder holds "nan" or "inf" in any field.
inline bool csv_all_finite(const fs::path& dir) {
  for (const fs::directory_entry& e : fs::directory_iterator(dir)) {
    if (e.path().extension() != ".csv") continue;
    std::ifstream in(e.path());
    std::string line;
    std::getline(in, line);  // header
    while (std::getline(in, line))
      if (line.find("nan") != std::string::npos || line.find("inf") != std::string::npos) return false;
  }
  return true;
}

}  // namespace blastsim::testing
