//! \file test_vibration.cpp
//! \brief Velocity probes and peak particle velocity (docs/validation.md V1-V3): a plane P wave in a confined bar,
//! the cylindrical wave from a pressurised hole against Selberg's solution, and probes across a restart.
#include "blastsim/core/checkpoint.hpp"
#include "blastsim/core/error.hpp"
#include "blastsim/fdem/rock_analysis.hpp"
#include "blastsim/fdem/rock_solver.hpp"
#include "../support/cavity_wave.hpp"
#include "../support/temp_files.hpp"
#include "catch.hpp"
#include "rock_cases.hpp"

#include <cmath>
#include <cstdio>
#include <cstring>

using namespace blastsim::fdem;
using namespace blastsim::fdem::testing;

namespace {

//! The paper's rock with joints that never break in these elastic tests (strength 1e10 Pa, far above the
//! stresses of the waves; fracture energies raised so the joint law stays consistent).
RockMaterial unbreakable_rock() {
  RockMaterial m = RockMaterial::paper_table2();
  m.tensile_strength = m.cohesion = 1e10;
  m.fracture_energy_mode1 = m.fracture_energy_mode2 = 1e9;
  return m;
}

}  // namespace

TEST_CASE("V1: a plane P wave in the confined bar of F1 gives PPV = v0 at a probe", "[fdem][V1]") {
  const double L = 0.6, H = 0.03, v0 = 0.1, rise = 20e-6;  // [m], [m/s], [s]
  const FdemTopology topo = build_topology(structured_rectangle(120, 6, 0.0, L, 0.0, H));
  const RockMaterial rock = unbreakable_rock();
  RockOptions opt;
  opt.joint_penalty_factor = 100;
  opt.contact = false;
  RockSolver s(topo, rock, opt);
  s.prescribe_velocity(nodes_where(topo, [&](double, double y) { return y < 1e-9 || y > H - 1e-9; }), false, true, 0, 0);
  const std::vector<int> left = nodes_where(topo, [](double x, double) { return x < 1e-9; });
  s.set_probes({{0.3, 0.011}, {0.45, 0.02}});
  const double c = rock.p_wave_speed() / std::sqrt(1 + 1.24 / opt.joint_penalty_factor);
  const double t_end = 0.45 / c + 1.5 * rise;  // past the rise at the far probe, before the reflection returns
  const double dt = 0.9 * s.stable_dt();
  // The piston speed rises as a half cosine over `rise`, spread over about 20 elements by the wave: the
  // dispersion of the discrete lattice makes a front resolved by fewer overshoot (10 elements: +4 % at
  // 0.3 m, +7 % at 0.45 m; 20 elements on a grid twice as fine: +1.7 %, +2.6 %), so the PPV of an FDEM
  // model is only as good as the resolution of the pulse's rise (docs/analysis.md, "Vibration").
  while (s.time() < t_end) {
    s.prescribe_velocity(left, true, false, v0 * half_cosine_ramp(s.time() + dt, rise), 0);
    s.step(dt);
  }
  const std::vector<ProbeSample> p = s.probe_samples();
  for (size_t k = 0; k < p.size(); ++k) {
    const double x = k == 0 ? 0.3 : 0.45;
    std::printf("V1: probe at x = %.2f m: PPV %.5f m/s vs v0 %.5f m/s (%+.2f %%) at %.2f us (front + rise: %.2f us)\n", x,
                p[k].peak_speed, v0, 100 * (p[k].peak_speed / v0 - 1), 1e6 * p[k].peak_time, 1e6 * (x / c + rise));
    CHECK(std::fabs(p[k].peak_speed / v0 - 1) < 0.02);
    CHECK(std::fabs(p[k].peak_vy) < 0.02 * v0);
    CHECK(p[k].peak_time > x / c);
  }
}

