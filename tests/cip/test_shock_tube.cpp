//! \file test_shock_tube.cpp
//! \brief validation.md G1 (Sod, along x and y) and G6 (the paper's seed states) against the exact Riemann solution.
#include "catch.hpp"
#include "gas_cases.hpp"

using namespace blastsim;
using namespace blastsim::test;

namespace {

//! Density L1 error (mean absolute error over the unit tube) of Sod at t = 0.2 with n cells.
double sod_l1(int n, Axis axis) {
  const Primitive L{1.0, 0.0, 1.0}, R{0.125, 0.0, 0.1};
  cip::GasSolver s = make_shock_tube(n, axis, L, R, 0.5);
  const double t = 0.2;
  run_to(s, t, 0.1);
  const ExactRiemann exact(L, R, 1.4);
  const std::vector<double> rho = strip(s.to_host(), s.to_host().rho, axis);
  double err = 0;
  for (int i = 0; i < n; ++i) err += std::fabs(rho[i] - exact.sample(((i + 0.5) / n - 0.5) / t).rho);
  return err / n;
}

}  // namespace

TEST_CASE("G1 Sod shock tube: density L1 error against Toro's exact solution", "[cip][G1]") {
  // Toro's star values (validation.md) check the exact solver itself first.
  const ExactRiemann exact({1.0, 0.0, 1.0}, {0.125, 0.0, 0.1}, 1.4);
  CHECK_THAT(exact.p_star(), WithinAbs(0.30313, 5e-5));
  CHECK_THAT(exact.u_star(), WithinAbs(0.92745, 5e-5));
  CHECK_THAT(exact.rho_star_left(), WithinAbs(0.42632, 5e-5));
  CHECK_THAT(exact.rho_star_right(), WithinAbs(0.26557, 5e-5));
  CHECK_THAT(exact.right_shock_speed(), WithinAbs(1.75216, 5e-5));

  for (Axis axis : {Axis::x, Axis::y}) {
    const double e100 = sod_l1(100, axis), e200 = sod_l1(200, axis), e400 = sod_l1(400, axis);
    std::printf("G1 Sod along %s: L1(rho) = %.3e (100) %.3e (200) %.3e (400) cells\n", axis == Axis::x ? "x" : "y",
                e100, e200, e400);
    CHECK(e400 <= 2.1e-3);  // validation.md G1 bound
    CHECK(e200 < e100);     // falling as cells double
    CHECK(e400 < e200);
  }
  // Same answer along x and y (the scheme is symmetric in its axes).
  CHECK_THAT(sod_l1(200, Axis::x), WithinRel(sod_l1(200, Axis::y), 1e-10));
}
