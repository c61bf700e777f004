//! \file test_contact.cpp
//! \brief Munjiza's distributed-potential contact of one pair against closed-form loads, with and without the
//! offset of pairs that meet at a mesh vertex (docs/fdem-solver.md, "Which pairs touch").
#include "blastsim/fdem/mesh.hpp"
#include "blastsim/fdem/rock_solver.hpp"
#include "blastsim/fdem/rock_step_kernels.hpp"
#include "catch.hpp"
#include "rock_cases.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

using namespace blastsim::fdem;

namespace {

//! Two right triangles meeting corner to corner: A = (0,0), (1,0), (0,1) and B, with its right angle at (c, c)
//! and legs of length L = 1.01 along -x and -y, so B's corner pokes into A's by c. Near A's corner phi_A =
//! 3 min(x, y); near B's, phi_B = 3 min(c - x, c - y) / L. With offset s the load along B's two edges inside A
//! is p int_0^c (3 x - s)^+ dx = p (3/2) (c - s/3)^2 each, along A's two edges inside B p (L/6) w^2 each with
//! w = (3 c / L - s)^+, and each pushes B along -x and -y (A along +x, +y): the total force on B is
//! -p [(3/2) (c - s/3)^2 + (L/6) w^2] (1, 1), and its depth max(3 c, 3 c / L) = 3 c.
struct CornerPair {
  static constexpr double L = 1.01;
  Vec2 x[2][3];
  Vec2 v[2][3] = {{{0, 0}, {0, 0}, {0, 0}}, {{0, 0}, {0, 0}, {0, 0}}};
  double m[2][3] = {{1, 1, 1}, {1, 1, 1}};
  explicit CornerPair(double c) : x{{{0, 0}, {1, 0}, {0, 1}}, {{c, c}, {c - L, c}, {c, c - L}}} {}
  static double force_on_b(double c, double s, double p) {
    const double u = c - s / 3 > 0 ? c - s / 3 : 0.0;
    const double w = 3 * c / L - s > 0 ? 3 * c / L - s : 0.0;
    return -p * (1.5 * u * u + L / 6 * w * w);
  }
};

Vec2 total(const Vec2 f[3]) { return {f[0].x + f[1].x + f[2].x, f[0].y + f[1].y + f[2].y}; }

}  // namespace

TEST_CASE("Contact of two corners: the load of the potentials and of the shrunk potentials in closed form",
          "[fdem][contact]") {
  const double p = 5.5e11, c = 0.01;
  const CornerPair pair(c);
  for (const double s : {0.0, 0.02, 0.0295, 0.03}) {
    const PairContact out = pair_contact(pair.x, pair.v, pair.m, p, 0.0, 1e-7, s);
    const Vec2 fb = total(out.f[1]), fa = total(out.f[0]);
    const double exact = CornerPair::force_on_b(c, s, p);
    std::printf("corner pair, offset %.4f: force on B (%.6e, %.6e) N/m, closed form %.6e; depth %.12f (3 c = %.12f)\n", s,
                fb.x, fb.y, exact, out.depth, 3 * c);
    CHECK(std::fabs(out.depth - 3 * c) < 1e-12);
    CHECK(std::fabs(fb.x - exact) <= 1e-9 * std::fabs(CornerPair::force_on_b(c, 0.0, p)));
    CHECK(std::fabs(fb.y - exact) <= 1e-9 * std::fabs(CornerPair::force_on_b(c, 0.0, p)));
    CHECK(std::fabs(fa.x + fb.x) <= 1e-12 * std::fabs(CornerPair::force_on_b(c, 0.0, p)));  // action = reaction
    CHECK(std::fabs(fa.y + fb.y) <= 1e-12 * std::fabs(CornerPair::force_on_b(c, 0.0, p)));
    CHECK(out.touching == (exact != 0.0));
  }
}

