//! \file backend.hpp
//! \brief The only header that knows which backend runs the kernels: CUDA (nvcc) or host threads (Thrust OpenMP).
//!
//! Every kernel in blastsim is a `BLAST_HD` functor or lambda handed to one of the launchers below; the
//! same source compiles with g++ (THRUST_DEVICE_SYSTEM_OMP) and with nvcc (THRUST_DEVICE_SYSTEM_CUDA).
#pragma once

#include "blastsim/core/atomic.hpp"
#include "blastsim/core/field2d.hpp"
#include "blastsim/core/kernel_profile.hpp"
#include "blastsim/core/macros.hpp"

#include <algorithm>
#include <cassert>
#include <chrono>
#include <climits>
#include <cstdio>
#include <string>
#include <vector>

#if !defined(__CUDACC__)
#include <omp.h>
#endif
#include <thrust/device_vector.h>
#include <thrust/execution_policy.h>
#if defined(__CUDACC__)
#include <thrust/system/cuda/execution_policy.h>
#endif
#include <thrust/binary_search.h>
#include <thrust/copy.h>
#include <thrust/for_each.h>
#include <thrust/functional.h>
#include <thrust/host_vector.h>
#include <thrust/iterator/counting_iterator.h>
#include <thrust/scan.h>
#include <thrust/sort.h>
#include <thrust/transform_reduce.h>

