//! \file test_joint_sets.cpp
//! \brief J1-J2: the traces of a natural joint set against its input: direction, spacing between lines, trace
//! length and gap along a line, persistence, clipping to the rock and its holes.
#include "blastsim/core/error.hpp"
#include "blastsim/fdem/joint_sets.hpp"
#include "blastsim/fdem/rock_model.hpp"
#include "catch.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <utility>
#include <vector>

using namespace blastsim;
using namespace blastsim::fdem;

namespace {

double trace_length_of(const Segment& s) { return std::hypot(s.b[0] - s.a[0], s.b[1] - s.a[1]); }

//! A built rectangle [-half, half]^2 with elements of size h [m].
MeshSpec square_box(double half, double h) {
  MeshSpec box;
  box.shape = MeshShape::rectangle;
  box.min = {-half, -half}, box.max = {half, half};
  box.element_size = h;
  return box;
}

}  // namespace

TEST_CASE("J1 joint set: the traces have the set's direction, spacing, trace length, gap and persistence",
          "[fdem][jointset][J1]") {
  const MeshSpec box = square_box(2.0, 0.01);
  JointSetSpec set;
  set.label = "rock.joint_set.0";
  set.angle = 30.0 * M_PI / 180;
  set.spacing = 0.1;
  set.trace_length = 0.15;
  set.persistence = 0.5;  // gap along a line = L (1 - p) / p = 0.15 m
  set.offset = 0.037;
  set.seed = 3;
  const double gap = set.trace_length * (1 - set.persistence) / set.persistence;
  const std::vector<Segment> traces = joint_set_traces(set, box, 0.5 * box.element_size);
  REQUIRE(traces.size() > 100);
  const double dx = std::cos(set.angle), dy = std::sin(set.angle), nx = -dy, ny = dx;
  std::map<long long, std::vector<std::pair<double, double>>> lines;  // line index -> traces along it (t0, t1)
  double traced = 0;
  for (const Segment& s : traces) {
    const double ex = s.b[0] - s.a[0], ey = s.b[1] - s.a[1], len = std::hypot(ex, ey);
    CHECK(std::abs(ex * dy - ey * dx) < 1e-12 * len);  // along the set's direction
    for (const auto& p : {s.a, s.b}) {  // inside the box (ends on it at most)
      CHECK(p[0] >= box.min[0] - 1e-12);
      CHECK(p[0] <= box.max[0] + 1e-12);
      CHECK(p[1] >= box.min[1] - 1e-12);
      CHECK(p[1] <= box.max[1] + 1e-12);
    }
    // Normal distance from the centre = offset + k spacing for an integer k.
    const double k = (s.a[0] * nx + s.a[1] * ny - set.offset) / set.spacing;
    CHECK(std::abs(k - std::round(k)) < 1e-9);
    const double t0 = s.a[0] * dx + s.a[1] * dy, t1 = s.b[0] * dx + s.b[1] * dy;
    lines[std::llround(k)].push_back({std::min(t0, t1), std::max(t0, t1)});
    traced += len;
  }
  // Lines: every k with |offset + k spacing| < half the box's diagonal that crosses the box.
  int inner = 0, gaps = 0;
  double chord_total = 0;
  for (auto& [k, along] : lines) {
    std::sort(along.begin(), along.end());
    for (std::size_t i = 0; i < along.size(); ++i) {
      const bool first = i == 0, last = i + 1 == along.size();
      if (!first && !last) {  // not clipped by the box: the set's trace length
        CHECK(along[i].second - along[i].first == Approx(set.trace_length).epsilon(1e-12));
        ++inner;
      }
      if (!first) {
        CHECK(along[i].first - along[i - 1].second == Approx(gap).epsilon(1e-9));
        ++gaps;
      }
    }
  }
  // The chord of each line through the box: the persistence is traced length over chord length.
  for (const auto& [k, along] : lines) {
    const double s = set.offset + k * set.spacing;
    double t_lo = -1e300, t_hi = 1e300;
    const double px = s * nx, py = s * ny;
    for (int a = 0; a < 2; ++a) {
      const double p = a == 0 ? px : py, d = a == 0 ? dx : dy;
      double u = (box.min[a] - p) / d, v = (box.max[a] - p) / d;
      if (u > v) std::swap(u, v);
      t_lo = std::max(t_lo, u), t_hi = std::min(t_hi, v);
    }
    chord_total += t_hi - t_lo;
  }
  const double persistence = traced / chord_total;
  // Each line's share deviates from p by less than one period over its chord; over the ~55 lines with
  // independent shifts the mean is within a few per cent: tolerance 5 %.
  std::printf("J1: %zu traces on %zu lines, %d unclipped traces of %.3f m (input %.3f m), %d gaps of %.3f m, "
              "persistence %.4f (input %.2f)\n",
              traces.size(), lines.size(), inner, set.trace_length, set.trace_length, gaps, gap, persistence,
              set.persistence);
  CHECK(inner > 200);
  CHECK(std::abs(persistence / set.persistence - 1) < 0.05);
  // The same seed gives the same traces; another shifts them.
  CHECK(joint_set_traces(set, box, 0.005).size() == traces.size());
  JointSetSpec other = set;
  other.seed = 4;
  CHECK(joint_set_traces(other, box, 0.005)[0].a != traces[0].a);
}