TEST_CASE("A pair that meets at a vertex enters contact without a load and pushes against overlap gained since",
          "[fdem][contact]") {
  const double p = 5.5e11, c0 = 0.01;
  // Entry: the vertex was bonded (offset -1); the kernel measures the depth with the offset at the peak.
  const PairContact entry = pair_contact(CornerPair(c0).x, CornerPair(c0).v, CornerPair(c0).m, p, 0.6, 1e-7, 1.0);
  const double s = next_contact_offset(-1.0, entry.depth);
  CHECK(!entry.touching);
  CHECK(std::fabs(s - 3 * c0) < 1e-12);
  // Unloaded at the depth it entered with; pressed deeper, the load grows continuously from zero as the
  // closed form with that offset; the offset stays while the pair is deeper than it.
  double previous = 0;
  for (const double c : {c0, c0 * (1 + 1e-6), c0 * 1.001, c0 * 1.01, c0 * 1.1}) {
    const CornerPair deeper(c);
    const PairContact out = pair_contact(deeper.x, deeper.v, deeper.m, p, 0.0, 1e-7, s);
    const double fb = total(out.f[1]).x, exact = CornerPair::force_on_b(c, s, p);
    std::printf("entered at c = %.4f m: c = %.8f m, force on B %.6e N/m, closed form %.6e\n", c0, c, fb, exact);
    CHECK(std::fabs(fb - exact) <= 1e-9 * std::fabs(CornerPair::force_on_b(c, 0.0, p)) + 1e-300);
    CHECK(fb <= previous);  // monotone: deeper pushes harder
    CHECK(next_contact_offset(s, out.depth) == s);
    previous = fb;
  }
  CHECK(previous < 0);
  // Parting: shallower than the offset, no load, and the offset follows the depth down (to 0 once apart).
  const CornerPair shallower(0.5 * c0);
  const PairContact out = pair_contact(shallower.x, shallower.v, shallower.m, p, 0.0, 1e-7, s);
  CHECK(!out.touching);
  CHECK(next_contact_offset(s, out.depth) == Approx(1.5 * c0).epsilon(1e-12));
  CHECK(next_contact_offset(s, 0.0) == 0.0);
}

