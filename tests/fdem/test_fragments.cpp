//! \file test_fragments.cpp
//! \brief Fragment analysis (docs/validation.md A1-A5): labels of pre-cut pieces, sieve sizes of known shapes,
//! Swebrec and Rosin-Rammler fits of synthetic samples, damage per triangle and the damage zone.
#include "blastsim/fdem/fragments.hpp"
#include "blastsim/fdem/rock_solver.hpp"
#include "catch.hpp"
#include "rock_cases.hpp"

#include <cmath>
#include <cstdio>
#include <map>
#include <numeric>
#include <random>

using namespace blastsim::fdem;
using namespace blastsim::fdem::testing;

namespace {

//! Independent reference labels: a breadth-first search over the topology's unbroken joints, labelling each
//! component by its smallest triangle index.
std::vector<int> reference_labels(const FdemTopology& topo, const std::vector<std::uint8_t>& broken) {
  const int T = topo.triangle_count();
  std::vector<std::vector<int>> adj(T);
  for (size_t j = 0; j < topo.joints.size(); ++j)
    if (!broken[j]) adj[topo.joints[j].triangle_a].push_back(topo.joints[j].triangle_b),
        adj[topo.joints[j].triangle_b].push_back(topo.joints[j].triangle_a);
  std::vector<int> label(T, -1);
  for (int t = 0; t < T; ++t) {  // t is the smallest unvisited index, so the smallest of its component
    if (label[t] >= 0) continue;
    std::vector<int> queue{t};
    label[t] = t;
    for (size_t q = 0; q < queue.size(); ++q)
      for (int n : adj[queue[q]])
        if (label[n] < 0) label[n] = t, queue.push_back(n);
  }
  return label;
}

//! A solver on `topo` with the joints on the given segments broken (pre-cut lines).
RockSolver cut(const FdemTopology& topo, const std::vector<std::array<double, 4>>& segments) {
  RockSolver s(topo, RockMaterial::paper_table2(), RockOptions{});
  for (const auto& g : segments) s.break_joints(s.joints_on_segment(g[0], g[1], g[2], g[3], 1e-9));
  return s;
}

//! Sizes x = F^-1(u) of `count` equal-mass fragments with u uniform in (0, 1) (a fixed-seed mt19937_64,
//! whose sequence the C++ standard fixes; u from its top 53 bits).
std::vector<Fragment> sample(int count, const std::function<double(double)>& inverse_cdf) {
  std::mt19937_64 rng(20261202);
  std::vector<Fragment> f(count);
  for (int i = 0; i < count; ++i) {
    const double u = ((rng() >> 11) + 0.5) * 0x1.0p-53;
    f[i].mass = 1.0, f[i].triangles = 10, f[i].sieve_size = inverse_cdf(u);
  }
  return f;
}

}  // namespace

TEST_CASE("A1: a square cut into k x k blocks gives k^2 fragments with the exact areas and sizes", "[fdem][A1]") {
  const double L = 0.12;  // [m]: elements of at most 20 mm keep the paper rock's joint law valid
  for (int k : {1, 2, 3, 5}) {
    const int n = 6 * k;  // cells per side
    const FdemTopology topo = build_topology(structured_rectangle(n, n, 0.0, L, 0.0, L));
    std::vector<std::array<double, 4>> lines;
    for (int i = 1; i < k; ++i) lines.push_back({i * L / k, 0, i * L / k, L}), lines.push_back({0, i * L / k, L, i * L / k});
    RockSolver s = cut(topo, lines);
    const std::vector<int> labels = fragment_labels(s.view());
    const RockSnapshot snap = s.snapshot();
    const std::vector<Fragment> f = measure_fragments(snap, labels, 2600.0);
    double area_error = 0, size_error = 0, mass_error = 0;
    for (const Fragment& g : f) {
      area_error = std::max(area_error, std::fabs(g.area / (L * L / (k * k)) - 1));
      size_error = std::max(size_error, std::fabs(g.sieve_size / (L / k) - 1));
      mass_error = std::max(mass_error, std::fabs(g.mass / (2600.0 * L * L / (k * k)) - 1));
    }
    std::printf("A1: k = %d, %d x %d cells: %zu fragments (expected %d); max relative error of area %.1e, mass %.1e, "
                "sieve size %.1e\n", k, n, n, f.size(), k * k, area_error, mass_error, size_error);
    CHECK(f.size() == static_cast<size_t>(k * k));
    CHECK(area_error < 1e-12);
    CHECK(mass_error < 1e-12);
    CHECK(size_error < 1e-12);  // a square's minimum width is its side
    CHECK(labels == reference_labels(topo, snap.joint_broken));
    CHECK(labels == fragment_labels(s.view()));  // repeated: the same labels
    for (const Fragment& g : f) CHECK_FALSE(g.fines);
  }
}

