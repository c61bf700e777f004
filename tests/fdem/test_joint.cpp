//! \file test_joint.cpp
//! \brief The cohesive joint law: softening curve, energy dissipated per unit area = G_I / G_II, Mohr-Coulomb
//! shear strength, irreversible damage (the constitutive part of docs/validation.md F3).
#include "blastsim/fdem/joint_kernels.hpp"
#include "blastsim/fdem/material.hpp"
#include "blastsim/fdem/rock_step_kernels.hpp"
#include "catch.hpp"

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

using namespace blastsim::fdem;

namespace {

//! A joint point of the paper's rock on an edge h = 9.5 mm with penalty p = 10 E.
JointStrength paper_joint() {
  const RockMaterial rock = RockMaterial::paper_table2();
  const double h = 9.5e-3, p = 10 * rock.youngs_modulus;
  const double op = 2 * h * rock.tensile_strength / p, sp = h * rock.cohesion / p;
  return {rock.tensile_strength,
          rock.cohesion,
          std::tan(rock.friction_angle),
          op,
          sp,
          softening_length(rock.fracture_energy_mode1, rock.tensile_strength, 2.0 / 3 * rock.tensile_strength * op),
          softening_length(rock.fracture_energy_mode2, rock.cohesion, 0.5 * rock.cohesion * sp)};
}

//! Work per unit area [J/m2] done on a point along straight segments through `path` (opening, slip) [m], n
//! trapezoid steps each; `h` carries the history in and out.
double path_work(const JointStrength& j, const std::vector<std::pair<double, double>>& path, JointHistory& h,
                 int n = 20000) {
  double w = 0;
  JointTraction prev = joint_traction(path[0].first, path[0].second, j, h);
  h = prev.history();
  for (size_t leg = 1; leg < path.size(); ++leg) {
    const auto [o0, s0] = path[leg - 1];
    const auto [o1, s1] = path[leg];
    for (int k = 1; k <= n; ++k) {
      const double t = static_cast<double>(k) / n;
      const JointTraction cur = joint_traction(o0 + t * (o1 - o0), s0 + t * (s1 - s0), j, h);
      h = cur.history();
      w += 0.5 * (prev.normal + cur.normal) * (o1 - o0) / n + 0.5 * (prev.shear + cur.shear) * (s1 - s0) / n;
      prev = cur;
    }
  }
  return w;
}

//! Work per unit area [J/m2] along the straight path from (o0, s0) to (o1, s1), from rest, on n steps.
double work(const JointStrength& j, double o0, double o1, double s0, double s1, int n = 200000) {
  JointHistory h;
  return path_work(j, {{o0, s0}, {o1, s1}}, h, n);
}

}  // namespace

TEST_CASE("Munjiza's softening curve: end values and its integral", "[fdem][joint]") {
  CHECK_THAT(softening_curve(0.0), WithinAbs(1.0, 1e-14));
  CHECK(softening_curve(1.0) == 0.0);
  for (double D = 0.0; D < 1.0; D += 0.05) CHECK(softening_curve(D + 0.05) <= softening_curve(D));  // monotone
  CHECK_THAT(softening_curve_integral(), WithinAbs(0.386, 0.001));  // docs/fdem-solver.md, "Cohesive joint"
  // The Y codes' softening length 3 G / f dissipates 3 x 0.386 = 1.16 G (the 16 % trap).
  std::printf("softening curve integral %.6f; 3 G / f would dissipate %.3f G\n", softening_curve_integral(),
              3 * softening_curve_integral());
}

