//! \file test_crack_coupling.cpp
//! \brief docs/validation.md C4-C5: the crack gas coupled to the grid gas and the rock (GasRockCoupler with
//! enable_crack_gas()): total gas mass kept exactly while cracks grow, and the lumped limit of a rigid crack
//! filled from a hole; C12: an open joint's aperture under normal stress.
#include "catch.hpp"
#include "hole_in_rock.hpp"

#include "blastsim/fdem/rock_model.hpp"
#include "blastsim/ibm/budget.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

using namespace blastsim;
using test::HoleInRock;
using test::table1_gas;

#if defined(BLASTSIM_TEST_HAVE_GMSH)

TEST_CASE("C4 crack gas: grid + crack gas mass kept to round-off while cracks grow from a hole", "[ibm][crack][C4]") {
  // The paper's rock (Table 2) around a 20 mm hole of Table 1 gas: radial cracks start at the wall and grow;
  // the hole's gas enters them. Total = grid gas + crack gas + what left the grid's edge - what the cell
  // transitions created.
  HoleInRock c(80, 0.12, 0.1, 0.02, 0.005, fdem::RockMaterial::paper_table2());
  c.coupler.enable_crack_gas(ibm::CrackGasOptions{});
  auto total = [&] {
    const ibm::CouplingDiagnostics d = c.coupler.diagnostics();
    return c.gas.totals().mass + d.crack.mass + c.gas.boundary_outflow().mass - d.transitions.mass_created;
  };
  const double m0 = total();
  const double e0 = ibm::initial_energy(c.gas, c.rock);
  c.run_to(30e-6);
  const double m1 = total();
  const ibm::CouplingDiagnostics d = c.coupler.diagnostics();
  const ibm::CoupledBudget b = ibm::coupled_budget(c.gas, c.rock, c.coupler, e0);
  std::printf("C4: %d joints broken by 30 us, %ld hold gas (%ld above 1.5 x ambient), crack gas %.3e kg/m, %.3e J/m, "
              "peak %.2f MPa; total gas mass %.15e -> %.15e kg/m (%.1e); energy budget residual %.2f %% of the work on "
              "the rock\n",
              c.rock.energies().broken_joints, d.crack.gas_segments, d.crack.wet_segments, d.crack.mass, d.crack.energy,
              1e-6 * d.crack.max_pressure, m0, m1, m1 / m0 - 1, 100 * b.residual / d.gas_work_on_rock);
  REQUIRE(c.rock.energies().broken_joints > 0);
  CHECK(d.crack.gas_segments > 0);  // (a joint that broke in the last rock step joins at the next step)
  CHECK(d.crack.gas_segments <= c.rock.energies().broken_joints);
  CHECK(d.crack.mass > 0);                  // the hole's gas entered the cracks
  CHECK(d.crack.wet_segments > 0);
  CHECK(std::fabs(m1 / m0 - 1) < 1e-12);
  CHECK(std::fabs(b.residual / d.gas_work_on_rock) < 0.05);
}