TEST_CASE("A2: an L-shaped and a ring-shaped piece get one label each", "[fdem][A2]") {
  SECTION("L: the top-right quarter cut out of a square") {
    const double L = 1.0;
    const FdemTopology topo = build_topology(structured_rectangle(12, 12, 0.0, L, 0.0, L));
    RockSolver s = cut(topo, {{L / 2, L / 2, L / 2, L}, {L / 2, L / 2, L, L / 2}});
    const std::vector<int> labels = fragment_labels(s.view());
    const std::vector<Fragment> f = measure_fragments(s.snapshot(), labels, 1000.0);
    REQUIRE(f.size() == 2);
    const Fragment& big = f[0].area > f[1].area ? f[0] : f[1];
    const Fragment& small = f[0].area > f[1].area ? f[1] : f[0];
    // The L's hull is the pentagon (0,0) (1,0) (1,0.5) (0.5,1) (0,1): width 1 across its sides, 1.5 / sqrt(2)
    // across the cut corner, so its minimum width is 1 m.
    std::printf("A2: L-shape area %.15g m2 (expected 0.75), quarter %.15g m2 (0.25); L-shape sieve size %.15g m "
                "(expected 1)\n", big.area, small.area, big.sieve_size);
    CHECK(std::fabs(big.area - 0.75) < 1e-12);
    CHECK(std::fabs(big.sieve_size - 1.0) < 1e-12);
    CHECK(std::fabs(small.area - 0.25) < 1e-12);
    CHECK(labels == reference_labels(topo, s.snapshot().joint_broken));
  }
  SECTION("ring: two circles cut in a disc with a hole") {
    const double R = 1.0, a = 0.2, h = 0.05;
    const NamedMesh mesh = ring_disc_with_hole(0, 0, R, a, h);
    const FdemTopology topo = build_topology(mesh.mesh);
    RockSolver s(topo, RockMaterial::paper_table2(), RockOptions{});
    // Break every joint whose two ends lie on the circles of radius r1 or r2 (the mesher's ring circles).
    const int rings = static_cast<int>(std::lround((R - a) / h));
    const double r1 = a + 4 * (R - a) / rings, r2 = a + 10 * (R - a) / rings;
    std::vector<int> on_circles;
    const RockSnapshot s0 = s.snapshot();
    for (size_t j = 0; j < s0.joint_nodes.size(); ++j) {
      const int n0 = s0.joint_nodes[j][0], n1 = s0.joint_nodes[j][1];
      for (double r : {r1, r2})
        if (std::fabs(std::hypot(s0.x0[n0], s0.y0[n0]) - r) < 1e-9 && std::fabs(std::hypot(s0.x0[n1], s0.y0[n1]) - r) < 1e-9)
          on_circles.push_back(static_cast<int>(j));
    }
    s.break_joints(on_circles);
    const std::vector<int> labels = fragment_labels(s.view());
    const RockSnapshot snap = s.snapshot();
    const std::vector<Fragment> f = measure_fragments(snap, labels, 1000.0);
    std::printf("A2: disc with two circles cut (%zu joints): %zu fragments (expected 3: inner ring, ring, outer ring)\n",
                on_circles.size(), f.size());
    REQUIRE(f.size() == 3);
    double total = 0;
    for (const Fragment& g : f) total += g.area;
    CHECK(labels == reference_labels(topo, snap.joint_broken));
    // The areas are those of the polygonal rings the mesher made: they add up to the mesh's area.
    double mesh_area = 0;
    for (int t = 0; t < topo.triangle_count(); ++t) {
      const auto& p = topo.node_positions;
      mesh_area += 0.5 * ((p[3 * t + 1][0] - p[3 * t][0]) * (p[3 * t + 2][1] - p[3 * t][1]) -
                          (p[3 * t + 2][0] - p[3 * t][0]) * (p[3 * t + 1][1] - p[3 * t][1]));
    }
    CHECK(std::fabs(total / mesh_area - 1) < 1e-12);
  }
}

