//! \file muscl_hancock.hpp
//! \brief Reference scheme for the gas tests: 1-D second-order MUSCL-Hancock with minmod slopes and the HLLC flux
//! (Toro, Riemann Solvers and Numerical Methods for Fluid Dynamics, 3rd ed., sec. 14.4 and 10.4-10.6), ideal gas.
#pragma once

#include "exact_riemann.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace blastsim::test {

//! Conserved variables (rho, rho u, E) of one cell.
using Conserved = std::array<double, 3>;

class MusclHancock {
 public:
  //! n cells over [0, length], initial state L left of x0 and R right of it, transmissive ends.
  MusclHancock(int n, double length, double x0, Primitive L, Primitive R, double gamma)
      : n_(n), dx_(length / n), g_(gamma), U_(n + 4) {
    for (int i = 0; i < n; ++i) U_[i + 2] = conserved((i + 0.5) * dx_ < x0 ? L : R);
  }

  //! Advances to t_end with Courant number `courant` (time step from the largest |u| + c).
  void run_to(double t_end, double courant = 0.9) {
    while (t_ < t_end * (1 - 1e-12)) {
      fill_ghosts();
      double smax = 0;
      for (int i = 2; i < n_ + 2; ++i) {
        const Primitive w = primitive(U_[i]);
        smax = std::max(smax, std::fabs(w.u) + sound(w));
      }
      const double dt = std::min(courant * dx_ / smax, t_end - t_);
      step(dt);
      t_ += dt;
    }
  }

  //! Cell-averaged density of cell i.
  double density(int i) const { return U_[i + 2][0]; }
  //! Pressure [Pa] of cell i, from its conserved averages.
  double pressure(int i) const { return primitive(U_[i + 2]).p; }
  //! Specific internal energy [J/kg] of cell i, from its conserved averages.
  double internal_energy(int i) const {
    const Primitive w = primitive(U_[i + 2]);
    return w.p / ((g_ - 1) * w.rho);
  }

 private:
  Conserved conserved(const Primitive& w) const {
    return {w.rho, w.rho * w.u, w.p / (g_ - 1) + 0.5 * w.rho * w.u * w.u};
  }
  Primitive primitive(const Conserved& U) const {
    const double u = U[1] / U[0];
    return {U[0], u, (g_ - 1) * (U[2] - 0.5 * U[0] * u * u)};
  }
  double sound(const Primitive& w) const { return std::sqrt(g_ * w.p / w.rho); }
  Conserved flux(const Conserved& U) const {
    const Primitive w = primitive(U);
    return {U[1], U[1] * w.u + w.p, w.u * (U[2] + w.p)};
  }
  static double minmod(double a, double b) {
    if (a * b <= 0) return 0;
    return std::fabs(a) < std::fabs(b) ? a : b;
  }

  //! HLLC flux (Toro sec. 10.4) with the wave speeds of the pressure-based estimate (sec. 10.5.2).
  Conserved hllc(const Conserved& UL, const Conserved& UR) const {
    const Primitive L = primitive(UL), R = primitive(UR);
    const double cL = sound(L), cR = sound(R);
    const double rho_bar = 0.5 * (L.rho + R.rho), c_bar = 0.5 * (cL + cR);
    const double p_pvrs = 0.5 * (L.p + R.p) - 0.5 * (R.u - L.u) * rho_bar * c_bar;
    const double p_star = std::max(0.0, p_pvrs);
    auto q = [&](const Primitive& K) {
      return p_star <= K.p ? 1.0 : std::sqrt(1 + (g_ + 1) / (2 * g_) * (p_star / K.p - 1));
    };
    const double SL = L.u - cL * q(L), SR = R.u + cR * q(R);
    const double S_star = (R.p - L.p + L.rho * L.u * (SL - L.u) - R.rho * R.u * (SR - R.u)) /
                          (L.rho * (SL - L.u) - R.rho * (SR - R.u));
    if (SL >= 0) return flux(UL);
    if (SR <= 0) return flux(UR);
    auto star = [&](const Conserved& U, const Primitive& K, double S) {
      const double f = K.rho * (S - K.u) / (S - S_star);
      return Conserved{f, f * S_star,
                       f * (U[2] / K.rho + (S_star - K.u) * (S_star + K.p / (K.rho * (S - K.u))))};
    };
    const bool left = S_star >= 0;
    const Conserved& U = left ? UL : UR;
    const Primitive& K = left ? L : R;
    const double S = left ? SL : SR;
    const Conserved F = flux(U), Us = star(U, K, S);
    return {F[0] + S * (Us[0] - U[0]), F[1] + S * (Us[1] - U[1]), F[2] + S * (Us[2] - U[2])};
  }

  void fill_ghosts() {
    U_[0] = U_[1] = U_[2];
    U_[n_ + 2] = U_[n_ + 3] = U_[n_ + 1];
  }

  //! One MUSCL-Hancock step (Toro sec. 14.4.1): minmod slopes of the conserved variables, boundary values
  //! evolved by half a step with their own flux difference, HLLC fluxes between them.
  void step(double dt) {
    const int m = n_ + 4;
    std::vector<Conserved> left(m), right(m);  // evolved boundary-extrapolated values of each cell
    for (int i = 1; i < m - 1; ++i) {
      Conserved a, b;
      for (int k = 0; k < 3; ++k) {
        const double d = minmod(U_[i][k] - U_[i - 1][k], U_[i + 1][k] - U_[i][k]);
        a[k] = U_[i][k] - 0.5 * d;
        b[k] = U_[i][k] + 0.5 * d;
      }
      const Conserved Fa = flux(a), Fb = flux(b);
      for (int k = 0; k < 3; ++k) {
        const double c = 0.5 * dt / dx_ * (Fb[k] - Fa[k]);
        left[i][k] = a[k] - c;
        right[i][k] = b[k] - c;
      }
    }
    std::vector<Conserved> F(m);  // F[i]: flux through the face between cells i and i + 1
    for (int i = 1; i < m - 2; ++i) F[i] = hllc(right[i], left[i + 1]);
    for (int i = 2; i < n_ + 2; ++i)
      for (int k = 0; k < 3; ++k) U_[i][k] -= dt / dx_ * (F[i][k] - F[i - 1][k]);
  }

  int n_;
  double dx_, g_, t_ = 0;
  std::vector<Conserved> U_;  // two ghost cells at each end
};

}  // namespace blastsim::test
