//! \file boundary_kernels.hpp
//! \brief Device-side boundary helpers of the gas step: what the ghost fill and the outflow faces need
//! (BoundaryContext) and the characteristic outflow face velocity from a cell state.
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

}  // namespace blastsim::cip
