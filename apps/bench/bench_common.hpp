//! \file bench_common.hpp
//! \brief Shared pieces of the benchmark programs: argument lists, thread count, measured copy bandwidth.
#pragma once

#include "blastsim/core/backend.hpp"

#include <thrust/copy.h>

#include <chrono>
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
inline double copy_bandwidth() {
  using Clock = std::chrono::steady_clock;
  const size_t n = size_t(1) << 25;
  DeviceVector<double> a(n, 1.0), b(n, 0.0);
  thrust::copy(thrust::device, a.begin(), a.end(), b.begin());  // warm-up
  synchronize();
  const int reps = 5;
  const auto t0 = Clock::now();
  for (int r = 0; r < reps; ++r) thrust::copy(thrust::device, a.begin(), a.end(), b.begin());
  synchronize();
  return 2.0 * sizeof(double) * n * reps / std::chrono::duration<double>(Clock::now() - t0).count();
}

}  // namespace blastsim::bench
