//! \file backend.hpp
//! \brief The only header that knows which backend runs the kernels: CUDA (nvcc) or host threads (Thrust OpenMP).
//!
//! Every kernel in blastsim is a `BLAST_HD` functor or lambda handed to one of the launchers below; the
//! same source compiles with g++ (THRUST_DEVICE_SYSTEM_OMP) and with nvcc (THRUST_DEVICE_SYSTEM_CUDA).
#pragma once

#include "blastsim/core/atomic.hpp"
#include "blastsim/core/field2d.hpp"
#include "blastsim/core/macros.hpp"

#include <cassert>
#include <chrono>
#include <map>
#include <string>
#include <vector>

#include <thrust/device_vector.h>
#include <thrust/execution_policy.h>
#include <thrust/for_each.h>
#include <thrust/functional.h>
#include <thrust/host_vector.h>
#include <thrust/iterator/counting_iterator.h>
#include <thrust/transform_reduce.h>

namespace blastsim {

//! Waits until every kernel launched so far has finished (for timings; the step loop never needs it).
inline void synchronize() {
#if defined(__CUDACC__)
  cudaDeviceSynchronize();
#endif
}

//! Wall time per kernel label, for benchmarks and profiles (`blastsim --profile`, blastsim-bench-coupled).
//! Off by default; when on, every launch through the launchers below is bracketed by synchronize(), so the
//! times are each kernel's own (and the run is slower). Host threads only read or change it between steps.
class KernelProfile {
 public:
  struct Entry {
    double seconds = 0;
    long launches = 0;
  };
  static KernelProfile& instance() {
    static KernelProfile p;
    return p;
  }
  bool enabled() const { return enabled_; }
  void enable(bool on) { enabled_ = on; }
  void reset() { entries_.clear(); }
  const std::map<std::string, Entry>& entries() const { return entries_; }
  //! Runs `launch`, and when enabled adds its synchronised wall time to `label`.
  template <class Launch>
  void time(const char* label, Launch&& launch) {
    if (!enabled_) {
      launch();
      return;
    }
    synchronize();
    const auto t0 = std::chrono::steady_clock::now();
    launch();
    synchronize();
    Entry& e = entries_[label];
    e.seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    ++e.launches;
  }

 private:
  bool enabled_ = false;
  std::map<std::string, Entry> entries_;
};

//! Runs f(i) for i in [0, n). `label` names the kernel for profilers and error messages.
template <class F>
void for_each_index(const char* label, index_t n, F f) {
  if (n <= 0) return;
  KernelProfile::instance().time(label, [&] {
    thrust::for_each_n(thrust::device, thrust::counting_iterator<index_t>(0), n, f);
  });
}

namespace detail {
template <class F>
struct Flatten2D {
  int i0, j0, ni;
  F f;
  BLAST_HD void operator()(index_t k) const {
    const int j = static_cast<int>(k / ni);
    const int i = static_cast<int>(k - static_cast<index_t>(j) * ni);
    f(i0 + i, j0 + j);
  }
};
template <class F, class T>
struct Transformed {
  F f;
  BLAST_HD T operator()(index_t k) const { return f(k); }
};
}  // namespace detail

//! Runs f(i, j) for i in [i0, i1), j in [j0, j1), with i fastest (AMReX ParallelFor style).
template <class F>
void for_each_cell(const char* label, int i0, int i1, int j0, int j1, F f) {
  const int ni = i1 - i0;
  const int nj = j1 - j0;
  if (ni <= 0 || nj <= 0) return;
  for_each_index(label, static_cast<index_t>(ni) * nj, detail::Flatten2D<F>{i0, j0, ni, f});
}

//! op-reduction of f(k) over k in [0, n), starting from init (the two reductions below).
template <class T, class F, class Op>
T reduce_with(const char* label, index_t n, T init, F f, Op op) {
  T out = init;
  KernelProfile::instance().time(label, [&] {
    out = thrust::transform_reduce(thrust::device, thrust::counting_iterator<index_t>(0),
                                   thrust::counting_iterator<index_t>(n), detail::Transformed<F, T>{f}, init, op);
  });
  return out;
}

//! Maximum of f(k) over k in [0, n) (order-independent, hence deterministic); `init` for n == 0.
template <class T, class F>
T reduce_max(const char* label, index_t n, T init, F f) {
  return reduce_with(label, n, init, f, thrust::maximum<T>());
}

//! Sum of f(k) over k in [0, n). The summation tree depends only on n and the thread count, so a run
//! repeated on the same backend with the same thread count gives the same bits.
template <class T, class F>
T reduce_sum(const char* label, index_t n, T init, F f) {
  return reduce_with(label, n, init, f, thrust::plus<T>());
}

//! Owning array in the backend's memory. Kernels never index it; they get a raw pointer or a view.
template <class T>
using DeviceVector = thrust::device_vector<T>;

template <class T>
T* device_ptr(DeviceVector<T>& v) {
  return thrust::raw_pointer_cast(v.data());
}
template <class T>
const T* device_ptr(const DeviceVector<T>& v) {
  return thrust::raw_pointer_cast(v.data());
}

//! Non-owning view of a device vector holding a padded 2-D array. An empty vector is an absent field (e.g. the
//! material fields of a one-gas run): its view must not be read.
template <class T>
Field2D<T> make_field_view(DeviceVector<T>& v, PaddedShape s) {
  assert(v.empty() || static_cast<index_t>(v.size()) == s.size());
  return Field2D<T>{device_ptr(v), s};
}
template <class T>
Field2D<const T> make_field_view(const DeviceVector<T>& v, PaddedShape s) {
  assert(v.empty() || static_cast<index_t>(v.size()) == s.size());
  return Field2D<const T>{device_ptr(v), s};
}

//! Explicit copy to host memory (the only way host code reads device data).
template <class T>
std::vector<T> to_host(const DeviceVector<T>& v) {
  std::vector<T> out(v.size());
  if (!v.empty()) thrust::copy(v.begin(), v.end(), out.begin());  // (an empty range has no data pointer)
  return out;
}

//! Explicit copy from host memory.
template <class T>
void copy_from_host(DeviceVector<T>& v, const std::vector<T>& host) {
  v.resize(host.size());
  if (!host.empty()) thrust::copy(host.begin(), host.end(), v.begin());
}

}  // namespace blastsim
