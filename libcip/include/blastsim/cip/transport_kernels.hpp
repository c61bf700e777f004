//! \file transport_kernels.hpp
//! \brief Kernels of the flux-form transport phase of the gas step: mass, momentum and total energy conserved to round-off.
//!
//! Replaces the paper's non-conservative CIP advection of the values (not of the derivatives) when
//! GasSolverOptions::transport is Transport::conservative. After the non-advection phase (which leaves the
//! density alone) the values move in flux form, the remedy of the "exactly conservative" CIP family
//! (Tanaka, Nakamura & Yabe, CPC 126 (2000) 232; Yabe, Tanaka, Nakamura & Xiao, MWR 129 (2001) 332):
//! - mass: rho^{n+1} = rho* - dt div(F), F = u* rho^ through every face, rho^ the average of the upwind
//!   cell's linear profile over the region swept through the face, its slopes the CIP derivatives
//!   (limited as described at swept_value_at());
//! - internal energy: (rho e)^{n+1} = rho* e* - dt div(F e^), e^ likewise;
//! - momentum on the staggered faces: dual-cell masses m = (rho_{i-1} + rho_i)/2 and dual mass fluxes
//!   averaged from F, so (m u)^{n+1} = m^n u* - dt div(F_dual u^) and a uniform velocity stays uniform;
//! - total energy: the kinetic energy that the momentum transport removes from a face,
//!   D = (1/2 m^n u*^2 - dt div(F_dual u^2/2)) - 1/2 m^{n+1} (u^{n+1})^2, goes to the internal energy of the
//!   two cells beside it (half each), the staggered-grid kinetic-energy correction of Lagrange-remap codes.
//! With the time-centred pressure work of the non-advection phase (paper eq. 3) the sum of internal and
//! face kinetic energies changes only by what crosses the outer boundary.
#pragma once

#include "blastsim/cip/gas_state.hpp"
#include "blastsim/cip/gas_types.hpp"
#include "blastsim/core/macros.hpp"

#include <cmath>
#include <cstdint>

