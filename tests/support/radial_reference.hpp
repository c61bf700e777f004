//! \file radial_reference.hpp
//! \brief Independent reference for cylindrically symmetric gas flow: 1-D finite volumes in r (MUSCL + HLL, RK2).
//!
//! Solves d(rU)/dt + d(rF)/dr = (0, p, 0) for U = (rho, rho u, rho E_total), ideal gas, with a mirror at
//! r = 0 and zero-gradient outflow at r_max. Used at high resolution as the "exact" answer of the 2-D
//! cylindrical explosion (Toro, Riemann Solvers, sec. 17.1); it shares no code with libcip.
#pragma once

#include <algorithm>
#include <cmath>
#include <functional>
#include <vector>

namespace blastsim::test {

struct RadialProfile {
  double r_max;
  std::vector<double> rho, u, p;  // cell averages on a uniform grid over [0, r_max]
  //! Linear interpolation at radius r.
  double density_at(double r) const { return interp(rho, r); }
  double pressure_at(double r) const { return interp(p, r); }
  double interp(const std::vector<double>& f, double r) const {
    const int n = static_cast<int>(f.size());
    const double s = r / r_max * n - 0.5;
    const int i = std::clamp(static_cast<int>(std::floor(s)), 0, n - 2);
    const double w = std::clamp(s - i, 0.0, 1.0);
    return (1 - w) * f[i] + w * f[i + 1];
  }
};

//! Runs the radial solver from rho0(r), p0(r) (at rest) to time t_end.
inline RadialProfile solve_radial(int n, double r_max, double gamma, double t_end,
                                  const std::function<double(double)>& rho0,
                                  const std::function<double(double)>& p0, double cfl = 0.4) {
  const double dr = r_max / n;
  const int g = 2;
  std::vector<double> q0(n + 2 * g), q1(n + 2 * g), q2(n + 2 * g);  // conserved, per cell
  std::vector<std::vector<double>> U(3, std::vector<double>(n + 2 * g)), W = U, K = U;
  auto rl = [&](int i) { return (i - g) * dr; };  // left face radius of cell i (padded index)
  auto vol = [&](int i) { return 0.5 * ((rl(i) + dr) * (rl(i) + dr) - rl(i) * rl(i)); };
  for (int i = g; i < n + g; ++i) {
    const double rc = rl(i) + 0.5 * dr;
    U[0][i] = rho0(rc);
    U[1][i] = 0.0;
    U[2][i] = p0(rc) / (gamma - 1);
  }
  auto prim = [&](const std::vector<std::vector<double>>& Q, int i, double& rho, double& u, double& p) {
    rho = Q[0][i];
    u = Q[1][i] / rho;
    p = (gamma - 1) * (Q[2][i] - 0.5 * rho * u * u);
  };
  auto fill = [&](std::vector<std::vector<double>>& Q) {
    for (int k = 0; k < g; ++k) {
      const int gi = g - 1 - k, src = g + k;  // mirror at r = 0
      Q[0][gi] = Q[0][src];
      Q[1][gi] = -Q[1][src];
      Q[2][gi] = Q[2][src];
      for (int c = 0; c < 3; ++c) Q[c][n + g + k] = Q[c][n + g - 1];
    }
  };
  auto minmod = [](double a, double b) { return a * b <= 0 ? 0.0 : (std::fabs(a) < std::fabs(b) ? a : b); };
  // Right-hand side: -1/V [r F]_faces + source.
  auto rhs = [&](std::vector<std::vector<double>>& Q, std::vector<std::vector<double>>& R) {
    fill(Q);
    std::vector<double> wr(n + 2 * g), wu(n + 2 * g), wp(n + 2 * g);
    for (int i = 0; i < n + 2 * g; ++i) prim(Q, i, wr[i], wu[i], wp[i]);
    std::vector<double> F0(n + 1), F1(n + 1), F2(n + 1);
    for (int f = 0; f <= n; ++f) {
      const int iL = g + f - 1, iR = g + f;
      auto recon = [&](const std::vector<double>& w, int i, double side) {
        return w[i] + 0.5 * side * minmod(w[i] - w[i - 1], w[i + 1] - w[i]);
      };
      const double rL = recon(wr, iL, 1), uL = recon(wu, iL, 1), pL = recon(wp, iL, 1);
      const double rR = recon(wr, iR, -1), uR = recon(wu, iR, -1), pR = recon(wp, iR, -1);
      const double cL = std::sqrt(gamma * pL / rL), cR = std::sqrt(gamma * pR / rR);
      const double SL = std::min(uL - cL, uR - cR), SR = std::max(uL + cL, uR + cR);
      const double EL = pL / (gamma - 1) + 0.5 * rL * uL * uL, ER = pR / (gamma - 1) + 0.5 * rR * uR * uR;
      const double fl[3] = {rL * uL, rL * uL * uL + pL, uL * (EL + pL)};
      const double fr[3] = {rR * uR, rR * uR * uR + pR, uR * (ER + pR)};
      const double ul[3] = {rL, rL * uL, EL}, ur[3] = {rR, rR * uR, ER};
      double out[3];
      for (int c = 0; c < 3; ++c) {
        if (SL >= 0) out[c] = fl[c];
        else if (SR <= 0) out[c] = fr[c];
        else out[c] = (SR * fl[c] - SL * fr[c] + SL * SR * (ur[c] - ul[c])) / (SR - SL);
      }
      const double rf = f * dr;
      F0[f] = rf * out[0];
      F1[f] = rf * out[1];
      F2[f] = rf * out[2];
    }
    for (int i = g; i < n + g; ++i) {
      const int f = i - g;
      const double V = vol(i);
      R[0][i] = -(F0[f + 1] - F0[f]) / V;
      R[1][i] = -(F1[f + 1] - F1[f]) / V + wp[i] * dr / V;
      R[2][i] = -(F2[f + 1] - F2[f]) / V;
    }
  };
  double t = 0;
  while (t < t_end) {
    double smax = 0;
    for (int i = g; i < n + g; ++i) {
      double r, u, p;
      prim(U, i, r, u, p);
      smax = std::max(smax, std::fabs(u) + std::sqrt(gamma * p / r));
    }
    const double dt = std::min(cfl * dr / smax, t_end - t);
    rhs(U, K);  // Heun (SSP RK2)
    for (int c = 0; c < 3; ++c)
      for (int i = g; i < n + g; ++i) W[c][i] = U[c][i] + dt * K[c][i];
    rhs(W, K);
    for (int c = 0; c < 3; ++c)
      for (int i = g; i < n + g; ++i) U[c][i] = 0.5 * (U[c][i] + W[c][i] + dt * K[c][i]);
    t += dt;
  }
  RadialProfile out{r_max, std::vector<double>(n), std::vector<double>(n), std::vector<double>(n)};
  for (int i = g; i < n + g; ++i) prim(U, i, out.rho[i - g], out.u[i - g], out.p[i - g]);
  return out;
}

}  // namespace blastsim::test