TEST_CASE("In the solver a corner pair enters contact at its vertex's first broken joint without doing work",
          "[fdem][contact]") {
  // 4 x 4 squares of 10 mm of the paper's rock at rest. Triangle A's copy of the centre vertex is pushed 5 um
  // out through the vertex, so A's corner pokes into a triangle B across it (they share only that vertex): the
  // overlap that a softening joint's slip builds up (5 um: no joint breaks from it, checked below). While the vertex's joints hold, the pair is no contact;
  // then one joint at the vertex, away from A, breaks. Munjiza's contact would now push A and B apart at
  // once (evaluated below on the same positions); the entering pair carries no load instead, so the solver's
  // contact work stays exactly 0 in that step.
  const FdemTopology topo = build_topology(structured_rectangle(4, 4, 0.0, 0.04, 0.0, 0.04));
  RockSolver s(topo, RockMaterial::paper_table2(), RockOptions{});
  const RockSnapshot s0 = s.snapshot();
  int centre = -1;
  for (size_t n = 0; n < s0.x0.size(); ++n)
    if (std::fabs(s0.x0[n] - 0.02) < 1e-12 && std::fabs(s0.y0[n] - 0.02) < 1e-12) centre = topo.node_vertex[n];
  REQUIRE(centre >= 0);
  std::vector<int> fan;  // nodes that copy the centre vertex
  for (size_t n = 0; n < s0.x0.size(); ++n)
    if (topo.node_vertex[n] == centre) fan.push_back(static_cast<int>(n));
  const int a_node = fan[0], A = a_node / 3;
  auto edge_neighbours = [&](int t, int u) {
    for (const Joint& j : topo.joints)
      if ((j.triangle_a == t && j.triangle_b == u) || (j.triangle_a == u && j.triangle_b == t)) return true;
    return false;
  };
  // Push A's corner out through the vertex, along the line from A's centroid.
  std::vector<double> xy(2 * s0.x.size());
  for (size_t n = 0; n < s0.x.size(); ++n) xy[2 * n] = s0.x[n], xy[2 * n + 1] = s0.y[n];
  const double cx = (s0.x[3 * A] + s0.x[3 * A + 1] + s0.x[3 * A + 2]) / 3, cy = (s0.y[3 * A] + s0.y[3 * A + 1] + s0.y[3 * A + 2]) / 3;
  const double dx = 0.02 - cx, dy = 0.02 - cy, d = std::hypot(dx, dy), push = 5e-6;
  xy[2 * a_node] += push * dx / d, xy[2 * a_node + 1] += push * dy / d;
  s.set_positions(xy);
  auto corners = [](const RockSnapshot& r, int t, Vec2 out[3]) {
    for (int k = 0; k < 3; ++k) out[k] = {r.x[3 * t + k], r.y[3 * t + k]};
  };
  const RockSnapshot s1 = s.snapshot();
  int B = -1;
  for (const int n : fan) {
    const int t = n / 3;
    Vec2 pa[3], pb[3];
    corners(s1, A, pa), corners(s1, t, pb);
    if (t != A && !edge_neighbours(A, t) && triangles_overlap(pa, pb)) B = t;
  }
  REQUIRE(B >= 0);
  // A joint at the centre vertex away from A and its edge neighbours, whose nodes the first step leaves in place.
  int joint = -1;
  auto near_a = [&](int t) { return t == A || edge_neighbours(A, t); };
  for (size_t j = 0; j < topo.joints.size(); ++j) {
    const Joint& J = topo.joints[j];
    const bool at_centre = topo.node_vertex[J.a0] == centre || topo.node_vertex[J.a1] == centre;
    if (at_centre && !near_a(J.triangle_a) && !near_a(J.triangle_b)) joint = static_cast<int>(j);
  }
  REQUIRE(joint >= 0);
  const double dt = 0.1 * s.stable_dt();
  s.step(dt);
  CHECK(s.energies().broken_joints == 0);
  CHECK(s.energies().contact_work == 0.0);  // bonded: no contact
  s.break_joints({joint});
  const RockSnapshot s2 = s.snapshot();
  s.step(dt);
  const double entry_work = s.energies().contact_work;
  CHECK(s.energies().broken_joints == 1);
  // What Munjiza's contact (offset 0) would have put on A and B at that step.
  Vec2 x[2][3], v[2][3] = {{{0, 0}, {0, 0}, {0, 0}}, {{0, 0}, {0, 0}, {0, 0}}};
  double m[2][3];
  corners(s2, A, x[0]), corners(s2, B, x[1]);
  for (int k = 0; k < 3; ++k) m[0][k] = m[1][k] = 1.0;
  const double p = RockOptions{}.contact_penalty_factor * RockMaterial::paper_table2().youngs_modulus;
  const PairContact classic = pair_contact(x, v, m, p, 0.0, dt, 0.0);
  const Vec2 fb = total(classic.f[1]);
  std::printf("corner pair at a broken vertex: depth %.4e, Munjiza's load on B %.4e N/m; contact work in the entry step "
              "%.3e J/m\n", classic.depth, std::hypot(fb.x, fb.y), entry_work);
  CHECK(classic.touching);
  CHECK(std::hypot(fb.x, fb.y) > 0);
  CHECK(entry_work == 0.0);
}

