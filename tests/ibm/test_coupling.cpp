//! \file test_coupling.cpp
//! \brief Immersed-boundary coupling: masks and imposed velocities from a moving block, and validation.md I1.
#include "blastsim/fdem/gmsh_mesh.hpp"
#include "blastsim/ibm/coupler.hpp"
#include "catch.hpp"
#include "exact_riemann.hpp"

#include <cmath>

#include <cstdio>

using namespace blastsim;

namespace {
const cip::EquationOfState eos = cip::EquationOfState::ideal(1.4);
const cip::GasPoint air{1.20, 2.09e5, 0.0, 0.0};  // Table 1 ambient gas: p = 0.4 x 1.2 x 2.09e5 = 100.32 kPa
const double L = 0.053;  // block [-L, L]^2 [m]: its edges fall between grid points (dx = 0.01 m)

//! A 40 x 40 grid over [-0.2, 0.2]^2 and a 4 x 4 block of the paper's rock, both at rest in uniform air.
struct BlockInAir {
  cip::GasSolver gas{cip::GasGrid::from_box(40, 40, -0.2, 0.2, -0.2, 0.2), eos};
  fdem::FdemTopology topo = fdem::build_topology(fdem::structured_rectangle(4, 4, -L, L, -L, L));
  fdem::RockSolver rock{topo, fdem::RockMaterial::paper_table2(), fdem::RockOptions{}};
  ibm::GasRockCoupler coupler{gas, rock, air};
  BlockInAir() {
    gas.initialise([](double, double) { return air; });
  }
};
}  // namespace

TEST_CASE("Rock to gas: faces inside a moving block take its velocity; fully covered cells are inactive",
          "[ibm][masks]") {
  BlockInAir c;
  std::vector<double> v(2 * c.rock.node_count());
  for (int n = 0; n < c.rock.node_count(); ++n) v[2 * n] = 3.0, v[2 * n + 1] = -2.0;  // rigid motion [m/s]
  c.rock.set_velocities(v);
  c.coupler.rock_to_gas();
  const cip::GasGrid g = c.gas.grid();
  // Expected by geometry: face points in the closed square [-L, L]^2 (dx = 0.01 m).
  auto in_block = [](double x, double y) { return std::fabs(x) <= L + 1e-12 && std::fabs(y) <= L + 1e-12; };
  const cip::HostGasFields h = c.gas.to_host();
  long expected_inactive = 0;
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i)
      if (in_block(g.face_x(i), g.cell_y(j)) && in_block(g.face_x(i + 1), g.cell_y(j)) &&
          in_block(g.cell_x(i), g.face_y(j)) && in_block(g.cell_x(i), g.face_y(j + 1)))
        ++expected_inactive;
  std::printf("I-masks: %ld inactive cells (expected %ld)\n", c.coupler.inactive_cells(), expected_inactive);
  CHECK(expected_inactive == 100);  // the 10 x 10 cells inside the block
  CHECK(c.coupler.inactive_cells() == expected_inactive);
  // Imposed velocities on the faces inside: the block's rigid velocity (shape functions reproduce it).
  const cip::ImmersedBoundaryView ib = c.gas.immersed_boundary();
  const int nx = g.nx, ny = g.ny;
  const index_t nu = static_cast<index_t>(nx + 1) * ny, nv = static_cast<index_t>(nx) * (ny + 1);
  const double u_count = reduce_sum("test.u_count", nu, 0.0, [=] BLAST_HD(index_t k) {
    return ib.u_prescribed(static_cast<int>(k % (nx + 1)), static_cast<int>(k / (nx + 1))) ? 1.0 : 0.0;
  });
  const double u_error = reduce_max("test.u_error", nu, 0.0, [=] BLAST_HD(index_t k) {
    const int i = static_cast<int>(k % (nx + 1)), j = static_cast<int>(k / (nx + 1));
    return ib.u_prescribed(i, j) ? fabs(ib.u_imposed(i, j) - 3.0) : 0.0;
  });
  const double v_error = reduce_max("test.v_error", nv, 0.0, [=] BLAST_HD(index_t k) {
    const int i = static_cast<int>(k % nx), j = static_cast<int>(k / nx);
    return ib.v_prescribed(i, j) ? fabs(ib.v_imposed(i, j) + 2.0) : 0.0;
  });
  std::printf("I-masks: %.0f x-faces prescribed (expected 11 x 10), velocity errors %.1e / %.1e m/s\n", u_count,
              u_error, v_error);
  CHECK(u_count == 110.0);  // x-faces at x = -0.05 ... 0.05 (11) in the 10 cell rows of the block
  CHECK(u_error < 1e-12);
  CHECK(v_error < 1e-12);
}

