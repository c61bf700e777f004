//! \file test_smooth_wave.cpp
//! \brief docs/validation.md G4: observed order of accuracy on smooth periodic waves (entropy wave and acoustic wave);
//! G17: sound and the time stepping (the lagged pressure work and the pressure predictor).
#include "catch.hpp"
#include "validation_courant.hpp"
#include "gas_cases.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <utility>
#include <vector>

using namespace blastsim;
using namespace blastsim::test;

namespace {

//! Density entropy wave rho = 1 + 0.2 sin(2 pi (x + y)) carried diagonally by u = v = 1 at p = 1 on the
//! periodic unit square; after t = 1 it is back where it started. Returns the mean |rho error|.
double entropy_wave_error(int n) {
  const cip::EquationOfState eos = cip::EquationOfState::ideal(1.4);
  cip::GasSolverOptions opt;
  opt.boundaries = cip::BoundaryConditions::all(cip::BoundaryKind::periodic);
  cip::GasSolver s(cip::GasGrid::from_box(n, n, 0, 1, 0, 1), eos, opt);
  auto rho_exact = [](double x, double y) { return 1.0 + 0.2 * std::sin(2 * M_PI * (x + y)); };
  s.initialise([&](double x, double y) {
    const double rho = rho_exact(x, y);
    return cip::GasPoint{rho, eos.internal_energy(rho, 1.0), 1.0, 1.0};
  });
  run_to(s, 1.0, blastsim::test::validation_courant(s.options().transport));
  const cip::HostGasFields h = s.to_host();
  double err = 0;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i)
      err += std::fabs(h.rho[static_cast<size_t>(j) * n + i] - rho_exact(s.grid().cell_x(i), s.grid().cell_y(j)));
  return err / (static_cast<double>(n) * n);
}

//! A right-running sound wave of one wavelength, amplitude 1e-4 of p0 = 1, on a periodic strip of n x 3 cells
//! with the given options (periodic boundaries are set here); after `periods` periods (t = periods / c) it is
//! back where it started. Returns {amplitude of the wavelength's Fourier mode / 1e-4, mean |p error| / 1e-4}.
std::pair<double, double> sound_wave(int n, int periods, cip::GasSolverOptions opt) {
  const double gamma = 1.4, c = std::sqrt(gamma), amp = 1e-4;
  opt.boundaries = cip::BoundaryConditions::all(cip::BoundaryKind::periodic);
  const cip::EquationOfState eos = cip::EquationOfState::ideal(gamma);
  cip::GasSolver s(cip::GasGrid::from_box(n, 3, 0, 1, 0, 3.0 / n), eos, opt);
  auto dp = [&](double x) { return amp * std::sin(2 * M_PI * x); };
  s.initialise([&](double x, double) {
    const double rho = 1.0 + dp(x) / (c * c);
    return cip::GasPoint{rho, eos.internal_energy(rho, 1.0 + dp(x)), dp(x) / c, 0.0};
  });
  run_to(s, periods / c, blastsim::test::validation_courant(s.options().transport));
  const cip::HostGasFields h = s.to_host();
  const std::vector<double> p = strip(h, h.p, Axis::x);
  double a = 0, b = 0, err = 0;
  for (int i = 0; i < n; ++i) {
    const double x = s.grid().cell_x(i);
    a += 2.0 / n * (p[i] - 1.0) * std::sin(2 * M_PI * x);
    b += 2.0 / n * (p[i] - 1.0) * std::cos(2 * M_PI * x);
    err += std::fabs(p[i] - 1.0 - dp(x));
  }
  return {std::hypot(a, b) / amp, err / n / amp};
}

//! G4's acoustic wave: the default scheme, one period. Returns the mean |p error| / amplitude.
double acoustic_wave_error(int n) { return sound_wave(n, 1, cip::GasSolverOptions{}).second; }

}  // namespace

TEST_CASE("G4 smooth waves: observed order of accuracy", "[long][cip][G4]") {
  const double e1 = entropy_wave_error(32), e2 = entropy_wave_error(64), e3 = entropy_wave_error(128);
  const double order_entropy = std::log2(e2 / e3);
  std::printf("G4 entropy wave (2-D diagonal): L1(rho) %.3e / %.3e / %.3e at 32 / 64 / 128 cells, order %.2f then %.2f\n",
              e1, e2, e3, std::log2(e1 / e2), order_entropy);
  const double a1 = acoustic_wave_error(50), a2 = acoustic_wave_error(100), a3 = acoustic_wave_error(200);
  const double order_acoustic = std::log2(a2 / a3);
  std::printf("G4 acoustic wave (1-D): relative L1(p) %.3e / %.3e / %.3e at 50 / 100 / 200 cells, order %.2f then %.2f\n",
              a1, a2, a3, std::log2(a1 / a2), order_acoustic);
  // docs/validation.md G4: order >= 2 on a smooth density wave (CIP's low numerical diffusion).
  CHECK(order_entropy >= 2.0);
  // Acoustic waves: the linear term c1 rho c |dU| of the paper's eq. (4) acts in every compression, so the
  // scheme damps sound at first order (docs/gas-solver.md). Reported; checked only to converge.
  CHECK(a3 < a2);
  CHECK(a2 < a1);
  CHECK(order_acoustic > 0.5);
}

