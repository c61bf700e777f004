//! \file rigid_crack.hpp
//! \brief The crack-flow tests' rigid crack (tests/ibm; needs Gmsh): a block of rock cut across its whole length
//! by a straight pre-cut crack, its two halves held by prescribed velocities, the crack's mouth on a reservoir of
//! the paper's Table 1 gas (traced) in air, on a square grid with walls.
#pragma once

#include "blastsim/cip/gas_solver.hpp"
#include "blastsim/fdem/gmsh_mesh.hpp"
#include "blastsim/fdem/rock_solver.hpp"
#include "blastsim/ibm/coupler.hpp"
#include "catch.hpp"

#include <cmath>
#include <memory>
#include <vector>

namespace blastsim::test {

//! Where the block, its crack and the reservoir lie [m].
struct RigidCrackGeometry {
  double length = 0.1;     //!< of the block and its crack, from x = 0 (the mouth) to x = length (closed end)
  double half_height = 0.02;
  double angle = 0.0;      //!< [rad] of the block and its crack about the mouth (0: along +x)
  double offset = 0.0;     //!< the crack's distance from the block's mid line (across it) [m]
  double element = 0.005;  //!< triangle size [m]
  double cell = 0.002;     //!< gas cell size [m]
  double reservoir = 0.06; //!< the gas reservoir's depth in front of the mouth [m]
  double gap = 0.0;        //!< the crack's geometric opening [m]: the upper half moved away from the lower
};

//! The block, its crack and the grid. The reservoir (the cells in front of the block's mouth face) holds the
//! Table 1 gas, traced; the rest of the grid air at rest; walls all round.
struct RigidCrack {
  RigidCrackGeometry geo;
  cip::GasSolver gas;
  fdem::RockSolver rock;
  std::unique_ptr<ibm::GasRockCoupler> coupler;
  std::vector<int> crack, upper;  //!< the crack's joints; the upper half's nodes

  static cip::GasMaterials traced_air() {
    cip::GasMaterials m;
    m.air = cip::EquationOfState::ideal(1.4);
    m.tracer = true;
    return m;
  }
  static fdem::RockOptions held() {
    fdem::RockOptions o;
    o.contact = false;
    return o;
  }
  static cip::GasGrid grid_of(const RigidCrackGeometry& g) {
    const double half = g.length + g.reservoir + 2 * g.cell;  // a square around the block, any angle
    const int n = 2 * static_cast<int>(std::ceil(half / g.cell));
    return cip::GasGrid::from_box(n, n, -0.5 * n * g.cell, 0.5 * n * g.cell, -0.5 * n * g.cell, 0.5 * n * g.cell);
  }
  //! A point of the block's own frame (x along the crack from the mouth, y across it) in the world [m].
  std::array<double, 2> world(double x, double y) const {
    const double c = std::cos(geo.angle), s = std::sin(geo.angle);
    return {c * x - s * y, s * x + c * y};
  }