TEST_CASE("C5 crack gas: a rigid crack filled from a hole oscillates about the lumped uniform state",
          "[long][ibm][crack][C5]") {
  // A 30 mm pre-cut crack from the wall of a 15 mm hole in rock held still, aperture 1 mm (residual; rigid
  // walls do not open it), no friction. Gas moves from the hole into the empty crack; the mean state about
  // which hole and crack then oscillate is that of the same mass and energy in the sum of their volumes,
  // p = (gamma - 1) E / V. Without friction and crack viscosity only the grid's artificial viscosity damps the
  // sloshing between hole and crack (period about 0.23 ms, crack pressures +-5 % about the mean at 1.3 ms), so
  // the state at one instant depends on the phase of the oscillation; asserted are the time means over the
  // last 0.5 ms (about two periods).
  const double a = 0.015, L = 0.03, t_mean = 1.0e-3, t_end = 1.5e-3;
  HoleInRock c(96, 0.12, 0.1, a, 0.004, test::intact_rock(), {fdem::Segment{{a, 0}, {a + L, 0}}});
  std::vector<int> all(c.rock.node_count());
  for (int k = 0; k < c.rock.node_count(); ++k) all[k] = k;
  c.rock.prescribe_velocity(all, true, true, 0, 0);
  const std::vector<int> crack = c.rock.joints_on_segment(a, 0, a + L, 0, 1e-6);
  REQUIRE(crack.size() >= 6);
  c.rock.break_joints(crack);
  ibm::CrackGasOptions opt;
  opt.residual_aperture = 1e-3, opt.friction_factor = 0, opt.viscosity = 0;
  c.coupler.enable_crack_gas(opt);
  const cip::CellRegion hole = cip::CellRegion::circle(0, 0, a + 2 * c.gas.grid().dx);
  const double hole_volume = [&] {  // the rock is held, so the hole's cells stay the same
    const cip::HostGasFields h = c.gas.to_host();
    const cip::GasGrid g = c.gas.grid();
    double v = 0;
    for (int j = 0; j < g.ny; ++j)
      for (int i = 0; i < g.nx; ++i)
        if (h.active[static_cast<size_t>(j) * g.nx + i] && hole.contains(g.cell_x(i), g.cell_y(j))) v += g.cell_area();
    return v;
  }();
  auto hole_pressure = [&] { return 0.4 * c.coupler.gas_in(hole).internal_energy / hole_volume; };
  c.run_to(t_mean, true);  // the gas at its Courant limit, the rock (held) subcycled
  std::vector<double> crack_mean(crack.size(), 0.0);
  double hole_mean = 0, window = 0;
  while (c.gas.time() < t_end - 1e-12) {
    const double dt = c.step_towards(t_end, true);
    const std::vector<ibm::ChannelPrimitive> cp = c.coupler.crack_gas()->crack_gas().primitives();
    for (size_t k = 0; k < crack.size(); ++k) crack_mean[k] += dt * cp[crack[k]].p;
    hole_mean += dt * hole_pressure();
    window += dt;
  }
  for (double& p : crack_mean) p /= window;
  hole_mean /= window;
  const cip::GasTotals hg = c.coupler.gas_in(hole);
  const ibm::CrackGasTotals cg = c.coupler.diagnostics().crack;
  const double V = hole_volume + cg.volume, E = hg.total_energy() + cg.energy;
  const double p_uniform = 0.4 * E / V;
  const std::vector<ibm::ChannelPrimitive> cp = c.coupler.crack_gas()->crack_gas().primitives();
  const std::vector<std::uint8_t> kind = c.coupler.crack_gas()->crack_gas().kinds();
  double p_lo = 1e300, p_hi = 0;
  for (int j : crack) {
    REQUIRE(kind[j] == ibm::kSegmentGas);
    p_lo = std::fmin(p_lo, cp[j].p), p_hi = std::fmax(p_hi, cp[j].p);
  }
  const double mean_lo = *std::min_element(crack_mean.begin(), crack_mean.end());
  const double mean_hi = *std::max_element(crack_mean.begin(), crack_mean.end());
  std::printf("C5: crack volume %.3e of %.3e m2 (%.1f %%), crack mass %.4e kg/m; lumped uniform state %.4f MPa; mean "
              "over %.1f to %.1f ms: crack %+.2f %% to %+.2f %%, hole %+.2f %%; at %.1f ms: crack %+.2f %% to %+.2f %%, "
              "hole %+.2f %%\n",
              cg.volume, V, 100 * cg.volume / V, cg.mass, 1e-6 * p_uniform, 1e3 * t_mean, 1e3 * t_end,
              100 * (mean_lo / p_uniform - 1), 100 * (mean_hi / p_uniform - 1), 100 * (hole_mean / p_uniform - 1),
              1e3 * t_end, 100 * (p_lo / p_uniform - 1), 100 * (p_hi / p_uniform - 1),
              100 * (hole_pressure() / p_uniform - 1));
  for (double p : crack_mean) CHECK(std::fabs(p / p_uniform - 1) < 0.02);
  CHECK(std::fabs(hole_mean / p_uniform - 1) < 0.02);
}

#endif

