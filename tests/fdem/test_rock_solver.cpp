//! \file test_rock_solver.cpp
//! \brief FDEM solver validation (docs/validation.md, F1, F3, F4, F5, F7) and bitwise determinism.
#include "blastsim/core/checkpoint.hpp"
#include "blastsim/core/error.hpp"
#include "blastsim/fdem/joint_kernels.hpp"
#include "blastsim/fdem/rock_analysis.hpp"
#include "blastsim/fdem/rock_solver.hpp"
#include "blastsim/fdem/rock_step_kernels.hpp"
#include "catch.hpp"
#include "rock_cases.hpp"

#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <random>
#include <string>

using namespace blastsim::fdem;
using namespace blastsim::fdem::testing;

namespace {

//! A soft rock-like material for the long friction tests (friction physics is independent of stiffness), with
//! fracture energies raised to match its larger joint peak separations (no joint comes near breaking).
RockMaterial soft_rock() {
  RockMaterial m = RockMaterial::paper_table2();
  m.youngs_modulus = 5.5e7;
  m.fracture_energy_mode1 = 1e5;
  m.fracture_energy_mode2 = 1e5;
  return m;
}

}  // namespace

TEST_CASE("F7: a body at rest stays at rest: no force, no damage, constant energy", "[fdem][F7]") {
  const FdemTopology topo = build_topology(structured_rectangle(20, 8, 0.0, 0.2, 0.0, 0.08));
  RockSolver s(topo, RockMaterial::paper_table2(), RockOptions{});
  run_to(s, 400 * s.stable_dt(), s.stable_dt());
  const RockSnapshot snap = s.snapshot();
  double max_dx = 0, max_v = 0, max_stress = 0, max_damage = 0;
  for (size_t n = 0; n < snap.x.size(); ++n) {
    max_dx = std::fmax(max_dx, std::hypot(snap.x[n] - snap.x0[n], snap.y[n] - snap.y0[n]));
    max_v = std::fmax(max_v, std::hypot(snap.vx[n], snap.vy[n]));
  }
  for (double v : snap.stress) max_stress = std::fmax(max_stress, std::fabs(v));
  for (double d : snap.joint_damage) max_damage = std::fmax(max_damage, d);
  const RockEnergies e = s.energies();
  std::printf("F7: 400 steps at rest: max |u| %.2e m, max |v| %.2e m/s, max |stress| %.2e Pa, energy %.2e J/m\n",
              max_dx, max_v, max_stress, e.kinetic + e.strain);
  // Round-off scales: F = FX F0^-1 is the identity to ~1e-14, so stresses are ~1e-14 E, speeds ~1e-14 c_p,
  // energies ~(1e-14)^2 E A; bounds 100 x those. No joint may see any damage.
  const RockMaterial rock = RockMaterial::paper_table2();
  CHECK(max_stress < 1e-12 * rock.youngs_modulus);
  CHECK(max_v < 1e-12 * rock.p_wave_speed());
  CHECK(max_dx < 1e-12 * 0.01);
  CHECK(max_damage == 0.0);
  CHECK(e.broken_joints == 0);
  CHECK(e.kinetic + e.strain < 1e-24 * rock.youngs_modulus * 0.016);
}

TEST_CASE("The peak speed kept as a square: the root of the largest square is the largest root, bit for bit",
          "[fdem][instability]") {
  // NodeUpdateKernel keeps max(vx^2 + vy^2) over a coupled step's substeps and NodeSpeedPeak takes one root; the
  // reference is the largest of the per-substep roots, the speed itself. The flag of a speed that is not finite
  // (or whose square exceeds 1e300) must survive either way.
  const auto speed_or_flag = [](double vx, double vy) {
    const double s = vx * vx + vy * vy;
    return s == s && s < 1e300 ? std::sqrt(s) : kSpeedFlag;
  };
  std::mt19937_64 gen(20261207);
  std::uniform_real_distribution<double> mantissa(-1.0, 1.0);
  std::uniform_int_distribution<int> exponent(-320, 160), substeps(1, 30);
  const double specials[] = {0.0, -0.0, 5e-324, 1e-160, 1e150, 7e149, std::numeric_limits<double>::infinity(),
                             std::numeric_limits<double>::quiet_NaN()};
  int cases = 0, equal = 0, flagged = 0;
  for (; cases < 20000; ++cases) {
    double peak_root = 0.0, peak_square = 0.0;  // both start cleared, as after finish_motion()
    const int k = substeps(gen);
    for (int q = 0; q < k; ++q) {
      double v[2];
      for (double& c : v)
        c = gen() % 50 == 0 ? specials[gen() % 8] : mantissa(gen) * std::ldexp(1.0, exponent(gen) / 2);
      const double root = speed_or_flag(v[0], v[1]), square = node_speed2_or_flag(v[0], v[1]);
      if (root > peak_root) peak_root = root;
      if (square > peak_square) peak_square = square;
    }
    const double read = NodeSpeedPeak{NodePeaks<blastsim::Access::read>{&peak_square}}(0);
    if (std::memcmp(&read, &peak_root, sizeof read) == 0) ++equal;
    if (peak_root == kSpeedFlag) ++flagged;
  }
  std::printf("peak speed from its square: %d of %d maxima identical to the largest root (%d flagged)\n", equal,
              cases, flagged);
  CHECK(equal == cases);
  CHECK(flagged > 0);
  CHECK(flagged < cases);
}