  //! `crack_gas` false: the grid alone carries the crack (the "grid alone" row of docs/coupling.md's hand-over
  //! table; a very large CrackGasOptions::handover_width gives the channel alone).
  RigidCrack(const RigidCrackGeometry& g, const ibm::CrackGasOptions& crack_options, bool crack_gas = true)
      : geo(g), gas(grid_of(g), traced_air(), walls()),
        rock(fdem::build_topology(mesh(g)), intact(), held()) {
    const cip::GasPoint hole{163.0, 4.29e5, 0.0, 0.0, 0.0, 1.0}, air{1.2, 2.09e5, 0.0, 0.0};
    const double c = std::cos(g.angle), s = std::sin(g.angle);
    gas.initialise([&](double x, double y) {
      const double along = c * x + s * y, across = -s * x + c * y;  // the block's frame
      return along < -g.cell && along > -g.reservoir && std::fabs(across) < g.half_height + g.reservoir ? hole : air;
    });
    // The crack: the joints along its line; the upper half: the nodes above it, moved by the gap.
    const std::array<double, 2> a = world(0, g.offset), b = world(g.length, g.offset);
    crack = rock.joints_on_segment(a[0], a[1], b[0], b[1], 1e-6 * g.length);
    REQUIRE(crack.size() >= 2);
    rock.break_joints(crack);
    const fdem::RockSnapshot s0 = rock.snapshot();
    std::vector<double> xy(2 * rock.node_count());
    for (int n = 0; n < rock.node_count(); ++n) {
      const int t = n / 3;  // a node belongs to one triangle: the triangle's side of the crack is the node's
      const double cx = (s0.x[3 * t] + s0.x[3 * t + 1] + s0.x[3 * t + 2]) / 3;
      const double cy = (s0.y[3 * t] + s0.y[3 * t + 1] + s0.y[3 * t + 2]) / 3;
      const bool above = -s * cx + c * cy > g.offset;
      if (above) upper.push_back(n);
      xy[2 * n] = s0.x[n] + (above ? -s * g.gap : 0.0);
      xy[2 * n + 1] = s0.y[n] + (above ? c * g.gap : 0.0);
    }
    rock.set_positions(xy);
    hold(0.0);
    ibm::CouplerOptions o;
    o.gas_load = ibm::GasLoad::face_forces;
    coupler = std::make_unique<ibm::GasRockCoupler>(gas, rock, air, o);
    if (crack_gas) coupler->enable_crack_gas(crack_options);
    coupler->rock_to_gas();
  }
  //! Holds the lower half at rest and moves the upper half across the crack at `closing` [m/s] (> 0: towards
  //! the lower half).
  void hold(double closing, double sliding = 0.0) {
    rock.prescribe_velocity(lower_nodes(), true, true, 0, 0);
    rock.prescribe_velocity(upper, true, true, std::sin(geo.angle) * closing + std::cos(geo.angle) * sliding,
                            -std::cos(geo.angle) * closing + std::sin(geo.angle) * sliding);
  }
  std::vector<int> lower_nodes() const {
    std::vector<int> lower;
    for (int n = 0, k = 0; n < rock.node_count(); ++n) {
      if (k < static_cast<int>(upper.size()) && upper[k] == n) ++k;
      else lower.push_back(n);
    }
    return lower;
  }
  //! Steps to t at the gas's Courant limit `courant`, the rock filling each step with its own.
  void run_to(double t, double courant = 0.2) {
    while (gas.time() < t - 1e-12) {
      const double dt = std::fmin(gas.courant_dt(courant), t - gas.time());
      if (!(dt > 0)) FAIL("no stable step at t = " << gas.time() << ": " << gas.describe_invalid_cell());
      coupler->step(dt, ibm::rock_substeps(dt, 0.9 * rock.stable_dt()));
    }
  }
  //! The traced gas [kg/m] in the crack farther than `from` [m] from its mouth: in the cracks' own gas (the
  //! segments whose midpoints lie beyond it) and in the grid's cells centred in the block beyond it, at least
  //! two cells inside its long sides.
  double traced_in_crack(double from) const {
    const cip::HostGasFields h = gas.to_host();
    const cip::GasGrid g = gas.grid();
    const double c = std::cos(geo.angle), s = std::sin(geo.angle);
    double m = 0;
    if (coupler->crack_gas()) {
      const fdem::RockSnapshot r = rock.snapshot();
      const std::vector<ibm::ChannelConserved> gas_of = coupler->crack_gas()->crack_gas().gas();
      const std::vector<std::uint8_t> kind = coupler->crack_gas()->crack_gas().kinds();
      for (int j : crack) {
        const auto& n = r.joint_nodes[j];
        const double along = c * 0.5 * (r.x[n[0]] + r.x[n[1]]) + s * 0.5 * (r.y[n[0]] + r.y[n[1]]);
        if (kind[j] == ibm::kSegmentGas && along > from) m += gas_of[j].m1;
      }
    }
    for (int j = 0; j < g.ny; ++j)
      for (int i = 0; i < g.nx; ++i) {
        const size_t k = static_cast<size_t>(j) * g.nx + i;
        const double along = c * g.cell_x(i) + s * g.cell_y(j), across = -s * g.cell_x(i) + c * g.cell_y(j);
        if (h.active[k] && along > from && along < geo.length && std::fabs(across) < geo.half_height - 2 * geo.cell)
          m += h.traced[k] * h.rho[k] * g.cell_area();
      }
    return m;
  }

 private:
  static cip::GasSolverOptions walls() {
    cip::GasSolverOptions o;
    o.boundaries = cip::BoundaryConditions::all(cip::BoundaryKind::wall);
    return o;
  }
  static fdem::RockMaterial intact() {
    fdem::RockMaterial m = fdem::RockMaterial::paper_table2();
    m.tensile_strength *= 100, m.cohesion *= 100, m.fracture_energy_mode1 *= 1e4, m.fracture_energy_mode2 *= 1e4;
    return m;
  }
  static fdem::TriangleMesh mesh(const RigidCrackGeometry& g) {
    const double c = std::cos(g.angle), s = std::sin(g.angle);
    auto w = [&](double x, double y) { return std::array<double, 2>{c * x - s * y, s * x + c * y}; };
    // Built along x, then turned: Gmsh meshes the axis-aligned block with the crack as an embedded line.
    fdem::TriangleMesh m =
        fdem::gmsh_rectangle(0, -g.half_height, g.length, g.half_height, g.element,
                             {fdem::Segment{{0, g.offset}, {g.length, g.offset}}}).mesh;
    for (auto& v : m.vertices) v = w(v[0], v[1]);
    return m;
  }
};

}  // namespace blastsim::test
