//! \file mie_gruneisen_riemann.hpp
//! \brief Exact solution of the 1-D Riemann problem between two materials, each with its own equation of state
//! (ideal gas or JWL, cip::EquationOfState): rarefactions integrated along the isentrope, shocks on the Hugoniot,
//! the star pressure from the condition that the two wave curves meet (Toro ch. 4 for the structure; Menikoff &
//! Plohr, Rev. Mod. Phys. 61 (1989) 75 for general equations of state).
#pragma once

#include "blastsim/cip/eos.hpp"
#include "exact_riemann.hpp"

#include <cmath>
#include <stdexcept>
#include <vector>

namespace blastsim::test {

class MieGruneisenRiemann {
 public:
  MieGruneisenRiemann(const cip::EquationOfState& eosL, Primitive L, const cip::EquationOfState& eosR, Primitive R)
      : left_(eosL, L), right_(eosR, R) {
    // f_L(p) + f_R(p) + u_R - u_L = 0 is increasing in p: bisection on log p.
    auto F = [&](double p) { return left_.f(p) + right_.f(p) + R.u - L.u; };
    // From the lowest pressure both tabulated isentropes reach (a far expansion) to a strong compression.
    double lo = 1.0001 * std::fmax(left_.p.back(), right_.p.back()), hi = 1e3 * std::fmax(L.p, R.p);
    if (F(lo) > 0) throw std::runtime_error("MieGruneisenRiemann: vacuum forms");
    for (int it = 0; it < 200; ++it) {
      const double mid = std::sqrt(lo * hi);
      (F(mid) > 0 ? hi : lo) = mid;
      if (hi / lo - 1 < 1e-14) break;
    }
    p_star_ = std::sqrt(lo * hi);
    u_star_ = 0.5 * (L.u + R.u) + 0.5 * (right_.f(p_star_) - left_.f(p_star_));
  }
  double p_star() const { return p_star_; }
  double u_star() const { return u_star_; }
  double rho_star_left() const { return left_.star_density(p_star_); }
  double rho_star_right() const { return right_.star_density(p_star_); }
  //! Fastest signal speeds of the solution (to size a test's domain and time).
  double leftmost_speed() const { return left_.outer_speed(p_star_, -1); }
  double rightmost_speed() const { return right_.outer_speed(p_star_, +1); }

  //! Solution at similarity coordinate s = (x - x0) / t.
  Primitive sample(double s) const {
    return s <= u_star_ ? left_.sample(s, p_star_, u_star_, -1) : right_.sample(s, p_star_, u_star_, +1);
  }

 private:
  //! One side's wave curve: the isentrope through its state tabulated in ln rho (classical RK4 of
  //! de/dln(rho) = p / rho and dI/dln(rho) = c, I = integral of c drho / rho), and its Hugoniot.
  struct Side {
    cip::EquationOfState eos;
    Primitive K;
    double eK;
    std::vector<double> rho, e, p, c, I;  // isentrope from rho_K down to 1e-8 rho_K, decreasing rho

