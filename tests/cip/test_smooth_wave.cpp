//! \file test_smooth_wave.cpp
//! \brief docs/validation.md G4: observed order of accuracy on smooth periodic waves (entropy wave and acoustic wave).
#include "catch.hpp"
#include "validation_courant.hpp"
#include "gas_cases.hpp"

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

//! Right-running acoustic wave of amplitude 1e-4 on a periodic strip; after one period (t = 1/c) it is
//! back. Returns the mean |p error| / amplitude.
double acoustic_wave_error(int n) {
  const double gamma = 1.4, c = std::sqrt(gamma), amp = 1e-4;
  cip::GasSolverOptions opt;
  opt.boundaries = cip::BoundaryConditions::all(cip::BoundaryKind::periodic);
  const cip::EquationOfState eos = cip::EquationOfState::ideal(gamma);
  cip::GasSolver s(cip::GasGrid::from_box(n, 3, 0, 1, 0, 3.0 / n), eos, opt);
  auto dp = [&](double x) { return amp * std::sin(2 * M_PI * x); };
  s.initialise([&](double x, double) {
    const double rho = 1.0 + dp(x) / (c * c);
    return cip::GasPoint{rho, eos.internal_energy(rho, 1.0 + dp(x)), dp(x) / c, 0.0};
  });
  run_to(s, 1.0 / c, blastsim::test::validation_courant(s.options().transport));
  const cip::HostGasFields h = s.to_host();
  const std::vector<double> p = strip(h, h.p, Axis::x);
  double err = 0;
  for (int i = 0; i < n; ++i) err += std::fabs(p[i] - 1.0 - dp(s.grid().cell_x(i)));
  return err / n / amp;
}

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
