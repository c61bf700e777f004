//! \file coupling_kernels.hpp
//! \brief Small geometric kernels that the coupling processes share (docs/coupling.md): points in triangles,
//! the grid cell holding a point or faced by a rock edge, sums for reductions. Plain header: no backend.
#pragma once

#include "blastsim/cip/grid.hpp"
#include "blastsim/core/macros.hpp"
#include "blastsim/fdem/rock_fields.hpp"

#include <cmath>

namespace blastsim::ibm {

BLAST_HD inline int imax(int a, int b) { return a > b ? a : b; }
BLAST_HD inline int imin(int a, int b) { return a < b ? a : b; }

//! A pair of sums for device reductions (forces).
struct Vec2Sum {
  double x, y;
  BLAST_HD Vec2Sum operator+(const Vec2Sum& o) const { return {x + o.x, y + o.y}; }
};

//! One named field of an array of records, for reductions over it: f(k) = records[k].*field.
template <class Record>
struct FieldOf {
  const Record* records;
  double Record::*field;
  BLAST_HD double operator()(index_t k) const { return records[k].*field; }
};

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

//! Cell (i, j) holding point (x, y), or false outside the grid.
BLAST_HD inline bool cell_of(const cip::GasGrid& g, double x, double y, int& i, int& j) {
  i = static_cast<int>(floor((x - g.x_min) / g.dx));
  j = static_cast<int>(floor((y - g.y_min) / g.dy));
  return i >= 0 && i < g.nx && j >= 0 && j < g.ny;
}

//! The cell an exposed edge from p0 to p1 faces: the one holding the point a hundredth of a cell off its
//! midpoint along its outward normal (rule 1 of docs/coupling.md "Gas -> rock"); false outside the grid.
BLAST_HD inline bool facing_cell(const cip::GasGrid& g, const fdem::Vec2& p0, const fdem::Vec2& p1, int& i, int& j) {
  const fdem::Vec2 n = fdem::edge_outward_normal(p0, p1);
  const double off = 0.01 * fmin(g.dx, g.dy) / sqrt(n.x * n.x + n.y * n.y);
  return cell_of(g, 0.5 * (p0.x + p1.x) + off * n.x, 0.5 * (p0.y + p1.y) + off * n.y, i, j);
}

}  // namespace blastsim::ibm
