//! \file test_contact.cpp
//! \brief Munjiza's distributed-potential contact of one pair against closed-form loads, with and without the
//! offset of pairs that meet at a mesh vertex (docs/fdem-solver.md, "Which pairs touch").
#include "blastsim/fdem/rock_step_kernels.hpp"
#include "catch.hpp"

#include <cmath>
#include <cstdio>

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
