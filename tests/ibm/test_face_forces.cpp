//! \file test_face_forces.cpp
//! \brief GasLoad::face_forces (docs/coupling.md "Gas -> rock"; docs/validation.md I8): the rock's power under the
//! face forces equals the gas's power on its prescribed faces, the forces act along the surface normal, and a
//! uniform pressure leaves a closed body with no net force beyond the staircase's sampling error.
#include "blastsim/core/backend.hpp"
#include "blastsim/fdem/rock_solver.hpp"
#include "blastsim/ibm/coupler.hpp"
#include "catch.hpp"

#include <cmath>
#include <cstdio>

using namespace blastsim;

namespace {
const cip::EquationOfState eos = cip::EquationOfState::ideal(1.4);
const cip::GasPoint air{1.20, 2.09e5, 0.0, 0.0};
const double block_half = 0.053;  // half the block's side before rotation [m] (dx = 0.01 m)

//! A 6 x 6 block of the paper's rock turned by `angle` [rad] about the origin, on a 40 x 40 grid over
//! [-0.2, 0.2]^2, coupled with face forces.
struct TurnedBlock {
  cip::GasSolver gas{cip::GasGrid::from_box(40, 40, -0.2, 0.2, -0.2, 0.2), eos};
  fdem::RockSolver rock;
  ibm::GasRockCoupler coupler{gas, rock, air, face_forces()};
  static ibm::CouplerOptions face_forces() {
    ibm::CouplerOptions o;
    o.gas_load = ibm::GasLoad::face_forces;
    return o;
  }
  static fdem::FdemTopology topology(double angle) {
    fdem::TriangleMesh m = fdem::structured_rectangle(6, 6, -block_half, block_half, -block_half, block_half);
    for (auto& v : m.vertices) {
      const double x = v[0], y = v[1];
      v = {std::cos(angle) * x - std::sin(angle) * y, std::sin(angle) * x + std::cos(angle) * y};
    }
    return fdem::build_topology(m);
  }
  explicit TurnedBlock(double angle) : rock(topology(angle), fdem::RockMaterial::paper_table2(), fdem::RockOptions{}) {}
};

//! The gas's power [W/m] on its prescribed faces, sum over faces of u_imposed A (p_low - p_high) over the active
//! cells beside each (ideal gas, p = (gamma - 1) rho e); also the sum of the terms' magnitudes.
std::array<double, 2> gas_power_on_faces(cip::GasSolver& gas) {
  const cip::GasGrid g = gas.grid();
  const cip::ImmersedBoundaryView ib = gas.immersed_boundary();
  const cip::GasStateView s = gas.state();
  const int nx = g.nx, ny = g.ny;
  const double dx = g.dx, dy = g.dy;
  auto p_of = [=] BLAST_HD(int i, int j) {
    return i >= 0 && j >= 0 && i < nx && j < ny && ib.cell_active(i, j) ? 0.4 * s.rho.f(i, j) * s.e.f(i, j) : 0.0;
  };
  auto term = [=] BLAST_HD(index_t k) {
    const index_t nu = static_cast<index_t>(nx + 1) * ny;
    if (k < nu) {
      const int i = static_cast<int>(k % (nx + 1)), j = static_cast<int>(k / (nx + 1));
      return ib.u_prescribed(i, j) ? ib.u_imposed(i, j) * dy * (p_of(i - 1, j) - p_of(i, j)) : 0.0;
    }
    k -= nu;
    const int i = static_cast<int>(k % nx), j = static_cast<int>(k / nx);
    return ib.v_prescribed(i, j) ? ib.v_imposed(i, j) * dx * (p_of(i, j - 1) - p_of(i, j)) : 0.0;
  };
  const index_t faces = static_cast<index_t>(nx + 1) * ny + static_cast<index_t>(nx) * (ny + 1);
  return {reduce_sum("test.gas_power", faces, 0.0, term),
          reduce_sum("test.gas_power_abs", faces, 0.0, [=] BLAST_HD(index_t k) { return fabs(term(k)); })};
}
}  // namespace

