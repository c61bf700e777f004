//! \file test_shock_tube.cpp
//! \brief docs/validation.md G1 (Sod, along x and y) and G6 (the paper's seed states) against the exact Riemann solution.
#include "catch.hpp"
#include "validation_courant.hpp"
#include "gas_cases.hpp"

using namespace blastsim;
using namespace blastsim::test;

namespace {

//! Density L1 error (mean absolute error over the unit tube) of Sod at t = 0.2 with n cells.
double sod_l1(int n, Axis axis) {
  const Primitive L{1.0, 0.0, 1.0}, R{0.125, 0.0, 0.1};
  cip::GasSolver s = make_shock_tube(n, axis, L, R, 0.5);
  const double t = 0.2;
  run_to(s, t, blastsim::test::validation_courant(s.options().transport));
  const ExactRiemann exact(L, R, 1.4);
  const std::vector<double> rho = strip(s.to_host(), s.to_host().rho, axis);
  double err = 0;
  for (int i = 0; i < n; ++i) err += std::fabs(rho[i] - exact.sample(((i + 0.5) / n - 0.5) / t).rho);
  return err / n;
}

}  // namespace

TEST_CASE("G1 Sod shock tube: density L1 error against Toro's exact solution", "[cip][G1][heavy]") {
  // Toro's star values (docs/validation.md) check the exact solver itself first.
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
    CHECK(e400 <= 2.1e-3);  // docs/validation.md G1 bound
    CHECK(e200 < e100);     // falling as cells double
    CHECK(e400 < e200);
  }
  // Same answer along x and y (the scheme is symmetric in its axes).
  CHECK_THAT(sod_l1(200, Axis::x), WithinRel(sod_l1(200, Axis::y), 1e-10));
}

namespace {

//! Position of the rightmost point where the pressure crosses the mid value between p_lo and p_hi.
double shock_position(const std::vector<double>& p, double p_mid, double dx) {
  for (int i = static_cast<int>(p.size()) - 1; i > 0; --i) {
    if (p[i - 1] >= p_mid && p[i] < p_mid) return (i - 0.5 + (p[i - 1] - p_mid) / (p[i - 1] - p[i])) * dx;
  }
  return -1;
}

}  // namespace

TEST_CASE("G6 the paper's seed states (Table 1): positive, finite, exact shock speed", "[long][cip][G6]") {
  // Table 1: 163 kg/m3 at 4.29e5 J/kg (28 MPa) against 1.20 kg/m3 at 2.09e5 J/kg (0.1 MPa); gamma 1.4.
  const cip::EquationOfState eos = cip::EquationOfState::ideal(1.4);
  const Primitive L{163.0, 0.0, eos.pressure(163.0, 4.29e5)}, R{1.20, 0.0, eos.pressure(1.20, 2.09e5)};
  CHECK_THAT(L.p, WithinRel(2.80e7, 0.01));
  CHECK_THAT(R.p, WithinRel(1.01e5, 0.01));
  const ExactRiemann exact(L, R, 1.4);
  const int n = 800;
  const double length = 1.0;  // [m]
  cip::GasSolver s = make_shock_tube(n, Axis::x, L, R, 0.2, length);
  const double p_mid = 0.5 * (exact.p_star() + R.p);
  const double t1 = 0.3 / exact.right_shock_speed(), t2 = 0.7 / exact.right_shock_speed();
  double x1 = 0, x2 = 0, rho_min = 1e300, e_min = 1e300;
  for (double t_stop : {t1, t2}) {
    while (s.time() < t_stop * (1 - 1e-12)) {
      run_to(s, std::fmin(t_stop, s.time() + 0.02 * t1), blastsim::test::validation_courant(s.options().transport));
      const cip::HostGasFields h = s.to_host();
      for (size_t k = 0; k < h.rho.size(); ++k) {
        REQUIRE(std::isfinite(h.rho[k]));
        REQUIRE(std::isfinite(h.e[k]));
        rho_min = std::fmin(rho_min, h.rho[k]);
        e_min = std::fmin(e_min, h.e[k]);
      }
    }
    const cip::HostGasFields h = s.to_host();
    (t_stop == t1 ? x1 : x2) = shock_position(strip(h, h.p, Axis::x), p_mid, length / n);
  }
  const double speed = (x2 - x1) / (t2 - t1);
  std::printf("G6 seed states: shock speed %.1f m/s (exact %.1f, error %.2f %%); min rho %.3f kg/m3, min e %.3e J/kg\n",
              speed, exact.right_shock_speed(), 100 * (speed / exact.right_shock_speed() - 1), rho_min, e_min);
  CHECK(rho_min > 0);
  CHECK(e_min > 0);
  CHECK_THAT(speed, WithinRel(exact.right_shock_speed(), 0.02));
}

