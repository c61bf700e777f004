//! \file test_coupling_kernels.cpp
//! \brief The coupling kernels (immersed_boundary_kernels.hpp, crack_coupling_kernels.hpp) called directly on a
//! few cells of host arrays: the gas moved between cells that change state, and the work a crack's gas does on
//! its walls.
#include "blastsim/ibm/crack_coupling_kernels.hpp"
#include "blastsim/ibm/immersed_boundary_kernels.hpp"
#include "catch.hpp"

#include <array>
#include <cmath>
#include <cstdio>
#include <vector>

using namespace blastsim;

namespace {
//! A small grid's cell arrays on the host (the gas state, masks, the cell update, the ledger), one gas.
struct Patch {
  static constexpr int n = 5;
  PaddedShape shape{n + 1, n + 1, 2};
  std::vector<double> rho, e, u, v, zero;
  std::vector<std::uint8_t> old_active, new_active, changed, prescribed;
  std::vector<cip::CellContent> next, taken;
  std::vector<int> claim;
  std::vector<ibm::TransitionLedger> ledger;
  Patch()
      : rho(shape.size(), 0.0), e(shape.size(), 0.0), u(shape.size(), 0.0), v(shape.size(), 0.0), zero(shape.size(), 0.0),
        old_active(shape.size(), 1), new_active(shape.size(), 1), changed(shape.size(), 0), prescribed(shape.size(), 0),
        next(shape.size(), cip::CellContent{0, 0, 0, 0}), taken(shape.size(), cip::CellContent{0, 0, 0, 0}),
        claim(shape.size(), ibm::kNoClaim), ledger(n * n, ibm::TransitionLedger{0, 0, 0, 0, 0, 0}) {
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) rho[shape.offset(i, j)] = 1.0 + 0.1 * i + 0.01 * j, e[shape.offset(i, j)] = 2e5 + 1e3 * j;
  }
  template <class T>
  Field2D<T> view(std::vector<T>& a) { return {a.data(), shape}; }
  cip::CipFieldView unknown(std::vector<double>& f) { return {view(f), view(zero), view(zero)}; }
  cip::GasCells cells() { return {{unknown(rho), unknown(e), unknown(u), unknown(v)}, cip::MaterialView{}, false}; }
  //! The transition (what every cell holds after the move), then its application to the state.
  void run(double area, double rho_ambient, double e_ambient) {
    const ibm::CellUpdate<Access::read_write> update{view(new_active), view(changed), view(next)};
    const ibm::TransitionKernel k{view(old_active), update, cells(), {ledger.data()}, {view(claim), view(taken)},
                                  n, n, area, rho_ambient, e_ambient, false};
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) k(i, j);
    const ibm::ApplyTransitionKernel apply{update, view(zero), view(zero), view(old_active), cells()};
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) apply(i, j);
  }
  //! Mass and internal energy per unit depth of the cells active in `mask`.
  std::array<double, 2> totals(const std::vector<std::uint8_t>& mask, double area) const {
    std::array<double, 2> t{0, 0};
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        if (mask[shape.offset(i, j)]) t[0] += rho[shape.offset(i, j)] * area, t[1] += rho[shape.offset(i, j)] * e[shape.offset(i, j)] * area;
    return t;
  }
  double at(const std::vector<double>& a, int i, int j) const { return a[shape.offset(i, j)]; }
};
}  // namespace

TEST_CASE("Coupling kernels: a covered cell hands its gas to its neighbours, mass and energy kept exactly",
          "[ibm][kernels][transitions]") {
  // Gas at rest (no face kinetic energy): the covered cell's mass and internal energy go in equal shares to
  // its four edge neighbours that stay active, so the totals over the active cells do not change.
  Patch p;
  const double area = 1e-4;
  p.new_active[p.shape.offset(2, 2)] = 0;
  const std::array<double, 2> before = p.totals(p.old_active, area);
  const double given = p.at(p.rho, 2, 2), left = p.at(p.rho, 1, 2), above = p.at(p.rho, 2, 3), far = p.at(p.rho, 0, 0);
  p.run(area, 1.2, 2.09e5);
  const std::array<double, 2> after = p.totals(p.new_active, area);
  CHECK_THAT(after[0], Catch::Matchers::WithinRel(before[0], 1e-14));
  CHECK_THAT(after[1], Catch::Matchers::WithinRel(before[1], 1e-14));
  // Each of the four neighbours got a quarter of the covered cell's mass.
  CHECK_THAT(p.at(p.rho, 1, 2), Catch::Matchers::WithinRel(left + 0.25 * given, 1e-14));
  CHECK_THAT(p.at(p.rho, 2, 3), Catch::Matchers::WithinRel(above + 0.25 * given, 1e-14));
  CHECK(p.at(p.rho, 0, 0) == far);  // far cells untouched
  // The covered cell holds the ambient state and the new mask is installed; the ledger counts one covered
  // cell and creates nothing.
  CHECK(p.at(p.rho, 2, 2) == 1.2);
  CHECK(p.old_active[p.shape.offset(2, 2)] == 0);
  double covered = 0, mass_created = 0;
  for (const ibm::TransitionLedger& l : p.ledger) covered += l.covered, mass_created += l.mass_created;
  CHECK(covered == 1.0);
  CHECK(mass_created == 0.0);
}

