//! \file test_step_kernels.cpp
//! \brief The gas step's kernels (gas_step_kernels.hpp, transport_kernels.hpp) called directly on a few cells of
//! host arrays, against what each formula must give on states where the answer is known exactly.
#include "blastsim/cip/gas_step_kernels.hpp"
#include "blastsim/cip/transport_kernels.hpp"
#include "catch.hpp"

#include <cmath>
#include <cstdio>
#include <vector>

using namespace blastsim;
using namespace blastsim::cip;

namespace {
//! Host storage of a whole gas state on a small grid, with its views.
struct HostState {
  GasGrid grid;
  PaddedShape shape;
  std::vector<std::vector<double>> a;  // 12 arrays: rho, e, u, v, each f, gx, gy
  explicit HostState(int n) : grid(GasGrid::from_box(n, n, 0, 1, 0, 1)), shape(grid.padded_shape()), a(12) {
    for (auto& v : a) v.assign(shape.size(), 0.0);
  }
  Field2D<double> field(int k) { return Field2D<double>{a[k].data(), shape}; }
  CipFieldView unknown(int k) { return {field(3 * k), field(3 * k + 1), field(3 * k + 2)}; }
  GasStateView view() { return {unknown(0), unknown(1), unknown(2), unknown(3)}; }
  //! Sets every point (ghosts included) of unknown k to f(x, y) of the point's index and its gradient.
  template <class F, class G>
  void set(int k, F f, G grad) {
    for (int j = -shape.ghost; j < shape.nj + shape.ghost; ++j)
      for (int i = -shape.ghost; i < shape.ni + shape.ghost; ++i) {
        const double x = i * grid.dx, y = j * grid.dy;
        field(3 * k)(i, j) = f(x, y);
        const auto g = grad(x, y);
        field(3 * k + 1)(i, j) = g[0];
        field(3 * k + 2)(i, j) = g[1];
      }
  }
};
}  // namespace

TEST_CASE("Gas kernels: the derivative update adds the gradient of the change exactly", "[cip][kernels]") {
  // Yabe, Xiao & Utsumi 2001, sec. 4: g* = g + grad(f* - f) - dt (g . grad u). With a frozen velocity field the
  // last term vanishes and a linear change a x + b y adds (a, b) to every derivative.
  HostState old(6), now(6);
  const double a = 0.7, b = -1.3;
  auto base = [](double x, double y) { return 1.0 + 0.2 * x * x - 0.4 * y; };
  auto base_grad = [](double x, double y) { return std::array<double, 2>{0.4 * x, -0.4 + 0.0 * y}; };
  old.set(0, base, base_grad);
  now.set(0, [&](double x, double y) { return base(x, y) + a * x + b * y; }, base_grad);
  for (int j = 1; j < 5; ++j)
    for (int i = 1; i < 5; ++i) {
      update_derivatives(old.view().rho, now.view().rho, i, j, old.grid.dx, old.grid.dy, 1e-3, 0, 0, 0, 0);
      const auto g = base_grad(i * old.grid.dx, j * old.grid.dy);
      CHECK_THAT(now.field(1)(i, j), Catch::Matchers::WithinAbs(g[0] + a, 1e-12));
      CHECK_THAT(now.field(2)(i, j), Catch::Matchers::WithinAbs(g[1] + b, 1e-12));
    }
}

