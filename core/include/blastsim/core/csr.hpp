//! \file csr.hpp
//! \brief Items grouped by an integer key on the host, in compressed-sparse-row form (a counting sort).
#pragma once

#include <vector>

namespace blastsim {

//! Group g holds entry[offset[g]] .. entry[offset[g + 1] - 1], its items in ascending order.
struct HostCsr {
  std::vector<int> offset;  //!< groups + 1 entries
  std::vector<int> entry;   //!< item indices
};

//! Items 0 .. keys.size() - 1 grouped by their key; every key must lie in [0, groups) (the caller checks).
inline HostCsr group_by_key(const std::vector<int>& keys, int groups) {
  HostCsr c;
  c.offset.assign(static_cast<std::size_t>(groups) + 1, 0);
  for (const int k : keys) ++c.offset[k + 1];
  for (int g = 0; g < groups; ++g) c.offset[g + 1] += c.offset[g];
  c.entry.resize(keys.size());
  std::vector<int> fill(c.offset.begin(), c.offset.end() - 1);
  for (std::size_t i = 0; i < keys.size(); ++i) c.entry[fill[keys[i]]++] = static_cast<int>(i);
  return c;
}

}  // namespace blastsim
