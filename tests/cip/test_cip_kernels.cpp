//! \file test_cip_kernels.cpp
//! \brief Unit checks of the CIP point formulas: exact reproduction of cubics, limiter bounds, viscosity, ghost rules.
#include "blastsim/cip/boundary.hpp"
#include "blastsim/cip/cip_kernels.hpp"
#include "catch.hpp"

using namespace blastsim::cip;

namespace {
// An arbitrary full cubic in x and y and its gradient.
double cubic(double x, double y) {
  return 0.3 + 1.1 * x - 0.7 * y + 0.5 * x * x - 0.9 * x * y + 0.4 * y * y + 0.8 * x * x * x - 0.6 * x * x * y +
         0.35 * x * y * y - 0.45 * y * y * y;
}
double cubic_x(double x, double y) { return 1.1 + x - 0.9 * y + 2.4 * x * x - 1.2 * x * y + 0.35 * y * y; }
double cubic_y(double x, double y) { return -0.7 - 0.9 * x + 0.8 * y - 0.6 * x * x + 0.7 * x * y - 1.35 * y * y; }
CipPoint at(double x, double y) { return {cubic(x, y), cubic_x(x, y), cubic_y(x, y)}; }
}  // namespace

TEST_CASE("2-D CIP reproduces any cubic polynomial exactly, for every upwind direction", "[cip][kernels]") {
  const double dx = 0.1, dy = 0.07, dt = 0.01;
  for (double u : {0.8, -1.3})
    for (double v : {0.6, -0.9}) {
      const double Dx = u >= 0 ? -dx : dx, Dy = v >= 0 ? -dy : dy;
      const UpwindBlock b{at(0, 0), at(Dx, 0), at(0, Dy), at(Dx, Dy)};
      const double X = -u * dt, Y = -v * dt;
      const CipPoint p = cip_advect_2d(b, Dx, Dy, X, Y, Limiter::none);
      CHECK_THAT(p.f, WithinAbs(cubic(X, Y), 1e-13));
      CHECK_THAT(p.gx, WithinAbs(cubic_x(X, Y), 1e-12));
      CHECK_THAT(p.gy, WithinAbs(cubic_y(X, Y), 1e-12));
    }
}

TEST_CASE("1-D CIP reproduces a cubic exactly and its limiter keeps values inside the upwind range",
          "[cip][kernels]") {
  auto f = [](double x) { return 2 - x + 3 * x * x - 5 * x * x * x; };
  auto g = [](double x) { return -1 + 6 * x - 15 * x * x; };
  const double D = -0.2, xi = -0.05;
  const CipPoint p = cip_advect_1d(f(0), g(0), f(D), g(D), D, xi, Limiter::none);
  CHECK_THAT(p.f, WithinAbs(f(xi), 1e-14));
  CHECK_THAT(p.gx, WithinAbs(g(xi), 1e-13));
  // A step with steep derivatives overshoots without the limiter and stays bounded with it.
  const CipPoint raw = cip_advect_1d(1.0, 0.0, 0.0, 40.0, D, -0.1, Limiter::none);
  const CipPoint lim = cip_advect_1d(1.0, 0.0, 0.0, 40.0, D, -0.1, Limiter::minmax);
  CHECK_THAT(raw.f, WithinAbs(1.5, 1e-12));  // overshoots by half the jump
  CHECK_THAT(lim.f, WithinAbs(0.5, 1e-12));  // linear interpolation half-way
  CHECK(lim.f >= 0.0);
  CHECK(lim.f <= 1.0);
}

TEST_CASE("2-D limiter falls back to bilinear interpolation only outside the block range", "[cip][kernels]") {
  const double dx = 0.1, dy = 0.1;
  const UpwindBlock jump{{1.0, 0.0, 0.0}, {0.0, 60.0, 0.0}, {1.0, 0.0, 0.0}, {0.0, 60.0, 0.0}};
  const CipPoint lim = cip_advect_2d(jump, -dx, -dy, -0.03, -0.02, Limiter::minmax);
  CHECK(lim.f >= 0.0);
  CHECK(lim.f <= 1.0);
  // Bilinear value at 30 % of the way to the upwind column: 0.7.
  const CipPoint raw = cip_advect_2d(jump, -dx, -dy, -0.03, -0.02, Limiter::none);
  CHECK_THAT(raw.f, WithinAbs(1.162, 1e-12));  // the cubic overshoots (1-D in x: a = 4000, b = 300)
  CHECK_THAT(lim.f, WithinAbs(0.7, 1e-14));
  // Inside the range the limiter leaves the cubic alone.
  const UpwindBlock smooth{at(0, 0), at(-dx, 0), at(0, -dy), at(-dx, -dy)};
  CHECK(cip_advect_2d(smooth, -dx, -dy, -0.03, -0.02, Limiter::minmax).f ==
        cip_advect_2d(smooth, -dx, -dy, -0.03, -0.02, Limiter::none).f);
}

TEST_CASE("Artificial viscosity follows the paper's eq. (4)", "[cip][kernels]") {
  CHECK(artificial_viscosity(2.0, 300.0, 5.0, 1.0, 2.0) == 0.0);  // expansion: none
  // rho = 2, c = 300, dU = -5: q = c1 rho c |dU| + c2 rho dU^2 = 1*2*300*5 + 2*2*25 = 3100.
  CHECK_THAT(artificial_viscosity(2.0, 300.0, -5.0, 1.0, 2.0), WithinRel(3100.0, 1e-15));
  CHECK(velocity_jump(1.0, 3.0, 2.0, -1.0) == -1.0);
}

TEST_CASE("Ghost rules: outflow copies, wall mirrors with odd normal velocity, periodic wraps", "[cip][kernels]") {
  const int n = 10;
  // Cell-centred, left side.
  GhostSource s = ghost_source(-1, n, false, BoundaryKind::outflow, 1.0);
  CHECK(s.source == 0);
  CHECK(s.normal_factor == 0.0);
  s = ghost_source(n + 2, n, true, BoundaryKind::outflow, -1.0);  // beyond an outflow face: copy of it
  CHECK(s.source == n);
  CHECK(s.value_factor == 1.0);
  s = ghost_source(-2, n, false, BoundaryKind::wall, 1.0);
  CHECK(s.source == 1);
  CHECK(s.normal_factor == -1.0);
  s = ghost_source(n + 1, n, false, BoundaryKind::periodic, 1.0);
  CHECK(s.source == 1);
  // Normal velocity on faces: zero on the wall face, odd mirror beyond it.
  s = ghost_source(n, n, true, BoundaryKind::wall, -1.0);
  CHECK(s.value_factor == 0.0);
  s = ghost_source(n + 2, n, true, BoundaryKind::wall, -1.0);
  CHECK(s.source == n - 2);
  CHECK(s.value_factor == -1.0);
  CHECK(s.normal_factor == 1.0);
  s = ghost_source(-1, n, true, BoundaryKind::periodic, -1.0);
  CHECK(s.source == n - 1);
}