TEST_CASE("Pairs that joints release between builds of the contact lists are evaluated as if listed",
          "[fdem][contact]") {
  // Contact evaluates the pairs free when its lists are made and those a break releases later (a joint's pair,
  // the pairs at a vertex that loses its bond; RockSolver::list_free_pairs). A block (16 x 8 squares of 10 mm,
  // the paper's rock) is pushed at 2 m/s against a fixed right side; when the wave has crossed it, every joint
  // along x = 80 mm and x = 120 mm is broken, after the lists were made, and the wave presses the cuts' faces
  // together. Run A keeps its lists (the cuts' pairs are released ones); run B rebuilds its lists right after
  // the break (they are listed); run C has no contact (the size of what contact does). A and B differ only in
  // the order of the contact sums (B's lists are numbered afresh), so they must agree to round-off: within
  // 1e-6 of the difference contact makes; a pair missed or evaluated twice would be of the order of that
  // difference.
  const FdemTopology topo = build_topology(structured_rectangle(16, 8, 0.0, 0.16, 0.0, 0.08));
  const double dt = 0.9 * RockSolver(topo, RockMaterial::paper_table2(), RockOptions{}).stable_dt();
  auto run = [&](bool contact, bool relist) {
    RockOptions opt;
    opt.contact = contact;
    RockSolver s(topo, RockMaterial::paper_table2(), opt);
    s.prescribe_velocity(testing::nodes_where(topo, [](double x, double) { return x < 1e-9; }), true, false, 2.0, 0);
    s.prescribe_velocity(testing::nodes_where(topo, [](double x, double) { return x > 0.16 - 1e-9; }), true, false, 0, 0);
    const long rebuilds = s.contact_rebuilds();
    for (int k = 0; k < 400; ++k) {
      if (k == 150) {
        std::vector<int> cut = s.joints_on_segment(0.08, 0.0, 0.08, 0.08, 1e-6);
        const std::vector<int> second = s.joints_on_segment(0.12, 0.0, 0.12, 0.08, 1e-6);
        cut.insert(cut.end(), second.begin(), second.end());
        s.break_joints(cut);
        if (relist) s.rebuild_contact_grid();
      }
      s.step(dt);
    }
    if (contact) CHECK(s.contact_rebuilds() - rebuilds == (relist ? 1 : 0));  // no rebuild of its own in A
    return std::make_pair(s.snapshot(), s.energies());
  };
  const auto a = run(true, false), b = run(true, true), c = run(false, false);
  auto largest_distance = [](const RockSnapshot& p, const RockSnapshot& q) {
    double d = 0;
    for (size_t n = 0; n < p.x.size(); ++n) d = std::max(d, std::hypot(p.x[n] - q.x[n], p.y[n] - q.y[n]));
    return d;
  };
  const double ab = largest_distance(a.first, b.first), ac = largest_distance(a.first, c.first);
  std::printf("released pairs: largest node distance A-B %.3e m (lists kept / rebuilt after the break), A-C %.3e m "
              "(contact / none); contact work %.9e / %.9e J/m\n",
              ab, ac, a.second.contact_work, b.second.contact_work);
  CHECK(a.second.broken_joints == b.second.broken_joints);
  CHECK(std::fabs(a.second.contact_work) > 0);  // contact acted (its work is negative while it holds faces pressed)
  CHECK(ac > 1e-7);  // contact mattered
  CHECK(ab <= 1e-6 * ac);
  CHECK(a.second.contact_work == Approx(b.second.contact_work).epsilon(1e-9));
}