TEST_CASE("Coupling kernels: a covered cell with nowhere to go gives its gas to the segment that claims it, else it "
          "is lost and booked", "[ibm][kernels][transitions]") {
  // A 3 x 3 block covered at once: its centre (2, 2) has no stable cell in its block. Unclaimed, its gas is lost,
  // booked as negative created mass and as lost mass; claimed (CellClaims::claim, a crack segment's gap), its gas
  // (mass, internal energy: gas at rest has no kinetic energy on its faces) goes to `taken` whole, nothing is
  // lost, and the active cells' gas plus what was taken equals the gas before, exactly as the ring's cells hand
  // theirs to their stable neighbours.
  const double area = 1e-4;
  for (const bool claimed : {false, true}) {
    Patch p;
    for (int j = 1; j <= 3; ++j)
      for (int i = 1; i <= 3; ++i) p.new_active[p.shape.offset(i, j)] = 0;
    if (claimed) p.claim[p.shape.offset(2, 2)] = 7;
    const std::array<double, 2> before = p.totals(p.old_active, area);
    const double rho = p.at(p.rho, 2, 2), rho_e = rho * p.at(p.e, 2, 2);
    p.run(area, 1.2, 2.09e5);
    const std::array<double, 2> after = p.totals(p.new_active, area);
    const ibm::TransitionLedger& l = p.ledger[2 * Patch::n + 2];
    const cip::CellContent t = p.taken[p.shape.offset(2, 2)];
    std::printf("transition, centre of a covered 3 x 3 block %s: taken %.6e kg/m, lost %.6e kg/m (its gas %.6e kg/m); "
                "active gas + taken + lost - before: %.1e kg/m, %.1e J/m\n",
                claimed ? "claimed" : "unclaimed", t.mass * area, l.mass_lost, rho * area,
                after[0] + t.mass * area + l.mass_lost - before[0], after[1] + t.energy * area + l.energy_lost - before[1]);
    CHECK_THAT(after[0] + t.mass * area + l.mass_lost, Catch::Matchers::WithinRel(before[0], 1e-14));
    CHECK_THAT(after[1] + t.energy * area + l.energy_lost, Catch::Matchers::WithinRel(before[1], 1e-14));
    if (claimed) {
      CHECK(t.mass == rho);
      CHECK(t.energy == rho_e);
      CHECK(l.mass_lost == 0.0);
      CHECK(l.mass_created == 0.0);
    } else {
      CHECK(t.mass == 0.0);
      CHECK_THAT(l.mass_lost, Catch::Matchers::WithinRel(rho * area, 1e-15));
      CHECK_THAT(l.energy_lost, Catch::Matchers::WithinRel(rho_e * area, 1e-15));
      CHECK(l.mass_created == -l.mass_lost);
    }
  }
}

TEST_CASE("Coupling kernels: an uncovered cell starts from the ambient state and the ledger counts it",
          "[ibm][kernels][transitions]") {
  Patch p;
  const double area = 1e-4, rho_amb = 1.2, e_amb = 2.09e5;
  p.old_active[p.shape.offset(3, 1)] = 0;
  const double neighbour = p.at(p.rho, 2, 1);
  p.run(area, rho_amb, e_amb);
  CHECK(p.at(p.rho, 3, 1) == rho_amb);
  CHECK(p.at(p.e, 3, 1) == e_amb);
  const ibm::TransitionLedger& l = p.ledger[1 * Patch::n + 3];
  CHECK(l.uncovered == 1.0);
  CHECK_THAT(l.mass_created, Catch::Matchers::WithinRel(rho_amb * area, 1e-15));
  CHECK_THAT(l.energy_created, Catch::Matchers::WithinRel(rho_amb * e_amb * area, 1e-15));
  // Its neighbours keep their gas: the gas flows in through the solver, not by the transition.
  CHECK(p.at(p.rho, 2, 1) == neighbour);
}

