//! \file fragment_kernels.hpp
//! \brief Kernels of the fragment labels on the device (fragment_labels(), fragments.hpp): connected components of
//! triangles through joints that still hold, by label propagation.
#pragma once

#include "blastsim/core/access.hpp"
#include "blastsim/core/macros.hpp"
#include "blastsim/fdem/rock_fields.hpp"

#include <cstdint>

namespace blastsim::fdem {

//! One label per triangle; fragment_labels() keeps two of them, the sweep reading one and writing the other.
#define BLASTSIM_FRAGMENT_LABELS(X) X(int, label, "per triangle: the smallest triangle index of its fragment found so far")
BLASTSIM_VIEW_GROUP(FragmentLabels, BLASTSIM_FRAGMENT_LABELS)

//! What joins a triangle to its neighbours: per edge slot the triangle across it and the joint between
//! them (-1 on the mesh boundary), and per joint whether it has broken.
struct FragmentLinks {
  EdgeParams edge;                  //!< neighbour, joint (per edge slot)
  JointState<Access::read> joints;  //!< broken
  //! The triangle joined to the owner of `slot` by a joint that still holds, or -1.
  BLAST_HD int held_neighbour(int slot) const {
    const int j = edge.joint[slot];
    return j >= 0 && !joints.broken[j] ? edge.neighbour[slot] : -1;
  }
};

//! One Jacobi sweep of label propagation with pointer jumping, one thread per triangle t:
//! m = min(label[t], label of each neighbour held by a joint), then label_out[t] = label[m].
//! Invariant: label[t] <= t and label[t] lies in t's fragment, so labels only fall; at the fixed point
//! every fragment carries the smallest triangle index it holds, whatever the sweep order (the sweep reads
//! only `in`, so the bytes do not depend on the thread schedule either).
struct LabelSweepKernel {
  FragmentLinks links;
  FragmentLabels<Access::read> in;
  FragmentLabels<Access::read_write> out;
  BLAST_HD void operator()(index_t tl) const {
    const int t = static_cast<int>(tl);
    int m = in.label[t];
    for (int k = 0; k < 3; ++k) {
      const int n = links.held_neighbour(3 * t + k);
      if (n >= 0 && in.label[n] < m) m = in.label[n];
    }
    out.label[t] = in.label[m];
  }
};

//! 1 where a sweep changed a triangle's label (a maximum over the triangles: 0 at the fixed point).
struct LabelChanged {
  FragmentLabels<Access::read> before, after;
  BLAST_HD int operator()(index_t t) const { return before.label[t] != after.label[t] ? 1 : 0; }
};

}  // namespace blastsim::fdem