TEST_CASE("I1: uniform gas around a closed block: edge pressures p, net force zero to round-off", "[ibm][I1]") {
  BlockInAir c;
  c.coupler.rock_to_gas();
  c.coupler.gas_to_rock();
  const double p = eos.pressure(air.density, air.internal_energy);
  // Every exposed edge (the block's outline) carries the gas pressure.
  const std::vector<double> edge_p = to_host(c.rock.edge_pressure());
  const std::vector<std::uint8_t> exposed = to_host(c.rock.edge_exposed());
  double worst = 0;
  int edges = 0;
  for (size_t s = 0; s < edge_p.size(); ++s)
    if (exposed[s]) worst = std::fmax(worst, std::fabs(edge_p[s] / p - 1)), ++edges;
  // One rock step: the pressure forces are the only load; their sum must vanish (a closed outline).
  const double dt = 0.9 * c.rock.stable_dt();
  c.rock.step(dt);
  const fdem::RockSnapshot snap = c.rock.snapshot();
  const double mass_node = fdem::RockMaterial::paper_table2().density * (2 * L / 4) * (2 * L / 4) / 2 / 3;
  double px = 0, py = 0;
  for (size_t n = 0; n < snap.vx.size(); ++n) px += mass_node * snap.vx[n], py += mass_node * snap.vy[n];
  const double scale = p * 8 * L * dt;  // impulse of the pressure on the whole perimeter in one step
  std::printf("I1: %d exposed edges, largest |p_edge / p - 1| = %.1e; net impulse (%.1e, %.1e) of p x perimeter x dt "
              "= %.3e N s/m\n", edges, worst, px / scale, py / scale, scale);
  CHECK(edges == 16);
  CHECK(worst < 0.01);
  CHECK(std::fabs(px) < 1e-12 * scale);
  CHECK(std::fabs(py) < 1e-12 * scale);
  // Each node on the outline is pushed inward by p x (its share of the edges): the strain is compressive.
  const fdem::RockEnergies e = c.rock.energies();
  CHECK(e.external_work > 0);
}

TEST_CASE("I2: a shock hitting an immersed fixed rock block reflects with the exact pressure", "[ibm][I2]") {
  // Sod's tube (dimensionless states) along x on 400 x 3 cells; a rock block held fixed (all nodes at rest)
  // covers x >= 0.75 through the coupler: its faces are the wall.
  using blastsim::test::ExactRiemann;
  using blastsim::test::Primitive;
  const Primitive Lq{1.0, 0.0, 1.0}, Rq{0.125, 0.0, 0.1};
  const int n = 400;
  const double wall = 0.75, height = 3.0 / n;
  cip::GasSolverOptions opt;
  opt.boundaries.side = {cip::BoundaryKind::outflow, cip::BoundaryKind::outflow, cip::BoundaryKind::wall,
                         cip::BoundaryKind::wall};
  cip::GasSolver gas(cip::GasGrid::from_box(n, 3, 0, 1, 0, height), eos, opt);
  gas.initialise([&](double x, double) {
    const Primitive& q = x < 0.5 ? Lq : Rq;
    return cip::GasPoint{q.rho, eos.internal_energy(q.rho, q.p), 0.0, 0.0};
  });
  // A soft, fixed block (its stiffness plays no part; soft keeps the rock's stable step above the gas's).
  fdem::RockMaterial soft{1000.0, 1000.0, 0.3, 1.0, 3.0, 0.5, 1000.0, 1000.0, 0.6};
  const fdem::FdemTopology topo =
      fdem::build_topology(fdem::structured_rectangle(4, 2, wall - 1e-4, 1.1, -0.01, height + 0.01));
  fdem::RockSolver rock(topo, soft, fdem::RockOptions{});
  std::vector<int> all(rock.node_count());
  for (int k = 0; k < rock.node_count(); ++k) all[k] = k;
  rock.prescribe_velocity(all, true, true, 0.0, 0.0);
  const cip::GasPoint ambient{Rq.rho, eos.internal_energy(Rq.rho, Rq.p), 0.0, 0.0};
  ibm::GasRockCoupler coupler(gas, rock, ambient);
  coupler.rock_to_gas();
  CHECK(coupler.inactive_cells() == 3 * 100);  // cells 300..399 of each row
  const ExactRiemann exact(Lq, Rq, 1.4);
  const Primitive s2{exact.rho_star_right(), exact.u_star(), exact.p_star()};
  const double p5 = ExactRiemann::reflected_shock_pressure(s2, 1.4);
  const double r = p5 / s2.p, m = 0.4 / 2.4;
  const double rho5 = s2.rho * (r + m) / (m * r + 1);
  const double w_reflected = s2.rho * s2.u / (s2.rho - rho5);
  const double t_end = (wall - 0.5) / exact.right_shock_speed() + 0.04 / std::fabs(w_reflected);
  while (gas.time() < t_end - 1e-12) coupler.step(std::fmin(coupler.stable_dt(0.1), t_end - gas.time()));
  const cip::HostGasFields h = gas.to_host();
  double sum = 0;
  int count = 0;
  for (int i = 0; i < n; ++i) {  // middle row, the cells within 0.025 of the wall
    const double x = (i + 0.5) / n;
    if (x > wall - 0.025 && x < wall) sum += h.p[static_cast<size_t>(n) + i], ++count;
  }
  const double p_wall = sum / count;
  std::printf("I2: reflected-shock pressure at the immersed rock %.5f vs exact %.5f (%+.2f %%)\n", p_wall, p5,
              100 * (p_wall / p5 - 1));
  CHECK_THAT(p_wall, WithinRel(p5, 0.03));
}

