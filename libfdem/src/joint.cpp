//! \file joint.cpp
//! \brief Host-side constants of the cohesive law: the softening-curve integral, softening lengths and a joint's
//! strength parameters from its properties.
#include "blastsim/fdem/joint_kernels.hpp"

#include "blastsim/fdem/heterogeneity.hpp"

#include "blastsim/core/error.hpp"

#include <cmath>
#include <string>

namespace blastsim::fdem {

double softening_curve_integral() {
  // Composite Simpson on 20000 intervals: the curve is smooth on [0, 1] (error far below 1e-10).
  static const double value = [] {
    const int n = 20000;
    double sum = softening_curve(0.0) + softening_curve(1.0);
    for (int k = 1; k < n; ++k) sum += (k % 2 ? 4.0 : 2.0) * softening_curve(static_cast<double>(k) / n);
    return sum / (3.0 * n);
  }();
  return value;
}

double softening_length(double fracture_energy, double strength, double pre_peak_work) {
  if (!(fracture_energy > 0) || !(strength > 0) || !(pre_peak_work >= 0))
    throw InputError("softening length needs a fracture energy > 0 J/m2, a strength > 0 Pa and a pre-peak work "
                     ">= 0 J/m2 (got " + std::to_string(fracture_energy) + ", " + std::to_string(strength) + ", " +
                     std::to_string(pre_peak_work) + ")");
  if (!(pre_peak_work < 0.5 * fracture_energy))
    throw InputError("joint pre-peak energy " + std::to_string(pre_peak_work) + " J/m2 is not below half the fracture "
                     "energy " + std::to_string(fracture_energy) + " J/m2: use smaller elements or a larger "
                     "joint_penalty_factor (the pre-peak work grows with h f^2 / p)");
  return (fracture_energy - pre_peak_work) / (strength * softening_curve_integral());
}


JointStrength joint_strength(const JointProperties& q, double h, double p, int joint) {
  if (joint >= 0) {  // a joint with its own strength: an error names it and its strength
    try {
      return joint_strength(q, h, p);
    } catch (const InputError& e) {
      throw InputError("joint " + std::to_string(joint) + " (its own strength, f_t = " + std::to_string(q.tensile_strength) +
                       " Pa): " + e.what());
    }
  }
  if (!(q.tensile_strength > 0) || !(q.cohesion > 0) || !(q.fracture_energy_mode1 > 0) ||
      !(q.fracture_energy_mode2 > 0) || !(q.friction_angle >= 0 && q.friction_angle < M_PI / 2) ||
      !std::isfinite(q.tensile_strength + q.cohesion + q.fracture_energy_mode1 + q.fracture_energy_mode2))
    throw InputError("strengths and fracture energies must be positive and finite, the friction angle in [0, 90) deg");
  JointStrength s;
  s.tensile_strength = q.tensile_strength;
  s.cohesion = q.cohesion;
  s.tan_friction = std::tan(q.friction_angle);
  s.peak_opening = 2 * h * q.tensile_strength / p;
  s.peak_slip = h * q.cohesion / p;
  s.opening_softening =
      softening_length(q.fracture_energy_mode1, q.tensile_strength, opening_pre_peak_work(s.tensile_strength, s.peak_opening));
  s.slip_softening = softening_length(q.fracture_energy_mode2, q.cohesion, slip_pre_peak_work(s.cohesion, s.peak_slip));
  return s;
}

}  // namespace blastsim::fdem
