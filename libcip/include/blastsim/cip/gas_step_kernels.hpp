//! \file gas_step_kernels.hpp
//! \brief The kernels of one CIP gas step (paper eqs. 1-5; Yabe & Aoki 1991; Yabe, Xiao & Utsumi 2001) as
//! functors over views: pressure with artificial viscosity, the non-advection phase, the derivative update,
//! CIP advection, and the reductions (signal rate, totals, boundary flow, samples). GasSolver::step() calls
//! them in order; tests call them on a few cells. Plain header: no backend dependency.
#pragma once

#include "blastsim/cip/boundary_kernels.hpp"
#include "blastsim/cip/cip_kernels.hpp"
#include "blastsim/cip/eos.hpp"
#include "blastsim/cip/gas_state.hpp"
#include "blastsim/cip/gas_types.hpp"
#include "blastsim/cip/grid.hpp"

#include <cmath>
#include <cstdint>

namespace blastsim::cip {


template <Access A>
BLAST_HD inline CipPoint load_point(const CipField<A>& F, int i, int j) { return {F.f(i, j), F.gx(i, j), F.gy(i, j)}; }
BLAST_HD inline void store_point(const CipFieldView& F, int i, int j, const CipPoint& p, bool derivatives_only = false) {
  if (!derivatives_only) F.f(i, j) = p.f;
  F.gx(i, j) = p.gx;
  F.gy(i, j) = p.gy;
}

//! P = p + q at the cell centres (paper eqs. 4-5), plus, with the pressure predictor (half_dt > 0), the
//! lagged-work term lagged_work_pressure(). Inactive cells get P = p.
struct PressureKernel {
  GasStateReadView s;
  MaterialReadView m;
  Field2D<const std::uint8_t> active;
  Field2D<double> P;
  GasMaterials mat;
  double c1, c2;
  double half_dt = 0;  //!< dt / 2 [s] with the pressure predictor, 0 without
  double dx = 1, dy = 1;
  BLAST_HD void operator()(int i, int j) const {
    const double rho = s.rho.f(i, j), e = s.e.f(i, j);
    const double du = s.u.f(i + 1, j) - s.u.f(i, j), dv = s.v.f(i, j + 1) - s.v.f(i, j);
    const double dU = du + dv;  // velocity_jump() of eq. (5)
    const PressureSound ps = cell_pressure_and_sound_speed(mat, m, rho, e, i, j);
    const bool on = active(i, j);
    const double q = on ? artificial_viscosity(rho, ps.c, dU, c1, c2) : 0.0;
    double Pij = ps.p + q;
    if (half_dt > 0 && on) {
      const double div = du / dx + dv / dy;
      Pij += lagged_work_pressure(mat.cell_gruneisen(mat.two ? m.alpha(i, j) : 0.0), ps.p, div, half_dt);
    }
    P(i, j) = Pij;
  }
};

//! P in the ghost cells next to the four sides (pressure_ghost()); k runs over 2 nx + 2 ny boundary cells.
struct PressureGhostKernel {
  Field2D<double> P;
  int nx, ny;
  BoundaryConditions bc;
  BLAST_HD void operator()(index_t k) const {
    if (k < 2 * ny) {  // left and right sides, row j
      const int j = static_cast<int>(k / 2);
      if (k % 2 == 0) P(-1, j) = pressure_ghost(bc.kind(left), P(0, j), P(nx - 1, j));
      else P(nx, j) = pressure_ghost(bc.kind(right), P(nx - 1, j), P(0, j));
    } else {  // bottom and top sides, column i
      const index_t m = k - 2 * ny;
      const int i = static_cast<int>(m / 2);
      if (m % 2 == 0) P(i, -1) = pressure_ghost(bc.kind(bottom), P(i, 0), P(i, ny - 1));
      else P(i, ny) = pressure_ghost(bc.kind(top), P(i, ny - 1), P(i, 0));
    }
  }
};

//! Non-advection phase for a face velocity (axis 0: u on x-faces, axis 1: v on y-faces):
//! u* = u - dt (P_i - P_{i-1}) / (dx (rho_{i-1} + rho_i)/2)   (paper eq. 2 without advection).
//! A prescribed face takes the solid's velocity; a face beside an inactive cell feels no pressure force;
//! an outflow boundary face follows the characteristic condition (outflow_face_velocity()).
struct FaceVelocityKernel {
  int axis;
  GasStateReadView old;
  Field2D<double> out;  // u* or v*
  Field2D<const double> rho, P;
  Field2D<const std::uint8_t> active, prescribed;
  Field2D<const double> imposed;
  GasGrid grid;
  BoundaryContext ctx;
  double dt;
  BLAST_HD void operator()(int i, int j) const {
    const int im = axis == 0 ? i - 1 : i, jm = axis == 0 ? j : j - 1;
    const int k = axis == 0 ? i : j, n = axis == 0 ? grid.nx : grid.ny, t = axis == 0 ? j : i;
    const double h = axis == 0 ? grid.dx : grid.dy;
    double w = axis == 0 ? old.u.f(i, j) : old.v.f(i, j);
    const int side = axis == 0 ? (k == 0 ? left : right) : (k == 0 ? bottom : top);
    if ((k == 0 || k == n) && kind_of(ctx.bc, side) == BoundaryKind::outflow) {
      w = (k == 0 ? -1.0 : 1.0) * outflow_face_from_state(old, grid, ctx, side, t);
    } else if (prescribed(i, j)) {
      w = imposed(i, j);
    } else if (active(im, jm) && active(i, j)) {
      w -= dt * (P(i, j) - P(im, jm)) / (h * 0.5 * (rho(im, jm) + rho(i, j)));
    }
    out(i, j) = w;
  }
};

//! Non-advection phase for cell quantities (paper eqs. 1 and 3 without advection):
//! rho* = rho - dt rho div(u^n);  e* = e - dt (P / rho) [div(u^n) + div(u*)] / 2.
struct CellNonAdvectionKernel {
  bool conservative;  // density changes only through the fluxes of the transport phase
  GasStateReadView s;
  Field2D<double> rho_out, e_out;
  Field2D<const double> us, vs, P;
  Field2D<const std::uint8_t> active;
  double dt, dx, dy;
  BLAST_HD void operator()(int i, int j) const {
    const double rho = s.rho.f(i, j), e = s.e.f(i, j);
    if (!active(i, j)) {
      rho_out(i, j) = rho;
      e_out(i, j) = e;
      return;
    }
    const double div_n = (s.u.f(i + 1, j) - s.u.f(i, j)) / dx + (s.v.f(i, j + 1) - s.v.f(i, j)) / dy;
    const double div_s = (us(i + 1, j) - us(i, j)) / dx + (vs(i, j + 1) - vs(i, j)) / dy;
    rho_out(i, j) = conservative ? rho : rho - dt * rho * div_n;
    e_out(i, j) = e - dt * (P(i, j) / rho) * 0.5 * (div_n + div_s);
  }
};

//! Derivative update after the non-advection phase (Yabe, Xiao & Utsumi 2001, sec. 4):
//!   gx* = gx + d(f* - f)/dx - dt (gx du/dx + gy dv/dx),  gy* = gy + d(f* - f)/dy - dt (gx du/dy + gy dv/dy),
//! with centred differences of the change and velocity gradients at the variable's own location.
BLAST_HD inline void update_derivatives(const CipFieldReadView& old, const CipFieldView& now, int i, int j, double dx,
                                        double dy, double dt, double ux, double uy, double vx, double vy) {
  const double dfx = ((now.f(i + 1, j) - old.f(i + 1, j)) - (now.f(i - 1, j) - old.f(i - 1, j))) / (2.0 * dx);
  const double dfy = ((now.f(i, j + 1) - old.f(i, j + 1)) - (now.f(i, j - 1) - old.f(i, j - 1))) / (2.0 * dy);
  const double gx = old.gx(i, j), gy = old.gy(i, j);
  now.gx(i, j) = gx + dfx - dt * (gx * ux + gy * vx);
  now.gy(i, j) = gy + dfy - dt * (gx * uy + gy * vy);
}

struct CellDerivativeKernel {
  GasStateReadView old;
  GasStateView now;
  Field2D<const std::uint8_t> active;
  double dt, dx, dy;
  BLAST_HD void operator()(int i, int j) const {
    if (!active(i, j)) {
      now.rho.gx(i, j) = old.rho.gx(i, j);
      now.rho.gy(i, j) = old.rho.gy(i, j);
      now.e.gx(i, j) = old.e.gx(i, j);
      now.e.gy(i, j) = old.e.gy(i, j);
      return;
    }
    const Field2D<double>& u = now.u.f;
    const Field2D<double>& v = now.v.f;
    const double ux = (u(i + 1, j) - u(i, j)) / dx;
    const double vy = (v(i, j + 1) - v(i, j)) / dy;
    const double vx = 0.5 * ((v(i + 1, j) + v(i + 1, j + 1)) - (v(i - 1, j) + v(i - 1, j + 1))) / (2.0 * dx);
    const double uy = 0.5 * ((u(i, j + 1) + u(i + 1, j + 1)) - (u(i, j - 1) + u(i + 1, j - 1))) / (2.0 * dy);
    update_derivatives(old.rho, now.rho, i, j, dx, dy, dt, ux, uy, vx, vy);
    update_derivatives(old.e, now.e, i, j, dx, dy, dt, ux, uy, vx, vy);
  }
};

//! Derivative update of a face velocity (axis 0: u at x-faces; axis 1: v at y-faces).
struct FaceDerivativeKernel {
  int axis;
  GasStateReadView old;
  GasStateView now;
  Field2D<const std::uint8_t> prescribed;
  double dt, dx, dy;
  BLAST_HD void operator()(int i, int j) const {
    const CipFieldReadView o = axis == 0 ? old.u : old.v;
    const CipFieldView n = axis == 0 ? now.u : now.v;
    if (prescribed(i, j)) {
      n.gx(i, j) = 0.0;
      n.gy(i, j) = 0.0;
      return;
    }
    const Field2D<double>& u = now.u.f;
    const Field2D<double>& v = now.v.f;
    double ux, uy, vx, vy;
    if (axis == 0) {  // at x-face (i, j), between cells i-1 and i
      ux = (u(i + 1, j) - u(i - 1, j)) / (2.0 * dx);
      uy = (u(i, j + 1) - u(i, j - 1)) / (2.0 * dy);
      vx = 0.5 * ((v(i, j) + v(i, j + 1)) - (v(i - 1, j) + v(i - 1, j + 1))) / dx;
      vy = 0.5 * ((v(i - 1, j + 1) - v(i - 1, j)) + (v(i, j + 1) - v(i, j))) / dy;
    } else {  // at y-face (i, j), between cells j-1 and j
      vy = (v(i, j + 1) - v(i, j - 1)) / (2.0 * dy);
      vx = (v(i + 1, j) - v(i - 1, j)) / (2.0 * dx);
      uy = 0.5 * ((u(i, j) + u(i + 1, j)) - (u(i, j - 1) + u(i + 1, j - 1))) / dy;
      ux = 0.5 * ((u(i + 1, j - 1) - u(i, j - 1)) + (u(i + 1, j) - u(i, j))) / dx;
    }
    update_derivatives(o, n, i, j, dx, dy, dt, ux, uy, vx, vy);
  }
};

//! Upwind geometry of one point: upwind indices, offsets D and departure shifts X = -u dt.
struct Upwind {
  int iu, ju;
  double Dx, Dy, X, Y;
};
BLAST_HD inline Upwind upwind(int i, int j, double uu, double vv, double dt, double dx, double dy) {
  const int sx = uu >= 0.0 ? 1 : -1;
  const int sy = vv >= 0.0 ? 1 : -1;
  return {i - sx, j - sy, -sx * dx, -sy * dy, -uu * dt, -vv * dt};
}

BLAST_HD inline CipPoint advect(const CipFieldReadView& F, int i, int j, const Upwind& w, Limiter limiter) {
  const UpwindBlock b{load_point(F, i, j), load_point(F, w.iu, j), load_point(F, i, w.ju), load_point(F, w.iu, w.ju)};
  return cip_advect_2d(b, w.Dx, w.Dy, w.X, w.Y, limiter);
}

//! Cell advection with an inactive upwind neighbour seen as a copy of the point itself (zero gradient).
BLAST_HD inline CipPoint advect_masked(const CipFieldReadView& F, int i, int j, const Upwind& w,
                                       Field2D<const std::uint8_t> active, Limiter limiter) {
  const CipPoint c = load_point(F, i, j);
  const CipPoint flat{c.f, 0.0, 0.0};
  const UpwindBlock b{c, active(w.iu, j) ? load_point(F, w.iu, j) : flat, active(i, w.ju) ? load_point(F, i, w.ju) : flat,
                      active(w.iu, w.ju) ? load_point(F, w.iu, w.ju) : flat};
  return cip_advect_2d(b, w.Dx, w.Dy, w.X, w.Y, limiter);
}

//! CIP advection of rho and e with the cell-centre velocity (average of the face velocities).
//! With derivatives_only (conservative transport) the values come from the flux form and only the
//! derivatives are advected here.
struct CellAdvectionKernel {
  GasStateReadView from;
  GasStateView to;
  Field2D<const std::uint8_t> active;
  double dt, dx, dy;
  Limiter limiter;
  bool derivatives_only;
  BLAST_HD void operator()(int i, int j) const {
    if (!active(i, j)) {
      store_point(to.rho, i, j, load_point(from.rho, i, j), derivatives_only);
      store_point(to.e, i, j, load_point(from.e, i, j), derivatives_only);
      return;
    }
    const double uc = 0.5 * (from.u.f(i, j) + from.u.f(i + 1, j));
    const double vc = 0.5 * (from.v.f(i, j) + from.v.f(i, j + 1));
    const Upwind w = upwind(i, j, uc, vc, dt, dx, dy);
    store_point(to.rho, i, j, advect_masked(from.rho, i, j, w, active, limiter), derivatives_only);
    store_point(to.e, i, j, advect_masked(from.e, i, j, w, active, limiter), derivatives_only);
  }
};

//! CIP advection of a face velocity with itself and the transverse velocity averaged from the four
//! nearest transverse faces (Yabe et al. 1991, staggered form).
struct FaceAdvectionKernel {
  int axis;
  GasStateReadView from;
  GasStateView to;
  Field2D<const std::uint8_t> prescribed;
  Field2D<const double> imposed;
  double dt, dx, dy;
  Limiter limiter;
  bool derivatives_only;
  BLAST_HD void operator()(int i, int j) const {
    const CipFieldReadView F = axis == 0 ? from.u : from.v;
    const CipFieldView T = axis == 0 ? to.u : to.v;
    if (prescribed(i, j)) {
      store_point(T, i, j, CipPoint{imposed(i, j), 0.0, 0.0}, derivatives_only);
      return;
    }
    double uu, vv;
    if (axis == 0) {
      uu = from.u.f(i, j);
      vv = 0.25 * (from.v.f(i - 1, j) + from.v.f(i, j) + from.v.f(i - 1, j + 1) + from.v.f(i, j + 1));
    } else {
      vv = from.v.f(i, j);
      uu = 0.25 * (from.u.f(i, j - 1) + from.u.f(i + 1, j - 1) + from.u.f(i, j) + from.u.f(i + 1, j));
    }
    store_point(T, i, j, advect(F, i, j, upwind(i, j, uu, vv, dt, dx, dy), limiter), derivatives_only);
  }
};


//! Initial derivatives of the four CIP unknowns from their values (mc_slope() in x and in y).
struct InitialDerivativesKernel {
  GasStateView s;
  double dx, dy;
  BLAST_HD void operator()(int i, int j) const {
    const CipFieldView* fields[4] = {&s.rho, &s.e, &s.u, &s.v};
    for (const CipFieldView* F : fields) {
      const Field2D<double>& f = F->f;
      F->gx(i, j) = mc_slope(f(i, j) - f(i - 1, j), f(i + 1, j) - f(i, j)) / dx;
      F->gy(i, j) = mc_slope(f(i, j) - f(i, j - 1), f(i, j + 1) - f(i, j)) / dy;
    }
  }
};

//! Signal rate max((|u_c| + c)/dx, (|v_c| + c)/dy) [1/s] of one cell; +inf for an invalid active cell.
struct SignalRate {
  GasStateReadView s;
  MaterialReadView m;
  Field2D<const std::uint8_t> active;
  GasMaterials mat;
  int nx;
  double dx, dy;
  BLAST_HD double operator()(index_t k) const {
    const int j = static_cast<int>(k / nx), i = static_cast<int>(k - static_cast<index_t>(j) * nx);
    if (!active(i, j)) return 0.0;
    const double rho = s.rho.f(i, j), e = s.e.f(i, j);
    const double uc = 0.5 * (s.u.f(i, j) + s.u.f(i + 1, j));
    const double vc = 0.5 * (s.v.f(i, j) + s.v.f(i, j + 1));
    const PressureSound ps = cell_pressure_and_sound_speed(mat, m, rho, e, i, j);
    const double c = ps.c;
    const double rx = (fabs(uc) + c) / dx, ry = (fabs(vc) + c) / dy;
    const double r = rx > ry ? rx : ry;
    // Products' internal energy may be negative (measured from the JWL reference curve): in a two-material
    // run the pressure must be positive instead.
    const bool positive = mat.two ? ps.p > 0.0 : e > 0.0;
    const bool ok = rho > 0.0 && positive && r < 1e300;  // false for NaN as well
    return ok ? r : INFINITY;
  }
};

//! Sums for GasTotals, reducible on the device.
struct TotalsSum {
  double m, mx, my, ei, ek, m1;
  BLAST_HD TotalsSum operator+(const TotalsSum& o) const {
    return {m + o.m, mx + o.mx, my + o.my, ei + o.ei, ek + o.ek, m1 + o.m1};
  }
};
struct TotalsOfCell {
  GasStateReadView s;
  MaterialReadView materials;
  bool traced;  // GasMaterials::traced(): m1 is summed
  Field2D<const std::uint8_t> active;
  int nx;
  double area;
  GasGrid g;
  CellRegion region;
  BLAST_HD TotalsSum operator()(index_t k) const {
    const int j = static_cast<int>(k / nx), i = static_cast<int>(k - static_cast<index_t>(j) * nx);
    if (!active(i, j) || !region.contains(g.cell_x(i), g.cell_y(j))) return {0, 0, 0, 0, 0, 0};
    const double m = s.rho.f(i, j) * area;
    // Momentum and kinetic energy live on the faces: each face carries the mass of its dual cell,
    // (rho_left + rho_right)/2 x area, and gives half of its share to each of its two cells.
    const Field2D<const double>& rho = s.rho.f;
    const double ul = s.u.f(i, j), ur = s.u.f(i + 1, j), vb = s.v.f(i, j), vt = s.v.f(i, j + 1);
    const double ml = 0.5 * (rho(i - 1, j) + rho(i, j)) * area, mr = 0.5 * (rho(i, j) + rho(i + 1, j)) * area;
    const double mb = 0.5 * (rho(i, j - 1) + rho(i, j)) * area, mt = 0.5 * (rho(i, j) + rho(i, j + 1)) * area;
    const double px = 0.5 * (ml * ul + mr * ur), py = 0.5 * (mb * vb + mt * vt);
    const double ke = 0.25 * (ml * ul * ul + mr * ur * ur + mb * vb * vb + mt * vt * vt);
    return {m, px, py, m * s.e.f(i, j), ke, traced ? materials.m1(i, j) * area : 0.0};
  }
};

//! Distance [m] from (cx, cy) of cell k's centre when the cell is active, holds at least min_fraction of the
//! traced gas (m1 / rho) at a pressure of at least min_pressure [Pa] and lies within max_radius; else 0.
struct TracedCellDistance {
  GasStateReadView s;
  MaterialReadView m;
  Field2D<const std::uint8_t> active;
  GasMaterials mat;
  GasGrid g;
  double cx, cy, min_fraction, min_pressure, max_radius;
  BLAST_HD double operator()(index_t k) const {
    const int j = static_cast<int>(k / g.nx), i = static_cast<int>(k - static_cast<index_t>(j) * g.nx);
    if (!active(i, j)) return 0.0;
    const double dx = g.cell_x(i) - cx, dy = g.cell_y(j) - cy, r = sqrt(dx * dx + dy * dy);
    const double rho = s.rho.f(i, j);
    if (!(r <= max_radius) || !(m.m1(i, j) >= min_fraction * rho)) return 0.0;
    return cell_pressure(mat, m, rho, s.e.f(i, j), i, j) >= min_pressure ? r : 0.0;
  }
};

//! Bilinear interpolation of a padded array whose point (i, j) sits at (x0 + i h_x, y0 + j h_y).
BLAST_HD inline double bilinear(Field2D<const double> F, double x0, double y0, double hx, double hy, int imax,
                                int jmax, double x, double y) {
  double sx = (x - x0) / hx, sy = (y - y0) / hy;
  int i = static_cast<int>(floor(sx)), j = static_cast<int>(floor(sy));
  i = i < -1 ? -1 : (i > imax ? imax : i);
  j = j < -1 ? -1 : (j > jmax ? jmax : j);
  sx -= i;
  sy -= j;
  return (1 - sx) * (1 - sy) * F(i, j) + sx * (1 - sy) * F(i + 1, j) + (1 - sx) * sy * F(i, j + 1) +
         sx * sy * F(i + 1, j + 1);
}

//! The points at which the gas is sampled and the samples (GasSolver::sample()).
#define BLASTSIM_GAS_SAMPLES(X)                                \
  X(double, xy, "x and y [m] of each point, two entries a point") \
  X(GasSample, out, "the sample at each point")
BLASTSIM_VIEW_GROUP(GasSamples, BLASTSIM_GAS_SAMPLES)

struct SampleKernel {
  GasStateReadView s;
  MaterialReadView m;
  GasGrid g;
  GasMaterials mat;
  GasSamples<Access::read_write> samples;  //!< reads xy; writes out
  BLAST_HD void operator()(index_t k) const {
    const double x = samples.xy[2 * k], y = samples.xy[2 * k + 1];
    const double xc = g.x_min + 0.5 * g.dx, yc = g.y_min + 0.5 * g.dy;
    Field2D<const double> rho{s.rho.f.data, s.rho.f.shape}, e{s.e.f.data, s.e.f.shape};
    Field2D<const double> u{s.u.f.data, s.u.f.shape}, v{s.v.f.data, s.v.f.shape};
    GasSample r;
    r.x = x;
    r.y = y;
    r.rho = bilinear(rho, xc, yc, g.dx, g.dy, g.nx - 1, g.ny - 1, x, y);
    r.e = bilinear(e, xc, yc, g.dx, g.dy, g.nx - 1, g.ny - 1, x, y);
    r.u = bilinear(u, g.x_min, yc, g.dx, g.dy, g.nx, g.ny - 1, x, y);
    r.v = bilinear(v, xc, g.y_min, g.dx, g.dy, g.nx - 1, g.ny, x, y);
    double m1 = 0.0;
    if (mat.traced()) {
      m1 = bilinear(m.m1, xc, yc, g.dx, g.dy, g.nx - 1, g.ny - 1, x, y);
      r.traced = m1 / r.rho;
    }
    if (mat.two) r.alpha = bilinear(m.alpha, xc, yc, g.dx, g.dy, g.nx - 1, g.ny - 1, x, y);
    r.p = mat.pressure(r.rho, r.e, r.alpha, m1);
    samples.out[k] = r;
  }
};

//! Flow through one boundary face per unit length and time: k runs over left rows, right rows, bottom
//! columns, top columns. Uses the state after the non-advection phase (face velocity u*, the boundary
//! cell's rho, e and P); with conservative transport the mass and internal-energy fluxes of the transport.
struct BoundaryFlowKernel {
  GasStateReadView s;
  Field2D<const double> P, Fx, Fy, Ex, Ey;
  Field2D<const double> Mx, My;  // traced mass fluxes (runs with products or a tracer; else unread)
  bool conservative, traced;
  GasGrid g;
  BoundaryConditions bc;
  BLAST_HD TotalsSum operator()(index_t k) const {
    const int nx = g.nx, ny = g.ny;
    const bool xside = k < 2 * ny;
    const bool low = xside ? k < ny : k - 2 * ny < nx;
    const int side = xside ? (low ? left : right) : (low ? bottom : top);
    if (kind_of(bc, side) == BoundaryKind::periodic) return {0, 0, 0, 0, 0, 0};  // what leaves comes back in
    const int t = static_cast<int>(xside ? (low ? k : k - ny) : (low ? k - 2 * ny : k - 2 * ny - nx));
    const int b = low ? 0 : (xside ? nx - 1 : ny - 1), f = low ? 0 : (xside ? nx : ny);
    const double sgn = low ? -1.0 : 1.0, len = xside ? g.dy : g.dx;
    const int ci = xside ? b : t, cj = xside ? t : b, fi = xside ? f : t, fj = xside ? t : f;
    const double w = sgn * (xside ? s.u.f(fi, fj) : s.v.f(fi, fj));  // outward normal velocity
    const double wt = xside ? 0.5 * (s.v.f(ci, cj) + s.v.f(ci, cj + 1)) : 0.5 * (s.u.f(ci, cj) + s.u.f(ci + 1, cj));
    double mass, internal, products = 0.0;
    if (traced) products = sgn * (xside ? Mx(fi, fj) : My(fi, fj));
    if (conservative) {
      mass = sgn * (xside ? Fx(fi, fj) : Fy(fi, fj));
      internal = sgn * (xside ? Ex(fi, fj) : Ey(fi, fj));
    } else {
      mass = s.rho.f(ci, cj) * w;
      internal = mass * s.e.f(ci, cj);
    }
    const double p = P(ci, cj);
    const double normal_momentum = mass * w + p, tangential_momentum = mass * wt;
    const double mx = xside ? sgn * normal_momentum : tangential_momentum;
    const double my = xside ? tangential_momentum : sgn * normal_momentum;
    const double energy = internal + mass * 0.5 * (w * w + wt * wt) + p * w;
    return {mass * len, mx * len, my * len, energy * len, 0.0, products * len};
  }
};

//! The outflow ledger: one record per boundary face (OutflowReference's order), checkpointed.
#define BLASTSIM_GAS_OUTFLOW_LEDGER(X) X(OutflowLedger, face, "what left through each boundary face since initialise()")
BLASTSIM_VIEW_GROUP(OutflowLedgers, BLASTSIM_GAS_OUTFLOW_LEDGER)

//! Boundary face k's outflow-ledger record as a TotalsSum term (GasSolver::boundary_outflow()).
struct OutflowLedgerTotals {
  OutflowLedgers<Access::read> ledger;
  BLAST_HD TotalsSum operator()(index_t k) const {
    const OutflowLedger& e = ledger.face[k];
    return TotalsSum{e.mass, e.momentum_x, e.momentum_y, e.energy, 0.0, e.products_mass};
  }
};

//! Entry k of a padded array, or the sum of two (a ledger's total over the padded shape; `b` without data: a alone).
struct PaddedEntries {
  Field2D<const double> a, b;
  BLAST_HD double operator()(index_t k) const { return b.data ? a.data[k] + b.data[k] : a.data[k]; }
};

//! Adds dt times what crosses boundary face k (BoundaryFlowKernel) to that face's outflow-ledger record: one
//! thread a face, so no atomics, and the ledger stays on the device.
struct OutflowLedgerKernel {
  BoundaryFlowKernel flow;
  OutflowLedgers<Access::read_write> ledger;
  double dt;
  BLAST_HD void operator()(index_t k) const {
    const TotalsSum f = flow(k);
    OutflowLedger& l = ledger.face[k];
    l.mass += dt * f.m;
    l.momentum_x += dt * f.mx;
    l.momentum_y += dt * f.my;
    l.energy += dt * f.ei;
    l.products_mass += dt * f.m1;
  }
};

}  // namespace blastsim::cip