TEST_CASE("A3: sieve size (minimum Feret width) of an ellipse-shaped and a rectangular fragment", "[fdem][A3]") {
  SECTION("ellipse cut out of a fine mesh, axes turned by 30 degrees") {
    const double L = 1.0, A = 0.36, B = 0.2, th = M_PI / 6;  // semi-axes [m]
    const int n = 120;
    const FdemTopology topo = build_topology(structured_rectangle(n, n, -L / 2, L / 2, -L / 2, L / 2));
    auto inside = [&](int t) {
      const auto& p = topo.node_positions;
      const double cx = (p[3 * t][0] + p[3 * t + 1][0] + p[3 * t + 2][0]) / 3;
      const double cy = (p[3 * t][1] + p[3 * t + 1][1] + p[3 * t + 2][1]) / 3;
      const double u = cx * std::cos(th) + cy * std::sin(th), v = -cx * std::sin(th) + cy * std::cos(th);
      return u * u / (A * A) + v * v / (B * B) <= 1;
    };
    std::vector<int> boundary;
    for (size_t j = 0; j < topo.joints.size(); ++j)
      if (inside(topo.joints[j].triangle_a) != inside(topo.joints[j].triangle_b)) boundary.push_back(static_cast<int>(j));
    RockSolver s(topo, RockMaterial::paper_table2(), RockOptions{});
    s.break_joints(boundary);
    const std::vector<Fragment> f = measure_fragments(s.snapshot(), fragment_labels(s.view()), 2600.0);
    REQUIRE(f.size() == 2);
    const Fragment& e = f[0].area < f[1].area ? f[0] : f[1];
    std::printf("A3: ellipse %g x %g m on %d x %d cells: sieve size %.5f m vs minor axis %.5f m (%+.2f %%); "
                "equivalent diameter %.5f vs %.5f m (%+.2f %%)\n", 2 * A, 2 * B, n, n, e.sieve_size, 2 * B,
                100 * (e.sieve_size / (2 * B) - 1), e.equivalent_diameter, 2 * std::sqrt(A * B),
                100 * (e.equivalent_diameter / (2 * std::sqrt(A * B)) - 1));
    CHECK(std::fabs(e.sieve_size / (2 * B) - 1) < 0.05);
    CHECK(std::fabs(e.equivalent_diameter / (2 * std::sqrt(A * B)) - 1) < 0.05);
  }
  SECTION("rectangle 0.8 x 0.3 m") {
    const FdemTopology topo = build_topology(structured_rectangle(16, 6, 0.0, 0.8, 0.0, 0.3));
    RockSolver s(topo, RockMaterial::paper_table2(), RockOptions{});
    const std::vector<Fragment> f = measure_fragments(s.snapshot(), fragment_labels(s.view()), 2600.0);
    REQUIRE(f.size() == 1);
    std::printf("A3: rectangle 0.8 x 0.3 m: sieve size %.15g m (expected 0.3)\n", f[0].sieve_size);
    CHECK(std::fabs(f[0].sieve_size / 0.3 - 1) < 1e-12);
  }
  SECTION("point sets") {
    std::vector<std::array<double, 2>> ellipse;
    for (int i = 0; i < 720; ++i) ellipse.push_back({3 * std::cos(i * M_PI / 360), 1.5 * std::sin(i * M_PI / 360)});
    CHECK(std::fabs(minimum_feret_width(ellipse) / 3.0 - 1) < 1e-4);
    CHECK(minimum_feret_width({{0, 0}, {1, 1}, {2, 2}}) == 0.0);  // collinear: no width
  }
}

