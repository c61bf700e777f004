//! \file test_strong_shocks.cpp
//! \brief docs/validation.md G7 (cylindrical Sedov blast), strong-shock convergence, and the conservative vs
//! paper transport side by side (the figures of docs/gas-solver.md).
#include "catch.hpp"
#include "validation_courant.hpp"
#include "gas_cases.hpp"

using namespace blastsim;
using namespace blastsim::test;

namespace {

struct SedovResult {
  double shock_radius;  // radius of the maximum of the angle-averaged density
  double energy_ratio;  // total energy at t = 1 / initial
  double peak_density;  // maximum of the angle-averaged density
};

//! Cylindrical Sedov blast (docs/validation.md G7): E = 1 per unit length deposited as internal energy in the
//! cells within 3.5 dx of the centre, rho0 = 1, background p = 1e-5, gamma 1.4, t = 1, on [-1.2, 1.2]^2.
SedovResult sedov(int n, cip::Transport transport) {
  const cip::EquationOfState eos = cip::EquationOfState::ideal(1.4);
  cip::GasSolverOptions opt;
  opt.transport = transport;
  opt.viscosity = cip::recommended_viscosity(transport);
  const double L = 1.2, dx = 2 * L / n, r_dep = 3.5 * dx;
  cip::GasSolver s(cip::GasGrid::from_box(n, n, -L, L, -L, L), eos, opt);
  int cells = 0;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i)
      if (std::hypot(s.grid().cell_x(i), s.grid().cell_y(j)) < r_dep) ++cells;
  const double e_dep = 1.0 / (cells * dx * dx), e_bg = eos.internal_energy(1.0, 1e-5);
  s.initialise([&](double x, double y) {
    return cip::GasPoint{1.0, std::hypot(x, y) < r_dep ? e_dep + e_bg : e_bg, 0.0, 0.0};
  });
  const double E0 = s.totals().total_energy();
  run_to(s, 1.0, blastsim::test::validation_courant(s.options().transport));
  const cip::HostGasFields h = s.to_host();
  std::vector<double> sum(n / 2, 0.0), count(n / 2, 0.0);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const size_t b = static_cast<size_t>(std::hypot(s.grid().cell_x(i), s.grid().cell_y(j)) / dx);
      if (b < sum.size()) sum[b] += h.rho[static_cast<size_t>(j) * n + i], count[b] += 1;
    }
  SedovResult r{0, s.totals().total_energy() / E0, 0};
  for (size_t b = 0; b < sum.size(); ++b)
    if (count[b] > 0 && sum[b] / count[b] > r.peak_density) r.peak_density = sum[b] / count[b], r.shock_radius = (b + 0.5) * dx;
  return r;
}

//! Shock position error [m] of the paper's seed states (Table 1) at t = 0.6 m / shock speed, n cells.
double seed_shock_error(int n, cip::Transport transport) {
  const cip::EquationOfState eos = cip::EquationOfState::ideal(1.4);
  const Primitive L{163.0, 0.0, eos.pressure(163.0, 4.29e5)}, R{1.20, 0.0, eos.pressure(1.20, 2.09e5)};
  cip::GasSolverOptions opt;
  opt.transport = transport;
  opt.viscosity = cip::recommended_viscosity(transport);
  cip::GasSolver s = make_shock_tube(n, Axis::x, L, R, 0.2, 1.0, 1.4, opt);
  const ExactRiemann exact(L, R, 1.4);
  const double t = 0.6 / exact.right_shock_speed();
  run_to(s, t, blastsim::test::validation_courant(s.options().transport));
  const std::vector<double> p = strip(s.to_host(), s.to_host().p, Axis::x);
  const double mid = 0.5 * (exact.p_star() + R.p);
  for (int i = n - 1; i > 0; --i)
    if (p[i - 1] >= mid && p[i] < mid)
      return std::fabs((i - 0.5 + (p[i - 1] - mid) / (p[i - 1] - p[i])) / n - 0.8);
  return 1.0;
}

}  // namespace

TEST_CASE("G7 cylindrical Sedov blast: shock radius and energy (conservative transport)", "[long][cip][G7]") {
  const double exact = 1.00402;  // xi0 (E t^2 / rho0)^(1/4) with E = rho0 = t = 1
  double previous_peak = 0;
  for (int n : {120, 240}) {
    const SedovResult r = sedov(n, cip::Transport::conservative);
    std::printf("G7 Sedov %dx%d (conservative): shock radius %.4f (exact %.4f, %+.2f %%), energy %.6f of initial, "
                "peak density %.2f (limit 6)\n",
                n, n, r.shock_radius, exact, 100 * (r.shock_radius / exact - 1), r.energy_ratio, r.peak_density);
    CHECK_THAT(r.shock_radius, WithinRel(exact, 0.02));
    CHECK_THAT(r.energy_ratio, WithinAbs(1.0, 0.01));
    CHECK(r.peak_density > previous_peak);  // approaching 6 rho0 with resolution
    previous_peak = r.peak_density;
  }
}

TEST_CASE("Strong shock: position error of the 277:1 seed-state shock falls with resolution", "[long][cip][G7][convergence]") {
  const double e1 = seed_shock_error(200, cip::Transport::conservative);
  const double e2 = seed_shock_error(400, cip::Transport::conservative);
  const double e3 = seed_shock_error(800, cip::Transport::conservative);
  std::printf("277:1 shock position error (conservative): %.2e / %.2e / %.2e m at 200 / 400 / 800 cells\n", e1, e2, e3);
  CHECK(e2 < e1);
  CHECK(e3 < e2);
}

TEST_CASE("Paper's transport against the conservative one on the strong-shock cases (reported)",
          "[long][cip][G7][compare]") {
  const SedovResult paper = sedov(120, cip::Transport::paper);
  const SedovResult cons = sedov(120, cip::Transport::conservative);
  std::printf("G7 Sedov 120x120: paper's transport radius %.4f energy %.4f; conservative radius %.4f energy %.6f\n",
              paper.shock_radius, paper.energy_ratio, cons.shock_radius, cons.energy_ratio);
  const double ep = seed_shock_error(800, cip::Transport::paper), ec = seed_shock_error(800, cip::Transport::conservative);
  std::printf("277:1 shock position error at 800 cells: paper's transport %.2e m, conservative %.2e m\n", ep, ec);
  // The point of the conservative transport: it keeps the blast energy the paper's form loses.
  CHECK(std::fabs(cons.energy_ratio - 1) < std::fabs(paper.energy_ratio - 1));
  CHECK(ec < ep);
}
