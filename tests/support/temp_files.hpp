//! \file temp_files.hpp
//! \brief Test helpers for output files: a fresh temporary folder per test, the first line of a file, a file's
//! bytes, a CSV file's columns by header name.
#pragma once

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace blastsim::testing {

//! An empty folder under the system's temporary directory, named after the test.
inline std::filesystem::path fresh_dir(const std::string& name) {
  const std::filesystem::path d = std::filesystem::temp_directory_path() / ("blastsim_test_" + name);
  std::filesystem::remove_all(d);
  return d;
}

//! The first line of a text file ("" if it cannot be read).
inline std::string first_line(const std::filesystem::path& p) {
  std::ifstream in(p);
  std::string l;
  std::getline(in, l);
  return l;
}

//! Every byte of a file ("" if it cannot be read).
inline std::string file_bytes(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

//! All rows of a CSV file with a header row, as columns keyed by header name (an empty field: NaN).
inline std::map<std::string, std::vector<double>> csv_columns(const std::filesystem::path& p) {
  std::ifstream in(p);
  std::string header, line;
  std::getline(in, header);
  std::vector<std::string> names;
  std::stringstream h(header);
  for (std::string n; std::getline(h, n, ',');) names.push_back(n);
  std::map<std::string, std::vector<double>> cols;
  while (std::getline(in, line)) {
    std::stringstream v(line);
    std::string value;
    for (size_t k = 0; k < names.size() && std::getline(v, value, ','); ++k) cols[names[k]].push_back(value.empty() ? std::nan("") : std::stod(value));
  }
  return cols;
}

}  // namespace blastsim::testing