TEST_CASE("A triangle turned inside out stops the rock step, naming the triangle", "[fdem][instability]") {
  const FdemTopology topo = build_topology(structured_rectangle(4, 2, 0.0, 0.04, 0.0, 0.02));
  RockSolver s(topo, RockMaterial::paper_table2(), RockOptions{});
  const RockSnapshot snap = s.snapshot();
  const double dt = s.stable_dt();
  // Node 0 of triangle 0 moves in one step to its mirror image across the opposite edge (nodes 1, 2).
  std::vector<double> v(2 * s.node_count(), 0.0);
  for (int d = 0; d < 2; ++d) {
    const double p0 = d ? snap.y[0] : snap.x[0], mid = 0.5 * ((d ? snap.y[1] : snap.x[1]) + (d ? snap.y[2] : snap.x[2]));
    v[2 * 0 + d] = 2 * (mid - p0) / dt;
  }
  s.set_velocities(v);
  try {
    for (int k = 0; k < 5; ++k) s.step(dt);
    FAIL("five steps with an inverted triangle ran without an error");
  } catch (const blastsim::InstabilityError& e) {
    INFO(e.what());
    CHECK(std::string(e.what()).find("inverted or without a finite area is 0") != std::string::npos);
  }
}

TEST_CASE("F1: P-wave in a laterally confined bar: speed and stress behind the front", "[fdem][F1]") {
  const double L = 0.6, H = 0.03, v0 = 0.1;  // [m], [m/s]
  const int nx = 120, ny = 6;
  for (double pf : {100.0, 10.0}) {
    const FdemTopology topo = build_topology(structured_rectangle(nx, ny, 0.0, L, 0.0, H));
    const RockMaterial rock = RockMaterial::paper_table2();
    RockOptions opt;
    opt.joint_penalty_factor = pf;
    opt.contact = false;
    RockSolver s(topo, rock, opt);
    s.prescribe_velocity(nodes_where(topo, [&](double, double y) { return y < 1e-9 || y > H - 1e-9; }), false, true,
                         0, 0);  // rollers: plane-strain, laterally confined (1-D strain)
    s.prescribe_velocity(nodes_where(topo, [](double x, double) { return x < 1e-9; }), true, false, v0, 0);
    const double c_expected = rock.p_wave_speed() / std::sqrt(1 + 1.24 / pf);
    const double dt = 0.9 * s.stable_dt();
    // Front = where the section-averaged velocity crosses v0 / 2; measured at two times.
    auto front = [&]() {
      const RockSnapshot snap = s.snapshot();
      const int bins = 600;
      std::vector<double> sum(bins, 0), count(bins, 0);
      for (size_t n = 0; n < snap.x.size(); ++n) {
        const int b = std::min(bins - 1, static_cast<int>(snap.x0[n] / L * bins));
        sum[b] += snap.vx[n], count[b] += 1;
      }
      for (int b = 0; b < bins; ++b)
        if (count[b] > 0 && sum[b] / count[b] < 0.5 * v0) return (b + 0.5) * L / bins;
      return L;
    };
    const double t1 = 0.25 * L / c_expected, t2 = 0.75 * L / c_expected;
    run_to(s, t1, dt);
    const double x1 = front();
    run_to(s, t2, dt);
    const double x2 = front();
    const double c_measured = (x2 - x1) / (t2 - t1);
    // Stress behind the front: mean sxx of the triangles with centroids in [0.1 L, x2 - 0.1 L].
    const RockSnapshot snap = s.snapshot();
    double sxx = 0;
    int count = 0;
    for (int t = 0; t < topo.triangle_count(); ++t) {
      const double cx = (snap.x0[3 * t] + snap.x0[3 * t + 1] + snap.x0[3 * t + 2]) / 3;
      if (cx > 0.1 * L && cx < x2 - 0.1 * L) sxx += snap.stress[3 * t], ++count;
    }
    sxx /= count;
    const double s_expected = -rock.density * c_expected * v0;
    std::printf("F1 (pf = %g): c = %.1f m/s vs %.1f m/s (%+.2f %%); sxx behind front %.4e vs %.4e Pa (%+.2f %%)\n",
                pf, c_measured, c_expected, 100 * (c_measured / c_expected - 1), sxx, s_expected,
                100 * (sxx / s_expected - 1));
    if (pf == 100.0) {
      CHECK(std::fabs(c_measured / c_expected - 1) < 0.02);
      CHECK(std::fabs(sxx / s_expected - 1) < 0.02);
    } else {
      // Reported, not asserted: at pf = 10 the joint compliance of this structured mesh (vertical,
      // horizontal and diagonal joints) exceeds the estimate 1.24 / pf of docs/fdem-solver.md, "Joint compliance and the P-wave speed"; the measured coefficient is printed.
      const double k = (std::pow(rock.p_wave_speed() / c_measured, 2) - 1) * pf;
      std::printf("    pf = %g: compliance coefficient of this mesh (c_p/c)^2 - 1 = %.2f / pf (docs/fdem-solver.md: 1.24 / pf)\n",
                  pf, k);
      CHECK(c_measured < rock.p_wave_speed());
    }
  }
}

