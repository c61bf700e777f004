//! \file rock_analysis.cpp
//! \brief Host-side analysis of rock states: energy residual, load ramp, Lame fits of the wall stress.
#include "blastsim/fdem/rock_analysis.hpp"

#include "blastsim/core/error.hpp"

#include <cmath>
#include <string>

namespace blastsim::fdem {

double energy_residual(const RockEnergies& e, const RockEnergies& e0) {
  return e.kinetic + e.strain + e.joint_work + e.contact_work + e.damping_dissipated -
         (e0.kinetic + e0.strain + e.external_work);
}

double half_cosine_ramp(double t, double T) { return T <= 0 || t >= T ? 1.0 : 0.5 * (1.0 - std::cos(M_PI * t / T)); }

std::vector<LameSectorFit> fit_wall_radial_stress(const RockSnapshot& snap, const std::array<double, 2>& center,
                                                  double hole_radius, int sectors, double fit_radius) {
  if (sectors < 1) throw InputError("fit_wall_radial_stress: sectors = " + std::to_string(sectors) + ": must be >= 1");
  std::vector<std::array<double, 5>> sums(sectors, {0, 0, 0, 0, 0});  // sums of 1, q, q^2, s, s q with q = 1/r^2
  for (size_t t = 0; t < snap.stress.size() / 3; ++t) {
    const double cx = (snap.x[3 * t] + snap.x[3 * t + 1] + snap.x[3 * t + 2]) / 3 - center[0];
    const double cy = (snap.y[3 * t] + snap.y[3 * t + 1] + snap.y[3 * t + 2]) / 3 - center[1];
    const double r = std::hypot(cx, cy);
    if (r > fit_radius) continue;
    const double cs = cx / r, sn = cy / r, q = 1 / (r * r);
    const double srr = snap.stress[3 * t] * cs * cs + 2 * snap.stress[3 * t + 1] * sn * cs + snap.stress[3 * t + 2] * sn * sn;
    std::array<double, 5>& f =
        sums[static_cast<int>(std::floor((std::atan2(cy, cx) + M_PI) / (2 * M_PI) * sectors)) % sectors];
    f[0] += 1, f[1] += q, f[2] += q * q, f[3] += srr, f[4] += srr * q;
  }
  std::vector<LameSectorFit> fits(sectors);
  for (int k = 0; k < sectors; ++k) {
    const std::array<double, 5>& f = sums[k];
    LameSectorFit& out = fits[k];
    out.triangles = static_cast<int>(f[0]);
    const double det = f[0] * f[2] - f[1] * f[1];
    if (f[0] < 3 || det <= 0) continue;
    out.valid = true;
    out.A = (f[3] * f[2] - f[4] * f[1]) / det;
    out.B = (f[0] * f[4] - f[1] * f[3]) / det;
    out.wall_stress = out.A + out.B / (hole_radius * hole_radius);
  }
  return fits;
}

}  // namespace blastsim::fdem
