//! \file test_crack_coupling.cpp
//! \brief docs/validation.md C4-C5: the crack gas coupled to the grid gas and the rock (GasRockCoupler with
//! enable_crack_gas()): total gas mass kept exactly while cracks grow, and the lumped limit of a rigid crack
//! filled from a hole.
#include "catch.hpp"
#include "hole_in_rock.hpp"

#include "blastsim/ibm/budget.hpp"

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

TEST_CASE("C5 crack gas: a rigid crack filled from a hole settles to the lumped uniform state", "[ibm][crack][C5]") {
  // A 30 mm pre-cut crack from the wall of a 15 mm hole in rock held still, aperture 1 mm (residual; rigid
  // walls do not open it), no friction. Gas moves from the hole into the empty crack until both hold one
  // state: that of the same mass and energy in the sum of their volumes, p = (gamma - 1) E / V.
  const double a = 0.015, L = 0.03;
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
  auto hole_volume = [&] {
    const cip::HostGasFields h = c.gas.to_host();
    const cip::GasGrid g = c.gas.grid();
    double v = 0;
    for (int j = 0; j < g.ny; ++j)
      for (int i = 0; i < g.nx; ++i)
        if (h.active[static_cast<size_t>(j) * g.nx + i] && hole.contains(g.cell_x(i), g.cell_y(j))) v += g.cell_area();
    return v;
  };
  c.run_to(1.5e-3, true);  // the gas at its Courant limit, the rock (held) subcycled
  const cip::GasTotals hg = c.coupler.gas_in(hole);
  const ibm::CrackGasTotals cg = c.coupler.diagnostics().crack;
  const double V = hole_volume() + cg.volume, E = hg.total_energy() + cg.energy;
  const double p_uniform = 0.4 * E / V;
  const std::vector<ibm::ChannelPrimitive> cp = c.coupler.crack_gas()->primitives();
  const std::vector<std::uint8_t> kind = c.coupler.crack_gas()->kinds();
  double p_lo = 1e300, p_hi = 0;
  for (int j : crack) {
    REQUIRE(kind[j] == ibm::kSegmentGas);
    p_lo = std::fmin(p_lo, cp[j].p), p_hi = std::fmax(p_hi, cp[j].p);
  }
  const double p_hole = 0.4 * hg.internal_energy / hole_volume();
  std::printf("C5: crack volume %.3e of %.3e m2 (%.1f %%), crack mass %.4e kg/m; at 1.5 ms crack pressures %.4f to %.4f "
              "MPa, hole %.4f MPa, lumped uniform state %.4f MPa (%+.2f %% / %+.2f %% / %+.2f %%)\n",
              cg.volume, V, 100 * cg.volume / V, cg.mass, 1e-6 * p_lo, 1e-6 * p_hi, 1e-6 * p_hole, 1e-6 * p_uniform,
              100 * (p_lo / p_uniform - 1), 100 * (p_hi / p_uniform - 1), 100 * (p_hole / p_uniform - 1));
  CHECK(std::fabs(p_lo / p_uniform - 1) < 0.02);
  CHECK(std::fabs(p_hi / p_uniform - 1) < 0.02);
  CHECK(std::fabs(p_hole / p_uniform - 1) < 0.02);
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
    const std::vector<ibm::ChannelPrimitive> p = c.coupler.crack_gas()->primitives();
    const std::vector<std::uint8_t> kind = c.coupler.crack_gas()->kinds();
    for (size_t k = 0; k < stations.size(); ++k)
      if (arrival[k] < 0 && kind[at[k]] == ibm::kSegmentGas && p[at[k]].p > p_quarter) arrival[k] = c.gas.time();
  }
  return arrival;
}
}  // namespace

TEST_CASE("C6 crack gas: arrival along a sub-cell crack in the paper's rock does not depend on the grid",
          "[ibm][crack][C6]") {
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
