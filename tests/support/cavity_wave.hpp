//! \file cavity_wave.hpp
//! \brief Analytic reference for PPV validation: elastic wave from a pressurised cylindrical cavity (Selberg 1952).
//!
//! Plane-strain cavity of radius a in an infinite, linear-elastic, isotropic medium at rest, wall loaded by
//! p(t) = p0 f(t), f = (1 - cos(pi t / T_r)) / 2 for t < T_r and 1 after (Selberg, "Transient compression
//! waves from spherical and cylindrical cavities", Arkiv for Fysik 5, 1952). Laplace transform in t:
//!   U(r,s) = P(s) K1(s r/c) / D(s),  D(s) = (lambda + 2 mu)(s/c) K0(s a/c) + 2 mu K1(s a/c) / a,
//!   V(r,s) = s U(r,s),  F(s) = L{f} = w^2 (1 + e^{-s T_r}) / (2 s (s^2 + w^2)),  w = pi / T_r,
//! from u_tt = c^2 (u_rr + u_r/r - u/r^2), sigma_rr = (lambda + 2 mu) u_r + lambda u/r = -p at r = a and
//! K1' = -K0 - K1/z. Static limit: u -> p0 a^2 / (2 mu r). Everything is written for the reduced time
//! tau = t - (r - a)/c with exponentially scaled Bessel functions e^z K(z), so nothing over/underflows.
//!
//! Inversion: Fourier series on the Bromwich line (Dubner & Abate, J. ACM 15, 1968; Crump, J. ACM 23, 1976)
//!   g(tau) ~ e^{gamma tau}/T [ G(gamma)/2 + sum_{k=1..N} Re( G(gamma + i k pi/T) e^{i k pi tau/T} ) ],
//! with half period T = 2 tau and gamma T = 9.2 for v (aliasing ~ e^{-2 gamma T} = 1e-8), 12 for u (its
//! subtracted front term grows like t, so aliasing is weighted by t/T_r). To make the series
//! converge fast, the two leading high-frequency terms (wave-front expansion from A&S 9.7.2),
//!   G(s) ~ (p0/(rho c)) sqrt(a/r) F(s) [1 + c kappa/(s + c/a)],  kappa = 3/(8r) + (1/8 - 2mu/(lambda+2mu))/a,
//! are subtracted and added back in closed form (their inverse is elementary); the rest decays as s^-5.
//!
//! Bessel functions (complex z, Re z > 0): |z| < 2 ascending series (Abramowitz & Stegun 9.6.10, 9.6.11,
//! 9.6.13); 2 <= |z| < 25 trapezoidal rule (step 0.2) on the integral (DLMF 10.32.8, u^2 = t)
//!   e^z K_nu(z) = (pi/2z)^{1/2} / Gamma(nu + 1/2) int_0^inf e^{-t} t^{nu-1/2} (1 + t/(2z))^{nu-1/2} dt,
//! whose integrand is analytic in a strip of half-width Re sqrt(2z) >= sqrt|z|, so the error is
//! ~ exp(-2 pi sqrt|z| / 0.2) < 1e-14; |z| >= 25 asymptotic series (A&S 9.7.2).
#pragma once

#include <algorithm>
#include <cmath>
#include <complex>
#include <utility>

