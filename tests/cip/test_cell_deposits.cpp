//! \file test_cell_deposits.cpp
//! \brief docs/validation.md G18: deposits into the staggered grid (cip::CellDeposits) change its mass, momentum
//! and total energy by exactly what they give, beside solids and the outer boundary, and a jet into gas at rest
//! moves the cell's faces as the momentum balance of its dual cells says.
#include "blastsim/cip/cell_deposits.hpp"
#include "blastsim/cip/gas_solver.hpp"
#include "catch.hpp"

#include <cmath>
#include <cstdio>
#include <vector>

using namespace blastsim;

namespace {

cip::GasMaterials traced_air() {
  cip::GasMaterials m;
  m.air = cip::EquationOfState::ideal(1.4);
  m.tracer = true;
  return m;
}

cip::CellDeposit entry(const cip::GasGrid& g, int i, int j, double given, double drawn, double ux, double uy,
                       double e_given, double e_drawn, double products) {
  return {j * g.nx + i, given, drawn, given * ux, given * uy,
          given * (e_given + 0.5 * (ux * ux + uy * uy)) + drawn * e_drawn, products, 0.0};
}

}  // namespace

TEST_CASE("G18 cell deposits: mass, momentum and total energy change by exactly what the entries give, beside solids "
          "and the outer boundary",
          "[cip][deposit][G18]") {
  // A 10 x 8 grid of 1 m cells; air with u = 30 y, v = -20 x on the faces; a solid over 3.9 < x < 5.1, y < 5
  // (cells (4, 0..3) inactive; cell (4, 4) between two imposed x-faces). Entries: two neighbours in open gas (one
  // drawing), a cell beside the solid, the cell between imposed faces (its x momentum has no free face: refused),
  // a cell on the outer boundary, and an empty entry.
  const cip::GasGrid g = cip::GasGrid::from_box(10, 8, 0, 10, 0, 8);
  cip::GasSolver gas(g, traced_air());
  gas.initialise([](double x, double y) {
    const double rho = 1.0 + 0.05 * x + 0.03 * y;
    return cip::GasPoint{rho, 2.5e5 * (1.0 + 0.01 * x), 30.0 * y, -20.0 * x, 0.0, 0.2};
  });
  cip::mark_static_solid(gas, [](double x, double y) { return x > 3.9 && x < 5.1 && y < 5.0; });
  const std::vector<cip::CellDeposit> entries = {
      entry(g, 1, 6, 0.3, 0.0, 40.0, -10.0, 2.0e5, 0.0, 0.1),
      entry(g, 2, 6, 0.1, -0.2, -25.0, 0.0, 3.0e5, 2.5e5, -0.04),
      entry(g, 3, 2, 0.2, 0.0, 60.0, 5.0, 2.0e5, 0.0, 0.05),
      entry(g, 4, 4, 0.1, 0.0, 50.0, -30.0, 2.0e5, 0.0, 0.0),
      {-1, 1.0, 0.0, 1.0, 1.0, 1.0, 0.0, 0.0},
      entry(g, 0, 3, 0.05, -0.1, 10.0, 5.0, 2.0e5, 2.6e5, 0.0),
  };
  const cip::HostGasFields h = gas.to_host();
  auto active = [&](int i, int j) { return i >= 0 && i < g.nx && j >= 0 && j < g.ny && h.active[j * g.nx + i] != 0; };
  // What the entries give, and what they must change: the given momentum (less, for the cell between imposed
  // x-faces, what no free face takes: its momentum less the given mass's share on those faces, at their
  // velocities, weighted as GasTotals weighs a face: 1/2 per active cell beside it), and the drawn mass at the
  // velocities of each face of its cell.
  double mass = 0, px = 0, py = 0, energy = 0, products = 0;
  for (const cip::CellDeposit& d : entries) {
    if (d.cell < 0) continue;
    const int i = d.cell % g.nx, j = d.cell / g.nx;
    mass += d.given + d.drawn, energy += d.energy, products += d.products_mass;
    px += d.px, py += d.py;
    // the faces' velocities as initialised (30 y, -20 x), those on the outer boundary as the boundary condition
    // left them (from the cell's mean of its two faces, HostGasFields)
    const double mean_u = h.u[j * g.nx + i], mean_v = h.v[j * g.nx + i];
    const double ul = i > 0 ? 30.0 * g.cell_y(j) : 2 * mean_u - 30.0 * g.cell_y(j), ur = 30.0 * g.cell_y(j);
    const double vb = j > 0 ? -20.0 * g.cell_x(i) : 2 * mean_v + 20.0 * g.cell_x(i), vt = -20.0 * g.cell_x(i);
    const double wl = 0.5 * (1.0 + active(i - 1, j)), wr = 0.5 * (1.0 + active(i + 1, j));
    const double wb = 0.5 * (1.0 + active(i, j - 1)), wt = 0.5 * (1.0 + active(i, j + 1));
    px += 0.5 * d.drawn * (wl * ul + wr * ur);
    py += 0.5 * d.drawn * (wb * vb + wt * vt);
    if (i == 4 && j == 4) px -= d.px - 0.5 * d.given * (wl * ul + wr * ur);  // refused
  }
  const cip::GasTotals before = gas.totals();
  const double heat_before = gas.positivity_energy();
  cip::CellDeposits deposits(g);
  deposits.set_entries(entries);
  deposits.apply(gas);
  const cip::GasTotals after = gas.totals();
  const double heat = gas.positivity_energy() - heat_before;
  const double dE = after.total_energy() + heat - before.total_energy();
  std::printf("G18 deposits: given mass %+.6e kg/m, momentum %+.6e %+.6e kg/s, energy %+.9e J/m, products %+.6e kg/m; "
              "the grid's change less these: %+.2e kg/m, %+.2e %+.2e kg/s, %+.2e J/m (positivity ledger %.1e), %+.2e "
              "kg/m\n",
              mass, px, py, energy, products, after.mass - before.mass - mass, after.momentum_x - before.momentum_x - px,
              after.momentum_y - before.momentum_y - py, dE - energy, heat,
              after.products_mass - before.products_mass - products);
  const double p_scale = std::fabs(before.momentum_x) + std::fabs(before.momentum_y) + 100.0;
  CHECK(std::fabs(after.mass - before.mass - mass) < 1e-13 * before.mass);
  CHECK(std::fabs(after.momentum_x - before.momentum_x - px) < 1e-13 * p_scale);
  CHECK(std::fabs(after.momentum_y - before.momentum_y - py) < 1e-13 * p_scale);
  CHECK(std::fabs(dE - energy) < 1e-13 * before.total_energy());
  CHECK(std::fabs(after.products_mass - before.products_mass - products) < 1e-13 * before.mass);
  CHECK(heat == 0.0);  // no deposit here takes more than half of a cell's internal energy
}