TEST_CASE("J1 joint set: any offset places the same lines (offset modulo the spacing), and the traces' period is "
          "bounded", "[fdem][jointset][J1]") {
  // The lines n . (x - c) = offset + k spacing do not change when offset moves by whole spacings: far offsets
  // (1e17 m used to hang, 1e14 m misplaced the lines) give the traces of the offset's remainder, bit for bit (the
  // remainder is exact).
  const MeshSpec box = square_box(1.0, 0.02);
  JointSetSpec set;
  set.label = "rock.joint_set.0";
  set.angle = 0.4;
  set.spacing = 0.125;  // a power of two: 1e17 and 1e300 are whole numbers of spacings
  set.trace_length = 0.3;
  set.persistence = 0.6;
  // Pairs (near, far) of offsets a whole number of spacings apart, each exactly representable.
  const std::vector<std::pair<double, double>> pairs{
      {0.0, 1e17}, {0.0, -1e17}, {0.0, 1e300}, {0.0625, std::ldexp(1.0, 47) + 0.0625}};
  for (const auto& [near, far] : pairs) {
    JointSetSpec a = set, b = set;
    a.offset = near, b.offset = far;
    const std::vector<Segment> ta = joint_set_traces(a, box, 0.01), tb = joint_set_traces(b, box, 0.01);
    INFO("offset " << far << " against " << near);
    REQUIRE(ta.size() > 20);
    REQUIRE(tb.size() == ta.size());
    for (size_t k = 0; k < ta.size(); ++k) CHECK((tb[k].a == ta[k].a && tb[k].b == ta[k].b));
  }
  // An offset of any size finishes and keeps every line within the rock.
  JointSetSpec huge = set;
  huge.offset = 3.7e250;
  const std::vector<Segment> far_traces = joint_set_traces(huge, box, 0.01);
  CHECK(!far_traces.empty());
  for (const Segment& t : far_traces)
    for (const auto& p : {t.a, t.b}) CHECK((std::fabs(p[0]) <= 1.0 + 1e-12 && std::fabs(p[1]) <= 1.0 + 1e-12));
  // A trace longer than 1000 extents of the rock (an infinite period) is refused naming trace_length.
  JointSetSpec longest = set;
  longest.trace_length = 1e308, longest.persistence = 0.5;
  CHECK_THROWS_WITH(joint_set_traces(longest, box, 0.01),
                    Catch::Contains("rock.joint_set.0.trace_length") && Catch::Contains("1000 times"));
  longest.trace_length = 2000.0;  // 707 extents: accepted, one trace or none a line
  const std::vector<Segment> whole = joint_set_traces(longest, box, 0.01);
  for (const Segment& t : whole) CHECK(trace_length_of(t) <= 2 * std::sqrt(2.0) + 1e-9);
  JointSetSpec tiny = set;
  tiny.trace_length = 0.001;
  CHECK_THROWS_WITH(joint_set_traces(tiny, box, 0.01), Catch::Contains("rock.joint_set.0.trace_length"));
}