#if defined(BLASTSIM_TEST_HAVE_GMSH)
namespace {
//! Times [s] at which the crack gas at 10, 20 and 30 mm along a 40 mm pre-cut crack from a 20 mm hole of Table 1
//! gas in the paper's elastic rock (strengths raised so that only the cut is a crack) first exceeds a quarter
//! of the hole's initial pressure, on an N x N grid over 0.24 m (-1: not by t_max).
std::vector<double> crack_arrivals(int N, double t_max) {
  // The cut runs at y = 0.5 mm, off every face point of both grids (faces at multiples of 2 mm, cell centres
  // at odd mm on the fine grid): on a face row, the faces in the micron gap would be uncovered and the grid
  // itself would carry gas along the cut.
  const double a = 0.02, L = 0.04, y = 0.0005, x0 = std::sqrt(a * a - y * y);
  HoleInRock c(N, 0.12, 0.1, a, 0.004, test::intact_rock(), {fdem::Segment{{x0, y}, {a + L, y}}});
  const std::vector<int> crack = c.rock.joints_on_segment(x0, y, a + L, y, 1e-6);
  REQUIRE(crack.size() >= 8);
  c.rock.break_joints(crack);
  c.coupler.enable_crack_gas(ibm::CrackGasOptions{});
  const fdem::RockSnapshot s0 = c.rock.snapshot();
  const std::vector<double> stations{0.010, 0.020, 0.030};
  std::vector<int> at(stations.size());
  for (size_t k = 0; k < stations.size(); ++k) {  // the cut joint whose midpoint is nearest the station
    double best = 1e300;
    for (int j : crack) {
      const auto& n = s0.joint_nodes[j];
      const double xm = 0.5 * (s0.x[n[0]] + s0.x[n[1]]);
      if (std::fabs(xm - a - stations[k]) < best) best = std::fabs(xm - a - stations[k]), at[k] = j;
    }
  }
  const double p_quarter = 0.25 * 0.4 * table1_gas.density * table1_gas.internal_energy;
  std::vector<double> arrival(stations.size(), -1);
  while (c.gas.time() < t_max && arrival.back() < 0) {
    c.run_to(c.gas.time() + 1e-6, true);
    const std::vector<ibm::ChannelPrimitive> p = c.coupler.crack_gas()->crack_gas().primitives();
    const std::vector<std::uint8_t> kind = c.coupler.crack_gas()->crack_gas().kinds();
    for (size_t k = 0; k < stations.size(); ++k)
      if (arrival[k] < 0 && kind[at[k]] == ibm::kSegmentGas && p[at[k]].p > p_quarter) arrival[k] = c.gas.time();
    // The crack gas's front at p_hole / 4 (blast_front() with no fraction asked) against the stations: the
    // distance from the hole centre of the farthest cut joint at it, computed here from the joints' gas.
    double farthest = 0.0;
    const fdem::RockSnapshot s = c.rock.snapshot();
    for (int j : crack) {
      if (kind[j] != ibm::kSegmentGas || !(p[j].p >= p_quarter)) continue;
      const auto& n = s.joint_nodes[j];
      double xm = 0, ym = 0;
      for (int q = 0; q < 4; ++q) xm += 0.25 * s.x[n[q]], ym += 0.25 * s.y[n[q]];
      farthest = std::fmax(farthest, std::hypot(xm, ym));
    }
    CHECK_THAT(c.coupler.crack_gas()->blast_front(c.rock, {0.0, 0.0}, 0.0, p_quarter), Catch::Matchers::WithinAbs(farthest, 1e-12));
  }
  std::printf("C6 (%d^2 cells): crack gas front above p_hole / 4 at the end: %.4f m from the hole centre\n", N,
              c.coupler.crack_gas()->blast_front(c.rock, {0.0, 0.0}, 0.0, p_quarter));
  return arrival;
}
}  // namespace

TEST_CASE("C6 crack gas: arrival along a sub-cell crack in the paper's rock does not depend on the grid",
          "[long][ibm][crack][C6]") {
  // The cut opens by microns under the gas (E = 55 GPa): far below both grids' cells (4 and 2 mm), so without
  // crack gas no gas would enter at all. With it, the gas's progress is the channel's, not the grid's.
  const std::vector<double> coarse = crack_arrivals(60, 2e-3), fine = crack_arrivals(120, 2e-3);
  for (size_t k = 0; k < coarse.size(); ++k) {
    std::printf("C6: crack gas above p_hole / 4 at %d mm: %.1f us (60^2 cells, 4 mm) vs %.1f us (120^2, 2 mm): %+.2f %%\n",
                10 * static_cast<int>(k + 1), 1e6 * coarse[k], 1e6 * fine[k], 100 * (coarse[k] / fine[k] - 1));
    REQUIRE(coarse[k] > 0);
    REQUIRE(fine[k] > 0);
    CHECK(std::fabs(coarse[k] / fine[k] - 1) < 0.10);
    if (k > 0) CHECK(fine[k] > fine[k - 1]);
  }
}
#endif

