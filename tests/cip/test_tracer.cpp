//! \file test_tracer.cpp
//! \brief docs/validation.md G13: the tracer of a one-gas run (GasMaterials::tracer): a passive scalar that
//! leaves the flow's bytes unchanged, conserves the traced mass, stays a fraction in [0, 1] and moves with the
//! contact of a Riemann problem.
#include "catch.hpp"
#include "gas_cases.hpp"
#include "same_bytes.hpp"

#include <algorithm>
#include <numeric>

using namespace blastsim;
using namespace blastsim::test;

namespace {

//! Sod's tube (Toro's test 1) on an n x 3 strip over [0, 1], the left gas traced when `traced`.
cip::GasSolver traced_sod(int n, bool traced, cip::BoundaryKind ends) {
  cip::GasMaterials mat;
  mat.air = cip::EquationOfState::ideal(1.4);
  mat.tracer = traced;
  cip::GasSolverOptions opt;
  opt.boundaries = cip::BoundaryConditions::all(cip::BoundaryKind::wall).set(cip::left, ends).set(cip::right, ends);
  cip::GasSolver s(cip::GasGrid::from_box(n, 3, 0, 1, 0, 3.0 / n), mat, opt);
  s.initialise([&](double x, double) {
    const bool left = x < 0.5;
    const double rho = left ? 1.0 : 0.125, p = left ? 1.0 : 0.1;
    return cip::GasPoint{rho, p / (0.4 * rho), 0.0, 0.0, 0.0, traced && left ? 1.0 : 0.0};
  });
  return s;
}

}  // namespace

TEST_CASE("G13 tracer: the same flow, the traced mass kept, the traced fraction bounded and moving with the contact",
          "[cip][G13][heavy]") {
  const int n = 200;
  const double t = 0.2;
  cip::GasSolver plain = traced_sod(n, false, cip::BoundaryKind::outflow);
  cip::GasSolver traced = traced_sod(n, true, cip::BoundaryKind::outflow);
  const double m0 = traced.totals().products_mass;
  run_to(plain, t, 0.2);
  run_to(traced, t, 0.2);
  const cip::HostGasFields a = plain.to_host(), b = traced.to_host();
  // A passive scalar: density, energy and velocity are the untraced run's to the byte.
  CHECK(same_bytes(a.rho, b.rho));
  CHECK(same_bytes(a.e, b.e));
  CHECK(same_bytes(a.u, b.u));
  REQUIRE(b.traced.size() == b.rho.size());
  // The traced mass: what is in the tube plus what left through its ends (none reaches them by t = 0.2).
  const double m1 = traced.totals().products_mass + traced.boundary_outflow().products_mass;
  const std::vector<double> Y = strip(b, b.traced, Axis::x);
  const double lo = *std::min_element(Y.begin(), Y.end()), hi = *std::max_element(Y.begin(), Y.end());
  // The contact: where the traced fraction crosses 1/2, against Toro's exact contact at 0.5 + u* t.
  const ExactRiemann exact({1.0, 0.0, 1.0}, {0.125, 0.0, 0.1}, 1.4);
  const double x_exact = 0.5 + exact.u_star() * t, dx = 1.0 / n;
  double x_half = -1;
  for (int i = 1; i < n; ++i)
    if (Y[i - 1] >= 0.5 && Y[i] < 0.5) x_half = (i - 0.5 + (Y[i - 1] - 0.5) / (Y[i - 1] - Y[i])) * dx;
  // The traced gas's equivalent sharp front: where the mass from the tube's left end equals the traced mass
  // (the smearing moves the Y = 1/2 crossing towards the lighter gas, not this).
  const std::vector<double> rho = strip(b, b.rho, Axis::x);
  const double traced_mass = std::accumulate(Y.begin(), Y.end(), 0.0, [&, k = 0](double acc, double y) mutable {
    return acc + y * rho[k++] * dx;
  });
  double x_mass = -1, cumulative = 0;
  for (int i = 0; i < n && x_mass < 0; ++i) {
    if (cumulative + rho[i] * dx >= traced_mass) x_mass = (i + (traced_mass - cumulative) / (rho[i] * dx)) * dx;
    cumulative += rho[i] * dx;
  }
  // Width of the traced front: cells with 0.05 < Y < 0.95 (first-order upwind smears it as sqrt of the steps).
  const long smeared = std::count_if(Y.begin(), Y.end(), [](double y) { return y > 0.05 && y < 0.95; });
  std::printf("G13 tracer on Sod (%d cells, t = %.1f): traced mass %.15e -> %.15e (%.1e); fraction in [%.3e, %.16f]; "
              "exact contact at %.5f; traced mass front at %.5f (%+.2f cells), Y = 1/2 at %.5f (%+.2f cells); %ld cells "
              "between 0.05 and 0.95\n",
              n, t, m0, m1, m1 / m0 - 1, lo, hi, x_exact, x_mass, (x_mass - x_exact) / dx, x_half,
              (x_half - x_exact) / dx, smeared);
  CHECK(std::fabs(m1 / m0 - 1) < 1e-12);
  CHECK(lo >= -1e-12);
  CHECK(hi <= 1 + 1e-12);
  CHECK(std::fabs(x_mass - x_exact) < 0.5 * dx);
  CHECK(std::fabs(x_half - x_exact) < 2 * dx);

  // A closed tube (walls): the shock and the rarefaction reflect for 2 time units; nothing leaves, and the
  // traced mass stays to round-off.
  cip::GasSolver closed = traced_sod(100, true, cip::BoundaryKind::wall);
  const double c0 = closed.totals().products_mass;
  run_to(closed, 2.0, 0.2);
  const cip::HostGasFields h = closed.to_host();
  const double c1 = closed.totals().products_mass;
  const double y_lo = *std::min_element(h.traced.begin(), h.traced.end());
  const double y_hi = *std::max_element(h.traced.begin(), h.traced.end());
  std::printf("G13 tracer in a closed tube (100 cells, t = 2): traced mass %.1e relative change; fraction in "
              "[%.3e, %.16f]\n", c1 / c0 - 1, y_lo, y_hi);
  CHECK(std::fabs(c1 / c0 - 1) < 1e-12);
  CHECK(y_lo >= -1e-12);
  CHECK(y_hi <= 1 + 1e-12);
}