TEST_CASE("G18 cell deposits: a jet into gas at rest sets the cell's two faces to its momentum over their dual "
          "masses",
          "[cip][deposit][G18]") {
  // Uniform air at rest (1.2 kg/m3, 0.5 m cells); a cell in the middle takes m = 0.01 kg/m moving at U = 300 m/s
  // along x. Each of its x-faces takes half the momentum, m U / 2, on its dual mass grown by m / 2:
  // u = (m U / 2) / (rho dx dy + m / 2); its y-faces stay at rest. Total energy grows by m (e + U^2 / 2).
  const cip::GasGrid g = cip::GasGrid::from_box(8, 8, 0, 4, 0, 4);
  cip::GasSolver gas(g, traced_air());
  gas.initialise([](double, double) { return cip::GasPoint{1.2, 2.1e5, 0.0, 0.0, 0.0}; });
  const double m = 0.01, U = 300.0, e = 2.0e5;
  cip::CellDeposits deposits(g);
  deposits.set_entries({entry(g, 3, 4, m, 0.0, U, 0.0, e, 0.0, m)});
  const cip::GasTotals before = gas.totals();
  deposits.apply(gas);
  const cip::GasTotals after = gas.totals();
  const cip::HostGasFields h = gas.to_host();
  const double expected = 0.5 * m * U / (1.2 * g.cell_area() + 0.5 * m);
  // HostGasFields' u is the cell-centred mean of its two x-faces: cell (3, 4) and its neighbours across each face
  const double u_cell = h.u[4 * g.nx + 3], u_left = h.u[4 * g.nx + 2], u_right = h.u[4 * g.nx + 4];
  std::printf("G18 jet: face velocity %.9f m/s (expected %.9f), momentum %.9e (m U %.9e), energy %+.9e (m (e + U^2/2) "
              "%.9e)\n",
              2 * u_left, expected, after.momentum_x, m * U, after.total_energy() - before.total_energy(),
              m * (e + 0.5 * U * U));
  CHECK(std::fabs(u_cell - expected) < 1e-12 * expected);
  CHECK(std::fabs(2 * u_left - expected) < 1e-12 * expected);
  CHECK(std::fabs(2 * u_right - expected) < 1e-12 * expected);
  CHECK(std::fabs(after.momentum_x - m * U) < 1e-12 * m * U);
  CHECK(std::fabs(after.momentum_y) < 1e-12 * m * U);
  CHECK(std::fabs(after.total_energy() - before.total_energy() - m * (e + 0.5 * U * U)) < 1e-12 * m * e);
}
