//! \file splitmix.hpp
//! \brief SplitMix64 hashing for the mesh's seeded perturbations (jitter, Gmsh realisations): the same bits on every machine.
#pragma once

#include <cstdint>

namespace blastsim::fdem::detail {

//! SplitMix64's finaliser (Steele, Lea & Flood 2014): a well-mixed 64-bit hash of a counter.
inline std::uint64_t splitmix64(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}
//! The top 53 bits as a number in [0, 1).
inline double unit_interval(std::uint64_t bits) { return static_cast<double>(bits >> 11) * 0x1.0p-53; }

}  // namespace blastsim::fdem::detail
