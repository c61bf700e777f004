//! \file joint_sets.cpp
//! \brief Traces of a joint set: parallel lines at the set's spacing, traces at its persistence, clipped to the
//! rock's outline less its holes.
#include "blastsim/fdem/joint_sets.hpp"

#include "blastsim/core/error.hpp"
#include "blastsim/fdem/rock_model.hpp"

#include <algorithm>
#include <cmath>
#include <random>
#include <sstream>
#include <utility>

namespace blastsim::fdem {

namespace {

using Interval = std::pair<double, double>;  // [t0, t1] along a line p + t d
constexpr double kMaxTraceReach = 1000;  // longest trace_length accepted, in extents of the rock
constexpr double kMaxLines = 100000;     // most lines of one set across the rock

//! The part of the line p + t d (|d| = 1) inside the circle (c, r), or an empty interval.
Interval circle_chord(const std::array<double, 2>& p, const std::array<double, 2>& d, const std::array<double, 2>& c,
                      double r) {
  const double wx = p[0] - c[0], wy = p[1] - c[1];
  const double b = wx * d[0] + wy * d[1], q = wx * wx + wy * wy - r * r;
  const double disc = b * b - q;
  if (disc <= 1e-12 * r * r) return {0.0, 0.0};  // a tangent (to round-off: half-chords below 1e-6 r) cuts nothing
  const double h = std::sqrt(disc);
  return {-b - h, -b + h};
}

//! The part of the line inside the box [lo, hi] (slab method), or an empty interval.
Interval box_chord(const std::array<double, 2>& p, const std::array<double, 2>& d, const std::array<double, 2>& lo,
                   const std::array<double, 2>& hi) {
  double t0 = -1e300, t1 = 1e300;
  for (int k = 0; k < 2; ++k) {
    if (std::abs(d[k]) < 1e-300) {
      if (p[k] < lo[k] || p[k] > hi[k]) return {0.0, 0.0};
      continue;
    }
    double a = (lo[k] - p[k]) / d[k], b = (hi[k] - p[k]) / d[k];
    if (a > b) std::swap(a, b);
    t0 = std::max(t0, a), t1 = std::min(t1, b);
  }
  return t1 > t0 ? Interval{t0, t1} : Interval{0.0, 0.0};
}

//! `pieces` less the interval `cut`.
std::vector<Interval> subtract(const std::vector<Interval>& pieces, const Interval& cut) {
  if (!(cut.second > cut.first)) return pieces;
  std::vector<Interval> out;
  for (const Interval& s : pieces) {
    if (cut.second <= s.first || cut.first >= s.second) {
      out.push_back(s);
      continue;
    }
    if (cut.first > s.first) out.push_back({s.first, cut.first});
    if (cut.second < s.second) out.push_back({cut.second, s.second});
  }
  return out;
}

}  // namespace

std::vector<Segment> joint_set_traces(const JointSetSpec& set, const MeshSpec& shape, double min_length) {
  if (!set.segments.empty()) return set.segments;  // explicit joints: the segments as given
  auto fail = [&](const std::string& what) { throw InputError(set.label + "." + what); };
  if (shape.shape == MeshShape::file) fail("spacing: joint sets need a built mesh shape (a mesh file has its own lines)");
  if (!(set.spacing > 0) || !std::isfinite(set.spacing)) fail("spacing must be a positive number of metres");
  if (!(set.persistence > 0 && set.persistence <= 1)) fail("persistence must be in (0, 1]");
  if (!(set.trace_length >= 0) || !std::isfinite(set.trace_length)) fail("trace_length must be >= 0 m");
  if (set.persistence < 1 && set.trace_length == 0) fail("trace_length: needed when persistence < 1");
  // Outline centre and a radius that covers it.
  std::array<double, 2> c{};
  double reach = 0;
  const bool box = shape.is_rectangle();
  if (box) {
    c = {0.5 * (shape.min[0] + shape.max[0]), 0.5 * (shape.min[1] + shape.max[1])};
    reach = 0.5 * std::hypot(shape.max[0] - shape.min[0], shape.max[1] - shape.min[1]);
  } else {
    c = shape.center;
    reach = shape.radius;
  }
  std::vector<Circle> holes = shape.holes;
  if (shape.shape == MeshShape::disc_with_hole || shape.shape == MeshShape::rectangle_with_hole)
    holes.push_back({shape.center, shape.hole_radius});
  const std::array<double, 2> d{std::cos(set.angle), std::sin(set.angle)}, n{-d[1], d[0]};
  const bool through = set.trace_length == 0 || set.persistence == 1;
  // The traces repeat along a line with period trace_length / persistence. A trace longer than the rock's extent
  // crosses it whole, so nothing is lost by a limit of kMaxTraceReach extents, which keeps the period finite; a
  // trace shorter than `min_length` would be dropped anyway, and the limit bounds the traces a line holds.
  const double extent = 2 * reach;
  if (!through && !(set.trace_length >= min_length)) {
    std::ostringstream os;
    os << "trace_length = " << set.trace_length << " m: must be at least " << min_length << " m (half an element)";
    fail(os.str());
  }
  if (!through && !(set.trace_length <= kMaxTraceReach * extent)) {
    std::ostringstream os;
    os << "trace_length = " << set.trace_length << " m: must be at most " << kMaxTraceReach
       << " times the rock's extent (" << kMaxTraceReach * extent << " m); a trace that long crosses the rock whole";
    fail(os.str());
  }
  const double period = through ? 0.0 : set.trace_length / set.persistence;
  std::mt19937_64 bits(static_cast<std::uint64_t>(set.seed));
  const double clearance = 2 * min_length;  // an element
  // The lines n . (x - c) = offset + k spacing are the same for any offset taken modulo the spacing; the exact
  // remainder keeps every line where it belongs for any offset (offset + k spacing would lose the lines' places
  // to round-off once offset / spacing is large), and the lines are visited in the same order.
  const double offset = std::remainder(set.offset, set.spacing);
  if (!std::isfinite(offset)) fail("offset must be a finite number of metres");
  // Lines k = k_lo..k_hi with |offset + k spacing| < reach, in order.
  if (!(extent / set.spacing <= kMaxLines)) fail("spacing: more than 100,000 lines across the rock");
  const long long k_lo = static_cast<long long>(std::ceil((-reach - offset) / set.spacing));
  const long long k_hi = static_cast<long long>(std::floor((reach - offset) / set.spacing));
  std::vector<Segment> out;
  for (long long k = k_lo; k <= k_hi; ++k) {
    const double s = offset + static_cast<double>(k) * set.spacing;
    const std::array<double, 2> p{c[0] + s * n[0], c[1] + s * n[1]};  // the line's point nearest the centre
    const double shift = static_cast<double>(bits() >> 11) * (1.0 / 9007199254740992.0);  // one per line
    const Interval rock = box ? box_chord(p, d, shape.min, shape.max) : circle_chord(p, d, shape.center, shape.radius);
    if (!(rock.second > rock.first)) continue;
    // A line that runs within `clearance` of the outline along its length (a shallow chord of a disc, a line
    // along a side of a box) would leave slivers of rock between them: no traces on it.
    if (box ? (std::abs(d[1]) < 1e-12 && std::min(p[1] - shape.min[1], shape.max[1] - p[1]) < clearance) ||
                  (std::abs(d[0]) < 1e-12 && std::min(p[0] - shape.min[0], shape.max[0] - p[0]) < clearance)
            : shape.radius - std::abs(s) < clearance)
      continue;
    // The holes on this line: one that the line meets at a shallow angle or misses by less than `clearance` is
    // cut out with `clearance` to spare (a trace would otherwise end in a sliver against its rim).
    std::vector<Interval> cuts;
    for (const Circle& h : holes) {
      const double miss = std::abs((h.center[0] - p[0]) * n[0] + (h.center[1] - p[1]) * n[1]);
      cuts.push_back(circle_chord(p, d, h.center, std::abs(miss - h.radius) < clearance ? h.radius + clearance : h.radius));
    }
    // A trace end within `clearance` of the outline or a cut moves onto it.
    auto snap = [&](double t) {
      for (double b : {rock.first, rock.second}) if (std::abs(t - b) < clearance) return b;
      for (const Interval& c : cuts)
        if (c.second > c.first)
          for (double b : {c.first, c.second}) if (std::abs(t - b) < clearance) return b;
      return t;
    };
    std::vector<Interval> traces;
    if (through) {
      traces.push_back(rock);
    } else {
      // Traces [t0 + m period, t0 + m period + trace_length] covering [rock.first, rock.second]: the chord
      // holds at most chord / period + 2 of them (the period is finite and at least half an element, above).
      const double t0 = -reach - shift * period;
      const long long m0 = static_cast<long long>(std::floor((rock.first - t0) / period)) - 1;
      const long long m_end = m0 + static_cast<long long>(std::ceil((rock.second - rock.first) / period)) + 3;
      for (long long m = m0; m < m_end; ++m) {
        const double a = snap(t0 + static_cast<double>(m) * period), b = snap(t0 + static_cast<double>(m) * period + set.trace_length);
        if (a >= rock.second) break;
        const double lo = std::max(a, rock.first), hi = std::min(b, rock.second);
        if (hi > lo) traces.push_back({lo, hi});
      }
    }
    for (const Interval& c : cuts) traces = subtract(traces, c);
    for (const Interval& t : traces)
      if (t.second - t.first >= min_length)
        out.push_back({{p[0] + t.first * d[0], p[1] + t.first * d[1]}, {p[0] + t.second * d[0], p[1] + t.second * d[1]}});
  }
  return out;
}

void snap_trace_ends(std::vector<std::vector<Segment>>& sets, double clearance, double min_length) {
  for (std::size_t a = 0; a < sets.size(); ++a)
    for (Segment& t : sets[a]) {
      for (int end = 0; end < 2; ++end) {
        std::array<double, 2>& e = end == 0 ? t.a : t.b;
        const std::array<double, 2>& o = end == 0 ? t.b : t.a;
        const double len = std::hypot(e[0] - o[0], e[1] - o[1]);
        const std::array<double, 2> u{(e[0] - o[0]) / len, (e[1] - o[1]) / len};  // outward at this end
        double best = clearance;
        std::array<double, 2> to = e;
        for (std::size_t b = 0; b < sets.size(); ++b) {
          if (b == a) continue;
          for (const Segment& q : sets[b]) {
            // e + x u = q.a + w (q.b - q.a): the crossing of this trace's line with segment q.
            const double qx = q.b[0] - q.a[0], qy = q.b[1] - q.a[1];
            const double den = u[0] * qy - u[1] * qx;
            if (std::abs(den) < 1e-12 * std::hypot(qx, qy)) continue;  // parallel
            const double rx = q.a[0] - e[0], ry = q.a[1] - e[1];
            const double x = (rx * qy - ry * qx) / den, w = (rx * u[1] - ry * u[0]) / den;
            if (w < 0 || w > 1 || std::abs(x) >= best || x == 0) continue;
            best = std::abs(x);
            to = {e[0] + x * u[0], e[1] + x * u[1]};
          }
        }
        e = to;
      }
    }
  for (std::vector<Segment>& set : sets)
    set.erase(std::remove_if(set.begin(), set.end(),
                             [&](const Segment& t) { return std::hypot(t.b[0] - t.a[0], t.b[1] - t.a[1]) < min_length; }),
              set.end());
}

std::vector<std::vector<Segment>> joint_sets_traces(const std::vector<JointSetSpec>& sets, const MeshSpec& shape) {
  const double min_length = 0.5 * shape.element_size;
  std::vector<std::vector<Segment>> out;
  for (const JointSetSpec& set : sets) out.push_back(joint_set_traces(set, shape, min_length));
  snap_trace_ends(out, 2 * min_length, min_length);
  return out;
}

}  // namespace blastsim::fdem
