//! \file bench_common.hpp
//! \brief Shared pieces of the benchmark programs: argument lists, thread count, measured copy bandwidth, the
//! device wait. Host code: the device code (the copy, the wait) is in bench_bandwidth.cpp, so the programs
//! compile without the backend.
#pragma once

#include "blastsim/core/kernel_profile.hpp"
#include "blastsim/core/macros.hpp"

#include <sstream>
#include <string>
#include <vector>

#if defined(_OPENMP)
#include <omp.h>
#endif

namespace blastsim::bench {

//! "a,b,c" -> {"a", "b", "c"} (empty items dropped).
inline std::vector<std::string> split_list(const std::string& text) {
  std::vector<std::string> out;
  std::stringstream ss(text);
  for (std::string s; std::getline(ss, s, ',');)
    if (!s.empty()) out.push_back(s);
  return out;
}

//! "64,128,256" -> {64, 128, 256}.
inline std::vector<int> parse_int_list(const std::string& text) {
  std::vector<int> out;
  for (const std::string& s : split_list(text)) out.push_back(std::stoi(s));
  return out;
}

//! "0.25,0.5" -> {0.25, 0.5}.
inline std::vector<double> parse_double_list(const std::string& text) {
  std::vector<double> out;
  for (const std::string& s : split_list(text)) out.push_back(std::stod(s));
  return out;
}

//! Host threads of the OpenMP backend (1 for CUDA).
inline int thread_count() {
#if defined(_OPENMP)
  return omp_get_max_threads();
#else
  return 1;
#endif
}

//! Device-to-device copy bandwidth [B/s] (bytes read + written, 256 MiB arrays): the floor's reference.
double copy_bandwidth();
//! Waits until every kernel launched so far has finished (synchronize(), for the timings).
void wait_for_device();

}  // namespace blastsim::bench