TEST_CASE("Contact's travel budgets: the bounds hold under rounding, and a pair skipped while apart is tested "
          "at the first step its triangles overlap", "[fdem][contact]") {
  // A free pair found apart with boxes a gap g apart is skipped until its triangles' travel counters grow by
  // g / 2 (pair_reach); the counters add node_step_travel() each step through add_travel(). The skip is
  // exact only if (1) node_step_travel() bounds the rounded move of a node, (2) add_travel() grows a counter by
  // at least what it adds, and (3) no pair is skipped past the step its triangles first overlap.
  std::mt19937_64 rng(20261207);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  int moves = 0, counters = 0;
  for (int k = 0; k < 100000; ++k) {
    const double x = 10 * unit(rng), y = 10 * unit(rng);
    const double vx = std::ldexp(unit(rng), static_cast<int>(20 * unit(rng))), vy = 100 * unit(rng);
    const double dt = std::ldexp(1.0 + unit(rng), -20 - static_cast<int>(8 * (1 + unit(rng))));
    const double xn = x + vx * dt, yn = y + vy * dt;  // as NodeUpdateKernel moves a node
    const long double bound = node_step_travel(vx, vy, xn, yn, dt);
    if (std::fabs(static_cast<long double>(xn) - x) <= bound && std::fabs(static_cast<long double>(yn) - y) <= bound) ++moves;
    const double c = std::ldexp(1.0 + unit(rng), static_cast<int>(10 * unit(rng)));
    const double s = std::ldexp(1.0 + unit(rng), static_cast<int>(-60 + 60 * (1 + unit(rng)) / 2));
    if (static_cast<long double>(add_travel(c, s)) - c >= s) ++counters;
  }
  std::printf("travel bounds: %d of 100000 rounded moves within node_step_travel, %d of 100000 counters grew by "
              "at least their step\n", moves, counters);
  CHECK(moves == 100000);
  CHECK(counters == 100000);

  // (3) Two free triangles of 10 mm legs, B thrown at A from 2-6 mm away at 20-80 m/s in six directions. A
  // contact force does work from the step it first acts, and none before (the ledger's contact work is exactly
  // zero while no pair touches), so that step must be the first whose starting positions overlap (the contact
  // kernel tests the positions a step starts from).
  const double a = 0.01;
  struct Throw {
    double angle, distance, speed;
  };
  const Throw throws[] = {{0.0, 0.004, 50}, {0.7, 0.006, 80}, {1.9, 0.002, 20}, {2.6, 0.005, 35}, {3.5, 0.003, 60},
                          {4.9, 0.006, 45}};
  int caught = 0;
  for (const Throw& th : throws) {
    const double cx = a / 3 + (a + th.distance) * std::cos(th.angle), cy = a / 3 + (a + th.distance) * std::sin(th.angle);
    TriangleMesh mesh;
    mesh.vertices = {{0, 0}, {a, 0}, {0, a}, {cx, cy - a / 2}, {cx + a / 2, cy + a / 2}, {cx - a / 2, cy + a / 2}};
    mesh.triangles = {{0, 1, 2}, {3, 4, 5}};
    const FdemTopology topo = build_topology(mesh);
    RockSolver s(topo, RockMaterial::paper_table2(), RockOptions{});
    std::vector<double> v(2 * s.node_count(), 0.0);
    const double ux = a / 3 - cx, uy = a / 3 - cy, ul = std::hypot(ux, uy);
    for (int n = 3; n < 6; ++n) v[2 * n] = th.speed * ux / ul, v[2 * n + 1] = th.speed * uy / ul;
    s.set_velocities(v);
    const double dt = 0.9 * s.stable_dt();
    int overlap_step = -1, change_step = -1;
    for (int k = 0; k < 100000 && change_step < 0; ++k) {
      const RockSnapshot before = s.snapshot();
      Vec2 x[2][3];
      for (int n = 0; n < 6; ++n) x[n / 3][n % 3] = {before.x[n], before.y[n]};
      if (overlap_step < 0 && triangles_overlap(x[0], x[1])) overlap_step = k;
      s.step(dt);
      if (s.energies().contact_work != 0.0) change_step = k;
    }
    std::printf("throw at %.1f rad from %.0f mm at %.0f m/s: triangles first overlap at step %d, contact first acts "
                "at step %d\n", th.angle, 1e3 * th.distance, th.speed, overlap_step, change_step);
    CHECK(overlap_step > 10);  // they start apart, so the pair is skipped for a while
    CHECK(change_step == overlap_step);
    if (change_step == overlap_step && overlap_step > 0) ++caught;
  }
  CHECK(caught == 6);
}