    Side(const cip::EquationOfState& eos_, Primitive K_) : eos(eos_), K(K_), eK(eos_.internal_energy(K_.rho, K_.p)) {
      const int n = 40000;
      const double ds = std::log(1e-8) / n;  // negative: towards lower density
      double s = std::log(K.rho), en = eK, In = 0;
      auto de = [&](double ls, double ee) { return eos.pressure(std::exp(ls), ee) / std::exp(ls); };
      auto dI = [&](double ls, double ee) { return eos.sound_speed(std::exp(ls), ee); };
      for (int k = 0; k <= n; ++k) {
        const double r = std::exp(s);
        rho.push_back(r);
        e.push_back(en);
        p.push_back(eos.pressure(r, en));
        c.push_back(eos.sound_speed(r, en));
        I.push_back(In);
        if (!(p.back() > 0) || !std::isfinite(c.back())) break;
        const double k1 = de(s, en), j1 = dI(s, en);
        const double k2 = de(s + ds / 2, en + ds / 2 * k1), j2 = dI(s + ds / 2, en + ds / 2 * k1);
        const double k3 = de(s + ds / 2, en + ds / 2 * k2), j3 = dI(s + ds / 2, en + ds / 2 * k2);
        const double k4 = de(s + ds, en + ds * k3), j4 = dI(s + ds, en + ds * k3);
        en += ds / 6 * (k1 + 2 * k2 + 2 * k3 + k4);
        In += ds / 6 * (j1 + 2 * j2 + 2 * j3 + j4);  // negative: I(rho) - I(rho_K)
        s += ds;
      }
    }
    //! Index k and weight w of the isentrope point with pressure q (linear between table points).
    void locate(double q, int& k, double& w) const {
      int a = 0, b = static_cast<int>(p.size()) - 1;
      if (q < p[b]) throw std::runtime_error("MieGruneisenRiemann: pressure below the tabulated isentrope");
      while (b - a > 1) {
        const int m = (a + b) / 2;
        (p[m] >= q ? a : b) = m;
      }
      k = a;
      w = (p[a] - q) / (p[a] - p[b]);
    }
    double lerp(const std::vector<double>& v, int k, double w) const { return (1 - w) * v[k] + w * v[k + 1]; }
    //! Density behind a shock to pressure q > p_K: the root of e(rho, q) - e_K = (q + p_K)/2 (1/rho_K - 1/rho).
    double hugoniot_density(double q) const {
      auto g = [&](double r) { return eos.internal_energy(r, q) - eK - 0.5 * (q + K.p) * (1 / K.rho - 1 / r); };
      double lo = K.rho, hi = K.rho;
      while (g(hi) > 0) hi *= 1.5;  // g = (q - p_K)/(Gamma rho_K) > 0 at rho_K for q > p_K, < 0 past the root
      for (int it = 0; it < 200; ++it) {
        const double mid = 0.5 * (lo + hi);
        (g(mid) > 0 ? lo : hi) = mid;
      }
      return 0.5 * (lo + hi);
    }
    //! Velocity jump across this side's wave to pressure q (Toro's f_K).
    double f(double q) const {
      if (q > K.p) {
        const double r = hugoniot_density(q);
        return std::sqrt((q - K.p) * (1 / K.rho - 1 / r));
      }
      int k;
      double w;
      locate(q, k, w);
      return lerp(I, k, w);  // -(integral of dp / (rho c) from q to p_K) < 0
    }
    double star_density(double q) const {
      if (q > K.p) return hugoniot_density(q);
      int k;
      double w;
      locate(q, k, w);
      return lerp(rho, k, w);
    }
    //! Mass flux through a shock to q: sqrt((q - p_K) / (1/rho_K - 1/rho)).
    double shock_speed(double q, int dir) const {
      const double r = hugoniot_density(q);
      return K.u + dir * std::sqrt((q - K.p) / (1 / K.rho - 1 / r)) / K.rho;
    }
    double outer_speed(double q, int dir) const {
      return q > K.p ? shock_speed(q, dir) : K.u + dir * c.front();
    }
    //! State at s on this side (dir = -1 left, +1 right) given the star pressure and velocity.
    Primitive sample(double s, double ps, double us, int dir) const {
      if (ps > K.p) {
        const double S = shock_speed(ps, dir);
        return dir * (s - S) >= 0 ? K : Primitive{hugoniot_density(ps), us, ps};
      }
      const double head = K.u + dir * c.front();
      int k;
      double w;
      locate(ps, k, w);
      const double c_star = lerp(c, k, w), tail = us + dir * c_star;
      if (dir * (s - head) >= 0) return K;
      if (dir * (s - tail) <= 0) return {lerp(rho, k, w), us, ps};
      // Inside the fan u = u_K + dir I (I <= 0 from rho_K down); find the point where u + dir c = s.
      int a = 0, b = k + 1;
      auto speed = [&](int m) { return K.u + dir * I[m] + dir * c[m]; };
      while (b - a > 1) {
        const int m = (a + b) / 2;
        (dir * (speed(m) - s) > 0 ? a : b) = m;
      }
      const double t = (speed(a) - s) / (speed(a) - speed(b));
      return {(1 - t) * rho[a] + t * rho[b], (1 - t) * (K.u + dir * I[a]) + t * (K.u + dir * I[b]),
              (1 - t) * p[a] + t * p[b]};
    }
  };
  Side left_, right_;
  double p_star_ = 0, u_star_ = 0;
};

}  // namespace blastsim::test