TEST_CASE("Gas kernels: pressure is p(rho, e) without a velocity jump, and the viscosity acts in compression",
          "[cip][kernels]") {
  // Paper eqs. (4)-(5): q = 0 unless the cell is compressed (dU < 0).
  HostState s(4);
  const EquationOfState eos = EquationOfState::ideal(1.4);
  s.set(0, [](double, double) { return 1.2; }, [](double, double) { return std::array<double, 2>{0, 0}; });
  s.set(1, [](double, double) { return 2.0e5; }, [](double, double) { return std::array<double, 2>{0, 0}; });
  std::vector<double> P(s.shape.size(), 0.0);
  std::vector<std::uint8_t> active(s.shape.size(), 1);
  GasMaterials one;
  one.air = eos;
  const PressureKernel k{s.view(), MaterialReadView{}, Field2D<const std::uint8_t>{active.data(), s.shape},
                         Field2D<double>{P.data(), s.shape}, one, 1.0, 2.0};
  k(1, 1);
  CHECK(P[s.shape.offset(1, 1)] == eos.pressure(1.2, 2.0e5));
  // A compressing cell: u drops across it by 10 m/s.
  s.field(6)(2, 2) = 5.0, s.field(6)(3, 2) = -5.0;
  k(2, 2);
  const double dU = velocity_jump(5.0, -5.0, 0.0, 0.0);
  CHECK(dU == -10.0);
  const double q = artificial_viscosity(1.2, eos.sound_speed(1.2, 2.0e5), dU, 1.0, 2.0);
  CHECK(q > 0);
  CHECK_THAT(P[s.shape.offset(2, 2)], Catch::Matchers::WithinRel(eos.pressure(1.2, 2.0e5) + q, 1e-15));
}

TEST_CASE("Gas kernels: the swept value of a linear profile is its value at the swept region's centre",
          "[cip][kernels][transport]") {
  // f = f_up + g_n s + g_t t over the region swept through the face in dt: width |w| dt along the normal,
  // centred (h - |w| dt)/2 downstream of the upwind cell centre, shifted -w_t dt / 2 across.
  const double f_up = 2.0, g_n = 0.5, g_t = -0.3, h = 0.1, dt = 0.01;
  for (double w : {3.0, -3.0}) {
    const double w_t = 1.5;
    const double centre_n = (w >= 0 ? 1.0 : -1.0) * 0.5 * (h - std::fabs(w) * dt);
    const double expected = f_up + g_n * centre_n + g_t * (-0.5 * w_t * dt);
    CHECK_THAT(swept_value(f_up, g_n, g_t, w, w_t, dt, h), Catch::Matchers::WithinAbs(expected, 1e-15));
  }
  // Slopes are kept where monotone between the smaller difference and twice it, raised to the smaller
  // difference (minmod), clipped to twice it, and zero at an extremum.
  CHECK(limited_slope(0.3, 0.2, 0.3) == 0.3);
  CHECK(limited_slope(0.1, 0.2, 0.3) == 0.2);
  CHECK(limited_slope(1.0, 0.2, 0.3) == 0.4);
  CHECK(limited_slope(0.1, 0.2, -0.3) == 0.0);
  // The curvature allowance is granted only at an extremum of the data: none on monotone data, none on a
  // plateau beside a jump (the seed of the contact spike of the earlier scheme), some at a smooth maximum.
  CHECK(extremum_slack(0.0, 0.5, 0.9, 1.0, 0.2) == 0.0);
  CHECK(extremum_slack(0.0, 0.9, 1.0, 1.0, 0.2) == 0.0);
  CHECK_THAT(extremum_slack(0.8, 1.0, 1.0, 0.8, 0.2), Catch::Matchers::WithinAbs(0.2 * 0.2, 1e-15));
  CHECK_THAT(mc_slope(0.2, 0.4), Catch::Matchers::WithinAbs(0.3, 1e-15));  // centred (0.2 + 0.4) / 2
  CHECK(mc_slope(0.1, 1.0) == 0.2);                  // twice the smaller difference
  CHECK(mc_slope(0.1, -1.0) == 0.0);
  // swept_mc() takes its three values along the flow: a linear profile q = x (cells at x = 1, 2, 3, h = 1)
  // gives the mean of q over the region swept through the face from cell 2 in either direction.
  const double wdt = 0.3;  // |w| dt [m]
  CHECK_THAT(swept_mc(1.0, 2.0, 3.0, 3.0, 0.1, 1.0), Catch::Matchers::WithinAbs(2.5 - 0.5 * wdt, 1e-15));
  CHECK_THAT(swept_mc(3.0, 2.0, 1.0, -3.0, 0.1, 1.0), Catch::Matchers::WithinAbs(1.5 + 0.5 * wdt, 1e-15));
}

