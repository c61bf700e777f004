//! \file test_viscous_boundary.cpp
//! \brief Viscous (non-reflecting) rock boundary, docs/validation.md F9: the dashpot coefficients, and the energy
//! a P and an S pulse leave behind when they meet it at normal incidence (Lysmer and Kuhlemeyer 1969).
#include "blastsim/core/error.hpp"
#include "blastsim/fdem/rock_solver.hpp"
#include "blastsim/fdem/rock_step_kernels.hpp"
#include "catch.hpp"
#include "rock_cases.hpp"

#include <cmath>
#include <cstdio>

using namespace blastsim::fdem;
using namespace blastsim::fdem::testing;

TEST_CASE("F9: viscous-boundary dashpots are rho c_p along the normal and rho c_s along the edge", "[fdem][F9]") {
  const double rho = 2600, cp = 5000, cs = 3000, L = 0.02;
  const double c = std::cos(0.3), s = std::sin(0.3);
  const Vec2 p0{1.0, 2.0}, p1{1.0 + L * c, 2.0 + L * s};  // tangent (c, s), unit normal (s, -c)
  const Mat2 C = viscous_boundary_coefficients(rho, cp, cs, p0, p1);
  const double k = 0.5 * rho * L;
  // C n = k c_p n and C t = k c_s t (each end node takes half the edge).
  const Vec2 Cn{C.a * s - C.b * c, C.c * s - C.d * c}, Ct{C.a * c + C.b * s, C.c * c + C.d * s};
  CHECK(std::fabs(Cn.x - k * cp * s) < 1e-12 * k * cp);
  CHECK(std::fabs(Cn.y + k * cp * c) < 1e-12 * k * cp);
  CHECK(std::fabs(Ct.x - k * cs * c) < 1e-12 * k * cp);
  CHECK(std::fabs(Ct.y - k * cs * s) < 1e-12 * k * cp);
  // The implicit update solves (m I + dt C) v = m v_free exactly.
  const double m = 0.7, dt = 1e-6;
  const Vec2 vf{0.3, -0.2}, v = viscous_boundary_velocity(m, dt, C, vf);
  CHECK(std::fabs(m * v.x + dt * (C.a * v.x + C.b * v.y) - m * vf.x) < 1e-14);
  CHECK(std::fabs(m * v.y + dt * (C.c * v.x + C.d * v.y) - m * vf.y) < 1e-14);
}

