//! \file macros.hpp
//! \brief Portability macros with no dependency (BLAST_HD), so plain host code can use the libraries' types.
#pragma once

#include <cstdint>

#if defined(__CUDACC__)
#define BLAST_HD __host__ __device__
#else
#define BLAST_HD
#endif

//! Unrolls the next loop (a short one of fixed trip count): in device code so that small arrays indexed by its
//! counter stay in registers, on host threads (GCC, CPU backend) so that its iterations' long-latency divisions
//! overlap. Not in nvcc's host pass, whose front end does not know GCC's pragma.
#if defined(__CUDA_ARCH__)
#define BLAST_UNROLL _Pragma("unroll")
#elif defined(__GNUC__) && !defined(__clang__) && !defined(__CUDACC__)
#define BLAST_UNROLL _Pragma("GCC unroll 8")
#else
#define BLAST_UNROLL
#endif

//! Inlines everything a host loop calls into that loop (GCC's `flatten`, on backend.hpp's host loops): GCC
//! otherwise keeps the larger kernels and their helpers out of line, a call in every cell. nvcc inlines device
//! code itself. Inlining changes no arithmetic, so the bytes stay the same. Only in optimised builds without
//! AddressSanitizer: debug and sanitizer builds keep their calls, and their compile time.
#if defined(__GNUC__) && !defined(__clang__) && !defined(__CUDACC__) && defined(__OPTIMIZE__) && \
    !defined(__SANITIZE_ADDRESS__)
#define BLAST_FLATTEN __attribute__((flatten))
#else
#define BLAST_FLATTEN
#endif

namespace blastsim {

using index_t = std::int64_t;

//! min / max of two doubles by plain comparison, on host and device (std::fmin / fmax are a libm call on the
//! CPU; the kernels use these on finite values only).
BLAST_HD inline double min_of(double a, double b) { return a < b ? a : b; }
BLAST_HD inline double max_of(double a, double b) { return a < b ? b : a; }

//! True where the kernels run on a GPU (the CUDA backend). Correct in host-only translation units too (the
//! build defines BLASTSIM_BACKEND_CUDA for a CUDA build).
#if defined(BLASTSIM_BACKEND_CUDA) || defined(__CUDACC__)
constexpr bool kBackendIsGpu = true;
#else
constexpr bool kBackendIsGpu = false;
#endif

//! Name of the backend this build's kernels run on, for logs and benchmark reports.
inline const char* backend_name() { return kBackendIsGpu ? "cuda" : "cpu-openmp"; }

}  // namespace blastsim