namespace {
//! F3 specimen: two strips joined along y = 0 (length n s), bottom edge fixed, top edge moved at (vx, vy)
//! until the interface has broken; returns the energy dissipated per unit crack length [J/m2].
double fracture_energy_per_length(int n, double s, const RockMaterial& rock, double vx, double vy, int& broken) {
  const FdemTopology topo = build_topology(two_strips(n, s));
  RockOptions opt;
  opt.contact = false;
  RockSolver solver(topo, rock, opt);
  const double h = s * std::sqrt(3.0) / 2;
  solver.prescribe_velocity(nodes_where(topo, [&](double, double y) { return y < -h + 1e-9; }), true, true, 0, 0);
  solver.prescribe_velocity(nodes_where(topo, [&](double, double y) { return y > h - 1e-9; }), true, true, vx, vy);
  // Past complete softening: separation of 1.5 softening lengths.
  const double travel = 1.5 * std::max(softening_length(rock.fracture_energy_mode1, rock.tensile_strength, 0),
                                       softening_length(rock.fracture_energy_mode2, rock.cohesion, 0));
  run_to(solver, travel / std::hypot(vx, vy), 0.9 * solver.stable_dt());
  const RockEnergies e = solver.energies();
  broken = e.broken_joints;
  const double dissipated = e.external_work - e.kinetic - e.strain - e.joint_stored - e.damping_dissipated;
  // The rock's own balance (what rock_series.csv reports) closes: the supports' work went into kinetic and
  // strain energy and the joints, to the time-integration error. The residual biases the dissipated energy
  // below by as much, so it must stay well inside F3's 3 % bound on G: at most 1 % of the external work.
  const double residual = energy_residual(e, RockEnergies{});
  std::printf("    energy residual %.3e J/m (%.2e of the external work)\n", residual, residual / e.external_work);
  CHECK(std::fabs(residual) < 0.01 * e.external_work);
  std::printf("    n = %d, s = %.4f m: external %.5e, kinetic %.3e, strain %.3e, joint stored %.3e, "
              "fracture (solver) %.5e J/m; %d joints broken\n",
              n, s, e.external_work, e.kinetic, e.strain, e.joint_stored, e.fracture_dissipated, broken);
  return dissipated / (n * s);
}
}  // namespace