TEST_CASE("Lines a built mesh follows meet or leave room for an element: closer ones are refused before meshing",
          "[fdem][jointset][clearance]") {
  // Two cracks 50 um apart made Gmsh mesh the strip between them at its width (1.3 million triangles, minutes of
  // set-up); the check refuses them, naming both, and takes lines that cross, touch, or stay h / 2 apart.
  MeshSpec box;
  box.shape = MeshShape::rectangle;
  box.min = {0.0, 0.0}, box.max = {1.0, 1.0};
  box.element_size = 0.02;
  box.label = "rock.mesh";
  const Segment a{{0.2, 0.5}, {0.8, 0.5}};
  auto pair = [&](const Segment& b) {
    check_segment_clearance(box, {{"rock.crack.0", a}, {"rock.crack.1", b}});
  };
  CHECK_THROWS_WITH(pair({{0.2, 0.50005}, {0.8, 0.50005}}),
                    Catch::Contains("rock.crack.1") && Catch::Contains("rock.crack.0") && Catch::Contains("5e-05 m"));
  CHECK_THROWS_WITH(pair({{0.807, 0.5}, {0.9, 0.6}}), Catch::Contains("0.007 m"));  // an end 7 mm short of it
  CHECK_NOTHROW(pair({{0.2, 0.511}, {0.8, 0.511}}));   // 11 mm: more than half an element
  CHECK_NOTHROW(pair({{0.5, 0.2}, {0.5, 0.8}}));       // crossing
  CHECK_NOTHROW(pair({{0.8, 0.5}, {0.9, 0.7}}));       // touching at an end
  // Ends near the outline; generated traces, which are not checked against each other (their own rules place them).
  CHECK_THROWS_WITH(check_segment_clearance(box, {{"rock.crack.0", {{0.005, 0.3}, {0.5, 0.3}}}}),
                    Catch::Contains("rock.crack.0") && Catch::Contains("boundary"));
  CHECK_NOTHROW(check_segment_clearance(box, {{"rock.crack.0", {{0.0, 0.3}, {0.5, 0.3}}}}));
  CHECK_NOTHROW(check_segment_clearance(box, {{"t0", {{0.0, 0.3}, {1.0, 0.3}}, 0}, {"t1", {{0.0, 0.305}, {1.0, 0.305}}, 1}}));
  // A shallow chord of a disc: both ends on the circle, its middle 2 mm inside.
  MeshSpec disc;
  disc.shape = MeshShape::disc;
  disc.radius = 0.5, disc.element_size = 0.02, disc.label = "rock.mesh";
  const double y = 0.498, x = std::sqrt(0.25 - y * y);
  CHECK_THROWS_WITH(check_segment_clearance(disc, {{"rock.joint.0", {{-x, y}, {x, y}}}}),
                    Catch::Contains("rock.joint.0") && Catch::Contains("chord"));
  // A mesh file's edges are given: nothing is checked.
  MeshSpec file;
  file.shape = MeshShape::file;
  CHECK_NOTHROW(check_segment_clearance(file, {{"rock.crack.0", a}, {"rock.crack.1", {{0.2, 0.50005}, {0.8, 0.50005}}}}));
}