#if defined(BLASTSIM_TEST_HAVE_GMSH)
TEST_CASE("I3: gas sealed in a hole of intact rock keeps its mass while the rock vibrates", "[ibm][I3]") {
  const double R = 0.1, a = 0.03;  // disc and hole radii [m]
  cip::GasSolverOptions opt;
  cip::GasSolver gas(cip::GasGrid::from_box(80, 80, -0.12, 0.12, -0.12, 0.12), eos, opt);
  const cip::GasPoint hole_gas{10.0, eos.internal_energy(10.0, 1.0e6), 0.0, 0.0};  // 1 MPa
  gas.initialise([&](double x, double y) { return x * x + y * y < a * a ? hole_gas : air; });
  const fdem::NamedMesh mesh = fdem::gmsh_disc_with_hole(0, 0, R, a, 0.008);
  fdem::RockOptions ropt;
  ropt.contact = false;  // intact rock: no piece can touch another
  fdem::RockSolver rock(fdem::build_topology(mesh.mesh), fdem::RockMaterial::paper_table2(), ropt);
  ibm::GasRockCoupler coupler(gas, rock, air);
  const cip::GasGrid g = gas.grid();
  auto cavity_mass = [&] {  // active cells centred within 1.5 cells of the hole
    const cip::HostGasFields h = gas.to_host();
    double m = 0;
    for (int j = 0; j < g.ny; ++j)
      for (int i = 0; i < g.nx; ++i) {
        const size_t k = static_cast<size_t>(j) * g.nx + i;
        if (h.active[k] && std::hypot(g.cell_x(i), g.cell_y(j)) < a + 1.5 * g.dx) m += h.rho[k] * g.cell_area();
      }
    return m;
  };
  coupler.rock_to_gas();
  const double m0 = cavity_mass();
  const long inactive0 = coupler.inactive_cells();
  const cip::GasTotals g0 = gas.totals();
  while (gas.time() < 1e-4) coupler.step(coupler.stable_dt(0.1));
  const double m1 = cavity_mass();
  const fdem::RockEnergies e = rock.energies();
  // Coupled energy budget (printed, not yet asserted): what the gas lost (less what left the grid) should
  // equal the work its pressure did on the rock. With immersed faces now conserving energy (a static mask
  // around the hole: round-off), the residual is -5.1 / +0.8 / +5.9 % on 80 / 120 / 160 cells: about the
  // 5 % bound but not converging with the grid (the rock is loaded by the nearest cell's pressure at each
  // edge midpoint, the gas by the staircase of prescribed faces). Issue #4 keeps this open.
  const cip::GasTotals g1 = gas.totals();
  const double gas_lost = (g0.internal_energy + g0.kinetic_energy) - (g1.internal_energy + g1.kinetic_energy) -
                          gas.boundary_outflow().energy;  // less what left through the grid's outer boundary
  std::printf("I3 energy: gas lost %.5e J/m, pressure work on the rock %.5e J/m (%+.2f %%), rock kinetic + strain "
              "%.5e J/m\n", gas_lost, e.external_work, 100 * (e.external_work / gas_lost - 1), e.kinetic + e.strain);
  std::printf("I3: cavity gas mass %.6e -> %.6e kg/m (relative change %.2e) after %ld steps; rock kinetic %.3e J/m, strain "
              "%.3e J/m; inactive cells %ld -> %ld\n", m0, m1, m1 / m0 - 1, rock.steps(), e.kinetic, e.strain,
              inactive0, coupler.inactive_cells());
  CHECK(e.kinetic + e.strain > 0);  // the rock is loaded and vibrates
  CHECK(std::fabs(m1 / m0 - 1) < 0.01);
}
#endif