TEST_CASE("Gas kernels: a face's kinetic-energy correction heats the cells on its two sides alike per kilogram",
          "[cip][kernels][transport]") {
  // The correction D [J/m3] of an interior face is the kinetic energy its dual cell (half of each neighbour)
  // lost in the momentum transport; shared by mass, both cells gain D / (rho_a + rho_b) [J/kg] and together D.
  // A face on a wall or beside an inactive cell gives all of its correction to the one gas cell.
  HostState s(4);
  const EquationOfState eos = EquationOfState::ideal(1.4);
  GasMaterials one;
  one.air = eos;
  const double rho[4] = {1.2, 4.0e-3, 1.2, 30.0}, e0 = 2.0e5;  // a near-vacuum cell between two dense ones
  for (int j = -s.shape.ghost; j < s.shape.nj + s.shape.ghost; ++j)
    for (int i = -s.shape.ghost; i < s.shape.ni + s.shape.ghost; ++i) {
      s.field(0)(i, j) = i >= 0 && i < 4 ? rho[i] : 1.0;
      s.field(3)(i, j) = e0;
    }
  std::vector<double> rho_e(s.shape.size()), Du(s.shape.size(), 0.0), Dv(s.shape.size(), 0.0), added(s.shape.size(), 0.0);
  std::vector<std::uint8_t> active(s.shape.size(), 1);
  const Field2D<double> RE{rho_e.data(), s.shape}, DU{Du.data(), s.shape}, DV{Dv.data(), s.shape};
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i) RE(i, j) = s.field(0)(i, j) * e0;
  const int j = 1;
  const double D1 = 300.0, D2 = 120.0, D0 = 50.0;  // faces x = 1 (cells 0|1), x = 2 (cells 1|2), x = 0 (wall|0)
  DU(1, j) = D1, DU(2, j) = D2, DU(0, j) = D0;
  const EnergyUpdateKernel k{s.view(), Field2D<const std::uint8_t>{active.data(), s.shape}, RE, DU, DV,
                             Field2D<double>{added.data(), s.shape}, 4, 4, false, false, one, MaterialView{},
                             Field2D<const double>{}};
  for (int i = 0; i < 3; ++i) k(i, j);
  const double de0 = s.field(3)(0, j) - e0, de1 = s.field(3)(1, j) - e0, de2 = s.field(3)(2, j) - e0;
  const double per_kg_1 = D1 / (rho[0] + rho[1]), per_kg_2 = D2 / (rho[1] + rho[2]);
  std::printf("Kinetic-energy heat: cells 1.2 | 0.004 | 1.2 kg/m3, faces 300 and 120 J/m3: de = %.6g, %.6g, %.6g "
              "J/kg (by mass %.6g + %.6g wall, %.6g + %.6g, %.6g)\n",
              de0, de1, de2, per_kg_1, D0 / rho[0], per_kg_1, per_kg_2, per_kg_2);
  CHECK_THAT(de0, Catch::Matchers::WithinRel(per_kg_1 + D0 / rho[0], 1e-12));
  CHECK_THAT(de1, Catch::Matchers::WithinRel(per_kg_1 + per_kg_2, 1e-12));
  CHECK_THAT(de2, Catch::Matchers::WithinRel(per_kg_2, 1e-12));
  // Conserved: the three cells' rho e together gain the three faces' corrections (face x = 3 carries none).
  const double gained = rho[0] * de0 + rho[1] * de1 + rho[2] * de2;
  CHECK_THAT(gained, Catch::Matchers::WithinRel(D0 + D1 + D2, 1e-12));
  CHECK(kinetic_heat_share(0.7, 0.7) == 0.5);  // equal densities: the halves, exactly
  CHECK_THAT(kinetic_heat_share(rho[0], rho[1]) + kinetic_heat_share(rho[1], rho[0]), Catch::Matchers::WithinAbs(1.0, 1e-15));
}