TEST_CASE("Pure mode I and mode II: dissipated energy per unit area equals G_I and G_II", "[fdem][joint][F3]") {
  const RockMaterial rock = RockMaterial::paper_table2();
  const JointStrength j = paper_joint();
  // Mode I: open from rest to full separation. Once broken the joint holds nothing, so all the work done on
  // it, pre-peak part included, has been dissipated.
  const double g1 = work(j, 0, j.peak_opening + j.opening_softening, 0, 0);
  // Mode II at zero normal stress: slide from rest to failure.
  const double g2 = work(j, 0, 0, 0, j.peak_slip + j.slip_softening);
  std::printf("F3 (law): mode I %.3f J/m2 (G_I %.1f), mode II %.3f J/m2 (G_II %.1f)\n", g1,
              rock.fracture_energy_mode1, g2, rock.fracture_energy_mode2);
  CHECK_THAT(g1, WithinRel(rock.fracture_energy_mode1, 0.001));
  CHECK_THAT(g2, WithinRel(rock.fracture_energy_mode2, 0.001));
  // Fully broken at the end of each path.
  CHECK(joint_traction(j.peak_opening + j.opening_softening, 0, j, JointHistory{}).damage == 1.0);
  CHECK(joint_traction(j.peak_opening + j.opening_softening, 0, j, JointHistory{}).normal == 0.0);
}

TEST_CASE("Peak tractions: tensile strength, Mohr-Coulomb shear strength, compression penalty", "[fdem][joint]") {
  const JointStrength j = paper_joint();
  CHECK_THAT(joint_traction(j.peak_opening, 0, j, JointHistory{}).normal, WithinRel(j.tensile_strength, 1e-14));
  CHECK_THAT(joint_traction(0, j.peak_slip, j, JointHistory{}).shear, WithinRel(j.cohesion, 1e-14));
  CHECK_THAT(joint_traction(0, -j.peak_slip, j, JointHistory{}).shear, WithinRel(-j.cohesion, 1e-14));
  // Closed by o = -o_p: sigma = -2 f_t; the shear strength rises to c + 2 f_t tan(phi) (Mohr-Coulomb).
  const double o = -j.peak_opening, sigma = -2 * j.tensile_strength, fs = j.cohesion - sigma * j.tan_friction;
  CHECK_THAT(joint_traction(o, 0, j, JointHistory{}).normal, WithinRel(sigma, 1e-14));
  // The elastic shear branch (stiffness c / s_p) meets the cap f_s at s_p f_s / c; beyond it the slip is plastic.
  const double sp = j.peak_slip * fs / j.cohesion;
  CHECK_THAT(joint_traction(o, sp, j, JointHistory{}).shear, WithinRel(fs, 1e-14));
  CHECK(joint_traction(o, sp, j, JointHistory{}).damage <= 1e-12);
  CHECK(joint_traction(o, 0.999 * sp, j, JointHistory{}).damage == 0.0);
  CHECK_THAT(joint_traction(o, 0.999 * sp, j, JointHistory{}).shear, WithinRel(0.999 * fs, 1e-14));
}

TEST_CASE("Damage never heals", "[fdem][joint]") {
  const JointStrength j = paper_joint();
  const JointTraction half = joint_traction(j.peak_opening + 0.5 * j.opening_softening, 0, j, JointHistory{});
  CHECK_THAT(half.damage, WithinAbs(0.5, 1e-12));
  // Back to half the peak opening: the damage stays and the traction is the reduced one.
  const JointTraction back = joint_traction(0.5 * j.peak_opening, 0, j, half.history());
  CHECK(back.damage == half.damage);
  CHECK_THAT(back.normal, WithinRel(softening_curve(0.5) * 0.75 * j.tensile_strength, 1e-12));
}

namespace {

//! Elastic energy per unit area [J/m2] a point holds, from the law's formulas (docs/fdem-solver.md, "Cohesive
//! joint"): the normal potential (f_t o^2 / o_p in compression; z f_t o_p (r^2 - r^3/3) before the peak in
//! tension, r = o / o_p, and z f_t o_p (r - 1/3) past it), plus (1/2) z k (s - s_pl)^2, k = c / s_p.
double stored(const JointStrength& j, double o, double s, const JointHistory& h) {
  const double z = softening_curve(h.damage), r = o / j.peak_opening, k = j.cohesion / j.peak_slip;
  const double normal = o < 0 ? j.tensile_strength * o * o / j.peak_opening
                              : z * j.tensile_strength * j.peak_opening * (r < 1 ? r * r - r * r * r / 3 : r - 1.0 / 3);
  return normal + 0.5 * z * k * (s - h.plastic_slip) * (s - h.plastic_slip);
}

}  // namespace