namespace blastsim::cip {


//! Slope limiter (van Leer's monotonised-central bounds) on the CIP slope (derivative x spacing): the CIP
//! slope where it has the sign of both one-sided differences, at most twice the smaller; else zero.
BLAST_HD inline double limited_slope(double cip_slope, double left_diff, double right_diff) {
  if (left_diff * right_diff <= 0.0 || cip_slope * left_diff <= 0.0) return 0.0;
  const double m = min_of(fabs(cip_slope), 2.0 * min_of(fabs(left_diff), fabs(right_diff)));
  return cip_slope > 0.0 ? m : -m;
}

//! Value carried through a face: the average, over the region swept through the face in dt, of the
//! upwind point's linear profile. Slopes: the CIP derivatives along (g_n) and across (g_t) the face, with
//! the minmax limiter bounded by limited_slope(). The region's centre lies (h - |w| dt)/2 upstream of the
//! face and w_t dt/2 upstream across it (the corner-transport term that keeps diagonal transport second
//! order).
BLAST_HD inline double swept_value(double f_up, double g_n, double g_t, double w, double w_t, double dt, double h) {
  return f_up + (w >= 0.0 ? 1.0 : -1.0) * g_n * 0.5 * (h - fabs(w) * dt) - g_t * 0.5 * w_t * dt;
}

//! Curvature allowance at a face between points 1 and 2 of f0 f1 | f2 f3: a fraction of the smaller
//! second difference when both have the same sign (a smooth extremum), zero otherwise (after the
//! monotonicity-preserving bounds of Suresh & Huynh, JCP 136 (1997) 83).
BLAST_HD inline double extremum_slack(double f0, double f1, double f2, double f3, double fraction) {
  const double a = f0 - 2.0 * f1 + f2, b = f1 - 2.0 * f2 + f3;
  return a * b <= 0.0 ? 0.0 : fraction * min_of(fabs(a), fabs(b));
}

//! swept_value() for variable F through the face between points a = (ia, ja) and a + 1 along axis
//! (0: x, 1: y); crossing velocity w, transverse velocity w_t; h, h_t the spacings along and across.
//! Minmax limiter: next to a smooth extremum (extremum_slack() > 0) the CIP slope is kept and the value
//! clipped to the range of the two points beside the face and the transverse upwind point, widened by
//! the slack (at most half the lower bound, so positive fields stay positive); elsewhere the slopes are
//! held within van Leer's monotonised-central bounds (limited_slope()). Jumps stay monotone, smooth
//! extrema keep second order. Fraction 0.2 measured: 0.1 costs order (1.93 on G4), 0.25 costs Sod's L1.
BLAST_HD inline double swept_value_at(const CipFieldReadView& F, int axis, int ia, int ja, double w, double w_t,
                                      double dt, double h, double h_t, Limiter limiter) {
  const int di = axis == 0 ? 1 : 0, dj = 1 - di;
  const int ib = ia + di, jb = ja + dj;
  const int iu = w >= 0.0 ? ia : ib, ju = w >= 0.0 ? ja : jb;
  double g_n = axis == 0 ? F.gx(iu, ju) : F.gy(iu, ju);
  double g_t = axis == 0 ? F.gy(iu, ju) : F.gx(iu, ju);
  const Field2D<const double>& f = F.f;
  if (limiter == Limiter::none) return swept_value(f(iu, ju), g_n, g_t, w, w_t, dt, h);
  double slack = extremum_slack(f(ia - di, ja - dj), f(ia, ja), f(ib, jb), f(ib + di, jb + dj), 0.2);
  const double c = f(iu, ju);
  if (slack == 0.0) g_n = limited_slope(g_n * h, c - f(iu - di, ju - dj), f(iu + di, ju + dj) - c) / h;
  g_t = limited_slope(g_t * h_t, c - f(iu - dj, ju - di), f(iu + dj, ju + di) - c) / h_t;
  const double v = swept_value(c, g_n, g_t, w, w_t, dt, h);
  if (slack == 0.0) return v;
  const int st = w_t >= 0.0 ? 1 : -1;
  const double f_t = f(iu - dj * st, ju - di * st);
  double lo = min_of(min_of(f(ia, ja), f(ib, jb)), f_t), hi = max_of(max_of(f(ia, ja), f(ib, jb)), f_t);
  if (lo > 0.0) slack = min_of(slack, 0.5 * lo);
  lo -= slack;
  hi += slack;
  return v < lo ? lo : (v > hi ? hi : v);
}

//! Mass and internal-energy fluxes [kg/(m2 s), J/(m2 s)] through x-faces (axis 0) or y-faces (axis 1).
//! Faces beside an inactive cell are closed.
struct MassFluxKernel {
  int axis;
  GasStateReadView s;
  Field2D<const std::uint8_t> active;
  Field2D<double> mass_flux, energy_flux;
  double dt, h, h_t;
  Limiter limiter;
  BLAST_HD void operator()(int i, int j) const {
    const int im = axis == 0 ? i - 1 : i, jm = axis == 0 ? j : j - 1;
    if (!active(im, jm) || !active(i, j)) {
      mass_flux(i, j) = 0.0;
      energy_flux(i, j) = 0.0;
      return;
    }
    const double w = axis == 0 ? s.u.f(i, j) : s.v.f(i, j);
    const Field2D<const double> t = axis == 0 ? s.v.f : s.u.f;  // transverse velocity, averaged to the face
    const double w_t = axis == 0 ? 0.25 * (t(im, j) + t(i, j) + t(im, j + 1) + t(i, j + 1))
                                 : 0.25 * (t(i, jm) + t(i, j) + t(i + 1, jm) + t(i + 1, j));
    const double F = w * swept_value_at(s.rho, axis, im, jm, w, w_t, dt, h, h_t, limiter);
    mass_flux(i, j) = F;
    energy_flux(i, j) = F * swept_value_at(s.e, axis, im, jm, w, w_t, dt, h, h_t, limiter);
  }
};

//! Cell update of mass and internal energy from the face fluxes.
struct CellFluxUpdateKernel {
  GasStateReadView s;
  GasStateView n;
  Field2D<const std::uint8_t> active;
  Field2D<const double> Fx, Fy, Ex, Ey;
  Field2D<double> rho_e;
  double dt, dx, dy;
  BLAST_HD void operator()(int i, int j) const {
    const double rho = s.rho.f(i, j), e = s.e.f(i, j);
    if (!active(i, j)) {
      n.rho.f(i, j) = rho;
      rho_e(i, j) = rho * e;
      return;
    }
    n.rho.f(i, j) = rho - dt * ((Fx(i + 1, j) - Fx(i, j)) / dx + (Fy(i, j + 1) - Fy(i, j)) / dy);
    rho_e(i, j) = rho * e - dt * ((Ex(i + 1, j) - Ex(i, j)) / dx + (Ey(i, j + 1) - Ey(i, j)) / dy);
  }
};

//! Momentum transport of one face velocity (axis 0: u on x-faces; axis 1: v on y-faces) over its dual cell,
//! and the kinetic energy it dissipates [J/m3]. `periodic_*`: index wrap of cells in x / y.
struct MomentumKernel {
  int axis;
  GasStateReadView s;
  GasStateView n;
  Field2D<const double> Fx, Fy;
  Field2D<const std::uint8_t> prescribed;
  Field2D<const double> imposed;
  Field2D<double> dissipation;
  Field2D<double> solid_work;  // cumulative energy the solid gave this face's gas [J/m3]
  int nx, ny;
  bool periodic_x, periodic_y;
  bool wall_low, wall_high;  // walls on the two sides normal to this face set
  double dt, dx, dy;
  Limiter limiter;

