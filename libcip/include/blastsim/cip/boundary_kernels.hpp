//! \file boundary_kernels.hpp
//! \brief Device-side boundary helpers of the gas step: what the ghost fill and the outflow faces need
//! (BoundaryContext), the characteristic outflow face velocity from a cell state, and the ghost-fill kernels.
#pragma once

#include "blastsim/cip/boundary.hpp"
#include "blastsim/cip/eos.hpp"
#include "blastsim/cip/gas_state.hpp"
#include "blastsim/cip/grid.hpp"

namespace blastsim::cip {

//! What the ghost fill needs besides the state: the boundary kinds, and for outflow sides the equation of
//! state and the reference state of the characteristic condition.
struct BoundaryContext {
  BoundaryConditions bc;
  GasMaterials mat;
  MaterialReadView materials;  //!< read in two-material runs only
  OutflowReference reference;
};

//! Outward-normal velocity of the outflow boundary face on `side` at row/column t, from the cell state of
//! s (cells b = boundary cell, bi = its inner neighbour; inner face fi). Shared by the fill and the step.
template <Access A>
BLAST_HD inline double outflow_face_from_state(const GasState<A>& s, const GasGrid& g, const BoundaryContext& ctx,
                                               int side, int t) {
  const bool xside = side == left || side == right;
  const bool low = side == left || side == bottom;
  const int n = xside ? g.nx : g.ny;
  const int b = low ? 0 : n - 1, bi = low ? 1 : n - 2, fi = low ? 1 : n - 1;
  const double sign = low ? -1.0 : 1.0;
  auto at = [&](const auto& F, int k) { return xside ? F(k, t) : F(t, k); };
  const double rho = at(s.rho.f, b), e = at(s.e.f, b);
  // Pressures and the boundary cell's sound speed, with the material fields in a two-material run.
  const PressureSound b_state = cell_pressure_and_sound_speed(ctx.mat, ctx.materials, rho, e, xside ? b : t, xside ? t : b);
  const double p_b = b_state.p;
  const double p_i = cell_pressure(ctx.mat, ctx.materials, at(s.rho.f, bi), at(s.e.f, bi), xside ? bi : t, xside ? t : bi);
  double p_face = 1.5 * p_b - 0.5 * p_i;
  if (!(p_face > 0.0)) p_face = p_b;
  const int r = side == left ? t : side == right ? g.ny + t : side == bottom ? 2 * g.ny + t : 2 * g.ny + g.nx + t;
  const access_field<double, A> w = xside ? s.u.f : s.v.f;
  return outflow_face_velocity(sign * at(w, fi), ctx.reference.velocity[r], p_face, ctx.reference.pressure[r], rho,
                               b_state.c);
}


// ---- the ghost fill (fill_ghosts(), fill_material_ghosts(): boundary.cpp) ----

namespace detail {

//! Applies the ghost rule to one CIP unknown at ghost index k along x (axis 0) or y (axis 1).
BLAST_HD inline void fill_one(const CipFieldView& F, int axis, int k, int t, int n, bool face_centred,
                              BoundaryKind kind, double parity) {
  const GhostSource s = ghost_source(k, n, face_centred, kind, parity);
  if (axis == 0) {
    F.f(k, t) = s.value_factor * F.f(s.source, t);
    F.gx(k, t) = s.normal_factor * F.gx(s.source, t);
    F.gy(k, t) = s.tangent_factor * F.gy(s.source, t);
  } else {
    F.f(t, k) = s.value_factor * F.f(t, s.source);
    F.gy(t, k) = s.normal_factor * F.gy(t, s.source);
    F.gx(t, k) = s.tangent_factor * F.gx(t, s.source);
  }
}

//! Does the ghost rule touch index k of a variable with this centring? Ghost indices always; the
//! boundary face itself only for a wall (normal velocity zero) or the far periodic face (copy of face 0).
BLAST_HD inline bool is_ghost(int k, int n, bool face_centred, BoundaryKind kind) {
  if (!face_centred) return k < 0 || k >= n;
  if (k < 0 || k > n) return true;
  if (kind == BoundaryKind::wall) return k == 0 || k == n;
  if (kind == BoundaryKind::periodic) return k == n;
  return false;
}

//! One thread per (ghost column, row): fills all four unknowns along x. Columns: -g..-1, 0 (boundary
//! face), nx..nx+g (nx is the first cell ghost and the last face).
//! Sets an outflow boundary face (value from outflow_face_from_state(), zero normal derivative).
BLAST_HD inline void set_outflow_face(const CipFieldView& F, const GasStateView& s, const GasGrid& g,
                                      const BoundaryContext& ctx, int side, int t) {
  const bool xside = side == left || side == right;
  const bool low = side == left || side == bottom;
  const int k = low ? 0 : (xside ? g.nx : g.ny), ki = low ? 1 : k - 1;
  const double w = (low ? -1.0 : 1.0) * outflow_face_from_state(s, g, ctx, side, t);
  if (xside) {
    F.f(k, t) = w;
    F.gx(k, t) = 0.0;
    F.gy(k, t) = F.gy(ki, t);
  } else {
    F.f(t, k) = w;
    F.gy(t, k) = 0.0;
    F.gx(t, k) = F.gx(t, ki);
  }
}

//! The outflow boundary faces go first: the ghost faces beyond them copy them.
struct FillOutflowFaces {
  GasStateView s;
  GasGrid grid;
  BoundaryContext ctx;
  BLAST_HD void operator()(index_t k) const {
    const int nx = grid.nx, ny = grid.ny;
    if (k < 2 * ny) {
      const int side = k < ny ? left : right, t = static_cast<int>(k < ny ? k : k - ny);
      if (t < ny && kind_of(ctx.bc, side) == BoundaryKind::outflow) set_outflow_face(s.u, s, grid, ctx, side, t);
    } else {
      const index_t m = k - 2 * ny;
      const int side = m < nx ? bottom : top, t = static_cast<int>(m < nx ? m : m - nx);
      if (kind_of(ctx.bc, side) == BoundaryKind::outflow) set_outflow_face(s.v, s, grid, ctx, side, t);
    }
  }
};

//! The ghosts of the state along Axis (0: x, over the logical rows, first; 1: y, over every padded column, so
//! that the corners follow from the x pass): `a` and `b` are (ghost index c, row t) along x and (column t, ghost
//! index c) along y, c in [0, 2 g + 2). The normal velocity (u along x, v along y) is face-centred and mirrored at
//! a wall; the density, the energy and the tangential velocity are cell-centred. Axis is a template parameter: a
//! run-time choice between the velocity fields would put the kernel's argument in local memory on the GPU
//! (docs/performance-gpu.md, "Local memory in the GPU kernels").
template <int Axis>
struct FillGhosts {
  GasStateView s;
  int n;                // cells along the axis
  BoundaryKind lo, hi;  // the boundaries at its low and high ends
  BLAST_HD void operator()(int a, int b) const {
    const int g = GasGrid::ghost;
    const int c = Axis == 0 ? a : b, t = Axis == 0 ? b : a;
    const int k = c < g + 1 ? c - g : n + (c - g - 1);
    const BoundaryKind kind = k <= 0 ? lo : hi;
    if (is_ghost(k, n, false, kind)) {
      fill_one(s.rho, Axis, k, t, n, false, kind, 1.0);
      fill_one(s.e, Axis, k, t, n, false, kind, 1.0);
      if constexpr (Axis == 0) fill_one(s.v, Axis, k, t, n, false, kind, 1.0);
      else fill_one(s.u, Axis, k, t, n, false, kind, 1.0);
    }
    if (is_ghost(k, n, true, kind)) {
      if constexpr (Axis == 0) fill_one(s.u, Axis, k, t, n, true, kind, -1.0);
      else fill_one(s.v, Axis, k, t, n, true, kind, -1.0);
    }
  }
};

//! Ghosts of the material fields (cell-centred values without derivatives) along x (axis 0) or y (axis 1):
//! c runs over the 2 g ghost indices, t over the rows (x pass) or every padded column (y pass).
struct FillMaterialGhosts {
  MaterialView m;
  int axis, n;
  BoundaryKind lo, hi;
  BLAST_HD void operator()(int c, int t) const {
    const int g = GasGrid::ghost;
    const int k = c < g ? c - g : n + (c - g);
    const GhostSource src = ghost_source(k, n, false, k < 0 ? lo : hi, 1.0);
    if (axis == 0) {
      m.alpha(k, t) = m.alpha(src.source, t);
      m.m1(k, t) = m.m1(src.source, t);
    } else {
      m.alpha(t, k) = m.alpha(t, src.source);
      m.m1(t, k) = m.m1(t, src.source);
    }
  }
};

}  // namespace detail

}  // namespace blastsim::cip