TEST_CASE("Coupling kernels: a crack's gas does p dV on its walls, and never more than keeps it positive",
          "[ibm][kernels][crack]") {
  // An ideal gas (gamma 1.4) at rest in a segment: 1e-3 kg/m at 2e5 J/kg in V0 = 1e-5 m2/m, so U = 200 J/m and
  // p = 0.4 rho e = 8e6 Pa. The gas pays the work its loads did on the rock (the cushion's ledger). Where that
  // would take more than half of U (faces that flew apart to 10 times the volume: p dV = 7.2e2 J/m), it pays the
  // isentropic expansion's work U (1 - (V0 / V1)^(gamma - 1)), exact for an ideal gas, with U (V0 / V1)^0.4 > 0
  // left. Compression is not limited.
  const ibm::ChannelConserved c{1e-3, 0.0, 200.0, 0.0, 0.0};
  const double V0 = 1e-5, p = 0.4 * (1e-3 / V0) * 2e5;
  CHECK(ibm::expansion_work(c, p * 0.01 * V0, p, V0, 1.01 * V0) == p * 0.01 * V0);
  CHECK(ibm::expansion_work(c, -p * 0.5 * V0, p, V0, 0.5 * V0) == -p * 0.5 * V0);
  const double W = ibm::expansion_work(c, p * 9 * V0, p, V0, 10 * V0);
  std::printf("crack expansion: p dV %.4e J/m, work taken %.6e J/m (isentropic %.6e J/m), internal energy left %.4e J/m\n",
              p * 9 * V0, W, 200.0 * (1 - std::pow(0.1, 0.4)), 200.0 - W);
  CHECK_THAT(W, Catch::Matchers::WithinRel(200.0 * (1 - std::pow(0.1, 0.4)), 1e-12));
  CHECK(200.0 - W > 0.0);
  // Moving gas: only its internal energy E - q^2 / 2m counts.
  const ibm::ChannelConserved moving{1e-3, 1e-3 * 300.0, 200.0 + 0.5 * 1e-3 * 300.0 * 300.0, 0.0, 0.0};
  CHECK_THAT(ibm::expansion_work(moving, p * 9 * V0, p, V0, 10 * V0), Catch::Matchers::WithinRel(W, 1e-12));
  // The faces' mean pressure over an isentropic volume change: the integral of p0 (V0 / V)^gamma over [V0, V1]
  // divided by V1 - V0, here by the midpoint rule on 100,000 intervals.
  for (const double r : {0.25, 0.5, 0.9, 1.1, 2.0, 10.0}) {
    const int n = 100000;
    double integral = 0;
    for (int k = 0; k < n; ++k) integral += p * std::pow(1.0 / (1.0 + (r - 1.0) * (k + 0.5) / n), 1.4) / n;
    const double mean = ibm::isentropic_mean_pressure(p, 200.0, V0, r * V0);
    std::printf("crack load: volume ratio %.2f, mean isentropic pressure %.6e Pa (quadrature %.6e Pa, p0 %.1e Pa)\n", r,
                mean, integral, p);
    CHECK_THAT(mean, Catch::Matchers::WithinRel(integral, 1e-8));
  }
  CHECK(ibm::isentropic_mean_pressure(p, 200.0, V0, V0) == p);
}