TEST_CASE("F11 Shear slip is plastic: elastic under the Coulomb cap, no energy from any cycle",
          "[fdem][joint][F11]") {
  const JointStrength j = paper_joint();
  const double k = j.cohesion / j.peak_slip;  // the elastic shear stiffness [Pa/m] (p / h)
  // 1. A slide from rest under a fixed compression: tau = k s up to the cap f_s = c - sigma tan(phi), then
  // z(D) f_s with D = (s - f_s / k) / s_t, the same in one evaluation as in many (the return is exact).
  const double o = -0.8 * j.peak_opening, sigma = 2 * o * j.tensile_strength / j.peak_opening;
  const double fs = j.cohesion - sigma * j.tan_friction, yield = fs / k;
  double worst = 0;
  JointHistory h;
  for (int step = 1; step <= 400; ++step) {
    const double s = step * 2.5e-3 * (yield + 1.2 * j.slip_softening);
    const double D = std::min(1.0, std::max(0.0, (s - yield) / j.slip_softening));
    const double expected = s < yield ? k * s : softening_curve(D) * fs;
    const JointTraction many = joint_traction(o, s, j, h), one = joint_traction(o, s, j, JointHistory{});
    h = many.history();
    worst = std::max({worst, std::fabs(many.shear - expected), std::fabs(one.shear - expected)});
    CHECK_THAT(many.damage, WithinAbs(D, 1e-12));
  }
  std::printf("F11 slide under %.2f MPa: largest |tau - (k s, then z f_s)| %.3e Pa (f_s %.4g MPa)\n", sigma / 1e6,
              worst, fs / 1e6);
  CHECK(worst <= 1e-8 * fs);
  // 2. Past the cap, unloading is elastic at k from the plastic slip s - c / k.
  const JointTraction up = joint_traction(0, 1.02 * j.peak_slip, j, JointHistory{});
  const double D = 0.02 * j.peak_slip / j.slip_softening;
  CHECK_THAT(up.plastic_slip, WithinRel(0.02 * j.peak_slip, 1e-12));
  CHECK_THAT(up.damage, WithinRel(D, 1e-12));
  CHECK_THAT(up.shear, WithinRel(softening_curve(D) * j.cohesion, 1e-12));
  const JointTraction back = joint_traction(0, 0.5 * j.peak_slip, j, up.history());
  CHECK_THAT(back.shear, WithinRel(softening_curve(D) * k * (0.5 - 0.02) * j.peak_slip, 1e-12));
  CHECK(back.plastic_slip == up.plastic_slip);
  // 3. Under the cap the joint is elastic whatever the compression does: slip back and forth to 0.9 s_p while the
  // compression comes and goes (0 to 30 MPa) gives back all the work, to the trapezoid rule's error.
  {
    const double oc = -30e6 * j.peak_opening / (2 * j.tensile_strength);
    std::vector<std::pair<double, double>> path{{0, 0}};
    for (int cycle = 0; cycle < 5; ++cycle)
      for (const auto& corner : {std::pair{0.0, 0.9}, std::pair{1.0, 0.9}, std::pair{1.0, -0.9}, std::pair{0.0, -0.9}})
        path.push_back({corner.first * oc, corner.second * j.peak_slip});
    path.push_back({0, 0});
    JointHistory he;
    const double w = path_work(j, path, he);
    std::printf("F11 elastic cycles under changing compression: work %.3e J/m2, plastic slip %.3e m\n", w, he.slip_path);
    CHECK(he.slip_path == 0.0);
    CHECK(std::fabs(w) <= 1e-9 * j.cohesion * j.peak_slip);
  }
  // 4. The cycle that returned 0.85 and 1.71 J/m2 with the earlier nonlinear-elastic shear (docs/fdem-solver.md):
  // from rest, slip to the cap, 1.5 times the yield slip, compress by 10 or 30 MPa, slip back to 0, release, and the
  // reverse. The work done must be at least the elastic energy held at the end: the rest is dissipated.
  for (const double compression : {10e6, 30e6}) {
    const double oc = -compression * j.peak_opening / (2 * j.tensile_strength);
    for (const bool reverse : {false, true}) {
      std::vector<std::pair<double, double>> path{{0, 0}, {0, 1.5 * j.peak_slip}, {oc, 1.5 * j.peak_slip}, {oc, 0}, {0, 0}};
      if (reverse) std::reverse(path.begin(), path.end());
      JointHistory hc;
      const double w = path_work(j, path, hc);
      const double left = stored(j, 0, 0, hc);
      std::printf("F11 cycle, %g MPa, %s: work %.4f J/m2, stored at the end %.4f J/m2, dissipated %.4f J/m2\n",
                  compression / 1e6, reverse ? "reversed" : "forward", w, left, w - left);
      CHECK(w - left > 0);
    }
  }
  // 5. Random paths of opening and slip through softening and breaking: on every leg the work done is at least the
  // change of the stored energy (dissipation >= 0), to the trapezoid rule's error (1e-6 of the leg's work).
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> uo(-2.0, 1.2), us(-3.0, 3.0);
  double least = 1e300;
  for (int trial = 0; trial < 20; ++trial) {
    std::vector<std::pair<double, double>> path{{0, 0}};
    for (int leg = 0; leg < 8; ++leg) path.push_back({uo(rng) * j.peak_opening, us(rng) * j.peak_slip});
    JointHistory hr, before;
    for (size_t leg = 1; leg < path.size(); ++leg) {
      const double e0 = stored(j, path[leg - 1].first, path[leg - 1].second, before);
      const double w = path_work(j, {path[leg - 1], path[leg]}, hr, 4000);
      const double e1 = stored(j, path[leg].first, path[leg].second, hr);
      least = std::min(least, w - (e1 - e0));
      CHECK(w - (e1 - e0) >= -1e-6 * std::fabs(w) - 1e-12);
      before = hr;
    }
  }
  std::printf("F11 random paths: least dissipation of a leg %.3e J/m2\n", least);
}

