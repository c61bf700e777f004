//! \file rock_analysis.hpp
//! \brief Analysis of a rock state on the host: the rock's own energy balance, the radial stress at a hole's
//! wall from Lame fits, and load schedules. What the driver writes and the tests assert, computed once here.
#pragma once

#include "blastsim/fdem/rock_types.hpp"

#include <array>
#include <vector>

namespace blastsim::fdem {

//! Residual [J/m] of the rock's energy balance (RockEnergies): kinetic + strain + joint work + contact work +
//! damping - (initial kinetic + initial strain + external work); zero to time-integration error.
double energy_residual(const RockEnergies& now, const RockEnergies& initial);

//! Half-cosine rise from 0 at t = 0 to 1 at t = rise_time [s], 1 after it (and always when rise_time <= 0):
//! a load ramp that starts and ends with zero rate.
double half_cosine_ramp(double t, double rise_time);

//! Lame fit sigma_rr(r) = A + B / r^2 of one angular sector around a hole.
struct LameSectorFit {
  int triangles = 0;       //!< triangles whose centroid lies in the sector within the fit radius
  bool valid = false;      //!< at least 3 triangles and a regular normal system
  double A = 0;            //!< [Pa]
  double B = 0;            //!< [N/m] (Pa m^2)
  double wall_stress = 0;  //!< A + B / a^2 [Pa], the radial stress at the wall r = a (tension positive)
};

//! Radial stress at the wall of a hole of radius a [m] centred at `center` [m], per sector: the triangles
//! whose centroids lie within `fit_radius` [m] of the centre are sorted into `sectors` equal sectors by
//! their angle (sector 0 starts at -pi) and Lame's form A + B / r^2 is fitted to their radial stress by least
//! squares, then evaluated at r = a. One constant-strain triangle at the wall is too coarse a sample; the
//! fit uses the whole near field (Lame 1852; e.g. Jaeger, Cook & Zimmerman 2007, Fundamentals of Rock
//! Mechanics, sec. 8.2, the thick-walled cylinder).
std::vector<LameSectorFit> fit_wall_radial_stress(const RockSnapshot& s, const std::array<double, 2>& center,
                                                  double hole_radius, int sectors, double fit_radius);

}  // namespace blastsim::fdem