namespace blastsim::test {

struct CavityWave {
  double a;       // cavity radius [m]
  double rho;     // density [kg/m3]
  double lambda;  // Lame lambda [Pa]
  double mu;      // shear modulus [Pa]
  double p0;      // final pressure [Pa]
  double rise;    // half-cosine rise time T_r [s], > 0
  double c() const;                                                                 // P-wave speed
  std::complex<double> velocity_transform(double r, std::complex<double> s) const;  // V(r, s)
  double velocity(double r, double t) const;           // v(r, t) [m/s], 0 before arrival (r-a)/c
  double displacement(double r, double t) const;       // u(r, t) [m]
  double peak_velocity(double r, double t_end) const;  // max of |v(r,t)| over t in [0, t_end]
};

namespace cavity_detail {
using cplx = std::complex<double>;
constexpr double kPi = 3.14159265358979323846;
constexpr double kEuler = 0.57721566490153286061;

//! e^z K0(z), e^z K1(z) by the ascending series (A&S 9.6.10, 9.6.11 with n = 1, 9.6.13); |z| <~ 2.
inline void k01_series(cplx z, cplx& k0, cplx& k1) {
  const cplx t = 0.25 * z * z;
  cplx term = 1.0, i0 = 0.0, i1 = 0.0, s0 = 0.0, s1 = 0.0;  // term = t^k / (k!)^2
  double h = 0.0;                                            // harmonic number H_k
  for (int k = 0; k < 80; ++k) {
    if (k > 0) {
      term *= t / double(k * k);
      h += 1.0 / k;
    }
    const cplx term1 = term / double(k + 1);  // t^k / (k! (k+1)!)
    i0 += term;
    i1 += term1;
    s0 += h * term;
    s1 += (2.0 * h + 1.0 / (k + 1)) * term1;  // (H_k + H_{k+1}) t^k / (k! (k+1)!)
    if (k > 2 && std::abs(term) < 1e-18) break;
  }
  const cplx lg = std::log(0.5 * z) + kEuler, ez = std::exp(z);
  k0 = ez * (-lg * i0 + s0);
  k1 = ez * (1.0 / z + lg * (0.5 * z) * i1 - 0.25 * z * s1);
}

//! e^z K0(z), e^z K1(z) by the trapezoidal rule on the integral in the file comment (u^2 = t); |z| >= 2.
inline void k01_integral(cplx z, cplx& k0, cplx& k1) {
  constexpr double h = 0.2;
  const cplx inv2z = 0.5 / z;
  cplx i0 = 0.5, i1 = 0.0;  // half of the symmetric sums; u = 0 node has weight 1/2 here
  for (int j = 1; j <= 36; ++j) {
    const double u2 = (j * h) * (j * h), e = std::exp(-u2);
    const cplx q = std::sqrt(1.0 + u2 * inv2z);
    i0 += e / q;
    i1 += u2 * e * q;
  }
  const cplx sq = std::sqrt(2.0 * z);
  k0 = 2.0 * h * i0 / sq;  // int_R e^{-u^2} (1 + u^2/2z)^{-1/2} du / sqrt(2z)
  k1 = 4.0 * h * i1 / sq;  // 2 int_R u^2 e^{-u^2} (1 + u^2/2z)^{1/2} du / sqrt(2z)
}

//! e^z K0(z), e^z K1(z) by the asymptotic expansion (A&S 9.7.2); |z| >= 25 gives ~1e-16.
inline void k01_asymptotic(cplx z, cplx& k0, cplx& k1) {
  const cplx x = 1.0 / (8.0 * z);
  cplx t0 = 1.0, t1 = 1.0, s0 = 1.0, s1 = 1.0;
  for (int k = 1; k < 60; ++k) {
    const double m = (2.0 * k - 1.0) * (2.0 * k - 1.0);
    t0 *= (-m / k) * x;
    t1 *= ((4.0 - m) / k) * x;
    s0 += t0;
    s1 += t1;
    if (std::abs(t1) < 1e-17) break;
  }
  const cplx pre = std::sqrt(kPi / (2.0 * z));
  k0 = pre * s0;
  k1 = pre * s1;
}

//! Exponentially scaled e^z K0(z), e^z K1(z) for Re z > 0.
inline void scaled_k01(cplx z, cplx& k0, cplx& k1) {
  const double az = std::abs(z);
  if (az < 2.0) k01_series(z, k0, k1);
  else if (az < 25.0) k01_integral(z, k0, k1);
  else k01_asymptotic(z, k0, k1);
}

//! F(s): Laplace transform of the normalised half-cosine ramp f = p / p0.
inline cplx load_transform(double tr, cplx s) {
  const double w = kPi / tr;
  return 0.5 * w * w * (1.0 + std::exp(-s * tr)) / (s * (s * s + w * w));
}

//! G(s) = V(r, s) e^{s (r - a)/c}: velocity transform in reduced time.
inline cplx shifted_velocity(const CavityWave& m, double r, cplx s) {
  const double c = m.c();
  cplx k0a, k1a, k0r, k1r;
  scaled_k01(s * (m.a / c), k0a, k1a);
  scaled_k01(s * (r / c), k0r, k1r);
  const cplx d = (m.lambda + 2.0 * m.mu) * (s / c) * k0a + 2.0 * m.mu * k1a / m.a;
  return m.p0 * s * load_transform(m.rise, s) * k1r / d;
}

//! Wave-front model G ~ amp F(s) (1 + ck / (s + sigma)) (see file comment).
struct Front {
  double amp, ck, sigma;
};
inline Front front(const CavityWave& m, double r) {
  const double c = m.c(), beta = 2.0 * m.mu / (m.lambda + 2.0 * m.mu);
  const double kappa = 3.0 / (8.0 * r) + (0.125 - beta) / m.a;
  return {m.p0 * std::sqrt(m.a / r) / (m.rho * c), c * kappa, c / m.a};
}

//! Time-domain counterparts: f(t), int_0^t f, and q(t) = int_0^t e^{-sigma (t - t')} f(t') dt'.
inline double ramp(double tr, double t) {
  return t <= 0 ? 0.0 : t >= tr ? 1.0 : 0.5 * (1.0 - std::cos(kPi * t / tr));
}
inline double ramp_integral(double tr, double t) {
  const double w = kPi / tr;
  return t <= 0 ? 0.0 : t >= tr ? t - 0.5 * tr : 0.5 * (t - std::sin(w * t) / w);
}
inline double ramp_filtered(double tr, double sigma, double t) {
  const double w = kPi / tr, w2 = w * w, d = sigma * sigma + w2;
  // inverse of 1 / (s (s + sigma) (s^2 + w^2)) by partial fractions
  auto h = [&](double x) {
    if (x <= 0) return 0.0;
    return 1.0 / (sigma * w2) - std::exp(-sigma * x) / (sigma * d) - sigma * std::cos(w * x) / (w2 * d) -
           std::sin(w * x) / (w * d);
  };
  return 0.5 * w2 * (h(t) + h(t - tr));
}

//! Fourier-series inversion of v (disp = false) or u (disp = true) at time t; gamma_t = gamma T,
//! t_factor = T / tau, n_factor scales the number of terms (defaults are the production values).
inline double invert(const CavityWave& m, double r, double t, bool disp, double gamma_t = 9.2,
                     double t_factor = 2.0, double n_factor = 1.0) {
  const double tau = t - (r - m.a) / m.c();
  if (!(tau > 0.0)) return 0.0;
  const Front fr = front(m, r);
  const double T = t_factor * tau, gam = gamma_t / T, w = kPi / m.rise;
  // truncation: the remainder ~ amp w^2 sigma^2 / s^5, tail ~ e^{gam tau} w^2 sigma^2 / (4 pi omega^4) < 1e-8 amp
  const double om = std::max(3.0 * w, std::pow(std::exp(gam * tau) * w * w * fr.sigma * fr.sigma / (4e-8 * kPi), 0.25));
  const long n = std::clamp(static_cast<long>(n_factor * om * T / kPi) + 32, 64L, 4000000L);
  auto rem = [&](cplx s) {
    const cplx g = shifted_velocity(m, r, s) - fr.amp * load_transform(m.rise, s) * (1.0 + fr.ck / (s + fr.sigma));
    return disp ? g / s : g;
  };
  double sum = 0.5 * rem(cplx(gam, 0.0)).real();
  const double dw = kPi / T;
  for (long k = 1; k <= n; ++k) {
    const double om_k = static_cast<double>(k) * dw;
    sum += (rem(cplx(gam, om_k)) * std::polar(1.0, om_k * tau)).real();
  }
  const double f1 = ramp_integral(m.rise, tau), q = ramp_filtered(m.rise, fr.sigma, tau);
  const double asym = disp ? fr.amp * (f1 + fr.ck * (f1 - q) / fr.sigma) : fr.amp * (ramp(m.rise, tau) + fr.ck * q);
  return std::exp(gam * tau) / T * sum + asym;
}

//! (max |v|, time of the max) on [0, t_end]: n samples after arrival, then golden-section refinement.
inline std::pair<double, double> peak_search(const CavityWave& m, double r, double t_end, int n = 480) {
  const double t0 = (r - m.a) / m.c();
  if (!(t_end > t0)) return {0.0, t_end};
  auto f = [&](double t) { return std::abs(invert(m, r, t, false)); };
  const double dt = (t_end - t0) / n;
  int ib = 1;
  double vb = f(t0 + dt);
  for (int i = 2; i <= n; ++i) {
    const double v = f(t0 + i * dt);
    if (v > vb) vb = v, ib = i;
  }
  double lo = t0 + (ib - 1) * dt, hi = std::min(t_end, t0 + (ib + 1) * dt), tb = t0 + ib * dt;
  const double g = 0.5 * (std::sqrt(5.0) - 1.0);
  double x1 = hi - g * (hi - lo), x2 = lo + g * (hi - lo), f1 = f(x1), f2 = f(x2);
  for (int it = 0; it < 40 && hi - lo > 1e-7 * dt; ++it) {
    if (f1 > f2) hi = x2, x2 = x1, f2 = f1, x1 = hi - g * (hi - lo), f1 = f(x1);
    else lo = x1, x1 = x2, f1 = f2, x2 = lo + g * (hi - lo), f2 = f(x2);
  }
  if (f1 > vb) vb = f1, tb = x1;
  if (f2 > vb) vb = f2, tb = x2;
  return {vb, tb};
}
}  // namespace cavity_detail

inline double CavityWave::c() const { return std::sqrt((lambda + 2.0 * mu) / rho); }
inline std::complex<double> CavityWave::velocity_transform(double r, std::complex<double> s) const {
  return cavity_detail::shifted_velocity(*this, r, s) * std::exp(-s * ((r - a) / c()));
}
inline double CavityWave::velocity(double r, double t) const { return cavity_detail::invert(*this, r, t, false); }
inline double CavityWave::displacement(double r, double t) const {
  return cavity_detail::invert(*this, r, t, true, 12.0);
}
inline double CavityWave::peak_velocity(double r, double t_end) const {
  return cavity_detail::peak_search(*this, r, t_end).first;
}

}  // namespace blastsim::test
