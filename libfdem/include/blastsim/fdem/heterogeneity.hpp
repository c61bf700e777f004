//! \file heterogeneity.hpp
//! \brief Per-joint strength of heterogeneous rock: each joint's tensile strength, cohesion and fracture energies
//! drawn, from a seed, as the material's values times a random factor of mean 1 (Weibull or log-normal), either
//! independently per joint or from a spatially correlated random field of the joint's position.
#pragma once

#include "blastsim/fdem/joint_kernels.hpp"
#include "blastsim/fdem/material.hpp"

#include <array>
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

//! The joint law's parameters of a joint of length h [m] with properties q at the joint penalty p [Pa] (the peak
//! opening and slip of the penalty, the softening lengths from the fracture energies). Throws InputError for
//! properties the law cannot take, naming `joint` (when >= 0: a joint with its own strength) and its strength.
JointStrength joint_strength(const JointProperties& q, double h, double p, int joint = -1);

//! The material's own joint properties (every joint of uniform rock).
JointProperties joint_properties_of(const RockMaterial& material);

enum class StrengthDistribution {
  weibull,   //!< F(x) = 1 - exp(-(x / lambda)^m), lambda = 1 / Gamma(1 + 1/m) so that the mean is 1
  lognormal  //!< ln x normal with sigma^2 = ln(1 + cov^2) and mean -sigma^2 / 2, so that the mean is 1
};

//! How the joints' strengths scatter. One factor X per joint multiplies the selected properties of that joint, so
//! a weak joint is weak in every mode it is weak in and the mean of each property over many joints is the
//! material's value. With `correlation_length` 0, X is drawn independently per joint, in joint order, from
//! `seed`; above 0 it is the value at the joint's midpoint of a random field of the position
//! (strength_field()), so the strength varies over that length whatever the mesh.
struct StrengthHeterogeneity {
  StrengthDistribution distribution = StrengthDistribution::weibull;
  double weibull_modulus = 0;      //!< m > 0 (Weibull): smaller m, wider scatter (coefficient of variation ~1.2/m)
  double cov = 0;                  //!< coefficient of variation > 0 (log-normal)
  std::uint64_t seed = 1;          //!< of the random sequence (std::mt19937_64)
  bool tensile_strength = true;    //!< scale f_t
  bool cohesion = true;            //!< scale c
  bool fracture_energy = true;     //!< scale G_I and G_II
  double correlation_length = 0;   //!< [m] of the field's Gaussian correlation exp(-r^2 / l^2); 0: independent joints
  //! Throws InputError naming the first parameter outside its range.
  void validate() const;
};

//! The shortest correlation length accepted, in mean joint lengths: neighbouring joints of a field 1000 times
//! shorter than a joint are correlated by exp(-10^6), i.e. independent, which correlation_length = 0 gives exactly.
inline constexpr double kMinCorrelationPerJoint = 1e-3;

//! Throws InputError naming rock.heterogeneity.correlation_length unless it is 0 or at least
//! kMinCorrelationPerJoint times `joint_length` [m] (the mesh's mean joint length; no check when that is not > 0).
void check_correlation_length(const StrengthHeterogeneity& h, double joint_length);

//! `count` factors of mean 1 drawn from the distribution, reproducibly: the same seed gives the same bytes on
//! every platform (mt19937_64 bits, turned into uniforms and the inverse distribution by this code, not by
//! the standard library's distributions, whose algorithms are unspecified).
std::vector<double> strength_factors(const StrengthHeterogeneity& h, int count);

//! The properties of `joints` joints: the material's, with the selected ones times strength_factors().
std::vector<JointProperties> heterogeneous_joints(const RockMaterial& material, const StrengthHeterogeneity& h,
                                                  int joints);

//! A stationary Gaussian random field of the plane with mean 0, variance 1 and correlation exp(-r^2 / l^2),
//! by the randomisation (spectral) method (Shinozuka & Deodatis 1991, Appl. Mech. Rev. 44, 191-204):
//! G(x) = sqrt(2 / N) sum_n cos(k_n . x + phi_n), N = kModes wave vectors k_n drawn from the field's spectral
//! density (normal, variance 2 / l^2 per component) and phases phi_n uniform in [0, 2 pi), all from the seed.
//! Over the draws of k and phi, G(x) and G(y) have exactly the field's covariance; one draw's covariance departs
//! from it by about 1 / sqrt(2 N) (a standard deviation). The field is a function of the position only: the same seed
//! gives the same value at a point on any mesh.
class GaussianField {
 public:
  static constexpr int kModes = 2048;
  GaussianField(double correlation_length, std::uint64_t seed);
  double operator()(double x, double y) const;  //!< G at (x, y) [m]
 private:
  std::vector<double> kx_, ky_, phase_;
};

//! The factor X at each point: the field G of `h.correlation_length` (> 0 required) and `h.seed` mapped onto the
//! distribution of `h` through the normal distribution function Phi (X = F^-1(Phi(G))), so that X has the
//! distribution of strength_factors() at every point and the field's correlation over distance.
std::vector<double> strength_field(const StrengthHeterogeneity& h, const std::vector<std::array<double, 2>>& points);

//! The properties of the joints whose midpoints are given: independent draws (strength_factors(), in this
//! order) when `h.correlation_length` is 0, the field's factors at the midpoints (strength_field()) otherwise.
std::vector<JointProperties> heterogeneous_joints(const RockMaterial& material, const StrengthHeterogeneity& h,
                                                  const std::vector<std::array<double, 2>>& joint_midpoints);

}  // namespace blastsim::fdem
