//! \file test_explosion2d.cpp
//! \brief docs/validation.md G2: Toro's 2-D cylindrical explosion against an independent high-resolution radial solution.
#include "catch.hpp"
#include "validation_courant.hpp"
#include "gas_cases.hpp"
#include "radial_reference.hpp"

using namespace blastsim;
using namespace blastsim::test;

namespace {

struct ExplosionResult {
  double l1;           // mean |rho - rho_ref| over the domain
  double ray_max_dev;  // max over smooth radii of |profile(45 or 90 deg) - profile(0 deg)| / jump
  double ray_max_radius; // where that maximum sits
  double ray_mean_dev; // mean of the same
  double shock_radius; // along 0 deg, where rho crosses (rho_shock_peak + 0.125)/2 outermost
};

//! Outermost radius where rho falls through the mid value between the ambient 0.125 and the post-shock
//! peak (the maximum over 0.7 < r < 0.95, between the contact near 0.6 and the shock); rho sampled at r = k h.
double shock_radius(const std::vector<double>& rho, double h) {
  double peak = 0;
  for (size_t k = 0; k < rho.size(); ++k)
    if (k * h > 0.7 && k * h < 0.95) peak = std::fmax(peak, rho[k]);
  const double mid = 0.5 * (peak + 0.125);
  for (size_t k = rho.size() - 1; k > 0; --k)
    if (k * h < 0.95 && rho[k - 1] >= mid && rho[k] < mid)
      return (k - 1 + (rho[k - 1] - mid) / (rho[k - 1] - rho[k])) * h;
  return 0;
}

ExplosionResult run_explosion(int n, const RadialProfile& ref) {
  // Toro sec. 17.1: rho = 1, p = 1 for r < 0.4; rho = 0.125, p = 0.1 outside; [-1, 1]^2, gamma 1.4, t = 0.25.
  const cip::EquationOfState eos = cip::EquationOfState::ideal(1.4);
  cip::GasSolver s(cip::GasGrid::from_box(n, n, -1, 1, -1, 1), eos);
  s.initialise([&](double x, double y) {
    const bool in = x * x + y * y < 0.16;
    const double rho = in ? 1.0 : 0.125, p = in ? 1.0 : 0.1;
    return cip::GasPoint{rho, eos.internal_energy(rho, p), 0.0, 0.0};
  });
  run_to(s, 0.25, blastsim::test::validation_courant(s.options().transport));
  const cip::HostGasFields h = s.to_host();
  ExplosionResult r{0, 0, 0, 0, 0};
  const cip::GasGrid& g = s.grid();
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i)
      r.l1 += std::fabs(h.rho[static_cast<size_t>(j) * n + i] - ref.density_at(std::hypot(g.cell_x(i), g.cell_y(j))));
  r.l1 /= static_cast<double>(n) * n;
  // Rays at 0, 45 and 90 degrees, sampled every half cell up to r = 0.95.
  const int m = static_cast<int>(0.95 / (0.5 * g.dx));
  std::vector<std::array<double, 2>> pts;
  for (double ang : {0.0, 45.0, 90.0})
    for (int k = 0; k < m; ++k) {
      const double rad = k * 0.5 * g.dx, a = ang * M_PI / 180;
      pts.push_back({rad * std::cos(a), rad * std::sin(a)});
    }
  const std::vector<cip::GasSample> smp = s.sample(pts);
  const double jump = 1.0 - 0.125;
  for (int ray = 1; ray < 3; ++ray)
    for (int k = 0; k < m; ++k) {
      const double d = std::fabs(smp[ray * m + k].rho - smp[k].rho) / jump;
      r.ray_mean_dev += d / (2 * m);
      // Pointwise agreement is asked of the smooth parts: skip points within 3 cells of a jump of the
      // reference (the contact near r = 0.6 and the shock at 0.813), where the smeared profiles differ.
      const double rad = k * 0.5 * g.dx, w = 3 * g.dx;
      if (std::fabs(ref.density_at(rad + w) - ref.density_at(std::fmax(rad - w, 0.0))) > 0.05 * jump) continue;
      if (d > r.ray_max_dev) r.ray_max_dev = d, r.ray_max_radius = rad;
    }
  std::vector<double> ray0(m);
  for (int k = 0; k < m; ++k) ray0[k] = smp[k].rho;
  r.shock_radius = shock_radius(ray0, 0.5 * g.dx);
  return r;
}

}  // namespace

TEST_CASE("G2 cylindrical explosion: rays agree and density matches the radial reference", "[long][cip][G2]") {
  // Reference: 1-D cylindrical finite volumes on 6000 cells over [0, 1.5] (covers the corners r = sqrt 2).
  const RadialProfile ref = solve_radial(6000, 1.5, 1.4, 0.25, [](double r) { return r < 0.4 ? 1.0 : 0.125; },
                                         [](double r) { return r < 0.4 ? 1.0 : 0.1; });
  // Toro reports the main shock at r = 0.813 at t = 0.25; the reference must agree before it is trusted.
  std::vector<double> ref_ray;
  const double h_ref = 1.5 / ref.rho.size();
  for (size_t k = 0; k < ref.rho.size(); ++k) ref_ray.push_back(ref.density_at(k * h_ref));
  const double ref_shock = shock_radius(ref_ray, h_ref);
  CHECK_THAT(ref_shock, WithinAbs(0.813, 0.004));

  double previous = 1;
  for (int n : {100, 200, 400}) {
    const ExplosionResult r = run_explosion(n, ref);
    std::printf("G2 explosion %dx%d: L1(rho) = %.3e, shock at r = %.4f (reference %.4f), ray deviation mean %.2f %% "
                "max (smooth parts) %.2f %% of the jump (at r = %.3f)\n",
                n, n, r.l1, r.shock_radius, ref_shock, 100 * r.ray_mean_dev, 100 * r.ray_max_dev,
                r.ray_max_radius);
    CHECK(r.l1 < previous);
    previous = r.l1;
    if (n == 400) {
      CHECK(r.l1 <= 2.9e-3);                       // docs/validation.md G2 bound
      CHECK(r.ray_max_dev <= 0.02);                // rays agree within 2 % of the jump (smooth parts)
      CHECK(r.ray_mean_dev <= 0.02);               // and on average everywhere
      CHECK_THAT(r.shock_radius, WithinAbs(ref_shock, 0.01));
    }
  }
}
