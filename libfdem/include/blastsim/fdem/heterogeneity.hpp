//! \file heterogeneity.hpp
//! \brief Per-joint strength of heterogeneous rock: each joint's tensile strength, cohesion and fracture energies
//! drawn, from a seed, as the material's values times a random factor of mean 1 (Weibull or log-normal).
#pragma once

#include "blastsim/fdem/material.hpp"

#include <cstdint>
#include <vector>

namespace blastsim::fdem {

//! The joint law's material inputs for one joint (SI; RockMaterial's fields of the same names).
struct JointProperties {
  double tensile_strength = 0;       //!< f_t [Pa]
  double cohesion = 0;               //!< c [Pa]
  double friction_angle = 0;         //!< phi [rad]
  double fracture_energy_mode1 = 0;  //!< G_I [J/m2]
  double fracture_energy_mode2 = 0;  //!< G_II [J/m2]
};

//! The material's own joint properties (every joint of uniform rock).
JointProperties joint_properties_of(const RockMaterial& material);

enum class StrengthDistribution {
  weibull,   //!< F(x) = 1 - exp(-(x / lambda)^m), lambda = 1 / Gamma(1 + 1/m) so that the mean is 1
  lognormal  //!< ln x normal with sigma^2 = ln(1 + cov^2) and mean -sigma^2 / 2, so that the mean is 1
};

//! How the joints' strengths scatter. One factor X is drawn per joint (in joint order, from `seed`) and
//! multiplies the selected properties of that joint, so a weak joint is weak in every mode it is weak in and
//! the mean of each property over many joints is the material's value.
struct StrengthHeterogeneity {
  StrengthDistribution distribution = StrengthDistribution::weibull;
  double weibull_modulus = 0;      //!< m > 0 (Weibull): smaller m, wider scatter (coefficient of variation ~1.2/m)
  double cov = 0;                  //!< coefficient of variation > 0 (log-normal)
  std::uint64_t seed = 1;          //!< of the random sequence (std::mt19937_64)
  bool tensile_strength = true;    //!< scale f_t
  bool cohesion = true;            //!< scale c
  bool fracture_energy = true;     //!< scale G_I and G_II
  //! Throws InputError naming the first parameter outside its range.
  void validate() const;
};

//! `count` factors of mean 1 drawn from the distribution, reproducibly: the same seed gives the same bytes on
//! every platform (mt19937_64 bits, turned into uniforms and the inverse distribution by this code, not by
//! the standard library's distributions, whose algorithms are unspecified).
std::vector<double> strength_factors(const StrengthHeterogeneity& h, int count);

//! The properties of `joints` joints: the material's, with the selected ones times strength_factors().
std::vector<JointProperties> heterogeneous_joints(const RockMaterial& material, const StrengthHeterogeneity& h,
                                                  int joints);

}  // namespace blastsim::fdem