  BLAST_HD int wx(int i) const { return periodic_x ? (i < 0 ? i + nx : (i >= nx ? i - nx : i)) : i; }
  BLAST_HD int wy(int j) const { return periodic_y ? (j < 0 ? j + ny : (j >= ny ? j - ny : j)) : j; }

  BLAST_HD void operator()(int i, int j) const {
    const CipFieldReadView V = axis == 0 ? s.u : s.v;
    const Field2D<double> out = axis == 0 ? n.u.f : n.v.f;
    const Field2D<const double>& u = s.u.f;
    const Field2D<const double>& v = s.v.f;
    // The two cells beside the face: (ia, ja) on the low side, (i, j) on the high side.
    const int ia = axis == 0 ? wx(i - 1) : i, ja = axis == 0 ? j : wy(j - 1);
    const double m_old = 0.5 * (s.rho.f(ia, ja) + s.rho.f(i, j));
    const double m_new = 0.5 * (n.rho.f(ia, ja) + n.rho.f(i, j));
    const double w0 = V.f(i, j);
    double flux = 0.0, ke_flux = 0.0;  // net outflow of momentum and of kinetic energy [per m3 and s]
    // Through a dual face with no mass flux (inside the rock, where every face is closed) nothing is carried:
    // its swept value is not computed (mass_flux x value would add an exact zero). Half the faces of the
    // single-hole grid are covered by rock.
    auto add = [&](double sign, double mass_flux, double h, auto swept) {
      if (mass_flux == 0.0) return;
      const double value = swept();
      flux += sign * mass_flux * value / h;
      ke_flux += sign * mass_flux * 0.5 * value * value / h;
    };
    for (int side = 0; side < 2; ++side) {
      const double sign = side == 0 ? -1.0 : 1.0;
      if (axis == 0) {
        // Along x: dual face at the centre of cell c (c = i-1 or i), between x-faces c and c+1.
        const int c = side == 0 ? i - 1 : i;
        const double Fd = 0.5 * (Fx(wx(c), j) + Fx(wx(c) + 1, j));
        add(sign, Fd, dx, [&] {
          const double w = 0.5 * (u(c, j) + u(c + 1, j)), w_t = 0.5 * (v(c, j) + v(c, j + 1));
          return swept_value_at(V, 0, c, j, w, w_t, dt, dx, dy, limiter);
        });
        // Across (y): dual face at the corner on y-face row r = j or j+1, between u(i, r-1) and u(i, r).
        const int r = side == 0 ? j : j + 1;
        const double Fc = 0.5 * (Fy(ia, r) + Fy(i, r));
        add(sign, Fc, dy, [&] {
          const double wc = 0.5 * (v(ia, r) + v(i, r)), wc_t = 0.5 * (u(i, r - 1) + u(i, r));
          return swept_value_at(V, 1, i, r - 1, wc, wc_t, dt, dy, dx, limiter);
        });
      } else {
        const int c = side == 0 ? j - 1 : j;
        const double Fd = 0.5 * (Fy(i, wy(c)) + Fy(i, wy(c) + 1));
        add(sign, Fd, dy, [&] {
          const double w = 0.5 * (v(i, c) + v(i, c + 1)), w_t = 0.5 * (u(i, c) + u(i + 1, c));
          return swept_value_at(V, 1, i, c, w, w_t, dt, dy, dx, limiter);
        });
        const int r = side == 0 ? i : i + 1;
        const double Fc = 0.5 * (Fx(r, ja) + Fx(r, j));
        add(sign, Fc, dx, [&] {
          const double wc = 0.5 * (u(r, ja) + u(r, j)), wc_t = 0.5 * (v(r - 1, j) + v(r, j));
          return swept_value_at(V, 0, r - 1, j, wc, wc_t, dt, dx, dy, limiter);
        });
      }
    }
    // A wall face stays at rest and an immersed (prescribed) face moves with the solid: the kinetic energy
    // carried into its dual cell that the face cannot keep becomes heat, as for any face. At a moving immersed
    // face the balance can come out negative (the solid accelerates the gas; the dual cell reaches into an
    // inactive cell whose ambient density does not follow the transport): that energy is not taken from the
    // gas's internal energy (beside a fast crack jet it drove a cold cell's negative) but counted as work of
    // the solid on the gas, summed in `solid_work` for the coupled budget (docs/gas-solver.md).
    const int k = axis == 0 ? i : j, n_cells = axis == 0 ? nx : ny;
    const bool wall_face = (k == 0 && wall_low) || (k == n_cells && wall_high);
    const double w_new = prescribed(i, j) ? imposed(i, j) : (wall_face ? 0.0 : (m_old * w0 - dt * flux) / m_new);
    out(i, j) = w_new;
    const double balance = (0.5 * m_old * w0 * w0 - dt * ke_flux) - 0.5 * m_new * w_new * w_new;  // [J/m3]
    if (prescribed(i, j) && !wall_face && w_new != 0.0 && balance < 0) {  // a face at rest does no work
      dissipation(i, j) = 0.0;
      solid_work(i, j) -= balance;
    } else {
      dissipation(i, j) = balance;
    }
  }
};

//! Internal energy of a cell: flux-form rho e plus half the kinetic energy dissipated on each of its four
//! faces (all of it for a face on the outer boundary or next to an inactive cell: no gas cell on the other
//! side takes the other half).
struct EnergyUpdateKernel {
  GasStateView n;
  Field2D<const std::uint8_t> active;
  Field2D<const double> rho_e, Du, Dv;
  int nx, ny;
  bool periodic_x, periodic_y;
  BLAST_HD void operator()(int i, int j) const {
    if (!active(i, j)) {
      n.e.f(i, j) = rho_e(i, j) / n.rho.f(i, j);
      return;
    }
    const int ir = periodic_x && i + 1 == nx ? 0 : i + 1;
    const int jt = periodic_y && j + 1 == ny ? 0 : j + 1;
    const int il = periodic_x && i == 0 ? nx - 1 : i - 1, jb = periodic_y && j == 0 ? ny - 1 : j - 1;
    const double wl = (!periodic_x && i == 0) || !active(il, j) ? 1.0 : 0.5;
    const double wr = (!periodic_x && i + 1 == nx) || !active(ir, j) ? 1.0 : 0.5;
    const double wb = (!periodic_y && j == 0) || !active(i, jb) ? 1.0 : 0.5;
    const double wt = (!periodic_y && j + 1 == ny) || !active(i, jt) ? 1.0 : 0.5;
    const double heat = wl * Du(i, j) + wr * Du(ir, j) + wb * Dv(i, j) + wt * Dv(i, jt);
    n.e.f(i, j) = (rho_e(i, j) + heat) / n.rho.f(i, j);
  }
};

}  // namespace blastsim::cip
