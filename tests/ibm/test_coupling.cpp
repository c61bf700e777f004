//! \file test_coupling.cpp
//! \brief Immersed-boundary coupling: masks and imposed velocities from a moving block, and docs/validation.md I1.
#include "blastsim/fdem/gmsh_mesh.hpp"
#include "validation_courant.hpp"
#include "blastsim/core/backend.hpp"
#include "blastsim/core/output_files.hpp"
#include "blastsim/fdem/rock_analysis.hpp"
#include "blastsim/ibm/blasthole_monitor.hpp"
#include "blastsim/ibm/budget.hpp"
#include "blastsim/ibm/coupler.hpp"
#include "catch.hpp"
#include "exact_riemann.hpp"
#include "hole_in_rock.hpp"

#include <cmath>
#include <cstdio>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

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

TEST_CASE("Rock to gas: faces inside a moving block take its velocity, fully covered cells are inactive",
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

TEST_CASE("Cells that change state: covered cells hand their gas on, uncovered cells start ambient", "[ibm][transitions]") {
  // The block of the mask test moves rigidly at 300 m/s through gas twice as dense as the ambient state; only
  // the coupler's rock_to_gas() acts on the gas (no gas step), so the gas mass changes only by transitions:
  // mass now = initial + what the ledger says the transitions created (the ambient gas of uncovered cells).
  BlockInAir c;
  const cip::GasPoint dense{2.0 * air.density, air.internal_energy, 0.0, 0.0};
  c.gas.initialise([&](double, double) { return dense; });
  std::vector<double> v(2 * c.rock.node_count());
  for (int n = 0; n < c.rock.node_count(); ++n) v[2 * n] = 300.0, v[2 * n + 1] = 0.0;
  c.rock.set_velocities(v);
  c.coupler.rock_to_gas();  // first call: cells under the block take the ambient state, nothing is counted
  const double m0 = c.gas.totals().mass;
  const cip::GasGrid g = c.gas.grid();
  double worst_mass = 0, worst_ambient = 0;
  long uncovered = 0;
  std::vector<std::uint8_t> before = c.gas.to_host().active;
  const double dt = 0.9 * c.rock.stable_dt();
  while (c.rock.time() < 2e-4) {  // 60 mm: six cells
    c.rock.step(dt);
    c.coupler.rock_to_gas();
    const cip::HostGasFields h = c.gas.to_host();
    const ibm::CouplingDiagnostics d = c.coupler.diagnostics();
    worst_mass = std::fmax(worst_mass, std::fabs(c.gas.totals().mass - d.transitions.mass_created - m0) / m0);
    for (size_t k = 0; k < h.active.size(); ++k)
      if (!before[k] && h.active[k]) {  // uncovered now: the ambient state
        ++uncovered;
        worst_ambient = std::fmax(worst_ambient, std::fabs(h.rho[k] / air.density - 1) + std::fabs(h.e[k] / air.internal_energy - 1));
      }
    before = h.active;
  }
  const ibm::CouplingDiagnostics d = c.coupler.diagnostics();
  std::printf("transitions: %ld covered, %ld uncovered (seen %ld); mass + created - initial: largest %.1e of the mass; "
              "uncovered cells off the ambient state by at most %.1e; created %.4e kg/m = %ld cells x ambient\n",
              d.transitions.covered, d.transitions.uncovered, uncovered, worst_mass, worst_ambient,
              d.transitions.mass_created, std::lround(d.transitions.mass_created / (air.density * g.cell_area())));
  CHECK(d.transitions.covered >= 50);  // a 10-cell-high block crossing six columns of cells
  CHECK(d.transitions.uncovered == uncovered);
  CHECK(worst_mass < 1e-12);
  CHECK(worst_ambient < 1e-12);
  CHECK(d.transitions.mass_created == Approx(uncovered * air.density * g.cell_area()).epsilon(1e-12));
}

namespace {
//! A process that only records the stages it is run at (the schedule's test).
class StageRecorder : public ibm::CouplingProcess {
 public:
  struct Call {
    ibm::Stage stage;
    ibm::StageStep step;
  };
  std::vector<Call> calls;
  const char* name() const override { return "recorder"; }
  std::vector<ibm::Stage> stages() const override {
    return {ibm::Stage::before_gas, ibm::Stage::before_rock_step, ibm::Stage::after_rock};
  }
  void run(ibm::Stage stage, ibm::CouplingContext&, const ibm::StageStep& step) override {
    if (stage == ibm::Stage::cover) ibm::stage_not_run(*this, stage);  // never scheduled there
    calls.push_back({stage, step});
  }
  void report(const ibm::CouplingDiagnostics&, CsvRecord& o) const override {
    o.integer("recorder_calls", static_cast<long long>(calls.size()));
  }
};
}  // namespace

TEST_CASE("Coupling processes: the schedule is the stages each declares, run in order with their step", "[ibm][schedule]") {
  BlockInAir c;
  auto owned = std::make_unique<StageRecorder>();
  StageRecorder& recorder = *owned;
  c.coupler.add(std::move(owned));
  const std::string schedule = c.coupler.schedule();
  std::printf("schedule of the block in air with a recorder:\n%s", schedule.c_str());
  // The immersed boundary and the gas load come first (GasRockCoupler's constructor), then the recorder.
  CHECK(schedule == "cover: immersed boundary\nupdate_cells: immersed boundary\nbefore_gas: gas load, recorder\n"
                    "load_rock: gas load\nbefore_rock_step: recorder\nafter_rock: gas load, recorder\n");
  c.coupler.rock_to_gas();
  CHECK(recorder.calls.empty());  // rock -> gas runs none of the recorder's stages
  const double dt = 1e-7;
  c.coupler.step(dt, 3);
  REQUIRE(recorder.calls.size() == 5);  // before_gas, three substeps, after_rock
  CHECK(recorder.calls[0].stage == ibm::Stage::before_gas);
  CHECK(recorder.calls[0].step.dt == dt);
  for (int k = 0; k < 3; ++k) {
    CHECK(recorder.calls[1 + k].stage == ibm::Stage::before_rock_step);
    CHECK(recorder.calls[1 + k].step.substep == k);
    CHECK(recorder.calls[1 + k].step.dt == dt / 3);
  }
  CHECK(recorder.calls[4].stage == ibm::Stage::after_rock);
  CHECK(recorder.calls[4].step.rock_substeps == 3);
  // The report: each process's columns in the order added, written without knowing them.
  CHECK(csv_text(CsvRecord::Mode::header, [&](CsvRecord& o) { c.coupler.report({}, o); }) ==
        "cells_covered,cells_uncovered,transition_energy_J_per_m,gas_work_on_rock_J_per_m,gas_force_x_N_per_m,"
        "gas_force_y_N_per_m,recorder_calls");
  CHECK(csv_text(CsvRecord::Mode::row, [&](CsvRecord& o) { recorder.report({}, o); }) == "5");
  // A stage a process does not declare is refused, naming both.
  ibm::CouplingContext ctx{c.gas, c.rock, air, 1e5, {}, {}, false, 0.0};
  try {
    recorder.run(ibm::Stage::cover, ctx, {});
    FAIL("no exception");
  } catch (const std::logic_error& e) {
    CHECK(std::string(e.what()).find("'recorder'") != std::string::npos);
    CHECK(std::string(e.what()).find("cover") != std::string::npos);
  }
}

TEST_CASE("I1: uniform gas around a closed block: edge pressures p, net force zero to round-off", "[ibm][I1]") {
  BlockInAir c;
  c.coupler.rock_to_gas();
  c.coupler.gas_to_rock();
  const double p = eos.pressure(air.density, air.internal_energy);
  // Every exposed edge (the block's outline) carries the gas pressure.
  const std::vector<double> edge_p = c.rock.edge_pressures();
  const std::vector<std::uint8_t> exposed = c.rock.edge_exposure();
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

TEST_CASE("I2: a shock hitting an immersed fixed rock block reflects with the exact pressure", "[ibm][I2][heavy]") {
  // Sod's tube (dimensionless states) along x on 400 x 3 cells; a rock block held fixed (all nodes at rest)
  // covers x >= 0.75 through the coupler: its faces are the wall.
  using blastsim::test::ExactRiemann;
  using blastsim::test::Primitive;
  const Primitive Lq{1.0, 0.0, 1.0}, Rq{0.125, 0.0, 0.1};
  const int n = 400;
  const double wall = 0.75, height = 3.0 / n;
  cip::GasSolverOptions opt;
  opt.boundaries = cip::BoundaryConditions::all(cip::BoundaryKind::wall)
                       .set(cip::left, cip::BoundaryKind::outflow)
                       .set(cip::right, cip::BoundaryKind::outflow);
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
  while (gas.time() < t_end - 1e-12) coupler.step(std::fmin(coupler.stable_dt(blastsim::test::validation_courant(coupler.courant())), t_end - gas.time()));
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
TEST_CASE("I3: gas sealed in a hole of intact rock keeps its mass while the rock vibrates", "[ibm][I3][heavy]") {
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
  while (gas.time() < 1e-4) coupler.step(coupler.stable_dt(blastsim::test::validation_courant(coupler.courant())));
  const double m1 = cavity_mass();
  const fdem::RockEnergies e = rock.energies();
  // Energy budget printed only: at 1 MPa in air (0.1 MPa) the net work is a small difference of the hole's
  // and the outer air's work, and the cut cells hold air here (the gas is set by cell centre, r < a). The
  // budget is asserted on the Table 1 hole (test "Coupled energy").
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

#if defined(BLASTSIM_TEST_HAVE_GMSH)
using test::HoleInRock;
using test::intact_rock;
using test::table1_gas;

TEST_CASE("Coupled energy: gas energy lost by a pressurised hole equals the work done on intact rock", "[long][ibm][energy]") {
  // Table 1 gas in a 20 mm hole of a 100 mm disc of elastic rock, in air. Budget of the whole gas: what it
  // lost (less what left the grid, plus what cell transitions and immersed faces gave it) against the work of the edge
  // pressures on the rock (RockEnergies::pressure_work). Bound 5 %. The cut cells around the
  // hole hold the hole gas.
  // The three gas loads (docs/coupling.md "Gas -> rock"): the paper's edge pressures, the face forces, and edge
  // pressures that the gas pays for.
  for (ibm::GasLoad load : {ibm::GasLoad::edge_pressures, ibm::GasLoad::face_forces, ibm::GasLoad::edge_pressures_paid}) {
  for (int N : {80, 160}) {
    const char* name = ibm::gas_load_name(load);
    HoleInRock c(N, 0.12, 0.1, 0.02, 0.005, intact_rock(), {}, load);
    const cip::GasTotals g0 = c.gas.totals();
    const double initial = ibm::initial_energy(c.gas, c.rock);
    for (double t : {20e-6, 40e-6}) {
      c.run_to(t);
      const cip::GasTotals g1 = c.gas.totals();
      const ibm::CouplingDiagnostics d = c.coupler.diagnostics();
      const double lost = g0.total_energy() - g1.total_energy() - c.gas.boundary_outflow().energy +
                          d.transitions.energy_created + c.gas.immersed_face_work();
      const fdem::RockEnergies e = c.rock.energies();
      std::printf("energy (%s, N = %d, t = %.0f us): gas lost %.4e J/m, work on the rock %.4e J/m (%+.2f %%); rock kinetic + "
                  "strain + joints %.4e J/m; cells covered/uncovered %ld/%ld, energy they created %.2e J/m; immersed "
                  "faces gave %.2e J/m\n", name, N, t * 1e6,
                  lost, d.gas_work_on_rock, 100 * (d.gas_work_on_rock / lost - 1), e.kinetic + e.strain + e.joint_work,
                  d.transitions.covered, d.transitions.uncovered, d.transitions.energy_created, c.gas.immersed_face_work());
      CHECK(d.gas_work_on_rock > 10.0);  // the hole does work: tens of J/m
      CHECK(e.broken_joints == 0);
      // By 40 us the vibrating wall has covered and uncovered about 20 (80 cells) or 150 (160 cells) cut cells.
      CHECK_THAT(d.gas_work_on_rock, WithinRel(lost, 0.05));
      // The whole budget as coupling_series.csv reports it (S4): its residual is the mismatch of the two sides
      // above (gas lost against work on the rock, the rock's balance closing on its own), within the same 5 %.
      const ibm::CoupledBudget b = ibm::coupled_budget(c.gas, c.rock, c.coupler, initial);
      std::printf("energy (%s, N = %d, t = %.0f us): budget residual %.4e J/m (%+.2f %% of the work on the rock)\n", name, N,
                  t * 1e6, b.residual, 100 * b.residual / b.coupling.gas_work_on_rock);
      CHECK(std::fabs(b.residual) < 0.05 * b.coupling.gas_work_on_rock);
    }
  }
  }
}

TEST_CASE("Rock subcycling: the energy budget closes and the rock responds as with one dt", "[ibm][energy][subcycling][heavy]") {
  // The energy case above (80 x 80 cells, 40 us) run twice: one dt for both solvers, and gas steps at the
  // gas's Courant limit with the rock subcycling. Bounds: the budget within 5 % (as above), the work on
  // the rock and the rock's kinetic + strain energy within 2 % of the single-dt run's. Both gas loads, each at
  // its recommended Courant number (the paper's 0.1 with edge pressures, 0.4 with face forces and with paid edge
  // pressures).
  for (ibm::GasLoad load : {ibm::GasLoad::edge_pressures, ibm::GasLoad::face_forces, ibm::GasLoad::edge_pressures_paid}) {
    HoleInRock one(80, 0.12, 0.1, 0.02, 0.005, intact_rock(), {}, load), sub(80, 0.12, 0.1, 0.02, 0.005, intact_rock(), {}, load);
    const cip::GasTotals g0 = sub.gas.totals();
    one.run_to(40e-6);
    sub.run_to(40e-6, true);
    const ibm::CouplingDiagnostics d1 = one.coupler.diagnostics(), ds = sub.coupler.diagnostics();
    const double lost = g0.total_energy() - sub.gas.totals().total_energy() - sub.gas.boundary_outflow().energy +
                        ds.transitions.energy_created + sub.gas.immersed_face_work();
    const fdem::RockEnergies e1 = one.rock.energies(), es = sub.rock.energies();
    std::printf("subcycling (%s, Courant %.2f): %ld gas steps (%ld rock steps) vs %ld; work on the rock %.4e vs %.4e J/m "
                "(%+.2f %%); gas lost %.4e J/m (work %+.2f %% of it); rock kinetic + strain %.4e vs %.4e J/m (%+.2f %%)\n",
                ibm::gas_load_name(load), blastsim::test::validation_courant(sub.coupler.courant()),
                static_cast<long>(sub.gas.steps()), sub.rock.steps(), static_cast<long>(one.gas.steps()), ds.gas_work_on_rock,
                d1.gas_work_on_rock, 100 * (ds.gas_work_on_rock / d1.gas_work_on_rock - 1), lost,
                100 * (ds.gas_work_on_rock / lost - 1), es.kinetic + es.strain, e1.kinetic + e1.strain,
                100 * ((es.kinetic + es.strain) / (e1.kinetic + e1.strain) - 1));
    CHECK(sub.rock.steps() > 3 * sub.gas.steps());  // the rock did subcycle
    CHECK_THAT(ds.gas_work_on_rock, WithinRel(lost, 0.05));
    CHECK_THAT(ds.gas_work_on_rock, WithinRel(d1.gas_work_on_rock, 0.02));
    CHECK_THAT(es.kinetic + es.strain, WithinRel(e1.kinetic + e1.strain, 0.02));
  }
}

TEST_CASE("I4: pressurised hole in elastic rock: wall stress = gas pressure, symmetric, Lame far field", "[long][ibm][I4]") {
  // Hole a = 20 mm in a disc R = 150 mm, Table 1 gas (27.97 MPa) suddenly applied, air (0.1 MPa) outside.
  // At 40 us the near field has settled and the wave reflected from the outer surface has not come back
  // ((2R - 2a)/c_p = 49 us). Per 45-degree sector, sigma_rr of the triangles within 3a is fitted by Lame's
  // form A + B/r^2 and evaluated at the wall. Both gas loads: the paper's edge pressures and the face forces, on
  // Gmsh's frontal lattice of 4 mm triangles (128^2 cells of 2.5 mm), whose regular triangles keep the elements'
  // own stress scatter below the fit's; and the edge pressures on the isotropic default mesh at 3 mm (170^2
  // cells of 1.9 mm). On the isotropic mesh at 4 mm the constant-strain triangles' scatter alone takes single
  // sectors to 6 % (B +5.95 % with edge pressures, -6.08 % with face forces; 2026-12-07). Face forces are not
  // run on the 3 mm isotropic mesh: they scatter from -22 % to +10 % there (docs/validation.md, I4).
  struct Setup {
    ibm::GasLoad load;
    fdem::GmshAlgorithm mesher;
    int cells;
    double h;
  };
  for (const Setup& setup : {Setup{ibm::GasLoad::edge_pressures, fdem::GmshAlgorithm::frontal, 128, 0.004},
                             Setup{ibm::GasLoad::face_forces, fdem::GmshAlgorithm::frontal, 128, 0.004},
                             Setup{ibm::GasLoad::edge_pressures, fdem::GmshAlgorithm::delaunay, 170, 0.003}}) {
    const ibm::GasLoad load = setup.load;
    const std::string label = std::string(ibm::gas_load_name(load)) +
                              (setup.mesher == fdem::GmshAlgorithm::frontal ? ", frontal 4 mm" : ", isotropic 3 mm");
    const char* name = label.c_str();
    const double R = 0.15, a = 0.02;
    HoleInRock c(setup.cells, 0.16, R, a, setup.h, intact_rock(), {}, load, setup.mesher);
    c.run_to(40e-6);
    const double p_out = eos.pressure(air.density, air.internal_energy);
    std::vector<std::array<double, 2>> wall_points;  // gas sampled around the whole wall, just inside the hole
    for (int k = 0; k < 32; ++k) wall_points.push_back({0.8 * a * std::cos(k * M_PI / 16), 0.8 * a * std::sin(k * M_PI / 16)});
    double p_min = 1e300, p_max = 0, p_mean = 0;
    for (const cip::GasSample& g : c.gas.sample(wall_points)) p_min = std::fmin(p_min, g.p), p_max = std::fmax(p_max, g.p), p_mean += g.p / 32;
    const double lame_B = -(p_mean - p_out) * a * a * R * R / (R * R - a * a);  // Lame with the gas pressure now
    // The fit the driver's blasthole monitor uses (wall_series.csv).
    const int S = 8;
    const std::vector<fdem::LameSectorFit> fits = fdem::fit_wall_radial_stress(c.rock.snapshot(), {0.0, 0.0}, a, S, 3 * a);
    double w_min = 1e300, w_max = -1e300;
    std::printf("I4 (%s): gas pressure around the wall %.5e .. %.5e Pa (spread %.2e of the mean)\n", name, p_min, p_max, (p_max - p_min) / p_mean);
    for (int k = 0; k < S; ++k) {
      REQUIRE(fits[k].valid);
      const double B = fits[k].B;
      const double wall = -fits[k].wall_stress;  // compression positive, like the gas pressure
      w_min = std::fmin(w_min, wall), w_max = std::fmax(w_max, wall);
      std::printf("I4 (%s): sector %d: radial stress at the wall %.4e Pa (%+.2f %% of the gas pressure); Lame B %.4e vs %.4e N/m "
                  "(%+.2f %%)\n", name, k, -wall, 100 * (wall / p_mean - 1), B, lame_B, 100 * (B / lame_B - 1));
      CHECK_THAT(wall, WithinRel(p_mean, 0.05));
      CHECK_THAT(B, WithinRel(lame_B, 0.05));
    }
    std::printf("I4 (%s): wall stress spread over the sectors %.2f %% of the gas pressure\n", name, 100 * (w_max - w_min) / p_mean);
    CHECK((p_max - p_min) / p_mean < 0.05);
    CHECK((w_max - w_min) / p_mean < 0.05);
    // The blasthole monitor of the driver (wall_series.csv) sees the same: wall stress = gas pressure within
    // 5 %, sectors within 5 %, no crack and no gas outside the intact rock.
    ibm::BlastholeMonitor monitor({{0.0, 0.0}, a, R}, c.gas.grid(), p_out);
    const ibm::BlastholeSample s = monitor.sample(c.gas, c.rock);
    std::printf("I4 (%s, blasthole monitor): gas at the wall %.5e Pa, rock radial stress %.5e Pa (sector spread %.2f %%); "
                "outer surface %.4e Pa\n", name, s.wall_pressure_mean, -s.wall_stress_mean, 100 * s.wall_stress_spread,
                s.outer_pressure_max);
    CHECK_THAT(-s.wall_stress_mean, WithinRel(s.wall_pressure_mean, 0.05));
    CHECK(s.wall_stress_spread < 0.05);
    CHECK(monitor.events().first_crack < 0);
    CHECK(monitor.events().ejection < 0);
  }
}

//! A soft rock (E = 0.5 GPa) whose cracks open to the grid scale within a few hundred microseconds under the
//! Table 1 gas, strong enough not to crack on its own.
fdem::RockMaterial soft_rock() {
  fdem::RockMaterial m = fdem::RockMaterial::paper_table2();
  m.youngs_modulus = 0.5e9, m.tensile_strength = 50e6, m.cohesion = 150e6;
  m.fracture_energy_mode1 = 2e4, m.fracture_energy_mode2 = 1e5;
  return m;
}

TEST_CASE("I5: gas enters a pre-cut crack from the hole and loads its faces", "[long][ibm][I5]") {
  // A 40 mm radial crack from the wall of a 20 mm hole along y = 0, where a row of y-faces lies. The crack
  // opens under the hole pressure; gas enters once it opens to the grid scale. Expected: arrival later with
  // distance along the crack, never faster than the gas's escape speed 2c/(gamma - 1), and crack faces
  // loaded by the gas beside them.
  const double a = 0.02, L = 0.04;
  HoleInRock c(120, 0.12, 0.1, a, 0.004, soft_rock(), {fdem::Segment{{a, 0}, {a + L, 0}}});
  const std::vector<int> crack = c.rock.joints_on_segment(a, 0, a + L, 0, 1e-6);
  REQUIRE(crack.size() >= 8);  // about L / h joints
  c.rock.break_joints(crack);
  const double p_hole = eos.pressure(table1_gas.density, table1_gas.internal_energy);
  const double escape = 2 * std::sqrt(1.4 * p_hole / table1_gas.density) / 0.4;  // [m/s]
  const std::vector<double> d{0.005, 0.015, 0.025, 0.035};
  std::vector<std::array<double, 2>> pts;
  for (double x : d) pts.push_back({a + x, 0.0});
  std::vector<double> arrival(d.size(), -1);
  const fdem::RockSnapshot s0 = c.rock.snapshot();
  while (c.gas.time() < 400e-6 && arrival.back() < 0) {
    c.run_to(c.gas.time() + 2e-6);
    const std::vector<cip::GasSample> smp = c.gas.sample(pts);
    for (size_t k = 0; k < d.size(); ++k)
      if (arrival[k] < 0 && smp[k].p > 0.25 * p_hole) arrival[k] = c.gas.time();
  }
  for (size_t k = 0; k < d.size(); ++k)
    std::printf("I5: gas (p > p_hole / 4) reaches %.0f mm into the crack at %.1f us (escape-speed bound %.1f us)\n",
                1e3 * d[k], 1e6 * arrival[k], 1e6 * d[k] / escape);
  for (size_t k = 0; k < d.size(); ++k) {
    CHECK(arrival[k] > d[k] / escape);
    if (k > 0) CHECK(arrival[k] > arrival[k - 1]);
  }
  // The crack faces: every face of the pre-cut joints is exposed, and those beside the gas now carry its
  // pressure (tens of MPa, the ambient pressure being 0.1 MPa).
  c.coupler.gas_to_rock();
  const std::vector<double> edge_p = c.rock.edge_pressures();
  const std::vector<std::uint8_t> exposed = c.rock.edge_exposure();
  const fdem::RockSnapshot snap = c.rock.snapshot();
  int faces = 0, loaded = 0;
  double opening = 0;
  for (size_t slot = 0; slot < exposed.size(); ++slot) {
    const size_t t = slot / 3, b = 3 * t + (slot % 3 + 1) % 3;
    const double ym0 = 0.5 * (s0.y[slot] + s0.y[b]), xm0 = 0.5 * (s0.x[slot] + s0.x[b]);
    if (std::fabs(ym0) > 1e-9 || xm0 < a || xm0 > a + L) continue;  // not a crack face
    ++faces;
    CHECK(exposed[slot] == fdem::kEdgeCrackFace);
    if (edge_p[slot] > 0.25 * p_hole) ++loaded;
    opening = std::fmax(opening, std::fabs(0.5 * (snap.y[slot] + snap.y[b])));
  }
  std::printf("I5: %d crack faces, %d loaded above p_hole / 4; largest face displacement off the crack line %.2f mm\n",
              faces, loaded, 1e3 * opening);
  CHECK(faces == 2 * static_cast<int>(crack.size()));
  CHECK(loaded >= faces / 2);
}

TEST_CASE("Joints that break during a coupled run join the exposed edges and take the gas pressure", "[ibm][cracking][heavy]") {
  // The paper's rock around a 20 mm hole of Table 1 gas: the hoop tension (about the gas pressure, 28 MPa)
  // exceeds the tensile strength (6.3 MPa), so radial cracks start at the wall. Their faces join the exposed
  // edges as crack faces and are given a pressure by the coupler every step: the ambient one while the crack
  // is narrower than the grid (no gas cell in it), the gas's once the cell they face is active.
  HoleInRock c(80, 0.12, 0.1, 0.02, 0.005, fdem::RockMaterial::paper_table2());
  const long boundary = static_cast<long>(c.rock.boundary_edges().size());
  c.run_to(40e-6);  // on this mesh the first joints break between 20 and 30 us
  // The loads for the rock's next steps: joints that broke in the last rock step get theirs now (2 of 22 here).
  c.coupler.gas_to_rock();
  const fdem::RockEnergies e = c.rock.energies();
  const std::vector<std::uint8_t> exposed = c.rock.edge_exposure();
  const std::vector<double> edge_p = c.rock.edge_pressures();
  const fdem::RockSnapshot snap = c.rock.snapshot();
  long n_boundary = 0, n_crack = 0, faces_with_pressure = 0;
  for (std::uint8_t x : exposed) n_boundary += x == fdem::kEdgeBoundary, n_crack += x == fdem::kEdgeCrackFace;
  const double p_air = eos.pressure(air.density, air.internal_energy);
  for (size_t j = 0; j < snap.joint_broken.size(); ++j) {
    if (!snap.joint_broken[j]) continue;
    for (int side : {0, 2})  // both faces' slots
      if (exposed[snap.joint_nodes[j][side]] == fdem::kEdgeCrackFace && edge_p[snap.joint_nodes[j][side]] >= p_air * (1 - 1e-9))
        ++faces_with_pressure;
  }
  std::printf("cracking: %d joints broken by 40 us; exposed edges: %ld boundary (mesh: %ld) + %ld crack faces, %ld of "
              "them with a gas pressure (>= ambient)\n", e.broken_joints, n_boundary, boundary, n_crack, faces_with_pressure);
  REQUIRE(e.broken_joints > 0);
  CHECK(n_boundary == boundary);
  CHECK(n_crack == 2L * e.broken_joints);
  CHECK(faces_with_pressure == n_crack);
}
#endif
