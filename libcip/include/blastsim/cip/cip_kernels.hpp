//! \file cip_kernels.hpp
//! \brief Point formulas of the CIP gas solver (interpolation, artificial viscosity), callable from kernels and tests.
#pragma once

#include "blastsim/core/macros.hpp"

#include <cmath>

namespace blastsim::cip {

//! Guard against over- and undershoots of the cubic next to jumps.
enum class Limiter {
  none,    //!< plain cubic CIP (the paper's scheme; overshoots about 5 % at a jump)
  minmax,  //!< where the cubic leaves the range of its upwind points, fall back to (bi)linear interpolation
};

//! A value with its two spatial derivatives, the unknowns CIP carries at every point.
struct CipPoint {
  double f;   //!< value
  double gx;  //!< df/dx
  double gy;  //!< df/dy
};

//! 1-D CIP (Yabe & Aoki 1991, eq. 10-12): cubic Hermite through the point i and its upwind neighbour,
//! shifted by xi = -u dt. D = -sign(u) dx is the offset of the upwind point. Returns {f, g, 0}.
BLAST_HD inline CipPoint cip_advect_1d(double f_i, double g_i, double f_up, double g_up, double D, double xi,
                                       Limiter limiter) {
  const double a = (g_i + g_up) / (D * D) + 2.0 * (f_i - f_up) / (D * D * D);
  const double b = 3.0 * (f_up - f_i) / (D * D) - (2.0 * g_i + g_up) / D;
  double f = ((a * xi + b) * xi + g_i) * xi + f_i;
  double g = (3.0 * a * xi + 2.0 * b) * xi + g_i;
  if (limiter == Limiter::minmax) {
    const double lo = f_i < f_up ? f_i : f_up;
    const double hi = f_i < f_up ? f_up : f_i;
    if (!(f >= lo && f <= hi)) {
      const double s = xi / D;  // in [0, 1]: fraction of the way to the upwind point
      f = (1.0 - s) * f_i + s * f_up;
      g = (f_up - f_i) / D;
    }
  }
  return {f, g, 0.0};
}

//! The 2 x 2 upwind block of a point for 2-D CIP: the point itself (i), its upwind neighbours in x (xu),
//! in y (yu) and diagonally (xyu).
struct UpwindBlock {
  CipPoint i, xu, yu, xyu;
};

//! 2-D unsplit cubic CIP (Yabe, Ishikawa, Wang et al., CPC 66 (1991) 233, type-A cubic with ten
//! coefficients; coefficients in docs/gas-solver.md, "2-D CIP interpolation"). Dx = -sign(u) dx, Dy = -sign(v) dy are the offsets of
//! the upwind points, X = -u dt, Y = -v dt the departure point. With Limiter::minmax, a cubic value outside
//! [min, max] of the four block values is replaced by the bilinear interpolant and its gradient, which
//! keeps positive fields positive.
BLAST_HD inline CipPoint cip_advect_2d(const UpwindBlock& b, double Dx, double Dy, double X, double Y,
                                       Limiter limiter) {
  const double Dx2 = Dx * Dx, Dy2 = Dy * Dy;
  const double c30 = (b.i.gx + b.xu.gx) / Dx2 + 2.0 * (b.i.f - b.xu.f) / (Dx2 * Dx);
  const double c20 = 3.0 * (b.xu.f - b.i.f) / Dx2 - (2.0 * b.i.gx + b.xu.gx) / Dx;
  const double c03 = (b.i.gy + b.yu.gy) / Dy2 + 2.0 * (b.i.f - b.yu.f) / (Dy2 * Dy);
  const double c02 = 3.0 * (b.yu.f - b.i.f) / Dy2 - (2.0 * b.i.gy + b.yu.gy) / Dy;
  const double t = b.i.f - b.xu.f - b.yu.f + b.xyu.f;
  const double c21 = (t - (b.yu.gx - b.i.gx) * Dx) / (Dx2 * Dy);
  const double c12 = (t - (b.xu.gy - b.i.gy) * Dy) / (Dx * Dy2);
  const double c11 = (b.xu.gy - b.i.gy) / Dx - c21 * Dx;

  CipPoint out;
  out.f = ((c30 * X + c21 * Y + c20) * X + c11 * Y + b.i.gx) * X + ((c03 * Y + c12 * X + c02) * Y + b.i.gy) * Y +
          b.i.f;
  out.gx = (3.0 * c30 * X + 2.0 * (c21 * Y + c20)) * X + (c12 * Y + c11) * Y + b.i.gx;
  out.gy = (3.0 * c03 * Y + 2.0 * (c12 * X + c02)) * Y + (c21 * X + c11) * X + b.i.gy;

  if (limiter == Limiter::minmax) {
    const double lo = min_of(min_of(b.i.f, b.xu.f), min_of(b.yu.f, b.xyu.f));
    const double hi = max_of(max_of(b.i.f, b.xu.f), max_of(b.yu.f, b.xyu.f));
    if (!(out.f >= lo && out.f <= hi)) {
      const double sx = X / Dx, sy = Y / Dy;  // both in [0, 1] under the Courant condition
      out.f = (1.0 - sx) * (1.0 - sy) * b.i.f + sx * (1.0 - sy) * b.xu.f + (1.0 - sx) * sy * b.yu.f +
              sx * sy * b.xyu.f;
      out.gx = ((1.0 - sy) * (b.xu.f - b.i.f) + sy * (b.xyu.f - b.yu.f)) / Dx;
      out.gy = ((1.0 - sx) * (b.yu.f - b.i.f) + sx * (b.xyu.f - b.xu.f)) / Dy;
    }
  }
  return out;
}

//! Monotonised-central slope (van Leer's MC limiter) from the left and right differences: the centred
//! difference where the data are smooth, zero at an extremum and next to a constant state.
BLAST_HD inline double mc_slope(double left_diff, double right_diff) {
  if (left_diff * right_diff <= 0.0) return 0.0;
  const double c = 0.5 * (left_diff + right_diff);
  const double m = 2.0 * (fabs(left_diff) < fabs(right_diff) ? left_diff : right_diff);
  return fabs(c) < fabs(m) ? c : m;
}

//! Artificial viscosity, paper eq. (4) after Caramana, Shashkov & Whalen (JCP 144, 1998):
//! q = c1 rho c_s |dU| + c2 rho dU^2 in compression (dU < 0), else 0. dU [m/s] is the undivided velocity
//! difference across the cell, eq. (5). Returns [Pa].
BLAST_HD inline double artificial_viscosity(double density, double sound_speed, double dU, double c1, double c2) {
  return dU < 0.0 ? density * (c1 * sound_speed * (-dU) + c2 * dU * dU) : 0.0;
}

//! The pressure predictor's term [Pa]: -(dt/2) Gamma p div(u^n). The conservative step moves the density and
//! rho e with the new face velocities u* but does the pressure work with the mean of div(u^n) and div(u*)
//! (which keeps internal plus kinetic energy exact); the part of the work done with the old velocity lags by
//! half a step and makes the scheme amplify sound: the amplification matrix of a wave of discrete number k' has
//! the determinant 1 + w (c dt k')^2, w = Gamma p / (2 rho c^2), so its amplitude grows by about w (c dt k')^2 / 2
//! a step (docs/gas-solver.md "Time centring of the pressure"). The same pressure taken that half step
//! ahead for this part, in the momentum and the work alike, cancels the amplification exactly for linear sound
//! and leaves the energy identity as it was. gamma_g: Gruneisen coefficient d p / d(rho e) [-]; div [1/s].
BLAST_HD inline double lagged_work_pressure(double gamma_g, double p, double div, double half_dt) {
  return -half_dt * gamma_g * p * div;
}

//! Undivided velocity difference of eq. (5): u(i+1/2) - u(i-1/2) + v(j+1/2) - v(j-1/2) [m/s].
BLAST_HD inline double velocity_jump(double u_left, double u_right, double v_bottom, double v_top) {
  return (u_right - u_left) + (v_top - v_bottom);
}

}  // namespace blastsim::cip
