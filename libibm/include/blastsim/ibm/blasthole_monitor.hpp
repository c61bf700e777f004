//! \file blasthole_monitor.hpp
//! \brief What a blast engineer watches around one blasthole in a coupled run: the gas pressure at the hole
//! wall against the rock's radial stress there (the paper's Fig. 4b; docs/validation.md S1), the first crack,
//! the gas reaching the rock's outer free surface with its speed (the paper's 3.14 ms and 214 m/s), and the
//! blast gas (the traced gas) with its front through the grid and the cracks and its arrival at the surface.
#pragma once

#include "blastsim/core/checkpoint_traits.hpp"
#include "blastsim/cip/gas_solver.hpp"
#include "blastsim/fdem/rock_solver.hpp"
#include "blastsim/ibm/coupling_options.hpp"
#include "blastsim/ibm/crack_gas_coupling.hpp"

#include <algorithm>
#include <array>
#include <vector>

namespace blastsim::ibm {


//! One sample [SI units; stresses tension positive].
struct BlastholeSample {
  double time = 0;
  double wall_pressure_mean = 0, wall_pressure_min = 0, wall_pressure_max = 0;  //!< gas just inside the wall
  double wall_stress_mean = 0, wall_stress_min = 0, wall_stress_max = 0;        //!< rock sigma_rr at the wall
  double wall_stress_spread = 0;  //!< (max - min) / |mean| over the sectors (symmetry, S1)
  int broken_joints = 0;
  double crack_length = 0;
  double outer_pressure_max = 0;   //!< largest gas pressure on the circle just outside the outer surface
  double outer_speed_max = 0;      //!< largest outward speed among the outflow points there
  double outer_flux_speed = 0;     //!< mass-flux-weighted mean outward speed there
  //! The blast gas (the traced gas: the hole's gas in a one-gas run with a tracer, or the detonation products;
  //! docs/analysis.md "Blast gas"): where it is at least kBlastFraction of the gas at a pressure of at least
  //! kBlastPressure x ambient (not a near-vacuum).
  double blast_front = 0;          //!< [m] its farthest reach inside the outer radius, grid and cracks
  double blast_front_crack = 0;    //!< [m] the same in the cracks' own gas alone
  double outer_blast_fraction = 0; //!< largest blast-gas fraction on the circle outside and at crack mouths there
  double outer_blast_speed = 0;    //!< mass-flux-weighted mean outward speed of the blast gas on that circle
};

//! The events, each the time of the first sample where it is seen (-1: not yet).
struct BlastholeEvents {
  double first_crack = -1;        //!< [s] a broken joint
  double ejection = -1;           //!< [s] gas pressure outside the outer surface above twice the ambient
  double ejection_speed = 0;      //!< [m/s] outer_speed_max at that sample
  double ejection_pressure = 0;   //!< [Pa] outer_pressure_max at that sample
  double jet_speed = 0;           //!< [m/s] largest outer_flux_speed from the ejection on
  double jet_time = -1;           //!< [s] when it was reached
  double blast_arrival = -1;      //!< [s] blast gas at the outer surface (on the circle, or at a crack mouth)
  double blast_arrival_crack = 0; //!< 1 when it first arrived at a crack mouth, 0 on the circle
  double blast_speed = 0;         //!< [m/s] largest outer_blast_speed from the arrival on
  double blast_speed_time = -1;   //!< [s] when it was reached
};
}  // namespace blastsim::ibm
BLASTSIM_CHECKPOINT_REALS(blastsim::ibm::BlastholeEvents)
namespace blastsim::ibm {

//! Samples the gas and the rock around a blasthole and keeps the events.
class BlastholeMonitor {
 public:
  //! Wall pressure: 64 points 1.5 cells inside the wall (where the bilinear stencil of the samples holds only
  //! hole cells); wall stress: Lame fits per 45-degree sector of the triangles within three hole radii
  //! (fdem::fit_wall_radial_stress); outer surface: points every cell on the circle half a cell outside it
  //! (at least 64). `ambient_pressure` [Pa] sets the ejection threshold (twice it).
  BlastholeMonitor(const BlastholeGeometry& geometry, const cip::GasGrid& grid, double ambient_pressure);

  //! Takes one sample at the solvers' current state and updates the events; `crack`: the coupling's crack gas,
  //! when it has one.
  BlastholeSample sample(const cip::GasSolver& gas, const fdem::RockSolver& rock, const CrackGasCoupling* crack = nullptr);
  //! Gas counts as blast gas where at least this mass fraction of it is the traced gas, at a pressure of at
  //! least kBlastPressure x the ambient.
  static constexpr double kBlastFraction = 0.5, kBlastPressure = 0.5;

  const BlastholeEvents& events() const { return events_; }
  void restore(const BlastholeEvents& e) { events_ = e; }  //!< a restart: the events of the checkpoint
  const BlastholeGeometry& geometry() const { return geometry_; }
  double ambient_pressure() const { return p_ambient_; }

  static constexpr int kWallPoints = 64, kSectors = 8;

 private:
  BlastholeGeometry geometry_;
  double p_ambient_;
  std::vector<std::array<double, 2>> points_, outward_;
  BlastholeEvents events_;
};

}  // namespace blastsim::ibm
