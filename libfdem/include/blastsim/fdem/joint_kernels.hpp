//! \file joint_kernels.hpp
//! \brief Cohesive joint law of FDEM (Munjiza 2004, ch. 7; Mahabadi et al. 2012): traction from opening and slip.
#pragma once

#include "blastsim/core/macros.hpp"

#include <cmath>

namespace blastsim::fdem {

//! Munjiza's softening curve z(D), D in [0, 1] the damage: z(0) = 1, z(1) = 0, with a = 0.63, b = 1.8, c = 6
//! (docs/fdem-solver.md, "Cohesive joint"): z = [1 - (a+b-1)/(a+b) exp(D (a + c b) / ((a+b)(1-a-b)))] [a (1-D) + b (1-D)^c].
BLAST_HD inline double softening_curve(double D) {
  const double a = 0.63, b = 1.8, c = 6.0;
  if (D >= 1.0) return 0.0;
  if (D <= 0.0) return 1.0;
  const double e = exp(D * (a + c * b) / ((a + b) * (1.0 - a - b)));
  return (1.0 - (a + b - 1.0) / (a + b) * e) * (a * (1.0 - D) + b * pow(1.0 - D, c));
}

//! Integral of softening_curve() over D in [0, 1] (about 0.386), computed once by quadrature.
double softening_curve_integral();

//! Softening length [m] chosen so that breaking a joint point from rest dissipates exactly the fracture
//! energy G [J/m2] at strength f [Pa] and peak separation `peak` [m]: the work of the whole curve is the
//! pre-peak part (2/3) f peak plus the softening part f x length x softening_curve_integral(), so
//! length = (G - (2/3) f peak) / (f softening_curve_integral()), about 2.59 G / f when the peak part is small.
//! (The Y codes' 3 G / f dissipates about 1.16 G plus the peak part: docs/fdem-solver.md, "Softening length
//! (the 16 % trap)".) Throws InputError unless the pre-peak part stays below G / 2 (element too large or joint
//! penalty too small).
double softening_length(double fracture_energy, double strength, double peak);

//! Peak-stress parameters of one joint integration point.
struct JointStrength {
  double tensile_strength;  //!< f_t [Pa]
  double cohesion;          //!< c [Pa]
  double tan_friction;      //!< tan(phi) [-]
  double peak_opening;      //!< o_p = 2 h f_t / p [m]
  double peak_slip;         //!< s_p = 2 h c / p [m] (at zero normal stress)
  double opening_softening; //!< o_t [m], softening_length(G_I, f_t, o_p)
  double slip_softening;    //!< s_t [m], softening_length(G_II, c, s_p)
};

//! Tractions and damage at one integration point.
struct JointTraction {
  double normal;   //!< sigma [Pa], tension positive
  double shear;    //!< tau [Pa], with the sign of the slip
  double damage;   //!< D in [0, 1]; 1: broken
};

//! Traction of the cohesive law for opening o and slip s [m] (docs/fdem-solver.md, "Cohesive joint"): before the peak
//! sigma = (2 o/o_p - (o/o_p)^2) f_t, a penalty 2 o f_t / o_p in compression; tau likewise with the shear
//! strength f_s = c - sigma tan(phi) under compression (Mohr-Coulomb), c otherwise. Past a peak the damage
//! D = sqrt(((o - o_p)/o_t)^2 + ((|s| - s_p)/s_t)^2) (each term only when past its own peak) and both
//! tractions scale with softening_curve(D). `previous_damage` makes damage irreversible.
BLAST_HD inline JointTraction joint_traction(double o, double s, const JointStrength& j, double previous_damage) {
  // Normal traction before softening (compression: penalty, never softened).
  const double r = o / j.peak_opening;
  double sigma = o <= 0.0 ? 2.0 * r * j.tensile_strength
                          : (r < 1.0 ? (2.0 * r - r * r) * j.tensile_strength : j.tensile_strength);
  const double fs = sigma < 0.0 ? j.cohesion - sigma * j.tan_friction : j.cohesion;
  const double sp = j.peak_slip * fs / j.cohesion;  // the peak slip grows with the shear strength
  const double q = fabs(s) / sp;
  double tau = (q < 1.0 ? (2.0 * q - q * q) : 1.0) * fs * (s < 0.0 ? -1.0 : 1.0);
  const double dn = o > j.peak_opening ? (o - j.peak_opening) / j.opening_softening : 0.0;
  const double ds = fabs(s) > sp ? (fabs(s) - sp) / j.slip_softening : 0.0;
  double D = sqrt(dn * dn + ds * ds);
  D = D > previous_damage ? D : previous_damage;
  D = D < 1.0 ? D : 1.0;
  const double z = softening_curve(D);
  if (D > 0.0) {
    if (sigma > 0.0) sigma = z * j.tensile_strength * (r < 1.0 ? (2.0 * r - r * r) : 1.0);
    tau *= z;
  }
  return {sigma, tau, D};
}

}  // namespace blastsim::fdem
