//! \file bench_bandwidth.cpp
//! \brief The benchmarks' device code: the memory-traffic reference (a device-to-device copy timed on the compiled
//! backend) and the device wait.
#include "bench_common.hpp"

#include "blastsim/core/backend.hpp"

#include <thrust/copy.h>

#include <chrono>

namespace blastsim::bench {

double copy_bandwidth() {
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

void wait_for_device() { synchronize(); }

}  // namespace blastsim::bench