TEST_CASE("A4: Swebrec and Rosin-Rammler fits recover the parameters of synthetic samples", "[fdem][A4]") {
  const int N = 20000;
  SECTION("Swebrec") {
    const double x50 = 0.12, xmax = 0.6, b = 2.2;
    // P = 1 / (1 + f^b) with f = ln(xmax / x) / ln(xmax / x50): x = xmax (x50 / xmax)^f, f = (1 / P - 1)^(1 / b).
    const SizeDistribution d = size_distribution(
        sample(N, [&](double u) { return xmax * std::pow(x50 / xmax, std::pow(1 / u - 1, 1 / b)); }), 0.3);
    const SwebrecFit& f = d.swebrec;
    std::printf("A4: Swebrec sample of %d: x50 %.5f (%.5f, %+.2f %%), xmax %.5f (%.5f, %+.2f %%), b %.4f (%.4f, %+.2f %%); "
                "R^2 %.6f, RMS %.2e; sample X50 %.5f; oversize > 0.3 m %.4f (exact %.4f)\n",
                N, f.x50, x50, 100 * (f.x50 / x50 - 1), f.xmax, xmax, 100 * (f.xmax / xmax - 1), f.b, b,
                100 * (f.b / b - 1), f.r_squared, f.rms, d.x50, d.oversize_fraction, 1 - swebrec_passing(0.3, x50, xmax, b));
    REQUIRE(f.valid);
    CHECK(std::fabs(f.x50 / x50 - 1) < 0.02);
    CHECK(std::fabs(f.xmax / xmax - 1) < 0.02);
    CHECK(std::fabs(f.b / b - 1) < 0.02);
    CHECK(std::fabs(d.x50 / x50 - 1) < 0.02);
    CHECK(std::fabs(d.oversize_fraction - (1 - swebrec_passing(0.3, x50, xmax, b))) < 0.01);
  }
  SECTION("Rosin-Rammler (Kuz-Ram form)") {
    const double x50 = 0.2, n = 1.4;
    // P = 1 - exp(-ln 2 (x / x50)^n): x = x50 (-ln(1 - P) / ln 2)^(1 / n).
    const SizeDistribution d = size_distribution(
        sample(N, [&](double u) { return x50 * std::pow(-std::log(1 - u) / std::log(2.0), 1 / n); }), 0.5);
    const RosinRammlerFit& f = d.rosin_rammler;
    std::printf("A4: Rosin-Rammler sample of %d: x50 %.5f (%.5f, %+.2f %%), n %.4f (%.4f, %+.2f %%); R^2 %.6f; "
                "sample X20 %.4f X50 %.4f X80 %.4f (exact %.4f %.4f %.4f)\n",
                N, f.x50, x50, 100 * (f.x50 / x50 - 1), f.n, n, 100 * (f.n / n - 1), f.r_squared, d.x20, d.x50, d.x80,
                x50 * std::pow(-std::log(0.8) / std::log(2.0), 1 / n), x50, x50 * std::pow(-std::log(0.2) / std::log(2.0), 1 / n));
    REQUIRE(f.valid);
    CHECK(std::fabs(f.x50 / x50 - 1) < 0.02);
    CHECK(std::fabs(f.n / n - 1) < 0.02);
    CHECK(std::fabs(d.x80 / (x50 * std::pow(-std::log(0.2) / std::log(2.0), 1 / n)) - 1) < 0.02);
  }
  SECTION("a few large pieces: the Swebrec fit stays bounded") {
    // 12 pieces of nearly one size (a disc split into wedges): without a bound xmax runs off to infinity.
    std::vector<Fragment> f(12);
    for (int i = 0; i < 12; ++i) f[i].mass = 1.0, f[i].triangles = 100, f[i].sieve_size = 0.8 + 0.01 * i;
    const SizeDistribution d = size_distribution(f, 0.5);
    std::printf("A4: 12 pieces of 0.80-0.91 m: Swebrec x50 %.4f m, xmax %.4g m (at bound: %d), b %.4g; "
                "Rosin-Rammler x50 %.4f m, n %.4g\n", d.swebrec.x50, d.swebrec.xmax, d.swebrec.xmax_at_bound, d.swebrec.b,
                d.rosin_rammler.x50, d.rosin_rammler.n);
    REQUIRE(d.swebrec.valid);
    CHECK(d.swebrec.xmax <= kSwebrecMaxRatio * d.swebrec.x50);
    CHECK(std::isfinite(d.swebrec.b));
    CHECK(std::fabs(d.swebrec.x50 / d.x50 - 1) < 0.05);
  }
  SECTION("fines pass every sieve; sizes below them are 0") {
    std::vector<Fragment> f(3);
    f[0].mass = 6, f[0].fines = true;          // 60 % fines
    f[1].mass = 1, f[1].sieve_size = 0.1;      // passing 0.7 at 0.1 m
    f[2].mass = 3, f[2].sieve_size = 0.4;      // passing 1.0 at 0.4 m
    const SizeDistribution d = size_distribution(f, 0.2);
    CHECK(d.x20 == 0.0);
    CHECK(d.x50 == 0.0);
    CHECK(std::fabs(d.x80 - std::exp(std::log(0.1) + (0.1 / 0.3) * std::log(4.0))) < 1e-12);
    CHECK(std::fabs(d.oversize_fraction - 0.3) < 1e-15);
    CHECK(d.sized == 2);
  }
}

