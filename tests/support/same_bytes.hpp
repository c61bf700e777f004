//! \file same_bytes.hpp
//! \brief Test helper for bit-for-bit comparisons of result arrays (determinism, restart, fused vs separate).
#pragma once

#include <cstring>
#include <vector>

namespace blastsim::test {

//! Bytes of two arrays equal (NaN-safe, -0 vs +0 told apart).
inline bool same_bytes(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0);
}

}  // namespace blastsim::test