#if defined(BLASTSIM_TEST_HAVE_GMSH)
TEST_CASE("C7 crack gas: a crack held at a gas pressure opens as Sneddon's crack", "[long][ibm][crack][C7]") {
  // A straight crack of half-length a (16 joints broken) in the middle of a square plate of the paper's rock
  // (E = 55 GPa, nu = 0.3, plane strain; strengths raised so that only the cut is a crack), half-width 5a,
  // damped. Its gas is held at p: a residual aperture of 1 m gives the crack a volume that the microns of
  // opening do not change (p stays within 1e-4). The gas grid lies inside the plate (every cell covered), so
  // the plate's outline carries the ambient pressure p0 of the coupler: the crack opens under p - p0.
  // Reference: Sneddon's opening of a pressurised crack in an infinite plane (Sneddon 1946, Proc. R. Soc. A
  // 187:229; plane strain), w(x) = 4 (1 - nu^2) (p - p0) / E sqrt(a^2 - x^2); the finite plate (a / W = 0.2)
  // opens it by about 2.5 % more (Tada, Paris & Irwin 2000, "The Stress Analysis of Cracks Handbook", the
  // centre-cracked plate's secant factor), within the 10 % asked.
  const double a = 0.04, W = 5 * a, h = a / 8, y = 0.5 * h;
  const cip::GasPoint ambient{1.2, 2.09e5, 0, 0};
  cip::GasSolver gas(cip::GasGrid::from_box(8, 8, -0.8 * W, 0.8 * W, -0.8 * W, 0.8 * W), cip::EquationOfState::ideal(1.4));
  gas.initialise([&](double, double) { return ambient; });
  fdem::RockOptions ro;
  ro.contact = false, ro.damping_ratio = 0.9, ro.joint_penalty_factor = 100;
  fdem::RockSolver rock(fdem::build_topology(fdem::gmsh_rectangle(-W, -W, W, W, h, {fdem::Segment{{-a, y}, {a, y}}}).mesh),
                        test::intact_rock(), ro);
  ibm::GasRockCoupler coupler(gas, rock, ambient);
  const std::vector<int> crack = rock.joints_on_segment(-a, y, a, y, 1e-6);
  REQUIRE(crack.size() >= 12);
  rock.break_joints(crack);
  ibm::CrackGasOptions opt;
  opt.residual_aperture = 1.0, opt.friction_factor = 0, opt.viscosity = 0;
  coupler.enable_crack_gas(opt);
  const double p = 10e6, p0 = 0.4 * ambient.density * ambient.internal_energy, rho = 10.0;
  const fdem::RockSnapshot s0 = rock.snapshot();
  std::vector<std::uint8_t> kind(rock.joint_count(), ibm::kSegmentNone);
  std::vector<ibm::ChannelConserved> cons(rock.joint_count(), ibm::ChannelConserved{0, 0, 0, 0, 0});
  std::vector<double> volume(rock.joint_count(), 1.0);
  for (int j : crack) {
    const auto& n = s0.joint_nodes[j];
    const double L = std::hypot(s0.x[n[1]] - s0.x[n[0]], s0.y[n[1]] - s0.y[n[0]]);
    kind[j] = ibm::kSegmentGas, volume[j] = L * opt.residual_aperture;
    cons[j] = {rho * volume[j], 0.0, p / 0.4 * volume[j], 0.0, 0.0};
  }
  coupler.crack_gas()->crack_gas().set_gas(kind, cons, volume);
  coupler.rock_to_gas();
  REQUIRE(coupler.inactive_cells() == 64);  // the grid lies inside the plate
  // Damped dynamic relaxation to 250 us (the crack's opening mode decays in about 30 us); the opening is
  // averaged over the last 80 us. Joint penalty 100 E: the intact joints' elastic compliance, which makes
  // an FDEM mesh softer than its triangles (docs/fdem-solver.md), opened the crack 27 % wider than Sneddon's
  // with the default 10 E.
  const double dt = 0.9 * rock.stable_dt() * 8;
  const int substeps = 8;
  std::vector<double> mean(crack.size(), 0.0);
  int samples = 0;
  auto opening = [](const fdem::RockSnapshot& s, int j) {  // mean normal opening of joint j's two ends [m]
    const auto& n = s.joint_nodes[j];  // a0, a1, b0, b1: a0 faces b1, a1 faces b0
    const double ax = s.x[n[1]] - s.x[n[0]], ay = s.y[n[1]] - s.y[n[0]], la = std::hypot(ax, ay);
    const double nx = ay / la, ny = -ax / la;
    return 0.5 * ((s.x[n[3]] - s.x[n[0]]) * nx + (s.y[n[3]] - s.y[n[0]]) * ny + (s.x[n[2]] - s.x[n[1]]) * nx +
                  (s.y[n[2]] - s.y[n[1]]) * ny);
  };
  for (int k = 0; gas.time() < 250e-6; ++k) {
    coupler.step(dt, substeps);
    if (gas.time() > 170e-6 && k % 5 == 0) {
      const fdem::RockSnapshot s = rock.snapshot();
      for (size_t c = 0; c < crack.size(); ++c) mean[c] += opening(s, crack[c]);
      ++samples;
    }
  }
  const double E = rock.material().youngs_modulus, nu = rock.material().poisson_ratio;
  auto sneddon = [&](double x) { return 4 * (1 - nu * nu) * (p - p0) / E * std::sqrt(std::max(0.0, a * a - x * x)); };
  const std::vector<ibm::ChannelPrimitive> cp = coupler.crack_gas()->crack_gas().primitives();
  int checked = 0;
  double worst = 0;
  for (size_t c = 0; c < crack.size(); ++c) {
    const auto& n = s0.joint_nodes[crack[c]];
    const double x0 = s0.x[n[0]], x1 = s0.x[n[1]];
    const double w_num = mean[c] / samples, w_ref = 0.5 * (sneddon(x0) + sneddon(x1));
    CHECK(std::fabs(cp[crack[c]].p / p - 1) < 1e-3);  // the gas pressure held
    if (std::max(std::fabs(x0), std::fabs(x1)) > 0.8 * a + 1e-9) continue;
    ++checked;
    worst = std::max(worst, std::fabs(w_num / w_ref - 1));
    std::printf("C7 Sneddon: joint from x = %+.4f to %+.4f m: opening %.4e m, Sneddon %.4e m (%+.2f %%)\n", x0, x1, w_num,
                w_ref, 100 * (w_num / w_ref - 1));
    CHECK(std::fabs(w_num / w_ref - 1) < 0.10);
  }
  std::printf("C7 Sneddon: %d joints in the middle 80 %% of the crack, largest deviation %.2f %% (%d samples)\n", checked,
              100 * worst, samples);
  CHECK(checked >= 8);
}
#endif