namespace {

//! The shortest wave along `axis`, p = p0 (1 + eps (-1)^k) over the 40 cells of a periodic strip (40 x 3 cells
//! along x, 3 x 40 along y), of air at rest, stepped at fixed dt = C h / c (h the spacing along the wave) without
//! artificial viscosity; the cells across the strip are twice as wide as along it (dx != dy). For linear sound
//! this mode is a two-variable system (its pressure and its face velocity), so its pressure amplitude q_n obeys
//! q_{n+1} = tr q_n - det q_{n-1} with the trace and determinant of the amplification matrix. Returns {tr, det}
//! fitted from q at steps 40 to 43.
std::pair<double, double> shortest_wave_matrix(bool predictor, double courant, Axis axis) {
  const int n = 40;
  const double gamma = 1.4, eps = 1e-8;
  cip::GasSolverOptions opt;
  opt.boundaries = cip::BoundaryConditions::all(cip::BoundaryKind::periodic);
  opt.viscosity = {0.0, 0.0};
  opt.pressure_predictor = predictor;
  const cip::EquationOfState eos = cip::EquationOfState::ideal(gamma);
  const double h = 1.0 / n, across = 3 * 2.0 * h;
  const bool along_x = axis == Axis::x;
  cip::GasSolver s(along_x ? cip::GasGrid::from_box(n, 3, 0, 1, 0, across) : cip::GasGrid::from_box(3, n, 0, across, 0, 1),
                   eos, opt);
  s.initialise([&](double x, double y) {
    const int k = static_cast<int>(std::floor((along_x ? x : y) / h));
    const double p = 1.0 + eps * (k % 2 == 0 ? 1.0 : -1.0);
    return cip::GasPoint{1.0, eos.internal_energy(1.0, p), 0.0, 0.0};
  });
  const double dt = courant * h / std::sqrt(gamma);
  auto mode = [&] {
    const cip::HostGasFields hf = s.to_host();
    const std::vector<double> p = strip(hf, hf.p, axis);
    double a = 0;
    for (int k = 0; k < n; ++k) a += (p[k] - 1.0) * (k % 2 == 0 ? 1.0 : -1.0);
    return a / n;
  };
  std::vector<double> q;
  for (int k = 1; k <= 43; ++k) {
    s.step(dt);
    if (k >= 40) q.push_back(mode());
  }
  // q2 = tr q1 - det q0 and q3 = tr q2 - det q1
  const double det = (q[1] * q[3] - q[2] * q[2]) / (q[0] * q[2] - q[1] * q[1]);
  const double tr = (q[2] + det * q[0]) / q[1];
  return {tr, det};
}

}  // namespace

TEST_CASE("G17 sound: with the pressure predictor the time stepping neither amplifies nor damps it", "[cip][G17][heavy]") {
  // docs/gas-solver.md "Time centring of the pressure": for the shortest wave (k' = 2 / dx) nu = 2 C. With the
  // work lagged by w = (gamma - 1) / (2 gamma) the amplification matrix of (u, p / (rho c)) has the trace
  // 2 - (1 - w) nu^2 and the determinant 1 + w nu^2; with the predictor (beta = w) 2 - nu^2 and exactly 1.
  // The Courant number is the default's (kConservativeCourant), not the tests' study setting: the analysis is
  // checked at one stated number.
  const double C = cip::kConservativeCourant, gamma = 1.4;
  const double w = (gamma - 1) / (2 * gamma), nu = 2 * C;
  for (const Axis axis : {Axis::x, Axis::y}) {
    const auto [tr_lagged, det_lagged] = shortest_wave_matrix(false, C, axis);
    const auto [tr_predicted, det_predicted] = shortest_wave_matrix(true, C, axis);
    std::printf("G17 shortest wave along %s at Courant %.2f, no viscosity: without the predictor trace %.9f det %.9f "
                "(exact %.9f, %.9f); with it trace %.9f det %.9f (exact %.9f, 1)\n",
                axis == Axis::x ? "x" : "y", C, tr_lagged, det_lagged, 2 - (1 - w) * nu * nu, 1 + w * nu * nu,
                tr_predicted, det_predicted, 2 - nu * nu);
    // The mode's amplitude is 1e-8 of p0 and held in doubles: the fit carries relative errors of about 1e-8.
    CHECK(std::fabs(det_lagged - (1 + w * nu * nu)) < 1e-6);
    CHECK(std::fabs(tr_lagged - (2 - (1 - w) * nu * nu)) < 1e-6);
    CHECK(std::fabs(det_predicted - 1) < 1e-6);
    CHECK(std::fabs(tr_predicted - (2 - nu * nu)) < 1e-6);
  }

  // A resolved sound wave, ten periods without viscosity: back where it started, amplitude kept.
  for (const int n : {50, 100}) {
    cip::GasSolverOptions opt;
    opt.viscosity = {0.0, 0.0};
    opt.pressure_predictor = true;
    const auto [amplitude, error] = sound_wave(n, 10, opt);
    std::printf("G17 sound wave on %d cells, ten periods, no viscosity: amplitude %.5f of the initial, L1(p) %.3e of it\n",
                n, amplitude, error);
    CHECK(std::fabs(amplitude - 1) < 1e-3);
    CHECK(error < 0.05);
  }
}
