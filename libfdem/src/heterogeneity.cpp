//! \file heterogeneity.cpp
//! \brief Random per-joint strength factors (Weibull, log-normal) and the joint properties they give.
#include "blastsim/fdem/heterogeneity.hpp"

#include "blastsim/core/error.hpp"

#include <cmath>
#include <random>
#include <sstream>

namespace blastsim::fdem {

JointProperties joint_properties_of(const RockMaterial& m) {
  return {m.tensile_strength, m.cohesion, m.friction_angle, m.fracture_energy_mode1, m.fracture_energy_mode2};
}

void StrengthHeterogeneity::validate() const {
  std::ostringstream os;
  if (distribution == StrengthDistribution::weibull && !(weibull_modulus > 0 && std::isfinite(weibull_modulus)))
    os << "modulus = " << weibull_modulus << ": the Weibull modulus must be a positive number";
  else if (distribution == StrengthDistribution::lognormal && !(cov > 0 && std::isfinite(cov)))
    os << "cov = " << cov << ": the log-normal coefficient of variation must be a positive number";
  else if (!tensile_strength && !cohesion && !fracture_energy)
    os << "properties: none selected (tensile_strength, cohesion, fracture_energy)";
  if (!os.str().empty()) throw InputError("rock.heterogeneity." + os.str());
}

std::vector<double> strength_factors(const StrengthHeterogeneity& h, int count) {
  h.validate();
  std::mt19937_64 bits(h.seed);
  constexpr double ulp = 1.0 / 9007199254740992.0;  // 2^-53
  // Uniform in (0, 1]: never 0, so the logarithms below stay finite.
  auto uniform = [&] { return (static_cast<double>(bits() >> 11) + 1.0) * ulp; };
  std::vector<double> x(count > 0 ? count : 0);
  if (h.distribution == StrengthDistribution::weibull) {
    // Inverse of F(x) = 1 - exp(-(x / lambda)^m) at 1 - u: x = lambda (-ln u)^(1/m); mean lambda Gamma(1 + 1/m).
    const double m = h.weibull_modulus;
    const double lambda = 1.0 / std::tgamma(1.0 + 1.0 / m);
    for (double& v : x) v = lambda * std::pow(-std::log(uniform()), 1.0 / m);
  } else {
    // Box-Muller: z = sqrt(-2 ln u1) cos(2 pi u2), one normal per pair of uniforms.
    const double s2 = std::log(1.0 + h.cov * h.cov);
    const double s = std::sqrt(s2), mu = -0.5 * s2;
    const double two_pi = 8.0 * std::atan(1.0);
    for (double& v : x) {
      const double u1 = uniform(), u2 = uniform();
      v = std::exp(mu + s * std::sqrt(-2.0 * std::log(u1)) * std::cos(two_pi * u2));
    }
  }
  return x;
}

std::vector<JointProperties> heterogeneous_joints(const RockMaterial& material, const StrengthHeterogeneity& h,
                                                  int joints) {
  const std::vector<double> x = strength_factors(h, joints);
  const JointProperties base = joint_properties_of(material);
  std::vector<JointProperties> out(x.size(), base);
  for (std::size_t j = 0; j < x.size(); ++j) {
    if (h.tensile_strength) out[j].tensile_strength *= x[j];
    if (h.cohesion) out[j].cohesion *= x[j];
    if (h.fracture_energy) out[j].fracture_energy_mode1 *= x[j], out[j].fracture_energy_mode2 *= x[j];
  }
  return out;
}

}  // namespace blastsim::fdem