TEST_CASE("C12 open joints under stress: an open pre-cut crack's aperture follows the Barton-Bandis hyperbola of its "
          "effective normal stress",
          "[ibm][crack][C12]") {
  // A plate of the paper's rock (strengths x 100: intact), 0.3 x 0.2 m on a structured mesh of 25 mm cells, held
  // on every side by a uniform in-situ stress -S in x and y; a horizontal pre-cut crack across its middle third
  // stands open by a0 = 1 mm, its gas at p = 1 MPa, and closes by the Barton-Bandis hyperbola with K_ni = 20
  // MPa/mm and V_m = 0.5 mm. The uniform field is carried across the crack by the faces' contact, so the
  // asperities see S - p, and the segments' aperture must be w_r + a0 - (S - p) V_m / (K_ni V_m + S - p), p the
  // gas's pressure as it stands (the closing joint compresses its gas): for S = 5 and 40 MPa a closure of about
  // 0.14 and 0.40 mm, on the hyperbola's bend towards V_m. The faces' contact overlap (microns) and the triangles'
  // stress near the crack tips enter too: bound 3 % of the closure, on the crack's middle joints.
  const double K = 2e10, Vm = 5e-4, a0 = 1e-3, p = 1e6, wr = 1e-5;
  for (const double S : {5e6, 40e6}) {
    fdem::NamedMesh mesh;
    mesh.mesh = fdem::structured_rectangle(12, 8, 0.0, 0.3, 0.0, 0.2);
    const fdem::FdemTopology topo = fdem::build_topology(mesh.mesh);
    fdem::RockOptions ro;
    ro.damping_ratio = 0.9;
    fdem::RockSolver rock(topo, test::intact_rock(), ro);
    const std::vector<int> crack = rock.joints_on_segment(0.1, 0.1, 0.2, 0.1, 1e-6);
    REQUIRE(crack.size() >= 4);
    rock.break_joints(crack);
    std::vector<int> all;
    for (const fdem::BoundaryEdge& b : topo.boundary_edges) all.push_back(b.n0);
    fdem::InSituStress field;
    field.at_reference = {-S, -S, 0.0};
    fdem::set_in_situ_stress(rock, field, all);
    const cip::GasPoint ambient{1.2, 2.09e5, 0, 0};
    cip::GasSolver gas(cip::GasGrid::from_box(8, 8, 0.02, 0.28, 0.02, 0.18), cip::EquationOfState::ideal(1.4));
    gas.initialise([&](double, double) { return ambient; });
    ibm::GasRockCoupler coupler(gas, rock, ambient);
    ibm::CrackGasOptions opt;
    opt.residual_aperture = wr, opt.friction_factor = 0, opt.viscosity = 0, opt.walls = ibm::WallHeat::adiabatic;
    opt.joint_closure = ibm::JointClosure{K, Vm};
    ibm::CrackGasCoupling& cg = coupler.enable_crack_gas(opt);
    cg.set_initial_apertures(crack, a0);
    std::vector<std::uint8_t> kind(rock.joint_count(), ibm::kSegmentNone);
    std::vector<ibm::ChannelConserved> cons(rock.joint_count(), ibm::ChannelConserved{0, 0, 0, 0, 0});
    std::vector<double> volume(rock.joint_count(), 1.0);
    for (int j : crack) {
      kind[j] = ibm::kSegmentGas, volume[j] = 0.025 * a0;
      cons[j] = {10.0 * volume[j], 0.0, p / 0.4 * volume[j], 0.0, 0.0};
    }
    cg.crack_gas().set_gas(kind, cons, volume);
    coupler.rock_to_gas();
    REQUIRE(coupler.inactive_cells() == 64);  // the grid lies inside the plate: the crack has no mouth
    const double dt = 0.9 * rock.stable_dt() * 4;
    for (int k = 0; k < 300; ++k) coupler.step(dt, 4);
    const std::vector<double> w = cg.crack_gas().apertures();
    const std::vector<ibm::ChannelPrimitive> prim = cg.crack_gas().primitives();
    const fdem::RockSnapshot snap = rock.snapshot();
    int checked = 0;
    for (int j : crack) {
      const auto& n = snap.joint_nodes[j];
      const double xm = 0.5 * (snap.x[n[0]] + snap.x[n[1]]);
      if (xm < 0.125 || xm > 0.175) continue;  // the middle joints
      const double sigma = S - prim[j].p, closure = sigma * Vm / (K * Vm + sigma), law = wr + a0 - closure;
      std::printf("C12 S = %.0f MPa, joint at x = %.4f m: gas %.4f MPa, aperture %.5e m, law %.5e m (closure %.4e m): "
                  "%+.2f %% of the closure (bound 3 %%)\n",
                  S / 1e6, xm, prim[j].p / 1e6, w[j], law, closure, 100 * (w[j] - law) / closure);
      CHECK(std::fabs(w[j] - law) < 0.03 * closure);
      ++checked;
    }
    CHECK(checked >= 2);
  }
  // The closure cannot exceed the aperture it closes.
  {
    fdem::NamedMesh mesh;
    mesh.mesh = fdem::structured_rectangle(4, 4, 0.0, 0.1, 0.0, 0.1);
    fdem::RockSolver rock(fdem::build_topology(mesh.mesh), test::intact_rock(), fdem::RockOptions{});
    const cip::GasPoint ambient{1.2, 2.09e5, 0, 0};
    cip::GasSolver gas(cip::GasGrid::from_box(4, 4, 0.0, 0.1, 0.0, 0.1), cip::EquationOfState::ideal(1.4));
    ibm::GasRockCoupler coupler(gas, rock, ambient);
    ibm::CrackGasOptions opt;
    opt.joint_closure = ibm::JointClosure{K, 2e-3};
    ibm::CrackGasCoupling& cg = coupler.enable_crack_gas(opt);
    CHECK_THROWS_WITH(cg.set_initial_apertures({0}, 1e-3), Catch::Contains("joint_max_closure"));
  }
}
