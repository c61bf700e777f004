//! \file heterogeneity.cpp
//! \brief Random per-joint strength factors (Weibull, log-normal; independent or from a correlated field) and the
//! joint properties they give.
#include "blastsim/fdem/heterogeneity.hpp"

#include "blastsim/core/error.hpp"

#include <cmath>
#include <random>
#include <sstream>
#include <string>

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
  else if (!(correlation_length >= 0 && std::isfinite(correlation_length)))
    os << "correlation_length = " << correlation_length << " m: must be 0 (independent joints) or a positive length";
  if (!os.str().empty()) throw InputError("rock.heterogeneity." + os.str());
}

namespace {

constexpr double kTwoPi = 6.283185307179586476925286766559;

//! Uniform in (0, 1] from 53 bits of the generator: never 0, so logarithms of it stay finite.
double uniform_of(std::mt19937_64& bits) {
  constexpr double ulp = 1.0 / 9007199254740992.0;  // 2^-53
  return (static_cast<double>(bits() >> 11) + 1.0) * ulp;
}

//! The factor of mean 1 of h's distribution at a standard normal value g: X = F^-1(Phi(g)).
double factor_of_normal(const StrengthHeterogeneity& h, double g) {
  if (h.distribution == StrengthDistribution::weibull) {
    // 1 - F(x) = exp(-(x / lambda)^m) = 1 - Phi(g): x = lambda (-ln(1 - Phi(g)))^(1/m). For g >= 0,
    // 1 - Phi(g) = erfc(g / sqrt 2) / 2 directly; for g < 0, -ln(1 - Phi(g)) = -log1p(-Phi(g)) with
    // Phi(g) = erfc(-g / sqrt 2) / 2, which keeps the weak tail's relative precision (x > 0 down to g = -38).
    const double m = h.weibull_modulus;
    const double lambda = 1.0 / std::tgamma(1.0 + 1.0 / m);
    const double z = g / std::sqrt(2.0);
    const double minus_log_tail = g >= 0 ? -std::log(0.5 * std::erfc(z)) : -std::log1p(-0.5 * std::erfc(-z));
    return lambda * std::pow(minus_log_tail, 1.0 / m);
  }
  const double s2 = std::log(1.0 + h.cov * h.cov);
  return std::exp(-0.5 * s2 + std::sqrt(s2) * g);
}

//! The material's joint properties with the selected ones times x[j], one joint per factor.
std::vector<JointProperties> scaled_joints(const RockMaterial& material, const StrengthHeterogeneity& h,
                                           const std::vector<double>& x) {
  std::vector<JointProperties> out(x.size(), joint_properties_of(material));
  for (std::size_t j = 0; j < x.size(); ++j) {
    if (h.tensile_strength) out[j].tensile_strength *= x[j];
    if (h.cohesion) out[j].cohesion *= x[j];
    if (h.fracture_energy) out[j].fracture_energy_mode1 *= x[j], out[j].fracture_energy_mode2 *= x[j];
  }
  return out;
}

}  // namespace

std::vector<double> strength_factors(const StrengthHeterogeneity& h, int count) {
  h.validate();
  std::mt19937_64 bits(h.seed);
  auto uniform = [&] { return uniform_of(bits); };
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
  return scaled_joints(material, h, strength_factors(h, joints));
}

void check_correlation_length(const StrengthHeterogeneity& h, double joint_length) {
  if (h.correlation_length == 0 || !(joint_length > 0)) return;
  const double shortest = kMinCorrelationPerJoint * joint_length;
  if (!(h.correlation_length >= shortest)) {
    std::ostringstream os;
    os << "rock.heterogeneity.correlation_length = " << h.correlation_length << " m: must be 0 (independent joints) "
       << "or at least " << shortest << " m (" << kMinCorrelationPerJoint << " times the mean joint length, "
       << joint_length << " m); a field that much shorter than a joint takes independent values at the joints: "
       << "give 0";
    throw InputError(os.str());
  }
}

GaussianField::GaussianField(double correlation_length, std::uint64_t seed)
    : kx_(kModes), ky_(kModes), phase_(kModes) {
  if (!(correlation_length > 0 && std::isfinite(correlation_length) && std::isfinite(1.0 / correlation_length)))
    throw InputError("rock.heterogeneity.correlation_length = " + std::to_string(correlation_length) +
                     " m: a field needs a positive length");
  std::mt19937_64 bits(seed);
  // C(r) = exp(-r^2 / l^2) = E[cos(k . r)] for k normal with variance 2 / l^2 per component (its spectral density).
  const double sigma_k = std::sqrt(2.0) / correlation_length;
  for (int n = 0; n < kModes; ++n) {
    const double u1 = uniform_of(bits), u2 = uniform_of(bits);  // Box-Muller: both components from one pair
    const double radius = sigma_k * std::sqrt(-2.0 * std::log(u1));
    kx_[n] = radius * std::cos(kTwoPi * u2);
    ky_[n] = radius * std::sin(kTwoPi * u2);
    phase_[n] = kTwoPi * uniform_of(bits);
  }
}

double GaussianField::operator()(double x, double y) const {
  double sum = 0;
  for (int n = 0; n < kModes; ++n) sum += std::cos(kx_[n] * x + ky_[n] * y + phase_[n]);
  return std::sqrt(2.0 / kModes) * sum;
}

std::vector<double> strength_field(const StrengthHeterogeneity& h, const std::vector<std::array<double, 2>>& points) {
  h.validate();
  const GaussianField g(h.correlation_length, h.seed);
  std::vector<double> x(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) x[i] = factor_of_normal(h, g(points[i][0], points[i][1]));
  return x;
}

std::vector<JointProperties> heterogeneous_joints(const RockMaterial& material, const StrengthHeterogeneity& h,
                                                  const std::vector<std::array<double, 2>>& joint_midpoints) {
  if (h.correlation_length == 0) return heterogeneous_joints(material, h, static_cast<int>(joint_midpoints.size()));
  return scaled_joints(material, h, strength_field(h, joint_midpoints));
}

}  // namespace blastsim::fdem
