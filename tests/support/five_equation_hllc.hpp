//! \file five_equation_hllc.hpp
//! \brief Reference scheme for the two-material gas tests: 1-D MUSCL-Hancock with minmod slopes and the HLLC flux for
//! Kapila's five-equation model of two materials in pressure equilibrium, each on its own equation of state.
//!
//! The model (Kapila, Menikoff, Bdzil, Son & Stewart, Phys. Fluids 13 (2001) 3002, eqs. 4.3-4.7): partial densities
//! m1 = a1 rho1, m2 = a2 rho2, momentum rho u and total energy E in conservation form, and the products' volume
//! fraction a1 by
//!   a1_t + u a1_x = K u_x,   K = a1 a2 (rho2 c2^2 - rho1 c1^2) / (a1 rho2 c2^2 + a2 rho1 c1^2),
//! the term that keeps each material on its own isentrope where the flow is smooth. The mixture closes with one
//! pressure (cip::GasMaterials::pressure(), the mixture rule of Allaire, Clerc & Kokh, JCP 181 (2002) 577).
//! Discretisation: the MUSCL-Hancock step of Toro (Riemann Solvers and Numerical Methods for Fluid Dynamics, 3rd ed.,
//! sec. 14.4) with minmod slopes of (m1, m2, u, p, a1); HLLC fluxes (sec. 10.4) with Davis's wave-speed bounds; the
//! volume fraction carried as in Johnsen & Colonius (JCP 219 (2006) 715): the face value upwind of the contact,
//! times the face velocity, and the source (a1 + K) times the difference of the face velocities. Nothing of
//! blastsim's transport is used; only its equations of state. Transmissive ends. Volume fractions start at eps and
//! 1 - eps (eps = 1e-8) instead of 0 and 1, the absent material at the other side's density.
#pragma once

#include "blastsim/cip/eos.hpp"
#include "exact_riemann.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <vector>

namespace blastsim::test {

class FiveEquationHllc {
 public:
  //! n cells over [0, length]: products (state L, volume fraction 1 - eps) left of x0 and air (state R, eps)
  //! right of it, or the other way round with products_right.
  FiveEquationHllc(int n, double length, double x0, Primitive L, Primitive R, const cip::GasMaterials& mat,
                   bool products_right = false)
      : n_(n), dx_(length / n), mat_(mat), U_(n + 4) {
    const double eps = 1e-8;
    const Primitive& P = products_right ? R : L;  // the products' state
    const Primitive& A = products_right ? L : R;  // the air's
    for (int i = 0; i < n; ++i) {
      const bool left = (i + 0.5) * dx_ < x0;
      const bool products = left != products_right;
      const Primitive& w = left ? L : R;
      const double a1 = products ? 1 - eps : eps;
      U_[i + 2] = conserved({a1 * P.rho, (1 - a1) * A.rho, w.u, w.p, a1});
    }
  }

  //! Advances to t_end with Courant number `courant` (time step from the largest |u| + c).
  void run_to(double t_end, double courant = 0.8) {
    while (t_ < t_end * (1 - 1e-12)) {
      fill_ghosts();
      double smax = 0;
      for (int i = 2; i < n_ + 2; ++i) {
        const State w = primitive(U_[i]);
        smax = std::max(smax, std::fabs(w.u) + sound(w));
      }
      if (!(smax > 0) || !std::isfinite(smax)) throw std::runtime_error("FiveEquationHllc: no real sound speed");
      const double dt = std::min(courant * dx_ / smax, t_end - t_);
      step(dt);
      t_ += dt;
    }
  }

  //! Mixture density [kg/m3], pressure [Pa], products volume fraction and partial density of cell i.
  double density(int i) const { return U_[i + 2][0] + U_[i + 2][1]; }
  double pressure(int i) const { return primitive(U_[i + 2]).p; }
  double alpha(int i) const { return U_[i + 2][4]; }
  double m1(int i) const { return U_[i + 2][0]; }

 private:
  //! Cell unknowns: m1, m2, rho u, E (conserved) and a1.
  using Vars = std::array<double, 5>;
  //! Primitive state: m1, m2, u, p, a1.
  struct State {
    double m1, m2, u, p, a1;
    double rho() const { return m1 + m2; }
  };
  //! The variables the slopes limit, in order.
  static constexpr double State::*kLimited[5] = {&State::m1, &State::m2, &State::u, &State::p, &State::a1};