TEST_CASE("A5: damage per triangle and the crushed and cracked zones around a hole", "[fdem][A5]") {
  const double R = 1.0, a = 0.1, h = 0.025;
  const FdemTopology topo = build_topology(ring_disc_with_hole(0, 0, R, a, h).mesh);
  RockSolver s(topo, RockMaterial::paper_table2(), RockOptions{});
  // Crushed to r1: every joint with its midpoint inside r1; cracked to r2: the joints along the x axis.
  const double r1 = 0.2, r2 = 0.6;
  std::vector<int> broken;
  const RockSnapshot s0 = s.snapshot();
  for (size_t j = 0; j < s0.joint_nodes.size(); ++j) {
    const int n0 = s0.joint_nodes[j][0], n1 = s0.joint_nodes[j][1];
    const double mx = 0.5 * (s0.x0[n0] + s0.x0[n1]), my = 0.5 * (s0.y0[n0] + s0.y0[n1]);
    if (std::hypot(mx, my) < r1 || (mx > 0 && std::fabs(my) < 0.6 * h && mx < r2)) broken.push_back(static_cast<int>(j));
  }
  s.break_joints(broken);
  const RockSnapshot snap = s.snapshot();
  const double w = 2 * h;
  const DamageZone z = damage_zone(snap, {0, 0}, a, w);
  std::printf("A5: crushed radius %.3f m (broken to %.3f m), cracked radius %.3f m (crack to %.3f m); ring width %.3f m\n",
              z.crushed_radius, r1, z.cracked_radius, r2, w);
  CHECK(std::fabs(z.crushed_radius - r1) <= w);
  CHECK(std::fabs(z.cracked_radius - r2) <= w);
  // Behind the hole only: the crack along +x lies in the half plane x >= 0, not in x <= 0.
  const DamageZone ahead = damage_zone(snap, {0, 0}, a, w, 0.5, {1.0, 0.0});
  const DamageZone back = damage_zone(snap, {0, 0}, a, w, 0.5, {-1.0, 0.0});
  std::printf("A5: half planes: x >= 0 cracked to %.3f m, x <= 0 cracked to %.3f m (crushed %.3f, %.3f m)\n",
              ahead.cracked_radius, back.cracked_radius, ahead.crushed_radius, back.crushed_radius);
  CHECK(std::fabs(ahead.cracked_radius - r2) <= w);
  CHECK(std::fabs(back.cracked_radius - r1) <= w);
  CHECK(std::fabs(back.crushed_radius - r1) <= w);
  // Crack rose: the crushed disc spreads over all twelve sectors alike; the crack along +x adds its length (the
  // broken joints beyond r1) to the sectors on either side of +x (0-30 and 330-360 deg).
  double crack = 0, crushed = 0;
  for (int j : broken) {
    const int n0 = snap.joint_nodes[j][0], n1 = snap.joint_nodes[j][1];
    const double len = std::hypot(snap.x0[n1] - snap.x0[n0], snap.y0[n1] - snap.y0[n0]);
    (std::hypot(0.5 * (snap.x0[n0] + snap.x0[n1]), 0.5 * (snap.y0[n0] + snap.y0[n1])) < r1 ? crushed : crack) += len;
  }
  double others = 0, total = 0;
  for (int q = 0; q < kRoseSectors; ++q) total += z.crack_rose[q], others += (q == 0 || q == 11) ? 0.0 : z.crack_rose[q];
  const double excess = z.crack_rose[0] + z.crack_rose[11] - others / 5;  // over the crushed disc's share
  std::printf("A5: crack rose: total %.4f m (broken %.4f m), sectors at +x %.4f m, the other ten %.4f m; excess at +x "
              "%.4f m vs the crack's %.4f m\n", total, crack + crushed, z.crack_rose[0] + z.crack_rose[11], others, excess, crack);
  CHECK(std::fabs(total - (crack + crushed)) <= 1e-12 * total);
  CHECK(std::fabs(excess - crack) <= 0.1 * crack);
  const std::vector<double> d = triangle_damage(snap);
  for (int t = 0; t < topo.triangle_count(); ++t) {
    double expected = 0;
    for (int j : broken)
      if (topo.joints[j].triangle_a == t || topo.joints[j].triangle_b == t) expected = 1;
    CHECK(d[t] == expected);
  }
  // Damage profile: each ring's broken length is the length of the joints broken above whose midpoints lie in it
  // (rings of w from the wall, counted here from the test's own list); every ring inside r1 is broken whole, none
  // beyond r2 holds a broken joint, and the rings' rock areas add up to the mesh's area (every triangle's centroid
  // lies outside the hole).
  std::vector<double> expected_broken(z.rings.size(), 0.0);
  for (int j : broken) {
    const int n0 = snap.joint_nodes[j][0], n1 = snap.joint_nodes[j][1];
    const double r = std::hypot(0.5 * (snap.x0[n0] + snap.x0[n1]), 0.5 * (snap.y0[n0] + snap.y0[n1]));
    const size_t k = static_cast<size_t>((r - a) / w);
    REQUIRE(k < expected_broken.size());
    expected_broken[k] += std::hypot(snap.x0[n1] - snap.x0[n0], snap.y0[n1] - snap.y0[n0]);
  }
  double mesh_area = 0, ring_area = 0;
  for (size_t t = 0; 3 * t + 2 < snap.x0.size(); ++t) {
    const double* x = &snap.x0[3 * t];
    const double* y = &snap.y0[3 * t];
    mesh_area += 0.5 * std::fabs((x[1] - x[0]) * (y[2] - y[0]) - (x[2] - x[0]) * (y[1] - y[0]));
  }
  for (size_t k = 0; k < z.rings.size(); ++k) {
    const DamageRing& g = z.rings[k];
    ring_area += g.rock_area;
    CHECK(std::fabs(g.broken_length - expected_broken[k]) <= 1e-12 * (1 + expected_broken[k]));
    CHECK(std::fabs(g.inner_radius - (a + k * w)) <= 1e-15);
    if (g.outer_radius <= r1) CHECK(g.broken_length == g.joint_length);
    if (g.inner_radius >= r2 + h) CHECK(g.broken_length == 0.0);
  }
  const DamageRing& inner = z.rings.front();
  const DamageRing& crack_ring = z.rings[static_cast<size_t>((0.5 * (r1 + r2) - a) / w)];
  std::printf("A5: damage profile: %zu rings; rock area %.6f m2 (mesh %.6f, annulus %.6f); P21 %.2f 1/m in the "
              "first ring (the mesh's own %.2f), %.2f 1/m in the ring at %.2f-%.2f m on the crack\n",
              z.rings.size(), ring_area, mesh_area, M_PI * (R * R - a * a), inner.broken_length / inner.rock_area,
              inner.joint_length / inner.rock_area, crack_ring.broken_length / crack_ring.rock_area,
              crack_ring.inner_radius, crack_ring.outer_radius);
  CHECK(std::fabs(ring_area - mesh_area) <= 1e-12 * mesh_area);
  CHECK(crack_ring.broken_length > 0.0);
}