TEST_CASE("V2: PPV against distance from a pressurised hole follows Selberg's cylindrical-cavity solution", "[fdem][V2][heavy]") {
  const double R = 0.5, a = 0.05, h = 0.0075, p0 = 10e6, rise = 20e-6;
  const FdemTopology topo = build_topology(ring_disc_with_hole(0, 0, R, a, h).mesh);
  const RockMaterial rock = unbreakable_rock();
  RockOptions opt;
  opt.joint_penalty_factor = 30;
  opt.contact = false;
  RockSolver s(topo, rock, opt);
  std::vector<int> hole_slots;
  for (const BoundaryEdge& e : topo.boundary_edges)
    if (std::hypot(topo.node_positions[e.n0][0], topo.node_positions[e.n0][1]) < a + 1e-9) hole_slots.push_back(e.n0);
  s.set_edge_pressure(hole_slots, p0);
  const std::vector<double> radii{0.1, 0.2, 0.3};
  std::vector<std::array<double, 2>> points;
  for (double r : radii)
    for (int q = 0; q < 4; ++q) points.push_back({r * std::cos(q * M_PI / 2 + 0.1), r * std::sin(q * M_PI / 2 + 0.1)});
  s.set_probes(points);
  const blastsim::test::CavityWave exact{a, rock.density, rock.lame_lambda(), rock.shear_modulus(), p0, rise};
  // Before the wave reflected from the outer surface returns to the farthest probe.
  const double t_end = (radii.back() - a) / exact.c() + 2 * rise;
  REQUIRE(t_end < (2 * R - a - radii.back()) / exact.c());
  const double dt = 0.9 * s.stable_dt();
  while (s.time() < t_end) {
    s.set_pressure_scale(half_cosine_ramp(s.time() + 0.5 * dt, rise));
    s.step(dt);
  }
  const std::vector<ProbeSample> p = s.probe_samples();
  for (size_t i = 0; i < radii.size(); ++i) {
    const double ref = exact.peak_velocity(radii[i], t_end);
    for (int q = 0; q < 4; ++q) {
      const ProbeSample& g = p[4 * i + q];
      std::printf("V2: r = %.2f m, angle %3d deg: PPV %.4f m/s vs Selberg %.4f m/s (%+.1f %% of the peak) at %.1f us\n",
                  radii[i], 90 * q, g.peak_speed, ref, 100 * (g.peak_speed / ref - 1), 1e6 * g.peak_time);
      CHECK(std::fabs(g.peak_speed / ref - 1) < 0.10);
    }
  }
}

TEST_CASE("V3: probe peaks survive a checkpoint and restart bit for bit, bad probes are refused", "[fdem][V3]") {
  const FdemTopology topo = build_topology(structured_rectangle(40, 4, 0.0, 0.2, 0.0, 0.02));
  RockOptions opt;
  opt.contact = false;
  auto make = [&]() {
    RockSolver s(topo, unbreakable_rock(), opt);
    s.prescribe_velocity(nodes_where(topo, [](double x, double) { return x < 1e-9; }), true, false, 0.1, 0);
    s.set_probes({{0.05, 0.01}, {0.15, 0.005}});
    return s;
  };
  const double dt = 0.9 * make().stable_dt();
  RockSolver whole = make();
  for (int k = 0; k < 200; ++k) whole.step(dt);
  RockSolver first = make();
  for (int k = 0; k < 80; ++k) first.step(dt);
  const std::filesystem::path dir = blastsim::testing::fresh_dir("probe_restart");
  std::filesystem::create_directories(dir);
  const std::string path = (dir / "rock.ckpt").string();
  {
    blastsim::CheckpointWriter w(path);
    first.write_checkpoint(w);
    w.commit();
  }
  RockSolver second = make();
  blastsim::CheckpointReader r(path);
  second.read_checkpoint(r);
  r.finish();
  for (int k = 80; k < 200; ++k) second.step(dt);
  const std::vector<ProbeSample> a = whole.probe_samples(), b = second.probe_samples();
  REQUIRE(a.size() == b.size());
  CHECK(std::memcmp(a.data(), b.data(), a.size() * sizeof(ProbeSample)) == 0);
  CHECK(a[0].peak_speed > 0.05);
  // A window: the same point with the peak counted only to 60 steps (before the wave reaches it) sees less.
  RockSolver windowed(topo, unbreakable_rock(), opt);
  windowed.prescribe_velocity(nodes_where(topo, [](double x, double) { return x < 1e-9; }), true, false, 0.1, 0);
  windowed.set_probes({{0.05, 0.01}, {0.05, 0.01}}, {1e308, 60.5 * dt});
  for (int k = 0; k < 200; ++k) windowed.step(dt);
  const std::vector<ProbeSample> w = windowed.probe_samples();
  CHECK(w[0].peak_speed == a[0].peak_speed);
  CHECK(w[1].peak_time <= 60.5 * dt);
  CHECK(w[1].peak_speed < w[0].peak_speed);
  RockSolver s(topo, unbreakable_rock(), opt);
  CHECK_THROWS_AS(s.set_probes({{0.3, 0.01}}), blastsim::InputError);
}