TEST_CASE("Mask interface: a wall placed through the immersed-boundary input reflects a shock exactly",
          "[cip][mask][heavy]") {
  // Sod's states; a solid block fills x > 0.75 through the mask (inactive cells, faces held at u = 0).
  const Primitive L{1.0, 0.0, 1.0}, R{0.125, 0.0, 0.1};
  const double wall = 0.75;
  const int n = 400;
  cip::GasSolver masked = make_shock_tube(n, Axis::x, L, R, 0.5);
  cip::mark_static_solid(masked, [=](double x, double) { return x >= wall - 1e-12; });
  // The same tube ending in a real reflective wall at x = 0.75.
  cip::GasSolverOptions opt;
  cip::GasSolver walled = make_shock_tube(300, Axis::x, L, R, 0.5, 0.75);
  {
    // make_shock_tube sets outflow at the tube ends; rebuild with a wall on the right.
    opt.boundaries = cip::BoundaryConditions::all(cip::BoundaryKind::wall).set(cip::left, cip::BoundaryKind::outflow);
    const cip::EquationOfState eos = cip::EquationOfState::ideal(1.4);
    walled = cip::GasSolver(cip::GasGrid::from_box(300, 3, 0, 0.75, 0, 3 * 0.75 / 300), eos, opt);
    walled.initialise([&](double x, double) {
      const Primitive& q = x < 0.5 ? L : R;
      return cip::GasPoint{q.rho, eos.internal_energy(q.rho, q.p), 0.0, 0.0};
    });
  }
  // Exact: state 2 behind the incident shock hits the wall; the reflected shock brings it to rest at p5.
  const ExactRiemann exact(L, R, 1.4);
  const Primitive s2{exact.rho_star_right(), exact.u_star(), exact.p_star()};
  const double p5 = ExactRiemann::reflected_shock_pressure(s2, 1.4);
  const double r = (p5 / s2.p), m = 0.4 / 2.4;
  const double rho5 = s2.rho * (r + m) / (m * r + 1);
  const double w_reflected = s2.rho * s2.u / (s2.rho - rho5);  // < 0: moves back from the wall
  const double t_hit = (wall - 0.5) / exact.right_shock_speed();
  const double t = t_hit + 0.04 / std::fabs(w_reflected);  // reflected shock 0.04 m from the wall
  REQUIRE(0.5 + exact.u_star() * t < wall - 0.06);          // the contact has not yet met it
  run_to(masked, t, blastsim::test::validation_courant(masked.options().transport));
  run_to(walled, t, blastsim::test::validation_courant(walled.options().transport));
  const std::vector<double> pm = strip(masked.to_host(), masked.to_host().p, Axis::x);
  const std::vector<double> pw = strip(walled.to_host(), walled.to_host().p, Axis::x);
  // Mean pressure over the cells within 0.025 m of the wall (behind the reflected shock).
  double sum_m = 0, sum_w = 0;
  int count = 0;
  for (int i = 0; i < 300; ++i) {
    const double x = (i + 0.5) / n;
    if (x > wall - 0.025 && x < wall) {
      sum_m += pm[i];
      sum_w += pw[i];
      ++count;
    }
  }
  const double pmask = sum_m / count, pwall = sum_w / count;
  std::printf("mask wall: reflected-shock pressure %.5f (masked) %.5f (boundary wall) exact %.5f\n", pmask, pwall,
              p5);
  CHECK_THAT(pmask, WithinRel(p5, 0.03));
  CHECK_THAT(pwall, WithinRel(p5, 0.03));
  CHECK_THAT(pmask, WithinRel(pwall, 0.01));
  // The inactive cells were not advanced: still the initial right state.
  const cip::HostGasFields hm = masked.to_host();
  CHECK(hm.rho[static_cast<size_t>(n) + n - 2] == R.rho);
}
