//! \file boundary.hpp
//! \brief Outer boundaries of the gas grid: non-reflecting outflow (the paper's), reflective wall, periodic.
#pragma once

#include "blastsim/core/access.hpp"

#include "blastsim/core/macros.hpp"

#include <string>

namespace blastsim::cip {

//! Kind of one side of the domain.
enum class BoundaryKind {
  outflow,   //!< zero-gradient extrapolation ("continuous" boundary of the paper): ghosts copy the edge
  wall,      //!< reflective slip wall: mirror ghosts, normal velocity odd, zero on the wall face
  periodic,  //!< the opposite side continues the domain (must be set on both sides)
};

//! The four sides of the rectangular domain.
enum Side { left = 0, right = 1, bottom = 2, top = 3 };

//! The kind of each side, by name: `BoundaryConditions::all(BoundaryKind::outflow).set(bottom, BoundaryKind::wall)`.
struct BoundaryConditions {
  BoundaryKind left_side = BoundaryKind::outflow;
  BoundaryKind right_side = BoundaryKind::outflow;
  BoundaryKind bottom_side = BoundaryKind::outflow;
  BoundaryKind top_side = BoundaryKind::outflow;
  static BoundaryConditions all(BoundaryKind k) { return BoundaryConditions{k, k, k, k}; }
  //! Sets side s to k; returns *this so that settings chain.
  BoundaryConditions& set(Side s, BoundaryKind k) {
    (s == Side::left ? left_side : s == Side::right ? right_side : s == Side::bottom ? bottom_side : top_side) = k;
    return *this;
  }
  //! The kind of side s (a comparison chain, not an array indexed at run time: in a CUDA kernel such an
  //! index makes the compiler copy the whole kernel argument to local memory).
  BLAST_HD BoundaryKind kind(int s) const {
    return s == Side::left ? left_side : s == Side::right ? right_side : s == Side::bottom ? bottom_side : top_side;
  }
  //! True when the x (axis 0) or y (axis 1) direction is periodic on both its sides.
  BLAST_HD bool periodic(int axis) const {
    return kind(2 * axis) == BoundaryKind::periodic && kind(2 * axis + 1) == BoundaryKind::periodic;
  }
  //! The first axis (0: x, 1: y) periodic on one side only, or -1: a periodic side needs its opposite one.
  int unpaired_periodic_axis() const {
    for (int a = 0; a < 2; ++a)
      if ((kind(2 * a) == BoundaryKind::periodic) != (kind(2 * a + 1) == BoundaryKind::periodic)) return a;
    return -1;
  }
};

//! bc.kind(s), kept for the kernels that call it by this name.
BLAST_HD inline BoundaryKind kind_of(const BoundaryConditions& bc, int s) { return bc.kind(s); }

const char* to_string(BoundaryKind k);
//! Parses "outflow" | "wall" | "periodic"; returns false on anything else.
bool parse_boundary_kind(const std::string& text, BoundaryKind& out);

//! Where a ghost (or boundary-face) value comes from, and the factors applied to it.
struct GhostSource {
  int source;              //!< index along the normal direction to copy from
  double value_factor;     //!< multiplies the value
  double normal_factor;    //!< multiplies the derivative along the boundary normal
  double tangent_factor;   //!< multiplies the derivative along the boundary
};

//! Ghost rule along one direction for index k outside the valid range (or on a boundary face).
//! n: cells in that direction; face_centred: the variable sits on faces 0..n in that direction;
//! parity: +1 for variables even under a mirror at the boundary, -1 for the normal velocity.
//! Rules: outflow copies the nearest valid point with zero normal derivative (an outflow boundary face
//! itself is advanced by the solver, see pressure_ghost()); wall mirrors about the
//! boundary (value * parity, normal derivative * -parity) and sets an odd variable to zero on the wall
//! face; periodic wraps by n.
BLAST_HD inline GhostSource ghost_source(int k, int n, bool face_centred, BoundaryKind kind, double parity) {
  const bool low = k <= 0;  // left/bottom side (k == 0 only reaches here for a boundary face)
  switch (kind) {
    case BoundaryKind::periodic:
      if (face_centred && k == 0) return {0, 1.0, 1.0, 1.0};
      return {low ? k + n : k - n, 1.0, 1.0, 1.0};
    case BoundaryKind::wall:
      if (face_centred) {
        if (k == 0 || k == n) return {k, parity > 0 ? 1.0 : 0.0, 1.0, parity > 0 ? 1.0 : 0.0};
        return {low ? -k : 2 * n - k, parity, -parity, parity};
      }
      return {low ? -k - 1 : 2 * n - 1 - k, parity, -parity, parity};
    case BoundaryKind::outflow:
    default:
      if (face_centred) return {low ? 0 : n, 1.0, 0.0, 1.0};
      return {low ? 0 : n - 1, 1.0, 0.0, 1.0};
  }
}

//! Pressure P = p + q in the ghost cell beyond boundary cell b: periodic takes the wrapped cell, the others
//! copy P_b (an outflow boundary face does not use it: see outflow_face_velocity()).
BLAST_HD inline double pressure_ghost(BoundaryKind kind, double P_b, double P_wrapped) {
  return kind == BoundaryKind::periodic ? P_wrapped : P_b;
}

//! Outward-normal velocity [m/s] of an outflow boundary face (non-reflecting, characteristic form).
//! Subsonic: the incoming acoustic characteristic keeps its reference value, w - p/(rho c) = w_ref -
//! p_ref/(rho c) (Thompson, JCP 68 (1987) 1, linearised), so an outgoing plane wave leaves without
//! reflection. Supersonic outflow (w_inner >= c): every characteristic leaves, the face copies its inner
//! neighbour. p_face is the pressure extrapolated to the face; rho, c those of the boundary cell.
//! Freezing the face instead (zero pressure gradient) would reflect an outgoing wave like a wall.
BLAST_HD inline double outflow_face_velocity(double w_inner, double w_ref, double p_face, double p_ref,
                                             double rho, double c) {
  if (w_inner >= c) return w_inner;
  return w_ref + (p_face - p_ref) / (rho * c);
}

//! Reference (far-field) state of the outflow faces, one entry per boundary face in the order left rows
//! [0, ny), right rows [ny, 2 ny), bottom columns [2 ny, 2 ny + nx), top columns [2 ny + nx, 2 ny + 2 nx),
//! set by GasSolver::initialise() (a field list: core/access.hpp).
#define BLASTSIM_GAS_OUTFLOW_REFERENCE(X)                                             \
  X(double, pressure, "pressure of the cell beside each boundary face at the start [Pa]") \
  X(double, velocity, "outward face velocity at the start [m/s]")
struct OutflowReference {
  BLASTSIM_GAS_OUTFLOW_REFERENCE(BLASTSIM_CONST_VIEW_MEMBER)
};

}  // namespace blastsim::cip
