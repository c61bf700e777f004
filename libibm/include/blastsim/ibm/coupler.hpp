//! \file coupler.hpp
//! \brief The immersed-boundary coupling of a GasSolver and a RockSolver through their device arrays (docs/ibm.md).
//!
//! Rock -> gas: every staggered velocity point inside a rock triangle takes the velocity interpolated from
//! the triangle's nodes; a cell whose four velocity points are all in rock is inactive and holds the ambient
//! state. Gas -> rock: every exposed rock edge (mesh boundary, faces of broken joints) gets the pressure of
//! the active cell nearest to its midpoint. Nothing leaves the device inside a step.
#pragma once

#include "blastsim/cip/gas_solver.hpp"
#include "blastsim/fdem/rock_solver.hpp"

namespace blastsim::ibm {

class GasRockCoupler {
 public:
  //! `ambient`: the state an inactive cell holds, and the one a cell gets when rock uncovers it (the paper:
  //! 1.2 kg/m3, 2.09e5 J/kg, at rest).
  GasRockCoupler(cip::GasSolver& gas, fdem::RockSolver& rock, const cip::GasPoint& ambient);

  //! Masks and imposed velocities from the rock's current nodes. Search: each triangle visits only the
  //! velocity points in its bounding box; a point covered by several (overlapping) triangles takes the one
  //! of highest index, found with an order-independent atomic maximum, so the result is deterministic.
  //! Cells that change state (covered or uncovered) are set to the ambient state with zero derivatives.
  void rock_to_gas();

  //! Pressure [Pa] of the nearest active cell (within 3 cells of the midpoint) on every exposed edge; the
  //! ambient pressure where none is active.
  void gas_to_rock();

  //! One coupled step: rock_to_gas(), gas step, gas_to_rock(), rock step, with the same dt [s].
  void step(double dt);

  //! Largest dt [s] that both solvers accept: min(gas Courant limit at `courant`, rock stable step).
  double stable_dt(double courant);

  //! Number of inactive (rock-covered) cells, for diagnostics and tests.
  long inactive_cells();

 private:
  cip::GasSolver& gas_;
  fdem::RockSolver& rock_;
  cip::GasPoint ambient_;
  DeviceVector<int> u_owner_, v_owner_;  // padded shape: triangle covering each x-face / y-face point, -1: none
};

}  // namespace blastsim::ibm
