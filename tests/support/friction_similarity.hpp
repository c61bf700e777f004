//! \file friction_similarity.hpp
//! \brief The similarity solution of an ideal gas filling an empty channel with walls of friction from a
//! reservoir at constant pressure (docs/validation.md C9, derived in docs/coupling.md "Front in a rigid crack"):
//! friction-dominated flow (inertia and kinetic energy neglected), adiabatic or isothermal walls, laminar (cubic
//! law) or fully rough turbulent (constant Darcy factor) friction; solved by shooting on the mouth's mass flux.
#pragma once

#include <cmath>
#include <stdexcept>

namespace blastsim::test {

//! The 1-D problem: pressure p(x, t), Theta = p / rho, mass flux G along a channel of aperture w [m] from a
//! reservoir at p0 [Pa], Theta0 [J/kg] (Theta = R T) into vacuum, with
//!   mass      d(p / Theta)/dt + dG/dx = 0,
//!   energy    dp/dt + gamma d(G Theta)/dx = 0          (adiabatic walls: total enthalpy flux G gamma Theta /
//!                                                      (gamma - 1)), or Theta = Theta0 (isothermal walls at
//!                                                      the reservoir's temperature),
//!   momentum  G = -K (p / Theta) dp/dx                  (laminar: K = w^2 / (12 mu)),
//!             G |G| = -K (p / Theta) dp/dx              (turbulent: K = 4 w / f).
//! With xi = x / t^a (a = 1/2 laminar, 2/3 turbulent) and G = t^(a - 1) g(xi) they become ordinary equations in
//! P(xi), Theta(xi), g(xi); P(0) = p0, Theta(0) = Theta0, and the mouth flux g(0) is the one whose solution
//! reaches P = 0 at the front (bisection between solutions that reach P = 0 with flux to spare and solutions
//! whose gas stops, g = a xi rho, before that).
class FrictionSimilarity {
 public:
  enum class Regime { laminar, turbulent };
  enum class Walls { adiabatic, isothermal };
  FrictionSimilarity(Regime regime, double K, double p0, double theta0, double gamma, Walls walls = Walls::adiabatic)
      : turbulent_(regime == Regime::turbulent), isothermal_(walls == Walls::isothermal), a_(turbulent_ ? 2.0 / 3.0 : 0.5),
        K_(K), p0_(p0), th0_(theta0), gamma_(gamma) {
    // Scales: xi ~ sqrt(K p0) (laminar), (K Theta0)^(1/3) (turbulent); g from the momentum law over that length.
    const double xi = turbulent_ ? std::cbrt(K * theta0) : std::sqrt(K * p0);
    step_ = 5e-5 * xi;
    const double g = turbulent_ ? std::sqrt(K * p0 * p0 / (theta0 * xi)) : K * p0 * p0 / (theta0 * xi);
    double lo = 1e-4 * g, hi = 1e4 * g;
    for (int k = 0; k < 50; ++k) {
      const double mid = std::sqrt(lo * hi);
      (shoot(mid, -1.0) < 0 ? hi : lo) = mid;
    }
    g0_ = hi;
  }
  //! The similarity coordinate xi = x / t^a [m / s^a] where the pressure first falls to fraction `kappa` of p0.
  double isobar(double kappa) const {
    const double xi = shoot(g0_, kappa);
    if (!(xi > 0)) throw std::runtime_error("FrictionSimilarity: the isobar was not reached");
    return xi;
  }
  double exponent() const { return a_; }  //!< a of x = xi t^a
  double mouth_flux() const { return g0_; }

 private:
  struct State {
    double P, T, g;
  };
  State slope(double xi, const State& s) const {
    const double flux = turbulent_ ? s.g * std::fabs(s.g) : s.g;
    const double Pp = -flux * s.T / (K_ * s.P);
    const double D = s.g - a_ * xi * s.P / s.T;
    const double Tp = isothermal_ ? 0.0 : a_ * xi * Pp * (1.0 - gamma_) / (gamma_ * D);
    return {Pp, Tp, a_ * xi * (Pp / s.T - s.P * Tp / (s.T * s.T))};
  }
  //! Integrates from the mouth with g(0) = g0 (RK4). With kappa < 0: -1 when P reaches 0 first (too much flux),
  //! +1 when the gas stops first. With kappa >= 0: the xi where P falls to kappa p0 (-1 if it does not).
  double shoot(double g0, double kappa) const {
    State s{p0_, th0_, g0};
    double xi = 0.0;
    const double h = step_;
    for (int n = 0; n < 1000000; ++n) {  // a near-critical solution's tail is long: past this, the gas counts as stopped
      auto add = [](const State& a, const State& d, double f) { return State{a.P + f * d.P, a.T + f * d.T, a.g + f * d.g}; };
      const State k1 = slope(xi, s), k2 = slope(xi + h / 2, add(s, k1, h / 2)), k3 = slope(xi + h / 2, add(s, k2, h / 2)),
                  k4 = slope(xi + h, add(s, k3, h));
      const State next{s.P + h / 6 * (k1.P + 2 * k2.P + 2 * k3.P + k4.P), s.T + h / 6 * (k1.T + 2 * k2.T + 2 * k3.T + k4.T),
                       s.g + h / 6 * (k1.g + 2 * k2.g + 2 * k3.g + k4.g)};
      if (kappa >= 0 && next.P < kappa * p0_) return xi + h * (s.P - kappa * p0_) / (s.P - next.P);
      xi += h;
      if (!(next.P > 0)) return kappa >= 0 ? -1.0 : -1.0;
      if (!(next.T > 0) || !(next.g - a_ * xi * next.P / next.T > 0)) return kappa >= 0 ? -1.0 : 1.0;
      s = next;
    }
    return kappa >= 0 ? -1.0 : 1.0;
  }
  bool turbulent_, isothermal_;
  double a_, K_, p0_, th0_, gamma_, step_ = 0, g0_ = 0;
};

}  // namespace blastsim::test