TEST_CASE("Coupling kernels: a crack's opening is the faces' normal opening while they face each other, and at "
          "least their distance once they turned away",
          "[ibm][kernels][crack]") {
  // Face A along x from a0 = (0, 0) to a1 = (L, 0); the gap on its right (y < 0). Face B runs back from b0 (facing
  // a1) to b1 (facing a0). References from the geometry: parallel faces o apart (open or pressed, slid along
  // each other or not): o; a hinge (touching at a1 = b0, B turned by theta): the mean of the ends' openings,
  // L sin(theta) / 2; faces slid past each other's ends by g: the distance of their nearest ends sqrt(g^2 + o^2).
  using fdem::Vec2;
  const double L = 0.024;
  auto opening = [&](Vec2 b0, Vec2 b1) {
    return ibm::faces_opening({0, 0}, {L, 0}, b0, b1, L, std::hypot(b1.x - b0.x, b1.y - b0.y));
  };
  for (const double o : {1e-4, 2e-6, -5e-6}) {
    for (const double slip : {0.0, 0.3 * L}) {
      const double w = opening({L + slip, -o}, {slip, -o});
      std::printf("crack opening: parallel faces %.1e m apart, slid %.1e m: %.6e m\n", o, slip, w);
      CHECK_THAT(w, Catch::Matchers::WithinRel(o, 1e-9));
    }
  }
  for (const double theta : {0.01, 0.1, 0.5}) {
    const double w = opening({L, 0}, {L - L * std::cos(theta), -L * std::sin(theta)});
    CHECK_THAT(w, Catch::Matchers::WithinRel(0.5 * L * std::sin(theta), 1e-9));
  }
  for (const double g : {1e-3, 1e-2}) {
    const double o = 2e-4, w = opening({2 * L + g, -o}, {L + g, -o});
    std::printf("crack opening: faces slid past each other by %.1e m, %.1e m apart: %.6e m (nearest ends %.6e m)\n",
                g, o, w, std::hypot(g, o));
    CHECK_THAT(w, Catch::Matchers::WithinRel(std::hypot(g, o), 1e-9));
  }
  // Faces of fragments thrown off (positions from runs of the single-hole example at 350^2 cells), against the
  // faces' smallest distance found by sampling face B at 100,001 points (to better than 1e-6 of it): one pair
  // turned away, whose quadrilateral folds into a bow tie that encloses almost no area, and two that passed
  // each other, whose quadrilaterals turn inside out (areas over length -44 and -66 mm). Each opening is the
  // faces' distance.
  struct Faces {
    Vec2 a0, a1, b0, b1;
  };
  for (const Faces& q : {Faces{{0.026287, -0.065995}, {0.007808, -0.052402}, {-0.003354, 0.035730}, {-0.011632, 0.014349}},
                         Faces{{0.021150, 0.051158}, {0.018596, 0.028079}, {0.015771, -0.059455}, {0.032129, -0.075924}},
                         Faces{{-0.036811, 0.030216}, {-0.042685, 0.000508}, {0.055268, -0.058718}, {0.037821, -0.034071}}}) {
    const double la = std::hypot(q.a1.x - q.a0.x, q.a1.y - q.a0.y), lb = std::hypot(q.b1.x - q.b0.x, q.b1.y - q.b0.y);
    double nearest = 1e30;
    for (int k = 0; k <= 100000; ++k) {
      const double t = k / 100000.0;
      const double px = q.b0.x + t * (q.b1.x - q.b0.x), py = q.b0.y + t * (q.b1.y - q.b0.y);
      nearest = std::fmin(nearest, std::sqrt(ibm::segment_distance2(q.a0, q.a1, px, py)));
    }
    const double twice = (q.a0.x * q.a1.y - q.a1.x * q.a0.y) + (q.a1.x * q.b0.y - q.b0.x * q.a1.y) +
                         (q.b0.x * q.b1.y - q.b1.x * q.b0.y) + (q.b1.x * q.a0.y - q.a0.x * q.b1.y);
    const double w = ibm::faces_opening(q.a0, q.a1, q.b0, q.b1, la, lb);
    std::printf("crack opening: faces turned away: %.6e m (area over length alone %.3e m; nearest points %.6e m)\n", w,
                -twice / (la + lb), nearest);
    CHECK_THAT(w, Catch::Matchers::WithinRel(nearest, 1e-6));
  }
  // Continuity: B turned about its midpoint through a half turn in 2,000 steps, 1 mm off A (through the bow tie
  // and the inside-out quadrilateral), then carried across A to 5 mm behind it in 2,000 steps: the opening moves
  // by at most 11 times the largest move of a node between samples (the fold's blend, of slope 5 at most,
  // enters twice, the faces' distance once; a jump would read in the thousands).
  double last = 0, jump = 0;
  for (int k = 0; k <= 2000; ++k) {
    const double phi = M_PI * k / 2000.0, cx = 0.5 * L, cy = -1e-3, h = 0.5 * L;
    const Vec2 q0{cx + h * std::cos(phi), cy + h * std::sin(phi)}, q1{cx - h * std::cos(phi), cy - h * std::sin(phi)};
    const double now = opening(q0, q1);
    if (k > 0) jump = std::fmax(jump, std::fabs(now - last) / (h * M_PI / 2000.0));
    last = now;
  }
  double across = 0;
  for (int k = 0; k <= 2000; ++k) {
    const double y = -1e-3 + 6e-3 * k / 2000.0;
    const double now = opening({L, y}, {0, y});
    across = std::fmax(across, std::fabs(now - last) / (6e-3 / 2000.0));
    last = now;
  }
  std::printf("crack opening: face turned through a half turn, then carried across: largest change %.3f and %.3f times "
              "the nodes' move\n", jump, across);
  CHECK(jump <= 11.0);
  CHECK(across <= 11.0);
}