TEST_CASE("F3: fracture energy per unit crack length equals G_I and G_II at two element sizes", "[fdem][F3]") {
  const double L = 0.04;
  RockMaterial rock = RockMaterial::paper_table2();
  for (int n : {4, 16}) {
    int broken = 0;
    const double g1 = fracture_energy_per_length(n, L / n, rock, 0.0, 0.2, broken);
    std::printf("F3 mode I, element size %.4f m: %.3f J/m2 (G_I %.1f, %+.2f %%)\n", L / n, g1,
                rock.fracture_energy_mode1, 100 * (g1 / rock.fracture_energy_mode1 - 1));
    CHECK(broken == n);  // exactly the interface line
    CHECK(std::fabs(g1 / rock.fracture_energy_mode1 - 1) < 0.03);
  }
  // Mode II: a tensile strength above the shear stress that the inclined joints see (0.87 c) keeps the
  // crack on the sheared line (pure shear would otherwise open wing cracks, as real rock does).
  // (G_I raised with it, so that the tensile pre-peak energy stays below G_I; it plays no part here.)
  rock.tensile_strength = 60e6;
  rock.fracture_energy_mode1 = 2000;
  for (int n : {4, 16}) {
    int broken = 0;
    const double g2 = fracture_energy_per_length(n, L / n, rock, 0.2, 0.0, broken);
    std::printf("F3 mode II, element size %.4f m: %.3f J/m2 (G_II %.1f, %+.2f %%)\n", L / n, g2,
                rock.fracture_energy_mode2, 100 * (g2 / rock.fracture_energy_mode2 - 1));
    CHECK(broken == n);
    CHECK(std::fabs(g2 / rock.fracture_energy_mode2 - 1) < 0.03);
  }
}

