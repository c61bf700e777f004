//! \file in_situ_stress.cpp
//! \brief The in-situ stress field, the triangles' prestretch (Newton on the neo-Hookean stress) and the joints'
//! preload (the joint law inverted before its peak).
#include "blastsim/fdem/in_situ_stress.hpp"

#include "blastsim/core/error.hpp"

#include <cmath>
#include <sstream>

namespace blastsim::fdem {

Mat2 InSituStress::at(double y) const {
  const double dy = y - reference_y;
  const double xx = at_reference[0] + dy * gradient[0], yy = at_reference[1] + dy * gradient[1];
  const double xy = at_reference[2] + dy * gradient[2];
  return {xx, xy, xy, yy};
}

Mat2 prestretch(const Mat2& sigma, double lambda, double mu) {
  // Plane-strain compliance: eps_xx = ((lambda + 2 mu) s_xx - lambda s_yy) / (4 mu (lambda + mu)), eps_xy = s_xy / 2 mu.
  const double k = 1.0 / (4.0 * mu * (lambda + mu));
  auto compliance = [&](double sxx, double syy, double sxy) {
    return Mat2{((lambda + 2 * mu) * sxx - lambda * syy) * k, 0.5 * sxy / mu, 0.5 * sxy / mu,
                ((lambda + 2 * mu) * syy - lambda * sxx) * k};
  };
  const Mat2 identity{1, 0, 0, 1}, no_motion{0, 0, 0, 0};
  const double scale = std::fabs(sigma.a) + std::fabs(sigma.d) + std::fabs(sigma.b);
  Mat2 F = identity;
  for (int it = 0; it < 60; ++it) {
    const Mat2 T = triangle_stress(identity, F, no_motion, lambda, mu, 0.0);
    const double rxx = sigma.a - T.a, ryy = sigma.d - T.d, rxy = sigma.b - T.b;
    if (!std::isfinite(rxx + ryy + rxy)) break;
    // Converged to round-off: that of B - I is about 1e-16 mu.
    if (std::fabs(rxx) + std::fabs(ryy) + std::fabs(rxy) <= 1e-13 * scale + 1e-14 * mu) return F;
    const Mat2 dF = compliance(rxx, ryy, rxy);
    F = {F.a + dF.a, F.b + dF.b, F.c + dF.c, F.d + dF.d};
  }
  std::ostringstream os;
  os << "in-situ stress [" << sigma.a << ", " << sigma.d << ", " << sigma.b
     << "] Pa (xx, yy, xy): no stretch of the rock carries it (the stress must be small against the elastic moduli, "
        "mu = " << mu << " Pa)";
  throw InputError(os.str());
}

JointPreload joint_preload(double normal, double shear, const JointStrength& j) {
  auto refuse = [&](const char* what, double limit) {
    std::ostringstream os;
    os << "in-situ traction sigma = " << normal << " Pa, tau = " << shear << " Pa: " << what << " (" << limit
       << " Pa); the joint would break before the blast";
    throw InputError(os.str());
  };
  JointPreload p{0.0, 0.0};
  // Normal: penalty 2 f_t o / o_p in compression, (2 r - r^2) f_t with r = o / o_p in tension before the peak.
  if (normal <= 0.0)
    p.opening = normal * j.peak_opening / (2.0 * j.tensile_strength);
  else if (normal < j.tensile_strength)
    p.opening = j.peak_opening * (1.0 - std::sqrt(1.0 - normal / j.tensile_strength));
  else
    refuse("not below the joint's tensile strength", j.tensile_strength);
  // Shear: elastic, tau = c s / s_p, below the Coulomb cap f_s = c - sigma tan(phi) under compression.
  const double fs = normal < 0.0 ? j.cohesion - normal * j.tan_friction : j.cohesion;
  if (!(std::fabs(shear) < fs)) refuse("|tau| not below the joint's shear strength", fs);
  p.slip = shear * j.peak_slip / j.cohesion;
  return p;
}

}  // namespace blastsim::fdem
