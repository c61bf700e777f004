//! \file temp_files.hpp
//! \brief Test helpers for output files: a fresh temporary folder per test, the first line of a file.
#pragma once

#include <filesystem>
#include <fstream>
#include <string>

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

}  // namespace blastsim::testing
