//! \file joint.cpp
//! \brief Host-side constants of the cohesive law: the softening-curve integral and softening lengths.
#include "blastsim/fdem/joint_kernels.hpp"

#include "blastsim/core/error.hpp"

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

}  // namespace blastsim::fdem
