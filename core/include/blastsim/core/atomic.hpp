//! \file atomic.hpp
//! \brief Order-independent atomics for kernels, on the device and on host threads (no backend headers).
#pragma once

#include "blastsim/core/macros.hpp"

namespace blastsim {

//! Atomic *p = max(*p, v) on device or host threads. The result does not depend on the order of the
//! writers, so kernels that use it stay deterministic.
BLAST_HD inline void atomic_max(int* p, int v) {
#if defined(__CUDA_ARCH__)
  atomicMax(p, v);
#else
  int old = __atomic_load_n(p, __ATOMIC_RELAXED);
  while (old < v && !__atomic_compare_exchange_n(p, &old, v, false, __ATOMIC_RELAXED, __ATOMIC_RELAXED)) {
  }
#endif
}

}  // namespace blastsim