TEST_CASE("I8 face forces: the rock's power is the gas's power on its prescribed faces", "[ibm][I8]") {
  // A turned block moving with an arbitrary (non-rigid) velocity field in gas whose pressure varies in x and y.
  // Reference: the gas's power on its prescribed faces, summed in the test from the imposed velocities and the
  // cell pressures; the rock's is sum over nodes of load . v. Equal to round-off (1e-12 of the summed
  // magnitudes), at several angles.
  for (double degrees : {0.0, 17.0, 30.0, 45.0}) {
    TurnedBlock c(degrees * M_PI / 180);
    c.gas.initialise([](double x, double y) {
      return cip::GasPoint{1.2 * (1 + 2 * x + 3 * y), 2.09e5 * (1 - x), 0.0, 0.0};
    });
    std::vector<double> v(2 * c.rock.node_count());
    for (int n = 0; n < c.rock.node_count(); ++n) v[2 * n] = 3.0 + std::sin(7.0 * n), v[2 * n + 1] = -2.0 + std::cos(3.0 * n);
    c.rock.set_velocities(v);
    c.coupler.rock_to_gas();
    c.coupler.gas_to_rock();
    const std::array<double, 2> gas = gas_power_on_faces(c.gas);
    const std::vector<fdem::Vec2> load = c.rock.node_loads();
    double rock = 0.0;
    for (size_t n = 0; n < load.size(); ++n) rock += load[n].x * v[2 * n] + load[n].y * v[2 * n + 1];
    std::printf("I8 (%2.0f deg): gas power on the prescribed faces %.10e W/m, rock power under the face forces %.10e W/m "
                "(difference %.1e of the summed magnitudes %.3e)\n", degrees, gas[0], rock, std::fabs(gas[0] - rock) / gas[1],
                gas[1]);
    CHECK(gas[1] > 0.0);
    CHECK(std::fabs(gas[0] - rock) <= 1e-12 * gas[1]);
    // Edge pressures carry nothing in this mode: the whole load is in the node forces.
    for (double p : c.rock.edge_pressures()) CHECK(p == 0.0);
  }
}

TEST_CASE("I8 face forces: uniform gas pushes a closed body inward along its normals, net force within sampling error",
          "[ibm][I8]") {
  // Uniform air (p = 100.32 kPa) around the turned block. Every node of a surface triangle (one with an exposed
  // edge) that lies on a side (corners excepted) is pushed along the side's normal, inward. (A face point covered
  // by a triangle with no exposed edge keeps the full velocity component, and its force the grid axis:
  // docs/coupling.md "Face forces"; those loads are reported, not checked for direction.) The net force is what the staircase of faces
  // samples of the closed outline: an axis-aligned block samples every side with equal rows of faces (zero to
  // round-off); a turned one is bounded by the force of one face per side, p dx x 4 sides.
  const double p = eos.pressure(air.density, air.internal_energy);
  for (double degrees : {0.0, 17.0, 30.0, 45.0}) {
    const double a = degrees * M_PI / 180;
    TurnedBlock c(a);
    c.gas.initialise([](double, double) { return air; });
    c.coupler.rock_to_gas();
    c.coupler.gas_to_rock();
    const std::vector<fdem::Vec2> load = c.rock.node_loads();
    const fdem::RockSnapshot snap = c.rock.snapshot();
    const std::vector<std::uint8_t> exposed = c.rock.edge_exposure();
    double fx = 0, fy = 0, inward = 0, worst_tangential = 0, off_surface = 0;
    for (size_t n = 0; n < load.size(); ++n) {
      fx += load[n].x, fy += load[n].y;
      const size_t t3 = n - n % 3;
      if (!exposed[t3] && !exposed[t3 + 1] && !exposed[t3 + 2]) {  // not a surface triangle
        off_surface = std::fmax(off_surface, std::hypot(load[n].x, load[n].y));
        continue;
      }
      // The block's own frame: a node on a side (not a corner) has one outward normal, +-e1 or +-e2 turned by a.
      const double xr = std::cos(a) * snap.x[n] + std::sin(a) * snap.y[n], yr = -std::sin(a) * snap.x[n] + std::cos(a) * snap.y[n];
      const double lx = std::cos(a) * load[n].x + std::sin(a) * load[n].y, ly = -std::sin(a) * load[n].x + std::cos(a) * load[n].y;
      const bool side_x = std::fabs(std::fabs(xr) - block_half) < 1e-9, side_y = std::fabs(std::fabs(yr) - block_half) < 1e-9;
      if (side_x == side_y) continue;  // off the outline, or a corner
      const double normal = side_x ? lx * (xr > 0 ? 1 : -1) : ly * (yr > 0 ? 1 : -1);  // outward component
      const double tangential = side_x ? ly : lx;
      inward += -normal;
      worst_tangential = std::fmax(worst_tangential, std::fabs(tangential));
      CHECK(normal <= 0.0);
    }
    const double perimeter_force = p * 8 * block_half, face_force = p * 0.01;
    std::printf("I8 uniform (%2.0f deg): inward load on the surface triangles' side nodes %.5e N/m (p x perimeter %.5e), "
                "largest tangential %.1e N/m; largest load on a node of a triangle with no exposed edge %.3e N/m; net force "
                "(%.3e, %.3e) N/m = %.2f face forces p dx\n", degrees, inward, perimeter_force, worst_tangential, off_surface, fx, fy, std::hypot(fx, fy) / face_force);
    CHECK(worst_tangential <= 1e-9 * face_force);
    CHECK(std::hypot(fx, fy) <= 4 * face_force);
    if (degrees == 0.0) CHECK(std::hypot(fx, fy) <= 1e-12 * perimeter_force);
  }
}

