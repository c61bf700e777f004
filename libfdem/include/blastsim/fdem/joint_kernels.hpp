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

//! Work per unit area [J/m2] done on a joint point opened from rest to its peak o_p [m] at tensile strength f_t
//! [Pa]: the integral of (2 r - r^2) f_t over o, (2/3) f_t o_p.
BLAST_HD inline double opening_pre_peak_work(double tensile_strength, double peak_opening) {
  return 2.0 / 3.0 * tensile_strength * peak_opening;
}
//! Work per unit area [J/m2] done on a joint point slid from rest to its yield slip s_p [m] at cohesion c [Pa]:
//! the elastic branch, (1/2) c s_p.
BLAST_HD inline double slip_pre_peak_work(double cohesion, double peak_slip) { return 0.5 * cohesion * peak_slip; }

//! Softening length [m] chosen so that breaking a joint point from rest dissipates exactly the fracture
//! energy G [J/m2] at strength f [Pa], given the work done on it up to its peak (opening_pre_peak_work(),
//! slip_pre_peak_work()): the whole curve's work is that pre-peak part plus the softening part
//! f x length x softening_curve_integral(), so length = (G - pre_peak_work) / (f softening_curve_integral()),
//! about 2.59 G / f when the pre-peak part is small. (The Y codes' 3 G / f dissipates about 1.16 G plus the
//! pre-peak part: docs/fdem-solver.md, "Softening length (the 16 % trap)".) Throws InputError unless the
//! pre-peak part stays below G / 2 (element too large or joint penalty too small).
double softening_length(double fracture_energy, double strength, double pre_peak_work);

//! Peak-stress parameters of one joint integration point.
struct JointStrength {
  double tensile_strength;  //!< f_t [Pa]
  double cohesion;          //!< c [Pa]
  double tan_friction;      //!< tan(phi) [-]
  double peak_opening;      //!< o_p = 2 h f_t / p [m]
  double peak_slip;         //!< s_p = h c / p [m]: the elastic slip at the shear strength c (zero normal stress)
  double opening_softening; //!< o_t [m], softening_length(G_I, f_t, (2/3) f_t o_p)
  double slip_softening;    //!< s_t [m], softening_length(G_II, c, (1/2) c s_p)
};

//! What one integration point remembers between steps: its damage and its plastic slip (all zero at rest).
struct JointHistory {
  double damage = 0;        //!< D in [0, 1]; never decreases
  double plastic_slip = 0;  //!< s_pl [m], signed: the slip the joint keeps when its shear traction is removed
  double slip_path = 0;     //!< kappa [m]: the plastic slip accumulated in either direction; never decreases
};

//! Tractions and history at one integration point.
struct JointTraction {
  double normal;        //!< sigma [Pa], tension positive
  double shear;         //!< tau [Pa], with the sign of the elastic slip s - s_pl
  double damage;        //!< D in [0, 1]; 1: broken
  double plastic_slip;  //!< s_pl [m] after this evaluation
  double slip_path;     //!< kappa [m] after this evaluation
  //! The history to pass to the next evaluation.
  BLAST_HD JointHistory history() const { return {damage, plastic_slip, slip_path}; }
};

//! Traction of the cohesive law for opening o and slip s [m] (docs/fdem-solver.md, "Cohesive joint").
//! Normal: before the peak sigma = (2 o/o_p - (o/o_p)^2) f_t, a penalty 2 o f_t / o_p in compression (never
//! softened). Shear: elastic-plastic, tau = k (s - s_pl) with k = c / s_p (= p / h, the initial stiffness of
//! the normal branch), capped at the shear strength f_s = c - sigma tan(phi) under compression (Mohr-Coulomb), c
//! otherwise: slip beyond the cap is plastic (s_pl moves by it, kappa grows by its size). Damage D = sqrt(((o -
//! o_p)/o_t)^2 + (kappa/s_t)^2) (the opening term only past its peak), never less than before, capped at 1; both
//! tractions then scale with softening_curve(D), the shear's stiffness and cap alike.
//! Energy: the shear's elastic energy (1/2) z k (s - s_pl)^2 does not depend on the opening, the plastic work
//! tau dkappa is >= 0 and damage only grows, so no path of opening and slip returns more energy than it stored.
BLAST_HD inline JointTraction joint_traction(double o, double s, const JointStrength& j, const JointHistory& previous) {
  // Normal traction before softening (compression: penalty, never softened).
  const double r = o / j.peak_opening;
  double sigma = o <= 0.0 ? 2.0 * r * j.tensile_strength
                          : (r < 1.0 ? (2.0 * r - r * r) * j.tensile_strength : j.tensile_strength);
  const double fs = sigma < 0.0 ? j.cohesion - sigma * j.tan_friction : j.cohesion;
  const double k = j.cohesion / j.peak_slip;  // elastic shear stiffness [Pa/m], the same at any compression
  // Shear, undamaged ("effective") traction: elastic trial, then the return to the Coulomb cap.
  double s_pl = previous.plastic_slip, kappa = previous.slip_path;
  const double elastic = s - s_pl;
  double tau = k * elastic;
  if (fabs(tau) > fs) {
    const double sign = elastic < 0.0 ? -1.0 : 1.0;
    const double slide = (fabs(tau) - fs) / k;
    s_pl += sign * slide;
    kappa += slide;
    tau = sign * fs;
  }
  // Both terms are >= 0; an undamaged point (the most common) skips the division and the root (the same bits).
  const double dn = o > j.peak_opening ? (o - j.peak_opening) / j.opening_softening : 0.0;
  const double ds = kappa > 0.0 ? kappa / j.slip_softening : 0.0;
  double D = dn > 0.0 || ds > 0.0 ? sqrt(dn * dn + ds * ds) : 0.0;
  D = D > previous.damage ? D : previous.damage;
  D = D < 1.0 ? D : 1.0;
  if (D > 0.0) {
    const double z = softening_curve(D);
    if (sigma > 0.0) sigma = z * j.tensile_strength * (r < 1.0 ? (2.0 * r - r * r) : 1.0);
    tau *= z;
  }
  return {sigma, tau, D, s_pl, kappa};
}

}  // namespace blastsim::fdem
