//! \file exact_riemann.hpp
//! \brief Exact Riemann solver for the 1-D Euler equations of an ideal gas (Toro, Riemann Solvers, ch. 4).
#pragma once

#include <cmath>
#include <stdexcept>

namespace blastsim::test {

struct Primitive {
  double rho, u, p;
};

//! Exact solution of the Riemann problem with left state L, right state R, ideal gas gamma.
class ExactRiemann {
 public:
  ExactRiemann(Primitive L, Primitive R, double gamma) : L_(L), R_(R), g_(gamma) {
    cL_ = std::sqrt(g_ * L.p / L.rho);
    cR_ = std::sqrt(g_ * R.p / R.rho);
    solve_star();
  }
  double p_star() const { return p_star_; }
  double u_star() const { return u_star_; }
  //! Density left / right of the contact.
  double rho_star_left() const { return star_density(L_, p_star_); }
  double rho_star_right() const { return star_density(R_, p_star_); }
  //! Speed of the right shock (valid when the right wave is a shock).
  double right_shock_speed() const {
    return R_.u + cR_ * std::sqrt((g_ + 1) / (2 * g_) * p_star_ / R_.p + (g_ - 1) / (2 * g_));
  }
  //! Solution at similarity coordinate s = (x - x0) / t (Toro sec. 4.5).
  Primitive sample(double s) const {
    const double g = g_;
    if (s <= u_star_) {  // left of the contact
      const Primitive& K = L_;
      const double c = cL_;
      if (p_star_ > K.p) {  // left shock
        const double SL = K.u - c * std::sqrt((g + 1) / (2 * g) * p_star_ / K.p + (g - 1) / (2 * g));
        return s <= SL ? K : Primitive{rho_star_left(), u_star_, p_star_};
      }
      const double SHL = K.u - c;
      const double cs = c * std::pow(p_star_ / K.p, (g - 1) / (2 * g));
      const double STL = u_star_ - cs;
      if (s <= SHL) return K;
      if (s >= STL) return {rho_star_left(), u_star_, p_star_};
      const double f = 2 / (g + 1) + (g - 1) / ((g + 1) * c) * (K.u - s);
      return {K.rho * std::pow(f, 2 / (g - 1)), 2 / (g + 1) * (c + (g - 1) / 2 * K.u + s),
              K.p * std::pow(f, 2 * g / (g - 1))};
    }
    const Primitive& K = R_;
    const double c = cR_;
    if (p_star_ > K.p) {  // right shock
      return s >= right_shock_speed() ? K : Primitive{rho_star_right(), u_star_, p_star_};
    }
    const double SHR = K.u + c;
    const double cs = c * std::pow(p_star_ / K.p, (g - 1) / (2 * g));
    const double STR = u_star_ + cs;
    if (s >= SHR) return K;
    if (s <= STR) return {rho_star_right(), u_star_, p_star_};
    const double f = 2 / (g + 1) - (g - 1) / ((g + 1) * c) * (K.u - s);
    return {K.rho * std::pow(f, 2 / (g - 1)), 2 / (g + 1) * (-c + (g - 1) / 2 * K.u + s),
            K.p * std::pow(f, 2 * g / (g - 1))};
  }

  //! Toro's pressure function f_K(p) and its derivative for one side (eq. 4.6-4.7).
  static void pressure_function(double p, const Primitive& K, double gamma, double& f, double& df) {
    const double c = std::sqrt(gamma * K.p / K.rho);
    if (p > K.p) {
      const double A = 2 / ((gamma + 1) * K.rho), B = (gamma - 1) / (gamma + 1) * K.p;
      const double q = std::sqrt(A / (p + B));
      f = (p - K.p) * q;
      df = q * (1 - 0.5 * (p - K.p) / (B + p));
    } else {
      const double r = p / K.p;
      f = 2 * c / (gamma - 1) * (std::pow(r, (gamma - 1) / (2 * gamma)) - 1);
      df = 1 / (K.rho * c) * std::pow(r, -(gamma + 1) / (2 * gamma));
    }
  }

  //! Pressure behind a shock reflected from a wall by gas K moving into the wall at speed |K.u|:
  //! the p > K.p with f_K(p) = |K.u| (the reflected shock brings the gas to rest).
  static double reflected_shock_pressure(const Primitive& K, double gamma) {
    double p = K.p * 2;
    for (int it = 0; it < 100; ++it) {
      double f, df;
      pressure_function(p, K, gamma, f, df);
      const double dp = (f - std::fabs(K.u)) / df;
      p = std::fmax(p - dp, 1e-3 * K.p);
      if (std::fabs(dp) < 1e-14 * p) return p;
    }
    throw std::runtime_error("reflected_shock_pressure: no convergence");
  }

 private:
  double star_density(const Primitive& K, double p) const {
    const double g = g_;
    if (p > K.p) {
      const double r = p / K.p, m = (g - 1) / (g + 1);
      return K.rho * (r + m) / (m * r + 1);
    }
    return K.rho * std::pow(p / K.p, 1 / g);
  }
  void solve_star() {
    double p = 0.5 * (L_.p + R_.p);
    for (int it = 0; it < 200; ++it) {
      double fL, dL, fR, dR;
      pressure_function(p, L_, g_, fL, dL);
      pressure_function(p, R_, g_, fR, dR);
      const double dp = (fL + fR + (R_.u - L_.u)) / (dL + dR);
      const double pn = std::fmax(p - dp, 1e-12 * p);
      if (std::fabs(pn - p) < 1e-14 * (pn + p)) {
        p = pn;
        break;
      }
      p = pn;
    }
    double fL, dL, fR, dR;
    pressure_function(p, L_, g_, fL, dL);
    pressure_function(p, R_, g_, fR, dR);
    p_star_ = p;
    u_star_ = 0.5 * (L_.u + R_.u) + 0.5 * (fR - fL);
  }
  Primitive L_, R_;
  double g_, cL_, cR_;
  double p_star_ = 0, u_star_ = 0;
};

}  // namespace blastsim::test
