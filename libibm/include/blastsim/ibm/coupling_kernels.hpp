//! \file coupling_kernels.hpp
//! \brief Small geometric kernels of the immersed-boundary coupling (docs/coupling.md): points in triangles and
//! shape-function interpolation.
#pragma once

#include "blastsim/core/macros.hpp"

namespace blastsim::ibm {

//! Barycentric coordinates (w0, w1, w2) of (px, py) in the triangle (x[k], y[k]); w sums to 1. Returns
//! false for a degenerate triangle.
BLAST_HD inline bool barycentric(const double x[3], const double y[3], double px, double py, double w[3]) {
  const double det = (x[1] - x[0]) * (y[2] - y[0]) - (x[2] - x[0]) * (y[1] - y[0]);
  if (det == 0.0) return false;
  w[1] = ((px - x[0]) * (y[2] - y[0]) - (x[2] - x[0]) * (py - y[0])) / det;
  w[2] = ((x[1] - x[0]) * (py - y[0]) - (px - x[0]) * (y[1] - y[0])) / det;
  w[0] = 1.0 - w[1] - w[2];
  return true;
}

//! Inside test of the immersed boundary: a point is inside a triangle when all its barycentric
//! coordinates are >= -1e-12. Points on an edge count as inside, so a face on a joint between two triangles
//! is covered by rock; the tolerance keeps it so when rounding puts such a point a hair outside both
//! triangles (seen: grid faces on a straight joint line of a moving block flickered uncovered).
BLAST_HD inline bool inside(const double w[3]) {
  const double tol = -1e-12;
  return w[0] >= tol && w[1] >= tol && w[2] >= tol;
}

}  // namespace blastsim::ibm