namespace {

struct PulseResult {
  double pulse_energy;      //!< [J/m] in the bar once the source stopped
  double energy_after;      //!< [J/m] left when the pulse has met the far end
  double radiated;          //!< [J/m] minus the dashpots' work
  double balance_residual;  //!< [J/m] energy balance of the whole run
};

//! A pulse of particle velocity v(t) = v0 sin^2(pi t / T) (0 < t < T) driven into the left end of a bar
//! [0, Lx] x [0, H], along x (a P wave) or y (an S wave); the other velocity component is held at zero on the
//! long sides, so the wave is one-dimensional (plane strain). The right end is a viscous boundary or free.
PulseResult pulse_into_end(bool shear, bool viscous_end) {
  const double Lx = 1.0, H = 0.05, h = 0.01, v0 = 0.1;
  const FdemTopology topo = build_topology(structured_rectangle(static_cast<int>(Lx / h + 0.5),
                                                                static_cast<int>(H / h + 0.5), 0.0, Lx, 0.0, H));
  RockMaterial rock = RockMaterial::paper_table2();
  rock.tensile_strength = rock.cohesion = 1e12;  // elastic: no joint may soften
  rock.fracture_energy_mode1 = rock.fracture_energy_mode2 = 1e15;
  RockOptions opt;
  opt.contact = false;
  RockSolver s(topo, rock, opt);
  const double c = shear ? rock.s_wave_speed() : rock.p_wave_speed();
  const double T = 20 * h / c;  // a pulse 20 elements long
  s.prescribe_velocity(nodes_where(topo, [&](double, double y) { return y < 1e-9 || y > H - 1e-9; }), shear,
                       !shear, 0, 0);
  const std::vector<int> source = nodes_where(topo, [](double x, double) { return x < 1e-9; });
  if (viscous_end) {
    std::vector<int> slots;
    for (const BoundaryEdge& b : topo.boundary_edges)
      if (topo.node_positions[b.n0][0] > Lx - 1e-9 && topo.node_positions[b.n1][0] > Lx - 1e-9) slots.push_back(b.n0);
    REQUIRE(slots.size() == static_cast<size_t>(H / h + 0.5));
    s.set_viscous_boundary(slots);
  }
  const double dt = 0.9 * s.stable_dt();
  auto energy = [&]() {
    const RockEnergies e = s.energies();
    return e.kinetic + e.strain + e.joint_stored;
  };
  run_to(s, T, dt, [&]() {
    const double t = std::fmin(s.time() + dt, T);  // the velocity the source has during the next step
    const double v = v0 * std::pow(std::sin(M_PI * t / T), 2);
    s.prescribe_velocity(source, !shear, shear, shear ? 0 : v, shear ? v : 0);
  });
  s.prescribe_velocity(source, true, true, 0, 0);  // then the left end is held
  run_to(s, 0.5 * Lx / c, dt);                      // the pulse in the middle of the bar
  PulseResult r;
  r.pulse_energy = energy();
  // The pulse's tail reaches the right end at Lx / c + T; two more pulse lengths let its dispersive trail in,
  // and a reflection could not yet have come back past the middle (it would return at 2 Lx / c).
  run_to(s, Lx / c + 3 * T, dt);
  r.energy_after = energy();
  const RockEnergies e = s.energies();
  r.radiated = -e.boundary_work;
  r.balance_residual = e.kinetic + e.strain + e.joint_work - e.external_work;
  return r;
}

}  // namespace

TEST_CASE("F9: a P and an S pulse leave a viscous boundary with less than 5 % of their energy reflected",
          "[fdem][F9]") {
  for (bool shear : {false, true}) {
    const PulseResult v = pulse_into_end(shear, true), f = pulse_into_end(shear, false);
    const double reflected = v.energy_after / v.pulse_energy;
    std::printf("F9 %s pulse at normal incidence: %.4e J/m in the bar; after meeting the end: viscous %.2f %% left "
                "(radiated %.2f %%, balance %.1e J/m), free %.2f %% left\n",
                shear ? "S" : "P", v.pulse_energy, 100 * reflected, 100 * v.radiated / v.pulse_energy,
                v.balance_residual, 100 * f.energy_after / f.pulse_energy);
    CHECK(reflected < 0.05);
    // What the bar lost is what the dashpots took (1 % of the pulse: time integration of the balance).
    CHECK(std::fabs(v.pulse_energy - v.energy_after - v.radiated) < 0.01 * v.pulse_energy);
    // The same bar with a free end keeps the pulse: the measurement sees a reflection when there is one.
    CHECK(f.energy_after > 0.95 * f.pulse_energy);
  }
}

TEST_CASE("F9: a viscous boundary is refused on an edge that is not on the mesh boundary", "[fdem][F9]") {
  const FdemTopology topo = build_topology(structured_rectangle(4, 2, 0.0, 0.4, 0.0, 0.2));
  RockSolver s(topo, RockMaterial::paper_table2(), RockOptions{});
  std::vector<int> inside;
  for (int slot = 0; slot < 3 * topo.triangle_count(); ++slot) {
    bool boundary = false;
    for (const BoundaryEdge& b : topo.boundary_edges) boundary = boundary || b.n0 == slot;
    if (!boundary) inside.push_back(slot);
  }
  REQUIRE(!inside.empty());
  CHECK_THROWS_AS(s.set_viscous_boundary({inside.front()}), blastsim::InputError);
  CHECK_THROWS_AS(s.set_viscous_boundary({-1}), blastsim::InputError);
}
