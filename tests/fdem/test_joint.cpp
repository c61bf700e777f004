//! \file test_joint.cpp
//! \brief The cohesive joint law: softening curve, energy dissipated per unit area = G_I / G_II, Mohr-Coulomb
//! shear strength, irreversible damage (the constitutive part of docs/validation.md F3).
#include "blastsim/fdem/joint_kernels.hpp"
#include "blastsim/fdem/material.hpp"
#include "catch.hpp"

#include <cmath>

using namespace blastsim::fdem;

namespace {

//! A joint point of the paper's rock on an edge h = 9.5 mm with penalty p = 10 E.
JointStrength paper_joint() {
  const RockMaterial rock = RockMaterial::paper_table2();
  const double h = 9.5e-3, p = 10 * rock.youngs_modulus;
  return {rock.tensile_strength,
          rock.cohesion,
          std::tan(rock.friction_angle),
          2 * h * rock.tensile_strength / p,
          2 * h * rock.cohesion / p,
          softening_length(rock.fracture_energy_mode1, rock.tensile_strength, 2 * h * rock.tensile_strength / p),
          softening_length(rock.fracture_energy_mode2, rock.cohesion, 2 * h * rock.cohesion / p)};
}

//! Work per unit area [J/m2] of the traction along a monotone path from (o0, s0) to (o1, s1), by the
//! trapezoid rule on n steps, carrying the damage along.
double work(const JointStrength& j, double o0, double o1, double s0, double s1, int n = 200000) {
  double w = 0, D = 0;
  JointTraction prev = joint_traction(o0, s0, j, D);
  for (int k = 1; k <= n; ++k) {
    const double t = static_cast<double>(k) / n;
    const JointTraction cur = joint_traction(o0 + t * (o1 - o0), s0 + t * (s1 - s0), j, D);
    D = cur.damage;
    w += 0.5 * (prev.normal + cur.normal) * (o1 - o0) / n + 0.5 * (prev.shear + cur.shear) * (s1 - s0) / n;
    prev = cur;
  }
  return w;
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
  CHECK(joint_traction(j.peak_opening + j.opening_softening, 0, j, 0).damage == 1.0);
  CHECK(joint_traction(j.peak_opening + j.opening_softening, 0, j, 0).normal == 0.0);
}

TEST_CASE("Peak tractions: tensile strength, Mohr-Coulomb shear strength, compression penalty", "[fdem][joint]") {
  const JointStrength j = paper_joint();
  CHECK_THAT(joint_traction(j.peak_opening, 0, j, 0).normal, WithinRel(j.tensile_strength, 1e-14));
  CHECK_THAT(joint_traction(0, j.peak_slip, j, 0).shear, WithinRel(j.cohesion, 1e-14));
  CHECK_THAT(joint_traction(0, -j.peak_slip, j, 0).shear, WithinRel(-j.cohesion, 1e-14));
  // Closed by o = -o_p: sigma = -2 f_t; the shear strength rises to c + 2 f_t tan(phi) (Mohr-Coulomb).
  const double o = -j.peak_opening, sigma = -2 * j.tensile_strength, fs = j.cohesion - sigma * j.tan_friction;
  CHECK_THAT(joint_traction(o, 0, j, 0).normal, WithinRel(sigma, 1e-14));
  const double sp = j.peak_slip * fs / j.cohesion;
  CHECK_THAT(joint_traction(o, sp, j, 0).shear, WithinRel(fs, 1e-14));
  CHECK(joint_traction(o, sp, j, 0).damage == 0.0);
}

TEST_CASE("Damage never heals", "[fdem][joint]") {
  const JointStrength j = paper_joint();
  const JointTraction half = joint_traction(j.peak_opening + 0.5 * j.opening_softening, 0, j, 0);
  CHECK_THAT(half.damage, WithinAbs(0.5, 1e-12));
  // Back to half the peak opening: the damage stays and the traction is the reduced one.
  const JointTraction back = joint_traction(0.5 * j.peak_opening, 0, j, half.damage);
  CHECK(back.damage == half.damage);
  CHECK_THAT(back.normal, WithinRel(softening_curve(0.5) * 0.75 * j.tensile_strength, 1e-12));
}