  Vars conserved(const State& w) const {
    const double rho = w.rho();
    const double rhoe = mat_.energy_density(w.p, w.a1, w.m1 / w.a1, w.m2 / (1 - w.a1));
    return {w.m1, w.m2, rho * w.u, rhoe + 0.5 * rho * w.u * w.u, w.a1};
  }
  State primitive(const Vars& U) const {
    const double rho = U[0] + U[1], u = U[2] / rho;
    const double e = (U[3] - 0.5 * rho * u * u) / rho;
    return {U[0], U[1], u, mat_.pressure(rho, e, U[4], U[0]), U[4]};
  }
  //! The mixture sound speed of the pressure-equilibrium closure (cip::GasMaterials::mixture_sound_speed()): at
  //! least Wood's speed of Kapila's model, so a safe bound for the HLLC wave speeds and the time step.
  double sound(const State& w) const { return mat_.mixture_sound_speed(w.rho(), w.a1, w.m1, w.p); }
  //! Kapila's K of the volume-fraction equation (phase sound speeds at the common pressure).
  double kapila_k(const State& w) const {
    const double a1 = w.a1, a2 = 1 - a1, r1 = w.m1 / a1, r2 = w.m2 / a2;
    const double c1 = mat_.products.sound_speed(r1, mat_.products.internal_energy(r1, w.p));
    const double c2 = mat_.air.sound_speed(r2, mat_.air.internal_energy(r2, w.p));
    const double z1 = r1 * c1 * c1, z2 = r2 * c2 * c2;
    if (!std::isfinite(z1) || !std::isfinite(z2)) return 0.0;
    return a1 * a2 * (z2 - z1) / (a1 * z2 + a2 * z1);
  }
  //! Physical flux of the conserved part (the last entry, a1 u, serves the half step's volume fraction only).
  Vars flux(const Vars& U, const State& w) const {
    return {w.m1 * w.u, w.m2 * w.u, U[2] * w.u + w.p, w.u * (U[3] + w.p), 0.0};
  }
  static double minmod(double a, double b) {
    if (a * b <= 0) return 0;
    return std::fabs(a) < std::fabs(b) ? a : b;
  }

  //! HLLC flux between boundary values UL | UR (Toro sec. 10.4, Davis's bounds, eq. 10.48), with the face velocity
  //! u_face [m/s] and the volume fraction a_face carried through the face.
  struct Face {
    Vars F;
    double u_face, a_face;
  };
  Face hllc(const Vars& UL, const Vars& UR) const {
    const State L = primitive(UL), R = primitive(UR);
    const double cL = sound(L), cR = sound(R), rL = L.rho(), rR = R.rho();
    const double SL = std::min(L.u - cL, R.u - cR), SR = std::max(L.u + cL, R.u + cR);
    const double S_star = (R.p - L.p + rL * L.u * (SL - L.u) - rR * R.u * (SR - R.u)) / (rL * (SL - L.u) - rR * (SR - R.u));
    if (SL >= 0) return {flux(UL, L), L.u, L.a1};
    if (SR <= 0) return {flux(UR, R), R.u, R.a1};
    const bool left = S_star >= 0;
    const Vars& U = left ? UL : UR;
    const State& K = left ? L : R;
    const double S = left ? SL : SR, rK = K.rho();
    const double f = (S - K.u) / (S - S_star);
    const Vars Us{f * K.m1, f * K.m2, f * rK * S_star,
                  f * (U[3] + (S_star - K.u) * (rK * S_star + K.p / (S - K.u))), 0.0};
    const Vars F = flux(U, K);
    Face out{{}, S_star, K.a1};
    for (int k = 0; k < 4; ++k) out.F[k] = F[k] + S * (Us[k] - U[k]);
    return out;
  }

  void fill_ghosts() {
    U_[0] = U_[1] = U_[2];
    U_[n_ + 2] = U_[n_ + 3] = U_[n_ + 1];
  }

  //! One MUSCL-Hancock step: minmod slopes of the primitive state, boundary values evolved by half a step (the
  //! conserved part with its own flux difference, a1 with its advection and Kapila's term), HLLC between them.
  void step(double dt) {
    const int m = n_ + 4;
    const double h = 0.5 * dt / dx_;
    std::vector<Vars> left(m), right(m);
    std::vector<State> W(m);
    for (int i = 0; i < m; ++i) W[i] = primitive(U_[i]);
    for (int i = 1; i < m - 1; ++i) {
      State a = W[i], b = W[i];
      for (double State::*q : kLimited) {
        const double d = minmod(W[i].*q - W[i - 1].*q, W[i + 1].*q - W[i].*q);
        a.*q -= 0.5 * d;
        b.*q += 0.5 * d;
      }
      const Vars Ua = conserved(a), Ub = conserved(b), Fa = flux(Ua, a), Fb = flux(Ub, b);
      const double K = kapila_k(W[i]);
      const double da1 = h * (-W[i].u * (b.a1 - a.a1) + K * (b.u - a.u));
      for (int k = 0; k < 4; ++k) {
        left[i][k] = Ua[k] - h * (Fb[k] - Fa[k]);
        right[i][k] = Ub[k] - h * (Fb[k] - Fa[k]);
      }
      left[i][4] = a.a1 + da1;
      right[i][4] = b.a1 + da1;
    }
    std::vector<Face> F(m);  // F[i]: the face between cells i and i + 1
    for (int i = 1; i < m - 2; ++i) F[i] = hllc(right[i], left[i + 1]);
    for (int i = 2; i < n_ + 2; ++i) {
      const double div_u = F[i].u_face - F[i - 1].u_face;
      const double source = (W[i].a1 + kapila_k(W[i])) * div_u;
      for (int k = 0; k < 4; ++k) U_[i][k] -= dt / dx_ * (F[i].F[k] - F[i - 1].F[k]);
      U_[i][4] -= dt / dx_ * (F[i].a_face * F[i].u_face - F[i - 1].a_face * F[i - 1].u_face - source);
    }
  }

  int n_;
  double dx_;
  cip::GasMaterials mat_;
  double t_ = 0;
  std::vector<Vars> U_;  // two ghost cells at each end
};

}  // namespace blastsim::test