TEST_CASE("J2 joint set: through traces are the rock's chords less its holes", "[fdem][jointset][J2]") {
  MeshSpec disc;
  disc.shape = MeshShape::disc_with_holes;
  disc.center = {0.0, 0.0};
  disc.radius = 1.0;
  disc.element_size = 0.02;
  disc.holes = {{{0.3, 0.0}, 0.1}, {{-0.4, 0.2}, 0.05}};
  JointSetSpec set;
  set.label = "rock.joint_set.1";
  set.angle = M_PI / 2;  // vertical lines x = -offset - k spacing (normal (-1, 0))
  set.spacing = 0.1;
  const std::vector<Segment> traces = joint_set_traces(set, disc, 0.01);
  double total = 0;
  for (const Segment& s : traces) {
    CHECK(s.a[0] == Approx(s.b[0]).margin(1e-12));
    for (const auto& p : {s.a, s.b}) {
      CHECK(std::hypot(p[0], p[1]) <= 1.0 + 1e-12);
      for (const Circle& h : disc.holes) CHECK(std::hypot(p[0] - h.center[0], p[1] - h.center[1]) >= h.radius - 1e-12);
    }
    total += trace_length_of(s);
  }
  // Exact total: chords 2 sqrt(1 - x^2) of the 19 lines x = -0.9..0.9, less the holes' chords on them; a line
  // that meets a hole's rim within the clearance (2 x 0.01 m) of a tangent loses the chord of the hole's circle
  // grown by the clearance instead (x = 0.2 and 0.4 touch the larger hole).
  const double clearance = 0.02;
  double exact = 0;
  for (int k = -9; k <= 9; ++k) {
    const double x = 0.1 * k;
    exact += 2 * std::sqrt(1 - x * x);
    for (const Circle& h : disc.holes) {
      const double dxh = std::abs(x - h.center[0]);
      const double r = std::abs(dxh - h.radius) < clearance ? h.radius + clearance : h.radius;
      if (dxh < r) exact -= 2 * std::sqrt(r * r - dxh * dxh);
    }
  }
  std::printf("J2: %zu traces, total length %.12f m (exact %.12f m)\n", traces.size(), total, exact);
  CHECK(total == Approx(exact).epsilon(1e-12));
  // The line x = 0.3 through the larger hole's centre is cut in two.
  int on_hole_line = 0;
  for (const Segment& s : traces) on_hole_line += std::abs(s.a[0] - 0.3) < 1e-9 ? 1 : 0;
  CHECK(on_hole_line == 2);
  // 19 lines, four of them cut in two: through a hole (x = 0.3, -0.4) or at a tangent with clearance (0.2, 0.4).
  CHECK(traces.size() == 23);
  // No trace end lies within the clearance of a hole's rim unless on it.
  for (const Segment& s : traces)
    for (const auto& p : {s.a, s.b})
      for (const Circle& h : disc.holes) {
        const double gap = std::hypot(p[0] - h.center[0], p[1] - h.center[1]) - h.radius;
        CHECK((gap < 1e-9 || gap > clearance - 1e-9));
      }
  // Bad sets are refused naming them.
  JointSetSpec bad = set;
  bad.spacing = 0;
  CHECK_THROWS_WITH(joint_set_traces(bad, disc, 0.01), Catch::Contains("rock.joint_set.1.spacing"));
  bad = set;
  bad.persistence = 0.5;
  CHECK_THROWS_WITH(joint_set_traces(bad, disc, 0.01), Catch::Contains("rock.joint_set.1.trace_length"));
}

TEST_CASE("J4 joint sets: a trace end near another set's trace moves onto it, so no sliver is left between them",
          "[fdem][jointset][J4]") {
  // A vertical trace ending 3 mm below and one ending 4 mm past a horizontal trace of another set (10 mm
  // clearance), and one ending 30 mm away (left alone).
  std::vector<std::vector<Segment>> sets = {{{{0.0, 0.0}, {1.0, 0.0}}},
                                            {{{0.2, -0.5}, {0.2, -0.003}}, {{0.5, -0.5}, {0.5, 0.004}},
                                             {{0.8, -0.5}, {0.8, -0.03}}}};
  snap_trace_ends(sets, 0.01, 0.005);
  CHECK(sets[1][0].b[1] == Approx(0.0).margin(1e-15));  // extended onto the line
  CHECK(sets[1][1].b[1] == Approx(0.0).margin(1e-15));  // shortened onto it
  CHECK(sets[1][2].b[1] == -0.03);                     // beyond the clearance: unchanged
  CHECK(sets[1][0].a[1] == -0.5);                      // the far ends stay
  CHECK(sets[0][0].a[0] == 0.0);
  CHECK(sets[0][0].b[0] == 1.0);
}