TEST_CASE("The joint's two passes: a turned joint's opening, slip and tangent, then the joint law on them",
          "[fdem][joint]") {
  // Face A runs from (0, 0) to (L, 0); face B lies opened by delta along the outward normal of A, n = (0, -1),
  // and slid by sigma along t = (1, 0): b1 = (sigma, -delta) opposite a0, b0 = (L + sigma, -delta) opposite a1.
  // The pair is turned by theta and moved by c. Exact: at all three points the opening is delta and the slip
  // sigma (plus a preload where one is given), the tangent (cos theta, sin theta). Tolerance 1e-13 m: positions of
  // about 1 m carry rounding of a few 1e-16 m. JointForceKernel must then give each point the tractions of
  // joint_traction() at those values (the same bits), and face A the force sum_q w_q (sigma_q n + tau_q t) with
  // weights L0/6, 4 L0/6, L0/6, face B its opposite.
  const JointStrength strength = paper_joint();
  const double L = 0.03, delta = 0.6 * strength.peak_opening, sigma = -0.4 * strength.peak_slip;
  const double cx = 1.3, cy = -0.4;
  const JointNodes nodes{0, 1, 2, 3};  // a0 a1 b0 b1
  const double length = L;
  for (const double theta : {0.0, 0.7, 2.4, -1.9}) {
    for (const JointPreload pre : {JointPreload{0.0, 0.0}, JointPreload{0.2 * strength.peak_opening, 0.1 * strength.peak_slip}}) {
      const double ct = std::cos(theta), st = std::sin(theta);
      auto place = [&](double x, double y) { return Vec2{cx + ct * x - st * y, cy + st * x + ct * y}; };
      const Vec2 p[4] = {place(0, 0), place(L, 0), place(L + sigma, -delta), place(sigma, -delta)};  // a0 a1 b0 b1
      std::vector<double> x(4), y(4), vx(4, 0.0), vy(4, 0.0);
      for (int k = 0; k < 4; ++k) x[k] = p[k].x, y[k] = p[k].y;
      JointPointDamage damage{{0, 0, 0}};
      JointPointPlastic plastic{{0, 0, 0}, {0, 0, 0}};
      JointPointValues separation{{-1, -1, -1}, {-1, -1, -1}}, traction{{0, 0, 0}, {0, 0, 0}};
      std::uint8_t broken = 0;
      Vec2 tangent{0, 0};
      const NodeMotion<blastsim::Access::read> motion{x.data(), y.data(), vx.data(), vy.data()};
      const JointParams params{&nodes, &strength, &length, &pre};
      const JointState<blastsim::Access::read_write> state{&damage, &plastic, &separation, &traction, &broken};
      JointGeometryKernel{motion, params, state, JointWork<blastsim::Access::read_write>{&tangent}}(0);
      CHECK(std::fabs(tangent.x - ct) <= 1e-12);
      CHECK(std::fabs(tangent.y - st) <= 1e-12);
      for (int q = 0; q < kJointPoints; ++q) {
        CHECK(std::fabs(separation.normal[q] - (delta + pre.opening)) <= 1e-13);
        CHECK(std::fabs(separation.shear[q] - (sigma + pre.slip)) <= 1e-13);
      }
      std::vector<SlotForce> slot(4, SlotForce{{9, 9}, {9, 9}});
      std::vector<std::uint8_t> exposed(4, 0);
      const EdgeState<blastsim::Access::read_write> edges{slot.data(), exposed.data()};
      JointForceKernel{params, state, edges, JointWork<blastsim::Access::read>{&tangent}}(0);
      const Vec2 n{tangent.y, -tangent.x};
      const double w[kJointPoints] = {length / 6.0, 4.0 * length / 6.0, length / 6.0};
      Vec2 total{0, 0};
      for (int q = 0; q < kJointPoints; ++q) {
        const JointTraction tr = joint_traction(separation.normal[q], separation.shear[q], strength, JointHistory{});
        CHECK(traction.normal[q] == tr.normal);
        CHECK(traction.shear[q] == tr.shear);
        CHECK(damage.point[q] == tr.damage);
        total = {total.x + w[q] * (tr.normal * n.x + tr.shear * tangent.x), total.y + w[q] * (tr.normal * n.y + tr.shear * tangent.y)};
      }
      const double scale = strength.tensile_strength * L;
      const SlotForce fa = slot[0], fb = slot[2];
      CHECK(std::fabs(fa.first.x + fa.second.x - total.x) <= 1e-12 * scale);
      CHECK(std::fabs(fa.first.y + fa.second.y - total.y) <= 1e-12 * scale);
      CHECK((fb.first.x == -fa.second.x && fb.first.y == -fa.second.y));
      CHECK((fb.second.x == -fa.first.x && fb.second.y == -fa.first.y));
      CHECK(broken == 0);
    }
  }
  // A broken joint is left alone by the geometry pass: its last opening and slip stay.
  const JointPreload none{0.0, 0.0};
  std::vector<double> x{0, L, L, 0}, y{0, 0, -1e-3, -1e-3}, v(4, 0.0);
  JointPointDamage damage{{1, 1, 1}};
  JointPointPlastic plastic{{0, 0, 0}, {0, 0, 0}};
  JointPointValues separation{{7e-6, 7e-6, 7e-6}, {1e-6, 1e-6, 1e-6}}, traction{{0, 0, 0}, {0, 0, 0}};
  std::uint8_t broken = 1;
  Vec2 tangent{0.25, 0.5};
  JointGeometryKernel{NodeMotion<blastsim::Access::read>{x.data(), y.data(), v.data(), v.data()},
                      JointParams{&nodes, &strength, &length, &none},
                      JointState<blastsim::Access::read_write>{&damage, &plastic, &separation, &traction, &broken},
                      &tangent}(0);
  CHECK(separation.normal[1] == 7e-6);
  CHECK(separation.shear[2] == 1e-6);
  CHECK((tangent.x == 0.25 && tangent.y == 0.5));
}