namespace {
//! Copies checkpoint `from` to `to` without the record `drop`, with a new trailer (record count, CRC-32): the
//! file an earlier build, which did not write that record, would have written (layout: core/checkpoint.hpp).
void copy_checkpoint_without(const std::string& from, const std::string& to, const std::string& drop) {
  std::ifstream in(from, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const size_t header = 8 + 4, body_end = bytes.size() - blastsim::detail::kCheckpointTrailer;
  std::string out = bytes.substr(0, header);
  std::uint64_t records = 0;
  auto u64 = [&](size_t at) {
    std::uint64_t v;
    std::memcpy(&v, bytes.data() + at, sizeof v);
    return v;
  };
  for (size_t at = header; at < body_end;) {
    const std::uint64_t name_length = u64(at);
    const std::string name = bytes.substr(at + 8, name_length);
    const size_t end = at + 8 + name_length + 16 + u64(at + 8 + name_length) * u64(at + 16 + name_length);
    if (name != drop) out += bytes.substr(at, end - at), ++records;
    at = end;
  }
  const std::uint32_t crc = blastsim::detail::crc32_of(0, out.data(), out.size());
  out.append(blastsim::detail::kCheckpointEnd, 8);
  out.append(reinterpret_cast<const char*>(&records), sizeof records);
  out.append(reinterpret_cast<const char*>(&crc), sizeof crc);
  std::ofstream(to, std::ios::binary) << out;
}
}  // namespace

TEST_CASE("A checkpoint without the joints' plastic slip restarts, and a joint that slid one way goes on as before",
          "[fdem][checkpoint]") {
  // Checkpoints of builds before the elastic-plastic shear hold no rock.joints.plastic; the solver restarts them
  // with zero plastic slip. For a slide in one direction the first evaluation returns each point to the same
  // plastic slip (all of it past the cap), so the run goes on as from the full checkpoint, to rounding.
  RockMaterial rock = RockMaterial::paper_table2();
  rock.tensile_strength = 60e6, rock.fracture_energy_mode1 = 2000;  // as F3's mode II: the sheared line slips
  const double s = 0.01, h = s * std::sqrt(3.0) / 2, v = 0.2;
  const FdemTopology topo = build_topology(two_strips(4, s));
  RockOptions opt;
  opt.contact = false;
  auto make = [&] {
    RockSolver solver(topo, rock, opt);
    solver.prescribe_velocity(nodes_where(topo, [&](double, double y) { return y < -h + 1e-9; }), true, true, 0, 0);
    solver.prescribe_velocity(nodes_where(topo, [&](double, double y) { return y > h - 1e-9; }), true, true, v, 0);
    return solver;
  };
  RockSolver first = make();
  const double dt = 0.9 * first.stable_dt();
  const double slide = 0.3 * softening_length(rock.fracture_energy_mode2, rock.cohesion, 0);  // into the softening
  run_to(first, slide / v, dt);
  REQUIRE(first.energies().broken_joints == 0);
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "blastsim_test_plastic_restart";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const std::string full = (dir / "full.ckpt").string(), old = (dir / "old.ckpt").string();
  {
    blastsim::CheckpointWriter w(full);
    first.write_checkpoint(w);
    w.commit();
  }
  copy_checkpoint_without(full, old, "rock.joints.plastic");
  RockSolver a = make(), b = make();
  for (auto [solver, path] : {std::pair{&a, full}, std::pair{&b, old}}) {
    blastsim::CheckpointReader r(path);
    solver->read_checkpoint(r);
    r.finish();
    REQUIRE(r.has("rock.joints.plastic") == (path == full));
    run_to(*solver, 2 * slide / v, dt);
  }
  const RockEnergies ea = a.energies(), eb = b.energies();
  std::printf("plastic-slip restart: fracture dissipated %.9e (full) / %.9e (without) J/m, joint stored %.6e / %.6e J/m\n",
              ea.fracture_dissipated, eb.fracture_dissipated, ea.joint_stored, eb.joint_stored);
  CHECK(ea.fracture_dissipated > 0);
  CHECK_THAT(eb.fracture_dissipated, WithinRel(ea.fracture_dissipated, 1e-9));
  CHECK_THAT(eb.joint_stored, WithinRel(ea.joint_stored, 1e-9));
  CHECK(eb.broken_joints == ea.broken_joints);
}

TEST_CASE("F5: two equal elastic bars collide: momentum, swapped velocities, energy, contact time",
          "[long][fdem][F5][contact]") {
  // 80 x 8 squares per bar: the lattice's dispersion leaves 1.7 % of the energy ringing inside the bars
  // after they part (40 x 8: 2.5 %), so this is the coarsest mesh that meets the 2 % bound.
  const double L = 0.1, H = 0.02, v0 = 1.0, gap = 1e-4;
  const int nx = 80, ny = 8;
  const TriangleMesh mesh =
      merge(structured_rectangle(nx, ny, -L - gap / 2, -gap / 2, 0, H), structured_rectangle(nx, ny, gap / 2, L + gap / 2, 0, H));
  const FdemTopology topo = build_topology(mesh);
  const RockMaterial rock = RockMaterial::paper_table2();
  RockOptions opt;
  opt.joint_penalty_factor = 100;  // wave speed within 0.6 % of c_p (contact penalty: the default 10 E)
  RockSolver s(topo, rock, opt);
  s.prescribe_velocity(nodes_where(topo, [&](double, double y) { return y < 1e-9 || y > H - 1e-9; }), false, true, 0, 0);
  std::vector<double> v(2 * s.node_count());
  for (int n = 0; n < s.node_count(); ++n) v[2 * n] = topo.node_positions[n][0] < 0 ? v0 : -v0;
  s.set_velocities(v);
  const std::vector<double> m_host = node_masses(topo, rock.density);
  double mass = 0;
  for (double m : m_host) mass += m;
  const double ke0 = 0.5 * mass * v0 * v0;
  const double c = rock.p_wave_speed() / std::sqrt(1 + 1.24 / opt.joint_penalty_factor);
  const double dt = 0.9 * s.stable_dt();
  // In contact = a contact force above 1e-3 of the impact force rho c v0 H (vertex neighbours inside each
  // bar touch at round-off level).
  const double threshold = 1e-3 * rock.density * c * v0 * H;
  double t_first = -1, t_last = -1, max_p = 0;
  long step = 0;
  run_to(s, gap / (2 * v0) + 3 * L / c, dt, [&] {
    if (++step % 500 == 0) {  // momentum now and then
      const RockSnapshot snap = s.snapshot();
      double p = 0;
      for (size_t n = 0; n < snap.vx.size(); ++n) p += m_host[n] * snap.vx[n];
      max_p = std::fmax(max_p, std::fabs(p));
    }
    if (s.contact_force_norm() > threshold) {
      if (t_first < 0) t_first = s.time();
      t_last = s.time();
    }
  });
  const RockSnapshot snap = s.snapshot();
  double p_left = 0, m_left = 0;
  for (size_t n = 0; n < snap.vx.size(); ++n)
    if (snap.x0[n] < 0) p_left += m_host[n] * snap.vx[n], m_left += m_host[n];
  const RockEnergies e = s.energies();
  const double duration = t_last - t_first + dt;
  std::printf("F5: max |momentum| %.2e of %.3e kg m/s; left bar %.4f m/s (expected %.1f); kinetic %.4f of initial; "
              "contact %.3f us vs 2L/c %.3f us (%+.2f %%)\n",
              max_p, mass * v0, p_left / m_left, -v0, e.kinetic / ke0, 1e6 * duration, 2e6 * L / c,
              100 * (duration / (2 * L / c) - 1));
  CHECK(max_p < 1e-12 * mass * v0);
  CHECK(std::fabs(p_left / m_left + v0) < 0.02 * v0);
  CHECK(std::fabs(e.kinetic / ke0 - 1) < 0.02);
  CHECK(std::fabs(duration / (2 * L / c) - 1) < 0.05);
}

namespace {
//! F4 set-up: a fixed base [-0.3, 0.3] x [-0.05, 0] and a block [0, 0.1] x [0, 0.05] resting on it.
struct SlidingBlock {
  FdemTopology topo;
  RockSolver solver;
  std::vector<int> block;
  SlidingBlock(double gx, double gy, double v0)
      : topo(build_topology(merge(structured_rectangle(24, 2, -0.3, 0.3, -0.05, 0.0),
                                  structured_rectangle(4, 2, 0.0, 0.1, 0.0, 0.05)))),
        solver(topo, soft_rock(), options(gx, gy)) {
    solver.prescribe_velocity(nodes_where(topo, [](double, double y) { return y < -1e-9; }), true, true, 0, 0);
    std::vector<double> v(2 * solver.node_count(), 0.0);
    for (int t = 96; t < topo.triangle_count(); ++t)  // the base's 2 x 24 x 2 triangles come first
      for (int k = 0; k < 3; ++k) block.push_back(3 * t + k), v[2 * (3 * t + k)] = v0;
    solver.set_velocities(v);
  }
  static RockOptions options(double gx, double gy) {
    RockOptions o;
    o.gravity = {gx, gy};
    // The reference is a rigid block. Gravity acts from t = 0 on a block that rests on the base with no
    // overlap, so the block bounces on its contact springs (normal force between 0 and 2 m g); the
    // triangles' viscous damping (10 %) lets that bounce die out instead of rocking the block for ever.
    o.damping_ratio = 0.1;
    return o;
  }
  //! Mean x position and velocity of the block's nodes.
  void block_motion(double& x, double& vx) const {
    const RockSnapshot s = solver.snapshot();
    x = vx = 0;
    for (int n : block) x += s.x[n] - s.x0[n], vx += s.vx[n];
    x /= block.size(), vx /= block.size();
  }
};
}  // namespace

TEST_CASE("F4: a block sliding with friction stops after v0^2 / (2 mu g)", "[fdem][F4][contact]") {
  const double g = 9.81, v0 = 0.5, mu = soft_rock().contact_friction;
  SlidingBlock b(0.0, -g, v0);
  const double dt = 0.9 * b.solver.stable_dt();
  const double t_stop = v0 / (mu * g);
  run_to(b.solver, 1.3 * t_stop, dt);
  double x, vx;
  b.block_motion(x, vx);
  const double expected = v0 * v0 / (2 * mu * g);
  std::printf("F4 flat: stopped after %.5f m vs v0^2/(2 mu g) = %.5f m (%+.2f %%), final speed %.2e m/s\n", x,
              expected, 100 * (x / expected - 1), vx);
  CHECK(std::fabs(x / expected - 1) < 0.02);
  CHECK(std::fabs(vx) < 1e-2 * v0);  // stopped
}

TEST_CASE("F4: on an incline the block accelerates at g (sin - mu cos) or sticks when tan <= mu",
          "[fdem][F4][contact]") {
  const double g = 9.81, mu = soft_rock().contact_friction;
  // The incline is modelled by tilting gravity: the base stays horizontal.
  for (double deg : {45.0, 25.0}) {
    const double th = deg * M_PI / 180;
    SlidingBlock b(g * std::sin(th), -g * std::cos(th), 0.0);
    const double dt = 0.9 * b.solver.stable_dt();
    const double t1 = 0.02, t2 = 0.06;
    run_to(b.solver, t1, dt);
    double x1, v1, x2, v2;
    b.block_motion(x1, v1);
    run_to(b.solver, t2, dt);
    b.block_motion(x2, v2);
    const double a = (v2 - v1) / (t2 - t1);
    const double expected = std::fmax(0.0, g * (std::sin(th) - mu * std::cos(th)));
    std::printf("F4 incline %.0f deg: acceleration %.4f m/s2 vs %.4f (frictionless %.4f); displacement at %.2f s "
                "%.3e m\n", deg, a, expected, g * std::sin(th), t2, x2);
    if (expected > 0) {
      CHECK(std::fabs(a / expected - 1) < 0.02);
    } else {
      // Sticks: the mean acceleration stays below 2 % of the frictionless g sin(theta) (what creep there is
      // comes from the contact bounce before the damping has taken it out).
      CHECK(std::fabs(a) < 0.02 * g * std::sin(th));
    }
  }
}

TEST_CASE("Determinism: a fracturing run repeated gives the same bytes", "[fdem][determinism]") {
  auto run = [] {
    const FdemTopology topo = build_topology(structured_rectangle(16, 8, 0.0, 0.16, 0.0, 0.08));
    RockSolver s(topo, RockMaterial::paper_table2(), RockOptions{});
    s.prescribe_velocity(nodes_where(topo, [](double, double y) { return y < 1e-9; }), true, true, 0, 0);
    s.prescribe_velocity(nodes_where(topo, [](double, double y) { return y > 0.08 - 1e-9; }), true, true, 0.5, 2.0);
    std::vector<int> left;  // a pressure on the left side as well (edge loads are part of the gather)
    for (const BoundaryEdge& b : topo.boundary_edges)
      if (topo.node_positions[b.n0][0] < 1e-9 && topo.node_positions[b.n1][0] < 1e-9) left.push_back(b.n0);
    s.set_edge_pressure(left, 5e6);
    run_to(s, 600 * 0.9 * s.stable_dt(), 0.9 * s.stable_dt());
    return s;
  };
  RockSolver a = run(), b = run();
  const RockSnapshot sa = a.snapshot(), sb = b.snapshot();
  const RockEnergies ea = a.energies(), eb = b.energies();
  std::printf("Determinism: %d joints broken, fracture energy %.6e J/m\n", ea.broken_joints, ea.fracture_dissipated);
  CHECK(ea.broken_joints > 0);
  CHECK(std::memcmp(sa.x.data(), sb.x.data(), sa.x.size() * sizeof(double)) == 0);
  CHECK(std::memcmp(sa.vy.data(), sb.vy.data(), sa.vy.size() * sizeof(double)) == 0);
  CHECK(std::memcmp(sa.stress.data(), sb.stress.data(), sa.stress.size() * sizeof(double)) == 0);
  CHECK(std::memcmp(sa.joint_damage.data(), sb.joint_damage.data(), sa.joint_damage.size() * sizeof(double)) == 0);
  CHECK(std::memcmp(&ea.fracture_dissipated, &eb.fracture_dissipated, sizeof(double)) == 0);
  CHECK(std::memcmp(&ea.strain, &eb.strain, sizeof(double)) == 0);
  CHECK(ea.broken_joints == eb.broken_joints);
}

TEST_CASE("Load ramp: a half cosine from 0 to 1 with zero rate at both ends", "[fdem][loads]") {
  const double T = 2e-4;
  CHECK(half_cosine_ramp(0.0, T) == 0.0);
  CHECK_THAT(half_cosine_ramp(0.5 * T, T), Catch::Matchers::WithinAbs(0.5, 1e-15));
  CHECK(half_cosine_ramp(T, T) == 1.0);
  CHECK(half_cosine_ramp(3 * T, T) == 1.0);
  CHECK(half_cosine_ramp(0.1 * T, 0.0) == 1.0);  // no ramp: the full load at once
  // Rates at the ends vanish: one-sided differences shrink like h (the ramp is quadratic there).
  const double h = 1e-6 * T;
  CHECK(half_cosine_ramp(h, T) / h < 1e-4 / T);
  CHECK((1.0 - half_cosine_ramp(T - h, T)) / h < 1e-4 / T);
  // Largest rate pi / (2 T) at the middle (derivative of (1 - cos(pi t / T)) / 2).
  const double rate = (half_cosine_ramp(0.5 * T + h, T) - half_cosine_ramp(0.5 * T - h, T)) / (2 * h);
  CHECK_THAT(rate, Catch::Matchers::WithinRel(M_PI / (2 * T), 1e-6));
}

TEST_CASE("A fixed time step above the stable step is refused with a clear message", "[fdem][errors]") {
  const FdemTopology topo = build_topology(structured_rectangle(2, 2, 0.0, 0.02, 0.0, 0.02));
  RockSolver s(topo, RockMaterial::paper_table2(), RockOptions{});
  CHECK_THROWS_WITH(s.step(2 * s.stable_dt()), Catch::Contains("stable step"));
}

TEST_CASE("Contact: intact rock gets no contact force, the faces of a cut do", "[fdem][contact]") {
  // A block of the paper's rock (16 x 8 squares of 10 mm) pushed at 0.5 m/s on its left side against a fixed
  // right side: a compression wave of about 7 MPa. Triangles that meet only at a vertex overlap there by the
  // joints' give (stress / penalty x edge, about a micron here); while all joints at the vertex are intact
  // they are copies of one vertex, not a contact (docs/fdem-solver.md), so intact rock has no contact at all:
  // no contact work and the same strain energy, to the last bit, as the run without contact. With the joints
  // along x = 80 mm broken first, the wave presses the two faces of that cut together: contact must hold
  // them apart.
  auto run = [](bool contact, bool cut, RockEnergies& e) {
    const FdemTopology topo = build_topology(structured_rectangle(16, 8, 0.0, 0.16, 0.0, 0.08));
    RockOptions opt;
    opt.contact = contact;
    RockSolver s(topo, RockMaterial::paper_table2(), opt);
    s.prescribe_velocity(nodes_where(topo, [](double x, double) { return x < 1e-9; }), true, false, 0.5, 0);
    s.prescribe_velocity(nodes_where(topo, [](double x, double) { return x > 0.16 - 1e-9; }), true, false, 0, 0);
    if (cut) s.break_joints(s.joints_on_segment(0.08, 0.0, 0.08, 0.08, 1e-6));
    RockOptions with_contact;  // the same dt in every run: the stable step with contact springs
    const double dt = 0.9 * RockSolver(topo, RockMaterial::paper_table2(), with_contact).stable_dt();
    run_to(s, 40e-6, dt);  // the wave (5.3 km/s) crosses the block once and comes back part way
    e = s.energies();
    return s.snapshot();
  };
  RockEnergies on, off, cut_on, cut_off;
  run(true, false, on);
  run(false, false, off);
  std::printf("Contact, intact block: contact work %.3e J/m, strain %.6e vs %.6e J/m (contact off); %d joints broken\n",
              on.contact_work, on.strain, off.strain, on.broken_joints);
  CHECK(on.broken_joints == 0);
  CHECK(on.contact_work == 0.0);
  CHECK(on.strain == off.strain);
  const RockSnapshot c = run(true, true, cut_on), d = run(false, true, cut_off);
  // Largest overlap of the cut's faces: left-face nodes (x0 = 80 mm, in a triangle left of the cut) that
  // moved past the right face's nodes at the same height.
  auto overlap = [](const RockSnapshot& s) {
    double worst = 0;
    for (size_t n = 0; n < s.x.size(); ++n) {
      if (std::fabs(s.x0[n] - 0.08) > 1e-9) continue;
      const size_t t = n / 3;
      const double cx0 = (s.x0[3 * t] + s.x0[3 * t + 1] + s.x0[3 * t + 2]) / 3;
      if (cx0 > 0.08) continue;  // a right-face node
      for (size_t m = 0; m < s.x.size(); ++m) {
        const size_t u = m / 3;
        if (std::fabs(s.x0[m] - 0.08) > 1e-9 || std::fabs(s.y0[m] - s.y0[n]) > 1e-9) continue;
        if ((s.x0[3 * u] + s.x0[3 * u + 1] + s.x0[3 * u + 2]) / 3 < 0.08) continue;
        worst = std::max(worst, s.x[n] - s.x[m]);
      }
    }
    return worst;
  };
  std::printf("Contact, cut block: contact work %.3e J/m; faces overlap %.3e m with contact, %.3e m without\n",
              cut_on.contact_work, overlap(c), overlap(d));
  CHECK(cut_on.contact_work > 0);
  CHECK(overlap(d) > 1e-6);                // without contact the left part runs into the right one
  CHECK(overlap(c) < 0.2 * overlap(d));    // contact holds the faces apart (to its penalty's give)
}