TEST_CASE("I8 a loose triangle in uniform gas: no net force with edge pressures, the staircase's with face forces",
          "[ibm][I8]") {
  // One equilateral triangle of side h = 24 mm (the triangles of the single-hole case that breaks up near the
  // hole, docs/single-hole.md "Refinement") on an 8 mm grid in uniform gas at 10 MPa, at 40 positions and angles.
  // Reference: a closed outline in uniform pressure carries no net force. Edge pressures load each exposed edge
  // with p times its outward normal, so their sum vanishes to round-off (1e-12 of p h). Face forces sample the
  // outline with the grid's faces: bounded, as in the block test above, by one face's force p dx per side (3 p dx).
  // The figure printed, the mean net force over p h and the acceleration it gives the triangle, is what a loose
  // piece in the blasthole's gas feels from the sampling alone.
  const double dx = 0.008, h = 0.024, p = 10e6;
  const cip::GasPoint hot{100.0, p / (0.4 * 100.0), 0.0, 0.0};
  for (const ibm::GasLoad load : {ibm::GasLoad::edge_pressures, ibm::GasLoad::face_forces}) {
    const bool faces = load == ibm::GasLoad::face_forces;
    double worst = 0, mean = 0;
    const int placements = 40;
    for (int k = 0; k < placements; ++k) {
      const double a = 0.37 * k, ox = 0.0011 * (k % 7), oy = 0.0017 * (k % 5);
      fdem::TriangleMesh m;
      for (int q = 0; q < 3; ++q) {
        const double t = a + q * 2 * M_PI / 3, r = h / std::sqrt(3.0);
        m.vertices.push_back({ox + r * std::cos(t), oy + r * std::sin(t)});
      }
      m.triangles.push_back({0, 1, 2});
      cip::GasSolver gas(cip::GasGrid::from_box(40, 40, -0.16, 0.16, -0.16, 0.16), eos);
      fdem::RockSolver rock(fdem::build_topology(m), fdem::RockMaterial::paper_table2(), fdem::RockOptions{});
      ibm::CouplerOptions o;
      o.gas_load = load;
      ibm::GasRockCoupler coupler(gas, rock, hot, o);
      gas.initialise([&](double, double) { return hot; });
      coupler.rock_to_gas();
      coupler.gas_to_rock();
      double fx = 0, fy = 0;
      if (faces) {
        for (const fdem::Vec2& l : rock.node_loads()) fx += l.x, fy += l.y;
      } else {  // edge e of the counter-clockwise triangle runs from node e to node e + 1; outward normal (dy, -dx)
        const std::vector<double> pe = rock.edge_pressures();
        const fdem::RockSnapshot s = rock.snapshot();
        for (int e = 0; e < 3; ++e) {
          const int n0 = e, n1 = (e + 1) % 3;
          fx -= pe[e] * (s.y[n1] - s.y[n0]);
          fy += pe[e] * (s.x[n1] - s.x[n0]);
        }
      }
      const double f = std::hypot(fx, fy);
      worst = std::fmax(worst, f), mean += f / placements;
    }
    const double mass = 2600 * std::sqrt(3.0) / 4 * h * h;  // [kg/m]
    std::printf("I8 loose 24 mm triangle, 8 mm cells, 10 MPa, %s: net force mean %.3f, largest %.3f of p h; mean "
                "acceleration %.2e m/s2\n",
                faces ? "face forces" : "edge pressures", mean / (p * h), worst / (p * h), mean / mass);
    if (faces)
      CHECK(worst <= 3 * p * dx);
    else
      CHECK(worst <= 1e-12 * p * h);
  }
}