namespace blastsim {

//! Waits until every kernel launched so far has finished (for timings; the step loop never needs it).
inline void synchronize() {
#if defined(__CUDACC__)
  cudaDeviceSynchronize();
#endif
}

namespace detail {
//! Runs `launch`, and when the KernelProfile is on adds its synchronised wall time to `label`.
template <class Launch>
void profiled(const char* label, Launch&& launch) {
  KernelProfile& profile = KernelProfile::instance();
  if (!profile.enabled()) {
    launch();
    return;
  }
  synchronize();
  const auto t0 = std::chrono::steady_clock::now();
  launch();
  synchronize();
  profile.add(label, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
}

//! The policy of the launchers: on CUDA the launch returns at once (`par_nosync`: the kernels of a step
//! queue on the default stream in order, and the host waits only where it reads a result); the Thrust
//! default (`thrust::device`) would wait for every kernel to finish. On host threads every call returns
//! when its work is done.
inline auto launch_policy() {
#if defined(__CUDACC__)
  return thrust::cuda::par_nosync;
#else
  return thrust::device;
#endif
}
}  // namespace detail

#if !defined(__CUDACC__)
namespace detail {
//! One host thread's share [b, e) of an index loop, with f and everything it calls inlined into the loop (GCC's
//! `flatten`; it otherwise keeps the larger kernels and their helpers out of line). The loop calls a copy of f
//! on this thread's stack: the kernel's stores through its pointers cannot reach a copy whose address never
//! leaves the function, so the compiler keeps the kernel's parameters (views, dt, flags) in registers instead of
//! reloading them from the shared functor after every store.
template <class F>
BLAST_FLATTEN void run_range(index_t b, index_t e, const F& f) {
  const F local = f;
  for (index_t k = b; k < e; ++k) local(k);
}
//! Thread t's share [b, e) of [0, n) split into equal contiguous blocks (OpenMP's static schedule).
inline void thread_block(index_t n, index_t& b, index_t& e) {
  const index_t threads = omp_get_num_threads(), t = omp_get_thread_num();
  const index_t chunk = (n + threads - 1) / threads;
  b = t * chunk < n ? t * chunk : n;
  e = b + chunk < n ? b + chunk : n;
}
}  // namespace detail
#endif

//! Runs f(i) for i in [0, n). `label` names the kernel for profilers and error messages. On host threads each
//! thread runs one contiguous block of i in order; every call of f is independent, so the split does not
//! change the bytes.
template <class F>
void for_each_index(const char* label, index_t n, F f) {
  if (n <= 0) return;
  ++LaunchCounts::instance().launches;
  detail::profiled(label, [&] {
#if defined(__CUDACC__)
    thrust::for_each_n(detail::launch_policy(), thrust::counting_iterator<index_t>(0), n, f);
#else
#pragma omp parallel
    {
      index_t b, e;
      detail::thread_block(n, b, e);
      detail::run_range(b, e, f);
    }
#endif
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

#if !defined(__CUDACC__)
namespace detail {
//! Row j0 + r of a cell loop, i in order: the host's unit of work in for_each_cell() (for_each_index() over rows).
template <class F>
struct RowOfCells {
  int i0, i1, j0;
  F f;
  void operator()(index_t r) const {
    const int j = j0 + static_cast<int>(r);
    for (int i = i0; i < i1; ++i) f(i, j);
  }
};
}  // namespace detail
#endif

//! Runs f(i, j) for i in [i0, i1), j in [j0, j1), with i fastest (AMReX ParallelFor style). On the GPU one
//! thread per (i, j); on host threads the rows are shared among the threads and each runs its rows' i in order
//! (AMReX's and Kokkos's host loops: no index division per cell, and the compiler sees the inner loop, into which
//! for_each_index() inlines f). The boxes with few rows are ghost strips, a fraction of a percent of a step. Every
//! call of f is independent, so either gives the same bytes.
template <class F>
void for_each_cell(const char* label, int i0, int i1, int j0, int j1, F f) {
  const int ni = i1 - i0;
  const int nj = j1 - j0;
  if (ni <= 0 || nj <= 0) return;
#if defined(__CUDACC__)
  for_each_index(label, static_cast<index_t>(ni) * nj, detail::Flatten2D<F>{i0, j0, ni, f});
#else
  for_each_index(label, nj, detail::RowOfCells<F>{i0, i1, j0, f});
#endif
}

//! A box of (i, j) indices, [i0, i1) x [j0, j1).
struct IndexBox {
  int i0, i1, j0, j1;
  BLAST_HD bool contains(int i, int j) const { return i >= i0 && i < i1 && j >= j0 && j < j1; }
};

//! One kernel of a group that may be fused (for_each_cell_fused()): its label, its index box, its functor.
template <class F>
struct CellPart {
  const char* label;
  IndexBox box;
  F f;
};
template <class F>
CellPart<F> cell_part(const char* label, IndexBox box, F f) {
  return {label, box, f};
}

namespace detail {
template <class... F>
struct FusedCells;
template <class F>
struct FusedCells<F> {
  IndexBox box;
  F f;
  BLAST_HD void operator()(int i, int j) const {
    if (box.contains(i, j)) f(i, j);
  }
};
template <class F, class G, class... R>
struct FusedCells<F, G, R...> {
  IndexBox box;
  F f;
  FusedCells<G, R...> rest;
  BLAST_HD void operator()(int i, int j) const {
    if (box.contains(i, j)) f(i, j);
    rest(i, j);
  }
};
template <class F>
FusedCells<F> fuse_parts(const CellPart<F>& p) {
  return {p.box, p.f};
}
template <class F, class G, class... R>
FusedCells<F, G, R...> fuse_parts(const CellPart<F>& p, const CellPart<G>& q, const CellPart<R>&... r) {
  return {p.box, p.f, fuse_parts(q, r...)};
}
}  // namespace detail

//! Runs a group of independent kernels (none reads what another writes) over their index boxes: with `fuse`,
//! as one kernel labelled `label` over the boxes' bounding box, each thread calling every part whose box holds
//! its (i, j) (one launch, and the arrays the parts share are read once from memory); without, as separate
//! launches under their own labels. Both give the same bytes: each part computes the same values either way.
template <class... F>
void for_each_cell_fused(const char* label, bool fuse, const CellPart<F>&... parts) {
  if (!fuse) {
    (for_each_cell(parts.label, parts.box.i0, parts.box.i1, parts.box.j0, parts.box.j1, parts.f), ...);
    return;
  }
  IndexBox all{INT_MAX, INT_MIN, INT_MAX, INT_MIN};
  const IndexBox boxes[] = {parts.box...};
  for (const IndexBox& b : boxes) {
    if (b.i0 >= b.i1 || b.j0 >= b.j1) continue;  // an empty part widens nothing
    all.i0 = std::min(all.i0, b.i0), all.i1 = std::max(all.i1, b.i1);
    all.j0 = std::min(all.j0, b.j0), all.j1 = std::max(all.j1, b.j1);
  }
  for_each_cell(label, all.i0, all.i1, all.j0, all.j1, detail::fuse_parts(parts...));
}

//! op-reduction of f(k) over k in [0, n), starting from init (the two reductions below).
template <class T, class F, class Op>
T reduce_with(const char* label, index_t n, T init, F f, Op op) {
  T out = init;
  ++LaunchCounts::instance().launches;
  ++LaunchCounts::instance().host_waits;  // the host reads the result
  detail::profiled(label, [&] {
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

//! Indices per partial sum of reduce_sum() on host threads.
inline constexpr index_t kSumBlock = 4096;

//! Sum of f(k) over k in [0, n), plus init. On host threads the summation tree depends only on n, so a run gives
//! the same bits whatever the number of threads or of the machine's processors: [0, n) is cut into blocks of
//! kSumBlock indices, each block summed in index order (the blocks shared among the threads), and init plus the
//! blocks' sums added in block order. (Thrust's OpenMP reduction splits [0, n) into omp_get_num_procs() parts,
//! so its bits changed from one machine to another.) On CUDA Thrust's tree depends on n and the device, so the
//! same GPU gives the same bits.
template <class T, class F>
T reduce_sum(const char* label, index_t n, T init, F f) {
#if defined(__CUDACC__)
  return reduce_with(label, n, init, f, thrust::plus<T>());
#else
  T out = init;
  if (n <= 0) return out;
  ++LaunchCounts::instance().launches;
  ++LaunchCounts::instance().host_waits;
  detail::profiled(label, [&] {
    const index_t blocks = (n + kSumBlock - 1) / kSumBlock;
    std::vector<T> part(static_cast<std::size_t>(blocks), init);  // each overwritten below
#pragma omp parallel for schedule(static)
    for (index_t b = 0; b < blocks; ++b) {
      const index_t k0 = b * kSumBlock, k1 = std::min(n, k0 + kSumBlock);
      T s = f(k0);
      for (index_t k = k0 + 1; k < k1; ++k) s = s + f(k);
      part[static_cast<std::size_t>(b)] = s;
    }
    for (const T& s : part) out = out + s;
  });
  return out;
#endif
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

namespace detail {
template <class T>
struct FillWith {
  T* out;
  T value;
  BLAST_HD void operator()(index_t k) const { out[k] = value; }
};
}  // namespace detail

//! Sets every element of v to value, as a kernel like any other (it does not make the host wait).
template <class T>
void fill_device(const char* label, DeviceVector<T>& v, T value) {
  for_each_index(label, static_cast<index_t>(v.size()), detail::FillWith<T>{device_ptr(v), value});
}

//! Sets every element of the padded 2-D array f to value (a kernel, no wait).
template <class T>
void fill_device(const char* label, Field2D<T> f, T value) {
  for_each_index(label, f.shape.size(), detail::FillWith<T>{f.data, value});
}

namespace detail {
template <class T>
struct IndexOf {
  T* out;
  BLAST_HD void operator()(index_t k) const { out[k] = static_cast<T>(k); }
};
}  // namespace detail

//! v[k] = k for every k (a kernel, no wait).
template <class T>
void fill_indices(const char* label, DeviceVector<T>& v) {
  for_each_index(label, static_cast<index_t>(v.size()), detail::IndexOf<T>{device_ptr(v)});
}

// ---- Device algorithms: labelled, timed under --profile, and counted (each launch; the host waits for each) ----

//! Sorts keys[0, n) ascending and moves values[0, n) with them, equal keys in index order (a stable sort, so a
//! sum over a sorted run is made in a fixed order whatever the backend). The host waits for it.
template <class K, class V>
void stable_sort_by_key(const char* label, DeviceVector<K>& keys, DeviceVector<V>& values, index_t n) {
  ++LaunchCounts::instance().launches;
  count_host_wait();
  detail::profiled(
      label, [&] { thrust::stable_sort_by_key(thrust::device, keys.begin(), keys.begin() + n, values.begin()); });
}

//! out[c] = the first position in the sorted keys[0, n) whose key is not below c, for every value c in [0, count)
//! (where each value's run starts). The host waits for it.
template <class K>
void lower_bounds(const char* label, const DeviceVector<K>& keys, index_t n, DeviceVector<int>& out, int count) {
  ++LaunchCounts::instance().launches;
  count_host_wait();
  detail::profiled(label, [&] {
    thrust::lower_bound(thrust::device, keys.begin(), keys.begin() + n, thrust::counting_iterator<int>(0),
                        thrust::counting_iterator<int>(count), out.begin());
  });
}

//! out[c] = the first position in the sorted keys[0, n) whose key is above c, for every value c in [0, count)
//! (where each value's run ends). The host waits for it.
template <class K>
void upper_bounds(const char* label, const DeviceVector<K>& keys, index_t n, DeviceVector<int>& out, int count) {
  ++LaunchCounts::instance().launches;
  count_host_wait();
  detail::profiled(label, [&] {
    thrust::upper_bound(thrust::device, keys.begin(), keys.begin() + n, thrust::counting_iterator<int>(0),
                        thrust::counting_iterator<int>(count), out.begin());
  });
}

//! Host read of the element k of v (the host waits for it).
template <class T>
T read_element(const DeviceVector<T>& v, index_t k) {
  count_host_wait();
  return v[static_cast<std::size_t>(k)];
}

//! Host write of the element k of v (the host waits for it).
template <class T>
void write_element(DeviceVector<T>& v, index_t k, T value) {
  count_host_wait();
  v[static_cast<std::size_t>(k)] = value;
}

//! Replaces v by its exclusive prefix sums in place (v[0] = 0, v[k] = the sum of the old v[0 .. k)) and returns
//! the last entry, which the host reads: the total of all but the old last entry (a CSR's size when that entry
//! was 0). The host waits twice: for the scan and for the read.
template <class T>
T exclusive_scan_total(const char* label, DeviceVector<T>& v) {
  ++LaunchCounts::instance().launches;
  count_host_wait();
  detail::profiled(label, [&] { thrust::exclusive_scan(thrust::device, v.begin(), v.end(), v.begin()); });
  return read_element(v, static_cast<index_t>(v.size()) - 1);
}

//! Writes the indices k in [0, n) for which keep(k) holds, ascending, into out[0 ..) (out holds at least that many)
//! and returns their number. The host waits for it.
template <class F>
index_t select_indices(const char* label, index_t n, DeviceVector<int>& out, F keep) {
  ++LaunchCounts::instance().launches;
  count_host_wait();
  index_t selected = 0;
  detail::profiled(label, [&] {
    const auto end = thrust::copy_if(thrust::device, thrust::counting_iterator<int>(0),
                                     thrust::counting_iterator<int>(static_cast<int>(n)), out.begin(), keep);
    selected = static_cast<index_t>(end - out.begin());
  });
  return selected;
}

//! Explicit copy to host memory (the only way host code reads device data; the host waits for it).
template <class T>
std::vector<T> to_host(const DeviceVector<T>& v) {
  count_host_wait();
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

//! Explicit copy from host memory into the padded 2-D array f (host holds f.shape.size() values).
template <class T>
void copy_from_host(Field2D<T> f, const std::vector<T>& host) {
  assert(static_cast<index_t>(host.size()) == f.shape.size());
  if (!host.empty()) thrust::copy(host.begin(), host.end(), thrust::device_pointer_cast(f.data));
}

}  // namespace blastsim
