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


//! Slope limiter (van Leer's monotonised-central bounds) on the CIP slope (derivative x spacing): where the
//! CIP slope has the sign of both one-sided differences, it is raised to at least the smaller difference (the
//! minmod slope: a CIP derivative that lags behind a steepening contact would smear it) and cut to at most
//! twice it; else zero.
BLAST_HD inline double limited_slope(double cip_slope, double left_diff, double right_diff) {
  if (left_diff * right_diff <= 0.0 || cip_slope * left_diff <= 0.0) return 0.0;
  const double small = min_of(fabs(left_diff), fabs(right_diff));
  const double m = min_of(max_of(fabs(cip_slope), small), 2.0 * small);
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
//! second difference where the data have an extremum (first differences change sign) with same-signed
//! second differences on both sides (a smooth extremum), zero otherwise (after the monotonicity-preserving
//! bounds of Suresh & Huynh, JCP 136 (1997) 83). Without the extremum test the corner of a step onto a
//! plateau passed as smooth and a density spike grew there (docs/gas-solver.md "Contacts").
BLAST_HD inline double extremum_slack(double f0, double f1, double f2, double f3, double fraction) {
  const double d0 = f1 - f0, d1 = f2 - f1, d2 = f3 - f2;
  // Only where the differences change sign (an extremum, not a plateau beside a jump) is there an extremum.
  const bool extremum = d0 * d1 < 0.0 || d1 * d2 < 0.0 || (d1 == 0.0 && d0 * d2 < 0.0);
  if (!extremum) return 0.0;
  const double a = d1 - d0, b = d2 - d1;
  return a * b <= 0.0 ? 0.0 : fraction * min_of(fabs(a), fabs(b));
}

//! swept_value() for variable F through the face between points a = (ia, ja) and a + 1 along axis
//! (0: x, 1: y); crossing velocity w, transverse velocity w_t; h, h_t the spacings along and across.
//! Minmax limiter: next to a smooth extremum (extremum_slack() > 0) the CIP slope is kept and the value
//! clipped to the range of the two points beside the face and the transverse upwind point, widened by
//! the slack (at most half the lower bound, so positive fields stay positive); elsewhere the slopes are
//! held within van Leer's monotonised-central bounds (limited_slope()). Jumps stay monotone, smooth
//! extrema keep second order. Fraction 0.2 measured: 0.1 costs order (1.93 on G4), 0.25 costs Sod's L1.
template <class Field>
BLAST_HD inline double swept_value_at(const Field& F, int axis, int ia, int ja, double w, double w_t,
                                      double dt, double h, double h_t, Limiter limiter) {
  const int di = axis == 0 ? 1 : 0, dj = 1 - di;
  const int ib = ia + di, jb = ja + dj;
  const int iu = w >= 0.0 ? ia : ib, ju = w >= 0.0 ? ja : jb;
  double g_n = axis == 0 ? F.gx(iu, ju) : F.gy(iu, ju);
  double g_t = axis == 0 ? F.gy(iu, ju) : F.gx(iu, ju);
  const auto f = [&F](int i, int j) { return F.value(i, j); };
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

//! A CIP field seen through value(i, j), gx(i, j), gy(i, j), the interface swept_value_at() reads.
struct CipValues {
  CipFieldReadView F;
  BLAST_HD double value(int i, int j) const { return F.f(i, j); }
  BLAST_HD double gx(int i, int j) const { return F.gx(i, j); }
  BLAST_HD double gy(int i, int j) const { return F.gy(i, j); }
};

//! Internal energy per unit volume rho e [J/m3] with its CIP derivatives from the product rule.
struct EnergyDensityValues {
  CipFieldReadView rho, e;
  BLAST_HD double value(int i, int j) const { return rho.f(i, j) * e.f(i, j); }
  BLAST_HD double gx(int i, int j) const { return e.f(i, j) * rho.gx(i, j) + rho.f(i, j) * e.gx(i, j); }
  BLAST_HD double gy(int i, int j) const { return e.f(i, j) * rho.gy(i, j) + rho.f(i, j) * e.gy(i, j); }
};

//! Slope-limited swept value of a cell quantity without CIP derivatives: the upwind value q_up plus van Leer's
//! monotonised-central slope of its two one-sided differences, over the region swept through the face. The
//! three values run along the flow: q_back upstream of the upwind cell, q_up, q_across beyond the face.
BLAST_HD inline double swept_mc(double q_back, double q_up, double q_across, double w, double dt, double h) {
  return q_up + mc_slope(q_up - q_back, q_across - q_up) * 0.5 * (h - fabs(w) * dt) / h;
}

//! What crosses a face in a two-material run, per unit face velocity: mixture density, products partial
//! density, internal energy per volume, the products volume fraction and the products' share of rho e.
struct MixtureFaceValues {
  double rho, m1, rho_e, alpha, rho_e1;
};

//! One cell's state as the two-material reconstruction sees it.
struct MixtureCell {
  double rho, e, alpha, m1;
};

//! The reconstructed variables of one cell: volume fraction, phase densities (0 where the phase is absent)
//! and pressure.
struct MixturePrimitives {
  double alpha, rho1, rho2, p;
  bool has1, has2;  // each phase present (its phase density defined)
};
BLAST_HD inline MixturePrimitives mixture_primitives(const GasMaterials& mat, const MixtureCell& c) {
  const double tiny = GasMaterials::kMinFraction;
  MixturePrimitives q;
  q.alpha = c.alpha;
  q.p = mat.pressure(c.rho, c.e, c.alpha, c.m1);
  q.has1 = c.alpha > tiny && c.m1 > 0.0;
  q.has2 = c.alpha < 1.0 - tiny && c.rho > c.m1;
  q.rho1 = c.alpha > tiny ? c.m1 / c.alpha : 0.0;
  q.rho2 = c.alpha < 1.0 - tiny ? (c.rho - c.m1) / (1.0 - c.alpha) : 0.0;
  return q;
}

//! Face values where products are near (docs/gas-solver.md, "Two materials"): the volume fraction alpha,
//! the phase densities rho1, rho2 and the pressure p are reconstructed (swept_mc()) and the conserved
//! quantities built from them, so that where p and the phase densities are uniform the fluxes of the partial
//! densities and of rho e are those of alpha alone: a material interface moving with uniform p and u keeps
//! them uniform (Abgrall, JCP 125 (1996) 150; Johnsen & Colonius, JCP 219 (2006) 715). The three cells run
//! along the flow: `back` upstream of the upwind cell `up`, `across` beyond the face; w the face velocity.
BLAST_HD inline MixtureFaceValues mixture_face_values(const GasMaterials& mat, const MixtureCell& back,
                                                      const MixtureCell& up, const MixtureCell& across, double w,
                                                      double dt, double h) {
  const MixturePrimitives b = mixture_primitives(mat, back), u = mixture_primitives(mat, up),
                          a = mixture_primitives(mat, across);
  const double a_f = swept_mc(b.alpha, u.alpha, a.alpha, w, dt, h);
  const double p_f = swept_mc(b.p, u.p, a.p, w, dt, h);
  // A phase missing in a neighbour has no phase density there: the upwind value alone.
  const double r1_f = b.has1 && u.has1 && a.has1 ? swept_mc(b.rho1, u.rho1, a.rho1, w, dt, h) : u.rho1;
  const double r2_f = b.has2 && u.has2 && a.has2 ? swept_mc(b.rho2, u.rho2, a.rho2, w, dt, h) : u.rho2;
  MixtureFaceValues v;
  v.alpha = a_f;
  v.m1 = a_f * r1_f;
  v.rho = v.m1 + (1.0 - a_f) * r2_f;
  v.rho_e = mat.energy_density(p_f, a_f, r1_f, r2_f);
  v.rho_e1 = mat.products_energy(p_f, a_f, v.m1);
  return v;
}

//! Mass and internal-energy fluxes [kg/(m2 s), J/(m2 s)] through x-faces (axis 0) or y-faces (axis 1).
//! Faces beside an inactive cell are closed. In a two-material run, faces with products among the four
//! cells along their normal take mixture_face_values() and also give the products mass flux, the volume
//! fraction flux w alpha^, the open-face velocity (for the alpha equation) and the products' internal-energy flux
//! (for the pressure relaxation, GasMaterials::relaxed_fraction()); elsewhere those are zero. In a
//! one-gas run with a tracer the traced gas's flux is the mass flux times the upwind cell's traced mass
//! fraction m1 / rho (first-order upwind: the fraction stays in [0, 1] wherever the mass does not empty a cell
//! in one step; docs/gas-solver.md "Tracer").
struct MassFluxKernel {
  int axis;
  GasStateReadView s;
  Field2D<const std::uint8_t> active;
  Field2D<double> mass_flux, energy_flux;
  double dt, h, h_t;
  Limiter limiter;
  GasMaterials mat;
  MaterialReadView materials;                      // read in two-material runs only
  Field2D<double> products_flux, alpha_flux, volume_flux;  // written in runs with products or a tracer only
  Field2D<double> products_energy_flux;                    // written in runs with products only
  BLAST_HD void operator()(int i, int j) const {
    const int im = axis == 0 ? i - 1 : i, jm = axis == 0 ? j : j - 1;
    if (!active(im, jm) || !active(i, j)) {
      mass_flux(i, j) = 0.0;
      energy_flux(i, j) = 0.0;
      if (mat.traced()) products_flux(i, j) = alpha_flux(i, j) = volume_flux(i, j) = 0.0;
      if (mat.two) products_energy_flux(i, j) = 0.0;
      return;
    }
    if (mat.two) {
      const double w = axis == 0 ? s.u.f(i, j) : s.v.f(i, j);
      const int di = axis == 0 ? 1 : 0, dj = 1 - di;
      // The four cells along the normal: c0 c1 | c2 c3, the face between c1 = (im, jm) and c2 = (i, j).
      auto cell = [&](int ci, int cj) {
        return MixtureCell{s.rho.f(ci, cj), s.e.f(ci, cj), materials.alpha(ci, cj), materials.m1(ci, cj)};
      };
      const MixtureCell c0 = cell(im - di, jm - dj), c1 = cell(im, jm), c2 = cell(i, j), c3 = cell(i + di, j + dj);
      volume_flux(i, j) = w;
      if (c0.alpha > 0.0 || c1.alpha > 0.0 || c2.alpha > 0.0 || c3.alpha > 0.0) {
        const bool forward = w >= 0.0;
        const MixtureFaceValues v =
            forward ? mixture_face_values(mat, c0, c1, c2, w, dt, h) : mixture_face_values(mat, c3, c2, c1, w, dt, h);
        mass_flux(i, j) = w * v.rho;
        energy_flux(i, j) = w * v.rho_e;
        products_flux(i, j) = w * v.m1;
        alpha_flux(i, j) = w * v.alpha;
        products_energy_flux(i, j) = w * v.rho_e1;
        return;
      }
      products_flux(i, j) = alpha_flux(i, j) = products_energy_flux(i, j) = 0.0;
    }
    const double w = axis == 0 ? s.u.f(i, j) : s.v.f(i, j);
    const Field2D<const double> t = axis == 0 ? s.v.f : s.u.f;  // transverse velocity, averaged to the face
    const double w_t = axis == 0 ? 0.25 * (t(im, j) + t(i, j) + t(im, j + 1) + t(i, j + 1))
                                 : 0.25 * (t(i, jm) + t(i, j) + t(i + 1, jm) + t(i + 1, j));
    mass_flux(i, j) = w * swept_value_at(CipValues{s.rho}, axis, im, jm, w, w_t, dt, h, h_t, limiter);
    energy_flux(i, j) = w * swept_value_at(EnergyDensityValues{s.rho, s.e}, axis, im, jm, w, w_t, dt, h, h_t, limiter);
    if (mat.tracer) {
      const int ui = w >= 0.0 ? im : i, uj = w >= 0.0 ? jm : j;
      products_flux(i, j) = mass_flux(i, j) * materials.m1(ui, uj) / s.rho.f(ui, uj);
    }
  }
};

//! Divergence of a face flux at cell (i, j): (F(i + 1, j) - F(i, j)) / dx + (G(i, j + 1) - G(i, j)) / dy, F on
//! x-faces, G on y-faces.
BLAST_HD inline double flux_divergence(const Field2D<const double>& F, const Field2D<const double>& G, int i, int j,
                                       double dx, double dy) {
  return (F(i + 1, j) - F(i, j)) / dx + (G(i, j + 1) - G(i, j)) / dy;
}

//! Index k of a cell row or column of n cells, wrapped into [0, n) when the boundary is periodic.
BLAST_HD inline int wrapped_index(int k, int n, bool periodic) {
  return periodic ? (k < 0 ? k + n : (k >= n ? k - n : k)) : k;
}

//! How many check-and-fall-back passes a step makes, and how far e may leave its neighbours' range, as a
//! fraction of their largest e (MOOD's relaxed maximum principle). Measured: on G4's smooth density wave
//! (orders 32 -> 64 -> 128 cells) and Sod's tube (G9, L1 order 200 -> 1600 cells): 1e-3: 2.09, 2.06 and 0.795;
//! 1e-4: 1.98, 2.06 and 0.854; 1e-5: 2.05, 2.43 and 0.865; 1e-6: 1.82, 2.04 and 0.869 (no check: 2.09, 2.06
//! and 0.806). 1e-5 keeps both G4 orders above 2.
inline constexpr int kTroubledPasses = 2;
inline constexpr double kTroubledRelax = 1e-5;

//! A posteriori check of the transport's high-order update (the "multi-dimensional optimal order detection" of
//! Clain, Diot & Loubere, JCP 230 (2011) 4028): cell (i, j) is troubled when the fluxes would leave it a
//! density or internal energy that is not positive, or a specific internal energy outside the range of the
//! active cells of its 3 x 3 block, widened by `relax` times the largest of them. Transport alone only moves gas about
//! (the compression work is done in the non-advection phase), so e after it should lie within its neighbours'
//! values; the limited swept values of rho and rho e are reconstructed independently (so that a contact keeps
//! its pressure) and at a sharp density minimum beside a jet they can drain a cell's mass and leave its
//! energy: e grew without bound (docs/gas-solver.md "Troubled cells"). Flags stay set within a step (the
//! block is checked again after its neighbours' faces changed). Runs with products are not checked (their
//! mixture energy is measured from each material's reference curve and is not bounded this way), nor the plain
//! scheme without limiter (Limiter::none).
struct TroubledCellKernel {
  GasStateReadView s;
  Field2D<const std::uint8_t> active;
  Field2D<const double> Fx, Fy, Ex, Ey;
  Field2D<std::uint8_t> troubled;
  double dt, dx, dy, relax;
  // After the first pass only a cell beside a flagged one can change (its other faces kept their fluxes, and
  // it passed the check with them): the others are skipped. Flags are read across a periodic wrap, as
  // DonorCellFluxKernel does.
  bool beside_flagged_only;
  int nx, ny;
  bool periodic_x, periodic_y;
  BLAST_HD void operator()(int i, int j) const {
    if (!active(i, j) || troubled(i, j)) return;
    if (beside_flagged_only) {
      const int il = wrapped_index(i - 1, nx, periodic_x), ir = wrapped_index(i + 1, nx, periodic_x);
      const int jb = wrapped_index(j - 1, ny, periodic_y), jt = wrapped_index(j + 1, ny, periodic_y);
      if (!troubled(il, j) && !troubled(ir, j) && !troubled(i, jb) && !troubled(i, jt)) return;
    }
    const double rho = s.rho.f(i, j) - dt * flux_divergence(Fx, Fy, i, j, dx, dy);
    const double E = s.rho.f(i, j) * s.e.f(i, j) - dt * flux_divergence(Ex, Ey, i, j, dx, dy);
    if (!(rho > 0.0) || !(E > 0.0)) {
      troubled(i, j) = 1;
      return;
    }
    // e outside its range over the block; then the density's discrete maximum principle, as MOOD checks it
    // (Clain, Diot and Loubere 2011, sec. 3). Transport does compress, so a shock can leave the density's
    // range and take donor-cell fluxes; what the density check catches is the contact that forms from a
    // Riemann problem with a density bump beside it (docs/gas-solver.md "Troubled cells", test G16).
    if (outside_block_range(s.e.f, E / rho, i, j) || outside_block_range(s.rho.f, rho, i, j)) troubled(i, j) = 1;
  }
  //! True when `candidate` lies outside the range of f over the active cells of the 3 x 3 block around (i, j),
  //! widened by `relax` of the largest value.
  template <class Field>
  BLAST_HD bool outside_block_range(const Field& f, double candidate, int i, int j) const {
    double lo = f(i, j), hi = lo;
    for (int b = -1; b <= 1; ++b)
      for (int a = -1; a <= 1; ++a)
        if (active(i + a, j + b)) lo = min_of(lo, f(i + a, j + b)), hi = max_of(hi, f(i + a, j + b));
    const double widen = relax * hi;
    return candidate < lo - widen || candidate > hi + widen;
  }
};

//! First-order upwind (donor-cell) fluxes through the faces of troubled cells (TroubledCellKernel): mass
//! w rho_up, internal energy w (rho e)_up and, with a tracer, the traced gas's share of the mass flux. A cell
//! whose faces all carry donor-cell fluxes gets a new e that is a mass-weighted mean of its own and its
//! upwind neighbours' values, positive while its outflow Courant numbers sum to less than one.
//! Axis 0: x-faces; 1: y-faces. With periodic boundaries the flags are read across the wrap, so that the two
//! copies of a boundary face agree.
struct DonorCellFluxKernel {
  int axis;
  GasStateReadView s;
  Field2D<const std::uint8_t> active, troubled;
  Field2D<double> mass_flux, energy_flux;
  bool tracer;
  MaterialReadView materials;
  Field2D<double> products_flux;
  int nx, ny;
  bool periodic;
  BLAST_HD void operator()(int i, int j) const {
    const int im = axis == 0 ? i - 1 : i, jm = axis == 0 ? j : j - 1;
    if (!active(im, jm) || !active(i, j)) return;
    const bool flagged = axis == 0 ? troubled(wrapped_index(im, nx, periodic), jm) || troubled(wrapped_index(i, nx, periodic), j)
                                   : troubled(im, wrapped_index(jm, ny, periodic)) || troubled(i, wrapped_index(j, ny, periodic));
    if (!flagged) return;
    const double w = axis == 0 ? s.u.f(i, j) : s.v.f(i, j);
    const int ui = w >= 0.0 ? im : i, uj = w >= 0.0 ? jm : j;
    const double rho = s.rho.f(ui, uj);
    mass_flux(i, j) = w * rho;
    energy_flux(i, j) = w * rho * s.e.f(ui, uj);
    if (tracer) products_flux(i, j) = mass_flux(i, j) * materials.m1(ui, uj) / rho;
  }
};

//! Cell update of mass and internal energy from the face fluxes; in a two-material run also the products'
//! partial density (flux form, conserved) and volume fraction: alpha_t + u . grad(alpha) = 0 as
//! alpha - dt (div(u alpha^) - alpha div(u)) with the same face values (alpha kept in [0, 1] against round-off),
//! and the products' internal energy per unit volume (flux form from the cell's equilibrium share at the start,
//! GasMaterials::products_energy(); read by the pressure relaxation in EnergyUpdateKernel); with a tracer the
//! traced gas's partial density (flux form).
struct CellFluxUpdateKernel {
  GasStateReadView s;
  GasStateView n;
  Field2D<const std::uint8_t> active;
  Field2D<const double> Fx, Fy, Ex, Ey;
  Field2D<double> rho_e;
  double dt, dx, dy;
  bool two, traced;                           // GasMaterials::two, GasMaterials::traced()
  MaterialView materials;                     // updated in place (runs with products or a tracer)
  Field2D<const double> Mx, My, Ax, Ay, Wx, Wy;  // products, alpha and volume fluxes
  GasMaterials mat;                              // read in two-material runs only
  Field2D<const double> Px, Py;                  // products' internal-energy fluxes (two-material runs)
  Field2D<double> products_energy;               // [J/m3] written in two-material runs
  BLAST_HD void operator()(int i, int j) const {
    const double rho = s.rho.f(i, j), e = s.e.f(i, j);
    if (!active(i, j)) {
      n.rho.f(i, j) = rho;
      rho_e(i, j) = rho * e;
      return;
    }
    n.rho.f(i, j) = rho - dt * flux_divergence(Fx, Fy, i, j, dx, dy);
    rho_e(i, j) = rho * e - dt * flux_divergence(Ex, Ey, i, j, dx, dy);
    if (!traced) return;
    const double m1 = materials.m1(i, j);
    materials.m1(i, j) = m1 - dt * ((Mx(i + 1, j) - Mx(i, j)) / dx + (My(i, j + 1) - My(i, j)) / dy);
    if (!two) return;
    const double a = materials.alpha(i, j);
    const double E1 = mat.air_only(a) ? 0.0 : mat.products_energy(mat.pressure(rho, e, a, m1), a, m1);
    products_energy(i, j) = E1 - dt * flux_divergence(Px, Py, i, j, dx, dy);
    const double div_a = (Ax(i + 1, j) - Ax(i, j)) / dx + (Ay(i, j + 1) - Ay(i, j)) / dy;
    const double div_u = (Wx(i + 1, j) - Wx(i, j)) / dx + (Wy(i, j + 1) - Wy(i, j)) / dy;
    const double a_new = a - dt * (div_a - a * div_u);
    materials.alpha(i, j) = a_new < 0.0 ? 0.0 : (a_new > 1.0 ? 1.0 : a_new);
  }
};

//! What one dual face of the face-velocity transport carries per unit area and time, over the dual cell's
//! width h: momentum (mass flux x swept value / h) and kinetic energy (mass flux x value^2 / 2 / h). A dual face
//! lies between two faces of the grid and belongs to both their dual cells.
struct DualFlux {
  double momentum, kinetic;
};

//! The dual faces of the face-velocity transport (axis 0: u on x-faces; axis 1: v on y-faces): along the axis
//! at cell centres, between faces (c, j) and (c + 1, j) for u; across it at cell corners, between faces (i, r - 1)
//! and (i, r) for u (transposed for v). Each is shared by two faces' dual cells, so its swept value can be
//! computed once (DualFluxKernel) or by each face (MomentumKernel without `shared`): the same arithmetic.
struct DualFaces {
  int axis;
  GasStateReadView s;
  Field2D<const double> Fx, Fy;
  int nx, ny;
  bool periodic_x, periodic_y;
  double dt, dx, dy;
  Limiter limiter;

  BLAST_HD int wx(int i) const { return periodic_x ? (i < 0 ? i + nx : (i >= nx ? i - nx : i)) : i; }
  BLAST_HD int wy(int j) const { return periodic_y ? (j < 0 ? j + ny : (j >= ny ? j - ny : j)) : j; }

  //! Mass flux [kg/(m2 s)] through the along dual face at (a, b): cell (c, j) for u, (i, c) for v.
  BLAST_HD double along_mass_flux(int a, int b) const {
    return axis == 0 ? 0.5 * (Fx(wx(a), b) + Fx(wx(a) + 1, b)) : 0.5 * (Fy(a, wy(b)) + Fy(a, wy(b) + 1));
  }
  //! Mass flux through the across dual face at (a, b): corner (i, r) for u, (r, j) for v.
  BLAST_HD double across_mass_flux(int a, int b) const {
    return axis == 0 ? 0.5 * (Fy(wx(a - 1), b) + Fy(a, b)) : 0.5 * (Fx(a, wy(b - 1)) + Fx(a, b));
  }
  //! Swept value of the face velocity through the along dual face at (a, b).
  BLAST_HD double along_value(int a, int b) const {
    const Field2D<const double>& u = s.u.f;
    const Field2D<const double>& v = s.v.f;
    if (axis == 0) {
      const double w = 0.5 * (u(a, b) + u(a + 1, b)), w_t = 0.5 * (v(a, b) + v(a, b + 1));
      return swept_value_at(CipValues{s.u}, 0, a, b, w, w_t, dt, dx, dy, limiter);
    }
    const double w = 0.5 * (v(a, b) + v(a, b + 1)), w_t = 0.5 * (u(a, b) + u(a + 1, b));
    return swept_value_at(CipValues{s.v}, 1, a, b, w, w_t, dt, dy, dx, limiter);
  }
  //! Swept value through the across dual face at (a, b).
  BLAST_HD double across_value(int a, int b) const {
    const Field2D<const double>& u = s.u.f;
    const Field2D<const double>& v = s.v.f;
    if (axis == 0) {
      const int ia = wx(a - 1);
      const double wc = 0.5 * (v(ia, b) + v(a, b)), wc_t = 0.5 * (u(a, b - 1) + u(a, b));
      return swept_value_at(CipValues{s.u}, 1, a, b - 1, wc, wc_t, dt, dy, dx, limiter);
    }
    const int ja = wy(b - 1);
    const double wc = 0.5 * (u(a, ja) + u(a, b)), wc_t = 0.5 * (v(a - 1, b) + v(a, b));
    return swept_value_at(CipValues{s.v}, 0, a - 1, b, wc, wc_t, dt, dx, dy, limiter);
  }
  //! Width of the dual cell along the dual face's normal: dx or dy.
  BLAST_HD double along_width() const { return axis == 0 ? dx : dy; }
  BLAST_HD double across_width() const { return axis == 0 ? dy : dx; }
  //! What a dual face carries (DualFlux); zero through one with no mass flux (inside the rock, where every face
  //! is closed), whose swept value is not computed. Half the faces of the single-hole grid are covered by rock.
  BLAST_HD DualFlux along(int a, int b) const { return carried(along_mass_flux(a, b), along_width(), [&] { return along_value(a, b); }); }
  BLAST_HD DualFlux across(int a, int b) const { return carried(across_mass_flux(a, b), across_width(), [&] { return across_value(a, b); }); }
  template <class Value>
  BLAST_HD static DualFlux carried(double mass_flux, double h, Value value) {
    if (mass_flux == 0.0) return {0.0, 0.0};
    const double q = value();
    return {mass_flux * q / h, mass_flux * 0.5 * q * q / h};
  }
};

//! The dual faces' fluxes of one axis computed once each (DualFaces::along() on `part` 0 over the cells (c, j) for
//! u, across() on part 1 over the corners), for MomentumKernel's `shared` path (docs/gas-solver.md, "One step").
struct DualFluxKernel {
  DualFaces d;
  int part;  // 0: along, 1: across
  Field2D<double> momentum, kinetic;
  BLAST_HD void operator()(int a, int b) const {
    const DualFlux f = part == 0 ? d.along(a, b) : d.across(a, b);
    momentum(a, b) = f.momentum;
    kinetic(a, b) = f.kinetic;
  }
};

//! The four shared dual-face flux arrays of one axis (DualFluxKernel's output; empty when each face computes its
//! own: `along_momentum.data` null).
struct SharedDualFluxes {
  Field2D<const double> along_momentum, along_kinetic, across_momentum, across_kinetic;
};

//! Momentum transport of one face velocity (axis 0: u on x-faces; axis 1: v on y-faces) over its dual cell,
//! and the kinetic energy it dissipates [J/m3]. `periodic_*`: index wrap of cells in x / y. The four dual faces'
//! fluxes come from `shared` when it has them (DualFluxKernel, computed once per dual face) or are computed
//! here (DualFaces): the same values either way, so the same bytes out.
struct MomentumKernel {
  DualFaces d;
  GasStateView n;
  Field2D<const std::uint8_t> prescribed;
  Field2D<const double> imposed;
  Field2D<double> dissipation;
  Field2D<double> solid_work;  // cumulative energy the solid gave this face's gas [J/m3]
  bool wall_low, wall_high;  // walls on the two sides normal to this face set
  SharedDualFluxes shared;

  BLAST_HD void operator()(int i, int j) const {
    const int axis = d.axis;
    const GasStateReadView& s = d.s;
    const double dt = d.dt;
    const CipFieldReadView V = axis == 0 ? s.u : s.v;
    const Field2D<double> out = axis == 0 ? n.u.f : n.v.f;
    // The two cells beside the face: (ia, ja) on the low side, (i, j) on the high side.
    const int ia = axis == 0 ? d.wx(i - 1) : i, ja = axis == 0 ? j : d.wy(j - 1);
    const double m_old = 0.5 * (s.rho.f(ia, ja) + s.rho.f(i, j));
    const double m_new = 0.5 * (n.rho.f(ia, ja) + n.rho.f(i, j));
    const double w0 = V.f(i, j);
    double flux = 0.0, ke_flux = 0.0;  // net outflow of momentum and of kinetic energy [per m3 and s]
    const bool have_shared = shared.along_momentum.data != nullptr;
    auto add = [&](double sign, double mass_flux, double h, const Field2D<const double>& mom,
                   const Field2D<const double>& ke, int a, int b, auto value) {
      if (mass_flux == 0.0) return;  // nothing carried (DualFaces::carried())
      const DualFlux f = have_shared ? DualFlux{mom(a, b), ke(a, b)} : DualFaces::carried(mass_flux, h, value);
      flux += sign * f.momentum;
      ke_flux += sign * f.kinetic;
    };
    for (int side = 0; side < 2; ++side) {
      const double sign = side == 0 ? -1.0 : 1.0;
      // Along the axis: the dual face at the centre of the cell on this side; across it: at the corners.
      const int ac = axis == 0 ? (side == 0 ? i - 1 : i) : i, bc = axis == 0 ? j : (side == 0 ? j - 1 : j);
      const int ar = axis == 0 ? i : (side == 0 ? i : i + 1), br = axis == 0 ? (side == 0 ? j : j + 1) : j;
      add(sign, d.along_mass_flux(ac, bc), d.along_width(), shared.along_momentum, shared.along_kinetic, ac, bc,
          [&] { return d.along_value(ac, bc); });
      add(sign, d.across_mass_flux(ar, br), d.across_width(), shared.across_momentum, shared.across_kinetic, ar, br,
          [&] { return d.across_value(ar, br); });
    }
    // A wall face stays at rest and an immersed (prescribed) face moves with the solid: the kinetic energy
    // carried into its dual cell that the face cannot keep becomes heat, as for any face. At a moving immersed
    // face the balance can come out negative (the solid accelerates the gas; the dual cell reaches into an
    // inactive cell whose ambient density does not follow the transport): that energy is not taken from the
    // gas's internal energy (beside a fast crack jet it drove a cold cell's negative) but counted as work of
    // the solid on the gas, summed in `solid_work` for the coupled budget (docs/gas-solver.md).
    const int k = axis == 0 ? i : j, n_cells = axis == 0 ? d.nx : d.ny;
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

//! Lowest pressure [Pa] the transport leaves in a cell with detonation products. Conservative transport of
//! the mixture's rho e next to alpha and m1 does not keep each material on its own curve: beside the contact
//! of products expanding into air (a decoupled charge), mixed cells were seen to lose more thermal energy
//! than any isentrope allows and reach negative pressures (docs/gas-solver.md, "Two materials"). Such a cell
//! gets the heat that lifts it to this pressure, counted in GasSolver::positivity_energy() like the bound below.
inline constexpr double kPressureFloor = 1.0;

//! Largest fraction of a cell's internal energy that the kinetic-energy correction may take in one step.
//! In a near-vacuum rarefaction (Toro's test 2) the faces beside an emptying cell gain more kinetic energy
//! from the momentum transport than they carried in, and the whole correction would leave the cell a
//! negative energy; what exceeds this fraction is not taken but counted as energy added to the gas.
inline constexpr double kMaxCorrectionFraction = 0.5;

//! Share of a face's kinetic-energy correction [J/m3 of its dual cell] that the cell of density rho_self
//! [kg/m3] beside the face takes, the cell across it holding rho_other: by mass, so that both cells gain the
//! same heat per kilogram, D / (rho_self + rho_other) for a correction D (the dual cell's mass is half of
//! each). The two shares of a face sum to one, so the correction is conserved; at equal densities each is
//! exactly 0.5. An equal split by volume would give a near-vacuum cell beside a dense jet as much heat as its
//! neighbour, and far more per kilogram (docs/gas-solver.md, "Troubled cells").
BLAST_HD inline double kinetic_heat_share(double rho_self, double rho_other) {
  return rho_self / (rho_self + rho_other);
}

//! Internal energy of a cell: flux-form rho e plus its share (kinetic_heat_share()) of the kinetic energy
//! dissipated on each of its four faces (all of it for a face on the outer boundary or next to an inactive
//! cell: no gas cell on the other side takes a share). A net loss is bounded by kMaxCorrectionFraction of the cell's thermal energy
//! rho e - sum_k alpha_k K_k(rho_k) = p xi >= 0 (GasMaterials: the energy above the materials' zero-pressure
//! curves; rho e itself for air), so the correction never drives the pressure negative; the part not taken is
//! summed in `added` [J/m3] (GasSolver::positivity_energy()).
//! In a two-material run a mixed cell then relaxes to one pressure (GasMaterials::relaxed_fraction()): the
//! products hold the internal energy the transport gave them (CellFluxUpdateKernel) plus their equilibrium share
//! alpha / (Gamma1 xi) of this kernel's change to rho e, the air the rest; only alpha changes.
struct EnergyUpdateKernel {
  GasStateView n;
  Field2D<const std::uint8_t> active;
  Field2D<const double> rho_e, Du, Dv;
  Field2D<double> added;
  int nx, ny;
  bool periodic_x, periodic_y;
  GasMaterials mat;
  MaterialView m;  // read when mat.two (alpha and m1 after this step's transport); alpha relaxed in place
  Field2D<const double> products_energy;  // [J/m3] after the transport (two-material runs)
  BLAST_HD void operator()(int i, int j) const {
    if (!active(i, j)) {
      n.e.f(i, j) = rho_e(i, j) / n.rho.f(i, j);
      return;
    }
    const int ir = periodic_x && i + 1 == nx ? 0 : i + 1;
    const int jt = periodic_y && j + 1 == ny ? 0 : j + 1;
    const int il = periodic_x && i == 0 ? nx - 1 : i - 1, jb = periodic_y && j == 0 ? ny - 1 : j - 1;
    const double r = n.rho.f(i, j);
    const double wl = (!periodic_x && i == 0) || !active(il, j) ? 1.0 : kinetic_heat_share(r, n.rho.f(il, j));
    const double wr = (!periodic_x && i + 1 == nx) || !active(ir, j) ? 1.0 : kinetic_heat_share(r, n.rho.f(ir, j));
    const double wb = (!periodic_y && j == 0) || !active(i, jb) ? 1.0 : kinetic_heat_share(r, n.rho.f(i, jb));
    const double wt = (!periodic_y && j + 1 == ny) || !active(i, jt) ? 1.0 : kinetic_heat_share(r, n.rho.f(i, jt));
    const double heat = wl * Du(i, j) + wr * Du(ir, j) + wb * Dv(i, j) + wt * Dv(i, jt);
    const bool mixed = mat.two && m.alpha(i, j) > GasMaterials::kMinFraction;
    const double offsets = mixed ? GasMaterials::offset(mat.products, m.alpha(i, j), m.m1(i, j)) +
                                       GasMaterials::offset(mat.air, 1.0 - m.alpha(i, j), n.rho.f(i, j) - m.m1(i, j))
                                 : 0.0;
    const double thermal = rho_e(i, j) - offsets;  // p xi [J/m3]
    const double floor = thermal > 0.0 ? -kMaxCorrectionFraction * thermal : (mat.two ? 0.0 : -INFINITY);
    if (heat < floor) added(i, j) += floor - heat;
    double energy = rho_e(i, j) + (heat < floor ? floor : heat);
    if (mixed) {  // products whose thermal energy the transport took below kPressureFloor (see there)
      const double xi = m.alpha(i, j) / mat.products.gruneisen() + (1.0 - m.alpha(i, j)) / mat.air.gruneisen();
      const double lack = xi * kPressureFloor - (energy - offsets);
      if (lack > 0.0) added(i, j) += lack, energy += lack;
      const double a = m.alpha(i, j), m1 = m.m1(i, j), m2 = n.rho.f(i, j) - m1;
      if (m1 > 0.0 && m2 > 0.0) {  // relaxed_fraction() leaves nearly pure cells alone
        const double E1 = products_energy(i, j) + a / (mat.products.gruneisen() * xi) * (energy - rho_e(i, j));
        m.alpha(i, j) = mat.relaxed_fraction(a, m1, m2, E1, energy - E1);
      }
    }
    n.e.f(i, j) = energy / n.rho.f(i, j);
  }
};

}  // namespace blastsim::cip
