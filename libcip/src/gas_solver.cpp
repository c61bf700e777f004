//! \file gas_solver.cpp
//! \brief The CIP gas step (paper eqs. 1-5; Yabe & Aoki 1991; Yabe, Xiao & Utsumi 2001) as device kernels.
#include "blastsim/cip/gas_solver.hpp"

#include "blastsim/core/checkpoint.hpp"

#include "blastsim/core/error.hpp"
#include "ghosts.hpp"

#include <cmath>
#include <limits>
#include <sstream>

namespace blastsim::cip {

GasGrid GasGrid::from_box(int nx, int ny, double x0, double x1, double y0, double y1) {
  if (nx < 3 || ny < 3) throw InputError("gas grid needs at least 3 cells along x and y");
  if (!(x1 > x0) || !(y1 > y0)) throw InputError("gas grid box is empty (need x_max > x_min, y_max > y_min)");
  return GasGrid{nx, ny, x0, y0, (x1 - x0) / nx, (y1 - y0) / ny};
}

EquationOfState EquationOfState::ideal(double gamma) {
  if (!(gamma > 1.0) || !std::isfinite(gamma)) throw InputError("ideal-gas gamma must be > 1");
  return EquationOfState{EosKind::ideal_gas, gamma};
}

namespace detail {

BLAST_HD inline CipPoint load(const CipFieldView& F, int i, int j) { return {F.f(i, j), F.gx(i, j), F.gy(i, j)}; }
BLAST_HD inline void store(const CipFieldView& F, int i, int j, const CipPoint& p, bool derivatives_only = false) {
  if (!derivatives_only) F.f(i, j) = p.f;
  F.gx(i, j) = p.gx;
  F.gy(i, j) = p.gy;
}

//! P = p + q at the cell centres (paper eqs. 4-5). Inactive cells get q = 0.
struct PressureKernel {
  GasStateView s;
  Field2D<const std::uint8_t> active;
  Field2D<double> P;
  EquationOfState eos;
  double c1, c2;
  BLAST_HD void operator()(int i, int j) const {
    const double rho = s.rho.f(i, j), e = s.e.f(i, j);
    const double dU = velocity_jump(s.u.f(i, j), s.u.f(i + 1, j), s.v.f(i, j), s.v.f(i, j + 1));
    const double q = active(i, j) ? artificial_viscosity(rho, eos.sound_speed(rho, e), dU, c1, c2) : 0.0;
    P(i, j) = eos.pressure(rho, e) + q;
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
      if (k % 2 == 0) P(-1, j) = pressure_ghost(bc.side[left], P(0, j), P(nx - 1, j));
      else P(nx, j) = pressure_ghost(bc.side[right], P(nx - 1, j), P(0, j));
    } else {  // bottom and top sides, column i
      const index_t m = k - 2 * ny;
      const int i = static_cast<int>(m / 2);
      if (m % 2 == 0) P(i, -1) = pressure_ghost(bc.side[bottom], P(i, 0), P(i, ny - 1));
      else P(i, ny) = pressure_ghost(bc.side[top], P(i, ny - 1), P(i, 0));
    }
  }
};

//! Non-advection phase for a face velocity (axis 0: u on x-faces, axis 1: v on y-faces):
//! u* = u - dt (P_i - P_{i-1}) / (dx (rho_{i-1} + rho_i)/2)   (paper eq. 2 without advection).
//! A prescribed face takes the solid's velocity; a face beside an inactive cell feels no pressure force;
//! an outflow boundary face follows the characteristic condition (outflow_face_velocity()).
struct FaceVelocityKernel {
  int axis;
  GasStateView old;
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
  GasStateView s;
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
BLAST_HD inline void update_derivatives(const CipFieldView& old, const CipFieldView& now, int i, int j, double dx,
                                        double dy, double dt, double ux, double uy, double vx, double vy) {
  const double dfx = ((now.f(i + 1, j) - old.f(i + 1, j)) - (now.f(i - 1, j) - old.f(i - 1, j))) / (2.0 * dx);
  const double dfy = ((now.f(i, j + 1) - old.f(i, j + 1)) - (now.f(i, j - 1) - old.f(i, j - 1))) / (2.0 * dy);
  const double gx = old.gx(i, j), gy = old.gy(i, j);
  now.gx(i, j) = gx + dfx - dt * (gx * ux + gy * vx);
  now.gy(i, j) = gy + dfy - dt * (gx * uy + gy * vy);
}

struct CellDerivativeKernel {
  GasStateView old, now;
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
  GasStateView old, now;
  Field2D<const std::uint8_t> prescribed;
  double dt, dx, dy;
  BLAST_HD void operator()(int i, int j) const {
    const CipFieldView o = axis == 0 ? old.u : old.v;
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

BLAST_HD inline CipPoint advect(const CipFieldView& F, int i, int j, const Upwind& w, Limiter limiter) {
  const UpwindBlock b{load(F, i, j), load(F, w.iu, j), load(F, i, w.ju), load(F, w.iu, w.ju)};
  return cip_advect_2d(b, w.Dx, w.Dy, w.X, w.Y, limiter);
}

//! Cell advection with an inactive upwind neighbour seen as a copy of the point itself (zero gradient).
BLAST_HD inline CipPoint advect_masked(const CipFieldView& F, int i, int j, const Upwind& w,
                                       Field2D<const std::uint8_t> active, Limiter limiter) {
  const CipPoint c = load(F, i, j);
  const CipPoint flat{c.f, 0.0, 0.0};
  const UpwindBlock b{c, active(w.iu, j) ? load(F, w.iu, j) : flat, active(i, w.ju) ? load(F, i, w.ju) : flat,
                      active(w.iu, w.ju) ? load(F, w.iu, w.ju) : flat};
  return cip_advect_2d(b, w.Dx, w.Dy, w.X, w.Y, limiter);
}

//! CIP advection of rho and e with the cell-centre velocity (average of the face velocities).
//! With derivatives_only (conservative transport) the values come from the flux form and only the
//! derivatives are advected here.
struct CellAdvectionKernel {
  GasStateView from, to;
  Field2D<const std::uint8_t> active;
  double dt, dx, dy;
  Limiter limiter;
  bool derivatives_only;
  BLAST_HD void operator()(int i, int j) const {
    if (!active(i, j)) {
      store(to.rho, i, j, load(from.rho, i, j), derivatives_only);
      store(to.e, i, j, load(from.e, i, j), derivatives_only);
      return;
    }
    const double uc = 0.5 * (from.u.f(i, j) + from.u.f(i + 1, j));
    const double vc = 0.5 * (from.v.f(i, j) + from.v.f(i, j + 1));
    const Upwind w = upwind(i, j, uc, vc, dt, dx, dy);
    store(to.rho, i, j, advect_masked(from.rho, i, j, w, active, limiter), derivatives_only);
    store(to.e, i, j, advect_masked(from.e, i, j, w, active, limiter), derivatives_only);
  }
};

//! CIP advection of a face velocity with itself and the transverse velocity averaged from the four
//! nearest transverse faces (Yabe et al. 1991, staggered form).
struct FaceAdvectionKernel {
  int axis;
  GasStateView from, to;
  Field2D<const std::uint8_t> prescribed;
  Field2D<const double> imposed;
  double dt, dx, dy;
  Limiter limiter;
  bool derivatives_only;
  BLAST_HD void operator()(int i, int j) const {
    const CipFieldView F = axis == 0 ? from.u : from.v;
    const CipFieldView T = axis == 0 ? to.u : to.v;
    if (prescribed(i, j)) {
      store(T, i, j, CipPoint{imposed(i, j), 0.0, 0.0}, derivatives_only);
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
    store(T, i, j, advect(F, i, j, upwind(i, j, uu, vv, dt, dx, dy), limiter), derivatives_only);
  }
};

//! Monotonised-central slope (van Leer's MC limiter) from the left and right differences: the centred
//! difference where the data are smooth, zero at an extremum and next to a constant state.
BLAST_HD inline double mc_slope(double left_diff, double right_diff) {
  if (left_diff * right_diff <= 0.0) return 0.0;
  const double c = 0.5 * (left_diff + right_diff);
  const double m = 2.0 * (fabs(left_diff) < fabs(right_diff) ? left_diff : right_diff);
  return fabs(c) < fabs(m) ? c : m;
}

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
  GasStateView s;
  Field2D<const std::uint8_t> active;
  EquationOfState eos;
  int nx;
  double dx, dy;
  BLAST_HD double operator()(index_t k) const {
    const int j = static_cast<int>(k / nx), i = static_cast<int>(k - static_cast<index_t>(j) * nx);
    if (!active(i, j)) return 0.0;
    const double rho = s.rho.f(i, j), e = s.e.f(i, j);
    const double uc = 0.5 * (s.u.f(i, j) + s.u.f(i + 1, j));
    const double vc = 0.5 * (s.v.f(i, j) + s.v.f(i, j + 1));
    const double c = eos.sound_speed(rho, e);
    const double rx = (fabs(uc) + c) / dx, ry = (fabs(vc) + c) / dy;
    const double r = rx > ry ? rx : ry;
    const bool ok = rho > 0.0 && e > 0.0 && r < 1e300;  // false for NaN as well
    return ok ? r : INFINITY;
  }
};

//! Sums for GasTotals, reducible on the device.
struct TotalsSum {
  double m, mx, my, ei, ek;
  BLAST_HD TotalsSum operator+(const TotalsSum& o) const {
    return {m + o.m, mx + o.mx, my + o.my, ei + o.ei, ek + o.ek};
  }
};
struct TotalsOfCell {
  GasStateView s;
  Field2D<const std::uint8_t> active;
  int nx;
  double area;
  GasGrid g;
  CellRegion region;
  BLAST_HD TotalsSum operator()(index_t k) const {
    const int j = static_cast<int>(k / nx), i = static_cast<int>(k - static_cast<index_t>(j) * nx);
    if (!active(i, j) || !region.contains(g.cell_x(i), g.cell_y(j))) return {0, 0, 0, 0, 0};
    const double m = s.rho.f(i, j) * area;
    // Momentum and kinetic energy live on the faces: each face carries the mass of its dual cell,
    // (rho_left + rho_right)/2 x area, and gives half of its share to each of its two cells.
    const Field2D<double>& rho = s.rho.f;
    const double ul = s.u.f(i, j), ur = s.u.f(i + 1, j), vb = s.v.f(i, j), vt = s.v.f(i, j + 1);
    const double ml = 0.5 * (rho(i - 1, j) + rho(i, j)) * area, mr = 0.5 * (rho(i, j) + rho(i + 1, j)) * area;
    const double mb = 0.5 * (rho(i, j - 1) + rho(i, j)) * area, mt = 0.5 * (rho(i, j) + rho(i, j + 1)) * area;
    const double px = 0.5 * (ml * ul + mr * ur), py = 0.5 * (mb * vb + mt * vt);
    const double ke = 0.25 * (ml * ul * ul + mr * ur * ur + mb * vb * vb + mt * vt * vt);
    return {m, px, py, m * s.e.f(i, j), ke};
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

struct SampleKernel {
  GasStateView s;
  GasGrid g;
  EquationOfState eos;
  const double* xy;
  GasSample* out;
  BLAST_HD void operator()(index_t k) const {
    const double x = xy[2 * k], y = xy[2 * k + 1];
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
    r.p = eos.pressure(r.rho, r.e);
    out[k] = r;
  }
};

//! Flow through one boundary face per unit length and time: k runs over left rows, right rows, bottom
//! columns, top columns. Uses the state after the non-advection phase (face velocity u*, the boundary
//! cell's rho, e and P); with conservative transport the mass and internal-energy fluxes of the transport.
struct BoundaryFlowKernel {
  GasStateView s;
  Field2D<const double> P, Fx, Fy, Ex, Ey;
  bool conservative;
  GasGrid g;
  BoundaryConditions bc;
  BLAST_HD TotalsSum operator()(index_t k) const {
    const int nx = g.nx, ny = g.ny;
    const bool xside = k < 2 * ny;
    const bool low = xside ? k < ny : k - 2 * ny < nx;
    const int side = xside ? (low ? left : right) : (low ? bottom : top);
    if (kind_of(bc, side) == BoundaryKind::periodic) return {0, 0, 0, 0, 0};  // what leaves comes back in
    const int t = static_cast<int>(xside ? (low ? k : k - ny) : (low ? k - 2 * ny : k - 2 * ny - nx));
    const int b = low ? 0 : (xside ? nx - 1 : ny - 1), f = low ? 0 : (xside ? nx : ny);
    const double sgn = low ? -1.0 : 1.0, len = xside ? g.dy : g.dx;
    const int ci = xside ? b : t, cj = xside ? t : b, fi = xside ? f : t, fj = xside ? t : f;
    const double w = sgn * (xside ? s.u.f(fi, fj) : s.v.f(fi, fj));  // outward normal velocity
    const double wt = xside ? 0.5 * (s.v.f(ci, cj) + s.v.f(ci, cj + 1)) : 0.5 * (s.u.f(ci, cj) + s.u.f(ci + 1, cj));
    double mass, internal;
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
    return {mass * len, mx * len, my * len, energy * len, 0.0};
  }
};

}  // namespace detail

void GasSolver::accumulate_boundary_outflow(double dt) {
  const PaddedShape sh = grid_.padded_shape();
  const detail::TotalsSum f = reduce_sum(
      "cip.boundary_outflow", 2 * static_cast<index_t>(grid_.nx + grid_.ny), detail::TotalsSum{0, 0, 0, 0, 0},
      detail::BoundaryFlowKernel{starred_.view(sh), make_field_view(pressure_, sh), make_field_view(mass_flux_x_, sh),
                                 make_field_view(mass_flux_y_, sh), make_field_view(energy_flux_x_, sh),
                                 make_field_view(energy_flux_y_, sh), options_.transport == Transport::conservative,
                                 grid_, options_.boundaries});
  outflow_.mass += dt * f.m;
  outflow_.momentum_x += dt * f.mx;
  outflow_.momentum_y += dt * f.my;
  outflow_.energy += dt * f.ei;
}

GasSolver::GasSolver(const GasGrid& grid, const EquationOfState& eos, const GasSolverOptions& options)
    : grid_(grid), eos_(eos), options_(options) {
  if (grid.nx < 3 || grid.ny < 3) throw InputError("gas grid needs at least 3 cells along x and y");
  if (!(grid.dx > 0) || !(grid.dy > 0)) throw InputError("gas grid spacing must be positive");
  for (int a = 0; a < 2; ++a) {
    const bool lo = options.boundaries.side[2 * a] == BoundaryKind::periodic;
    const bool hi = options.boundaries.side[2 * a + 1] == BoundaryKind::periodic;
    if (lo != hi) throw InputError("a periodic boundary must be set on both opposite sides");
  }
  const index_t n = grid.padded_shape().size();
  state_.resize(n);
  starred_.resize(n);
  immersed_.resize(n);
  pressure_.assign(n, 0.0);
  for (DeviceVector<double>* w : {&mass_flux_x_, &mass_flux_y_, &energy_flux_x_, &energy_flux_y_,
                                 &internal_energy_density_, &dissipation_u_, &dissipation_v_, &solid_work_u_,
                                 &solid_work_v_})
    w->assign(n, 0.0);
  outflow_pressure_.assign(2 * static_cast<size_t>(grid.nx + grid.ny), 0.0);
  outflow_velocity_.assign(2 * static_cast<size_t>(grid.nx + grid.ny), 0.0);
}

void GasSolver::initialise(const std::function<GasPoint(double, double)>& state_at) {
  const PaddedShape sh = grid_.padded_shape();
  std::vector<double> rho(sh.size(), 0.0), e(sh.size(), 0.0), u(sh.size(), 0.0), v(sh.size(), 0.0);
  for (int j = 0; j <= grid_.ny; ++j) {
    for (int i = 0; i <= grid_.nx; ++i) {
      if (i < grid_.nx && j < grid_.ny) {
        const GasPoint c = state_at(grid_.cell_x(i), grid_.cell_y(j));
        rho[sh.offset(i, j)] = c.density;
        e[sh.offset(i, j)] = c.internal_energy;
      }
      if (j < grid_.ny) u[sh.offset(i, j)] = state_at(grid_.face_x(i), grid_.cell_y(j)).velocity_x;
      if (i < grid_.nx) v[sh.offset(i, j)] = state_at(grid_.cell_x(i), grid_.face_y(j)).velocity_y;
    }
  }
  // Reference state of the outflow faces (OutflowReference order): the initial boundary state.
  const int nx = grid_.nx, ny = grid_.ny;
  std::vector<double> p_ref(2 * static_cast<size_t>(nx + ny)), w_ref(p_ref.size());
  for (int j = 0; j < ny; ++j) {
    p_ref[j] = eos_.pressure(rho[sh.offset(0, j)], e[sh.offset(0, j)]);
    w_ref[j] = -u[sh.offset(0, j)];
    p_ref[ny + j] = eos_.pressure(rho[sh.offset(nx - 1, j)], e[sh.offset(nx - 1, j)]);
    w_ref[ny + j] = u[sh.offset(nx, j)];
  }
  for (int i = 0; i < nx; ++i) {
    p_ref[2 * ny + i] = eos_.pressure(rho[sh.offset(i, 0)], e[sh.offset(i, 0)]);
    w_ref[2 * ny + i] = -v[sh.offset(i, 0)];
    p_ref[2 * ny + nx + i] = eos_.pressure(rho[sh.offset(i, ny - 1)], e[sh.offset(i, ny - 1)]);
    w_ref[2 * ny + nx + i] = v[sh.offset(i, ny)];
  }
  copy_from_host(outflow_pressure_, p_ref);
  copy_from_host(outflow_velocity_, w_ref);
  state_.resize(sh.size());
  copy_from_host(state_.rho.f, rho);
  copy_from_host(state_.e.f, e);
  copy_from_host(state_.u.f, u);
  copy_from_host(state_.v.f, v);
  time_ = 0.0;
  steps_ = 0;
  outflow_ = BoundaryOutflow{};
  thrust::fill(thrust::device, solid_work_u_.begin(), solid_work_u_.end(), 0.0);
  thrust::fill(thrust::device, solid_work_v_.begin(), solid_work_v_.end(), 0.0);
  apply_boundaries();
  // Derivatives: zero in uniform regions and next to jumps between them (the paper's Table 1), centred
  // differences where the initial data are smooth (zero there would cost CIP its order of accuracy).
  for_each_cell("cip.initial_derivatives", 0, grid_.nx + 1, 0, grid_.ny + 1,
                detail::InitialDerivativesKernel{state(), grid_.dx, grid_.dy});
  apply_boundaries();
}

void GasSolver::apply_boundaries() { fill_ghosts(state(), grid_, boundary_context()); }

BoundaryContext GasSolver::boundary_context() const {
  return {options_.boundaries, eos_, {device_ptr(outflow_pressure_), device_ptr(outflow_velocity_)}};
}

double GasSolver::max_signal_rate() {
  const GasStateView s = state();
  const ImmersedBoundaryView ib = immersed_boundary();
  return reduce_max("cip.signal_rate", static_cast<index_t>(grid_.nx) * grid_.ny, 0.0,
                    detail::SignalRate{s, {ib.cell_active.data, ib.cell_active.shape}, eos_, grid_.nx, grid_.dx,
                                       grid_.dy});
}

StepViews GasSolver::step_views() {
  const ImmersedBoundaryView ib = immersed_boundary();
  return {state(), starred_.view(grid_.padded_shape()), ib.cell_active, ib.u_prescribed, ib.v_prescribed,
          ib.u_imposed, ib.v_imposed};
}

void GasSolver::step(double dt) {
  const GasGrid g = grid_;
  const PaddedShape sh = g.padded_shape();
  const StepViews v = step_views();
  const GasStateView& n = v.now;
  const GasStateView& s = v.starred;
  const auto& active = v.active;
  const auto &u_pres = v.u_prescribed, &v_pres = v.v_prescribed;
  const auto &u_imp = v.u_imposed, &v_imp = v.v_imposed;
  const Field2D<double> P = pressure_with_viscosity();
  const Field2D<const double> Pc{P.data, sh}, rho_n{n.rho.f.data, sh};
  const Field2D<const double> us{s.u.f.data, sh}, vs{s.v.f.data, sh};

  const BoundaryContext ctx = boundary_context();
  // 1. P = p + q (paper eqs. 4-5). The ghosts of the current state are valid: initialise(), the end of
  //    the previous step, or apply_boundaries() after an outside write to state() filled them.
  for_each_cell("cip.pressure", 0, g.nx, 0, g.ny,
                detail::PressureKernel{n, active, P, eos_, options_.viscosity.linear, options_.viscosity.quadratic});
  for_each_index("cip.pressure.ghosts", 2 * static_cast<index_t>(g.nx + g.ny),
                 detail::PressureGhostKernel{P, g.nx, g.ny, options_.boundaries});
  // 2. Non-advection phase: face velocities, then density and energy (paper eqs. 1-3).
  for_each_cell("cip.face_velocity.u", 0, g.nx + 1, 0, g.ny,
                detail::FaceVelocityKernel{0, n, s.u.f, rho_n, Pc, active, u_pres, u_imp, g, ctx, dt});
  for_each_cell("cip.face_velocity.v", 0, g.nx, 0, g.ny + 1,
                detail::FaceVelocityKernel{1, n, s.v.f, rho_n, Pc, active, v_pres, v_imp, g, ctx, dt});
  for_each_cell("cip.cell_nonadvection", 0, g.nx, 0, g.ny,
                detail::CellNonAdvectionKernel{options_.transport == Transport::conservative, n, s.rho.f, s.e.f, us, vs, Pc, active, dt, g.dx, g.dy});
  fill_ghosts(s, g, ctx);
  if (options_.transport == Transport::paper) accumulate_boundary_outflow(dt);
  // 3. Derivative update (Yabe, Xiao & Utsumi 2001).
  for_each_cell("cip.derivatives.cell", 0, g.nx, 0, g.ny, detail::CellDerivativeKernel{n, s, active, dt, g.dx, g.dy});
  for_each_cell("cip.derivatives.u", 0, g.nx + 1, 0, g.ny,
                detail::FaceDerivativeKernel{0, n, s, u_pres, dt, g.dx, g.dy});
  for_each_cell("cip.derivatives.v", 0, g.nx, 0, g.ny + 1,
                detail::FaceDerivativeKernel{1, n, s, v_pres, dt, g.dx, g.dy});
  fill_ghosts(s, g, ctx);
  // 4. Transport. Conservative: values in flux form (conservative_transport.cpp); the paper's: values by
  // CIP. Either way the derivatives are advected by CIP with the updated velocity.
  const bool conservative = options_.transport == Transport::conservative;
  if (conservative) {
    transport_conservatively(dt);
    accumulate_boundary_outflow(dt);
  }
  for_each_cell("cip.advection.cell", 0, g.nx, 0, g.ny,
                detail::CellAdvectionKernel{s, n, active, dt, g.dx, g.dy, options_.limiter, conservative});
  for_each_cell("cip.advection.u", 0, g.nx + 1, 0, g.ny,
                detail::FaceAdvectionKernel{0, s, n, u_pres, u_imp, dt, g.dx, g.dy, options_.limiter, conservative});
  for_each_cell("cip.advection.v", 0, g.nx, 0, g.ny + 1,
                detail::FaceAdvectionKernel{1, s, n, v_pres, v_imp, dt, g.dx, g.dy, options_.limiter, conservative});
  fill_ghosts(n, g, ctx);
  time_ += dt;
  ++steps_;
}

GasTotals GasSolver::totals(const CellRegion& region) {
  const ImmersedBoundaryView ib = immersed_boundary();
  const detail::TotalsSum t = reduce_sum(
      "cip.totals", static_cast<index_t>(grid_.nx) * grid_.ny, detail::TotalsSum{0, 0, 0, 0, 0},
      detail::TotalsOfCell{state(), {ib.cell_active.data, ib.cell_active.shape}, grid_.nx, grid_.cell_area(), grid_, region});
  GasTotals out;
  out.mass = t.m;
  out.momentum_x = t.mx;
  out.momentum_y = t.my;
  out.internal_energy = t.ei;
  out.kinetic_energy = t.ek;
  return out;
}

std::vector<GasSample> GasSolver::sample(const std::vector<std::array<double, 2>>& points) {
  if (points.empty()) return {};
  std::vector<double> xy(2 * points.size());
  for (size_t k = 0; k < points.size(); ++k) {
    xy[2 * k] = points[k][0];
    xy[2 * k + 1] = points[k][1];
  }
  DeviceVector<double> xy_d;
  copy_from_host(xy_d, xy);
  DeviceVector<GasSample> out_d(points.size());
  for_each_index("cip.sample", static_cast<index_t>(points.size()),
                 detail::SampleKernel{state(), grid_, eos_, device_ptr(xy_d), device_ptr(out_d)});
  return blastsim::to_host(out_d);
}

HostGasFields GasSolver::to_host() {
  const PaddedShape sh = grid_.padded_shape();
  const std::vector<double> rho = blastsim::to_host(state_.rho.f), e = blastsim::to_host(state_.e.f);
  const std::vector<double> u = blastsim::to_host(state_.u.f), v = blastsim::to_host(state_.v.f);
  const std::vector<std::uint8_t> active = blastsim::to_host(immersed_.cell_active);
  HostGasFields h;
  h.nx = grid_.nx;
  h.ny = grid_.ny;
  const size_t n = static_cast<size_t>(grid_.nx) * grid_.ny;
  h.rho.resize(n);
  h.e.resize(n);
  h.p.resize(n);
  h.u.resize(n);
  h.v.resize(n);
  h.active.resize(n);
  for (int j = 0; j < grid_.ny; ++j) {
    for (int i = 0; i < grid_.nx; ++i) {
      const size_t k = static_cast<size_t>(j) * grid_.nx + i;
      h.rho[k] = rho[sh.offset(i, j)];
      h.e[k] = e[sh.offset(i, j)];
      h.p[k] = eos_.pressure(h.rho[k], h.e[k]);
      h.u[k] = 0.5 * (u[sh.offset(i, j)] + u[sh.offset(i + 1, j)]);
      h.v[k] = 0.5 * (v[sh.offset(i, j)] + v[sh.offset(i, j + 1)]);
      h.active[k] = active[sh.offset(i, j)];
    }
  }
  return h;
}

std::string GasSolver::describe_invalid_cell() {
  const PaddedShape sh = grid_.padded_shape();
  const std::vector<double> rho = blastsim::to_host(state_.rho.f), e = blastsim::to_host(state_.e.f);
  const std::vector<double> u = blastsim::to_host(state_.u.f), v = blastsim::to_host(state_.v.f);
  const std::vector<std::uint8_t> active = blastsim::to_host(immersed_.cell_active);
  for (int j = 0; j < grid_.ny; ++j) {
    for (int i = 0; i < grid_.nx; ++i) {
      const index_t k = sh.offset(i, j);
      if (!active[k]) continue;
      const char* what = nullptr;
      double value = 0.0;
      if (!(rho[k] > 0.0) || !std::isfinite(rho[k])) what = "density", value = rho[k];
      else if (!(e[k] > 0.0) || !std::isfinite(e[k])) what = "internal energy", value = e[k];
      else if (!std::isfinite(u[k])) what = "x-velocity", value = u[k];
      else if (!std::isfinite(v[k])) what = "y-velocity", value = v[k];
      if (what) {
        std::ostringstream os;
        os << what << " = " << value << " in cell (" << i << ", " << j << ") at x = " << grid_.cell_x(i)
           << " m, y = " << grid_.cell_y(j) << " m";
        return os.str();
      }
    }
  }
  return "";
}

void mark_static_solid(GasSolver& solver, const std::function<bool(double, double)>& inside) {
  const GasGrid& g = solver.grid();
  const PaddedShape sh = g.padded_shape();
  std::vector<std::uint8_t> active(sh.size(), 1), up(sh.size(), 0), vp(sh.size(), 0);
  for (int j = 0; j <= g.ny; ++j) {
    for (int i = 0; i <= g.nx; ++i) {
      if (j < g.ny && inside(g.face_x(i), g.cell_y(j))) up[sh.offset(i, j)] = 1;
      if (i < g.nx && inside(g.cell_x(i), g.face_y(j))) vp[sh.offset(i, j)] = 1;
    }
  }
  for (int j = 0; j < g.ny; ++j) {
    for (int i = 0; i < g.nx; ++i) {
      const bool all = up[sh.offset(i, j)] && up[sh.offset(i + 1, j)] && vp[sh.offset(i, j)] && vp[sh.offset(i, j + 1)];
      if (all) active[sh.offset(i, j)] = 0;
    }
  }
  ImmersedBoundaryView ib = solver.immersed_boundary();
  thrust::copy(active.begin(), active.end(), thrust::device_pointer_cast(ib.cell_active.data));
  thrust::copy(up.begin(), up.end(), thrust::device_pointer_cast(ib.u_prescribed.data));
  thrust::copy(vp.begin(), vp.end(), thrust::device_pointer_cast(ib.v_prescribed.data));
  thrust::fill(thrust::device, thrust::device_pointer_cast(ib.u_imposed.data),
               thrust::device_pointer_cast(ib.u_imposed.data) + sh.size(), 0.0);
  thrust::fill(thrust::device, thrust::device_pointer_cast(ib.v_imposed.data),
               thrust::device_pointer_cast(ib.v_imposed.data) + sh.size(), 0.0);
}

namespace {
std::string fmt_shape_mismatch(const std::string& path, int nx, int ny, int gx, int gy) {
  return "checkpoint " + path + ": its grid is " + std::to_string(nx) + " x " + std::to_string(ny) + " cells, this case's " +
         std::to_string(gx) + " x " + std::to_string(gy);
}

//! The arrays of a checkpoint, in order (shared by writing and reading).
template <class State, class Immersed, class Fn>
void for_each_checkpoint_array(State& st, Immersed& ib, Fn&& fn) {
  const char* unknowns[4] = {"rho", "e", "u", "v"};
  const std::array<decltype(&st.rho), 4> fields{&st.rho, &st.e, &st.u, &st.v};
  for (int k = 0; k < 4; ++k) {
    fn(std::string("gas.") + unknowns[k] + ".f", fields[k]->f);
    fn(std::string("gas.") + unknowns[k] + ".gx", fields[k]->gx);
    fn(std::string("gas.") + unknowns[k] + ".gy", fields[k]->gy);
  }
  fn("gas.cell_active", ib.cell_active);
  fn("gas.u_prescribed", ib.u_prescribed);
  fn("gas.v_prescribed", ib.v_prescribed);
  fn("gas.u_imposed", ib.u_imposed);
  fn("gas.v_imposed", ib.v_imposed);
}
}  // namespace

void GasSolver::write_checkpoint(CheckpointWriter& w) const {
  w.value("gas.shape", std::array<int, 2>{grid_.nx, grid_.ny});
  for_each_checkpoint_array(state_, immersed_, [&](const std::string& name, const auto& v) { w.array(name, v); });
  w.array("gas.outflow_pressure", outflow_pressure_);
  w.array("gas.outflow_velocity", outflow_velocity_);
  w.value("gas.time", time_);
  w.value("gas.steps", steps_);
  w.value("gas.outflow", outflow_);
  w.array("gas.solid_work_u", solid_work_u_);
  w.array("gas.solid_work_v", solid_work_v_);
}

double GasSolver::immersed_face_work() {
  const double* wu = device_ptr(solid_work_u_);
  const double* wv = device_ptr(solid_work_v_);
  return grid_.dx * grid_.dy *
         reduce_sum("cip.solid_work", static_cast<index_t>(solid_work_u_.size()), 0.0,
                    [=] BLAST_HD(index_t k) { return wu[k] + wv[k]; });
}

void GasSolver::read_checkpoint(CheckpointReader& r) {
  const std::array<int, 2> shape = r.value<std::array<int, 2>>("gas.shape");
  if (shape[0] != grid_.nx || shape[1] != grid_.ny)
    throw InputError(fmt_shape_mismatch(r.path(), shape[0], shape[1], grid_.nx, grid_.ny));
  const std::size_t n = static_cast<std::size_t>(grid_.padded_shape().size());
  for_each_checkpoint_array(state_, immersed_, [&](const std::string& name, auto& v) { r.array(name, v, n); });
  r.array("gas.outflow_pressure", outflow_pressure_, outflow_pressure_.size());
  r.array("gas.outflow_velocity", outflow_velocity_, outflow_velocity_.size());
  time_ = r.value<double>("gas.time");
  steps_ = r.value<long long>("gas.steps");
  outflow_ = r.value<BoundaryOutflow>("gas.outflow");
  r.array("gas.solid_work_u", solid_work_u_, n);
  r.array("gas.solid_work_v", solid_work_v_, n);
}

}  // namespace blastsim::cip
