//! \file blasthole_monitor.cpp
//! \brief BlastholeMonitor: gas samples at the hole wall and the outer surface, Lame fits of the wall stress,
//! and the events of a single-hole blast.
#include "blastsim/ibm/blasthole_monitor.hpp"

#include "blastsim/core/error.hpp"
#include "blastsim/fdem/rock_analysis.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace blastsim::ibm {

void BlastholeGeometry::validate() const {
  if (!(hole_radius > 0) || !(outer_radius > hole_radius) || !std::isfinite(outer_radius))
    throw InputError("blasthole monitor: hole_radius = " + std::to_string(hole_radius) + " m, outer_radius = " +
                     std::to_string(outer_radius) + " m: need 0 < hole_radius < outer_radius");
}

BlastholeMonitor::BlastholeMonitor(const BlastholeGeometry& g, const cip::GasGrid& grid, double ambient_pressure)
    : geometry_(g), p_ambient_(ambient_pressure) {
  geometry_.validate();
  const double h = std::min(grid.dx, grid.dy);
  const double r_wall = std::max(0.0, g.hole_radius - 1.5 * std::max(grid.dx, grid.dy));
  for (int k = 0; k < kWallPoints; ++k) {
    const double th = 2 * M_PI * (k + 0.5) / kWallPoints;
    points_.push_back({g.center[0] + r_wall * std::cos(th), g.center[1] + r_wall * std::sin(th)});
  }
  const int ring = std::max(64, static_cast<int>(2 * M_PI * g.outer_radius / h));
  for (int k = 0; k < ring; ++k) {
    const double th = 2 * M_PI * (k + 0.5) / ring;
    points_.push_back({g.center[0] + (g.outer_radius + 0.5 * h) * std::cos(th),
                       g.center[1] + (g.outer_radius + 0.5 * h) * std::sin(th)});
    outward_.push_back({std::cos(th), std::sin(th)});
  }
}

BlastholeSample BlastholeMonitor::sample(const cip::GasSolver& gas, const fdem::RockSolver& rock,
                                         const CrackGasCoupling* crack) {
  BlastholeSample s;
  s.time = gas.time();
  const std::vector<cip::GasSample> g = gas.sample(points_);
  double pm = 0, pmin = 1e300, pmax = -1e300;
  for (int k = 0; k < kWallPoints; ++k) pm += g[k].p / kWallPoints, pmin = std::min(pmin, g[k].p), pmax = std::max(pmax, g[k].p);
  s.wall_pressure_mean = pm, s.wall_pressure_min = pmin, s.wall_pressure_max = pmax;
  double sm = 0, smin = 1e300, smax = -1e300;
  int n = 0;
  for (const fdem::LameSectorFit& f : fdem::fit_wall_radial_stress(rock.snapshot(), geometry_.center, geometry_.hole_radius,
                                                                   kSectors, 3 * geometry_.hole_radius)) {
    if (!f.valid) continue;
    sm += f.wall_stress, smin = std::min(smin, f.wall_stress), smax = std::max(smax, f.wall_stress), ++n;
  }
  if (n > 0) sm /= n;
  s.wall_stress_mean = sm, s.wall_stress_min = smin, s.wall_stress_max = smax;
  s.wall_stress_spread = n > 0 && sm != 0 ? (smax - smin) / std::fabs(sm) : 0.0;
  // Gas at the outer surface: detonation gas is taken to have left the rock where the pressure just outside
  // the original surface exceeds twice the ambient (the air pushed by the rock stays within a few kPa). The
  // outflow's speed: the mass-flux-weighted mean outward speed, sum rho u_n^2 / sum rho u_n, over the points
  // where such gas flows out (u_n > 0), and the largest single outward speed there. The blast gas (the traced
  // gas) is measured the same way on the points where it is at least kBlastFraction of the gas.
  const double p_blast = kBlastPressure * p_ambient_;
  double out_p = 0, out_speed = 0, flux = 0, momentum_flux = 0, blast_flux = 0, blast_momentum = 0, blast_y = 0;
  for (size_t k = kWallPoints; k < g.size(); ++k) {
    out_p = std::max(out_p, g[k].p);
    const std::array<double, 2>& o = outward_[k - kWallPoints];
    const double un = g[k].u * o[0] + g[k].v * o[1];
    if (g[k].p > 2 * p_ambient_ && un > 0) {
      out_speed = std::max(out_speed, un);
      flux += g[k].rho * un, momentum_flux += g[k].rho * un * un;
    }
    if (g[k].p >= p_blast) blast_y = std::max(blast_y, g[k].traced);
    if (g[k].p >= p_blast && g[k].traced >= kBlastFraction && un > 0) {
      blast_flux += g[k].rho * g[k].traced * un, blast_momentum += g[k].rho * g[k].traced * un * un;
    }
  }
  s.outer_pressure_max = out_p, s.outer_speed_max = out_speed;
  s.outer_flux_speed = flux > 0 ? momentum_flux / flux : 0.0;
  s.outer_blast_speed = blast_flux > 0 ? blast_momentum / blast_flux : 0.0;
  const BlastholeGeometry& geo = geometry_;
  s.blast_front = gas.traced_reach(geo.center, kBlastFraction, p_blast, geo.outer_radius);
  double crack_y = 0;
  if (crack) {
    s.blast_front_crack = crack->blast_front(rock, geo.center, kBlastFraction, p_blast);
    s.blast_front = std::max(s.blast_front, s.blast_front_crack);
    crack_y = crack->outer_blast_fraction(rock, geo.center, 0.5 * (geo.hole_radius + geo.outer_radius), p_blast);
  }
  s.outer_blast_fraction = std::max(blast_y, crack_y);
  const fdem::RockEnergies e = rock.energies();
  s.broken_joints = e.broken_joints, s.crack_length = e.crack_length;
  BlastholeEvents& ev = events_;
  if (ev.first_crack < 0 && e.broken_joints > 0) ev.first_crack = s.time;
  if (ev.ejection < 0 && out_p > 2 * p_ambient_) ev.ejection = s.time, ev.ejection_speed = out_speed, ev.ejection_pressure = out_p;
  if (ev.ejection >= 0 && s.outer_flux_speed > ev.jet_speed) ev.jet_speed = s.outer_flux_speed, ev.jet_time = s.time;
  if (ev.blast_arrival < 0 && s.outer_blast_fraction >= kBlastFraction)
    ev.blast_arrival = s.time, ev.blast_arrival_crack = blast_y >= kBlastFraction ? 0.0 : 1.0;
  if (ev.blast_arrival >= 0 && s.outer_blast_speed > ev.blast_speed)
    ev.blast_speed = s.outer_blast_speed, ev.blast_speed_time = s.time;
  return s;
}

}  // namespace blastsim::ibm
