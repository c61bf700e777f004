//! \file gas_types.hpp
//! \brief Plain option and result types of the gas solver (no backend headers: usable from any host code).
#pragma once

#include "blastsim/cip/boundary.hpp"
#include "blastsim/cip/cip_kernels.hpp"

#include <cstdint>
#include <vector>

namespace blastsim::cip {

//! Coefficients of the artificial viscosity, paper eq. (4). The paper does not give them. The defaults
//! c1 = 1, c2 = 2 were chosen by measurement (docs/gas-solver.md): with the common c1 = 0.5, c2 = 1 the
//! non-conservative form runs the shock of the paper's 277:1 jump 2.6 % slow; with 1 and 2 it is 0.8 %.
struct ArtificialViscosity {
  double linear = 1.0;     //!< c1 [-]
  double quadratic = 2.0;  //!< c2 [-]
};

struct GasSolverOptions {
  BoundaryConditions boundaries;
  ArtificialViscosity viscosity;
  Limiter limiter = Limiter::minmax;
};

//! Primitive state at a point, used to initialise the grid.
struct GasPoint {
  double density;          //!< [kg/m3]
  double internal_energy;  //!< [J/kg]
  double velocity_x;       //!< [m/s]
  double velocity_y;       //!< [m/s]
};

//! Interpolated state at a sample point (bilinear from the staggered arrays).
struct GasSample {
  double x, y;  //!< [m]
  double rho;   //!< [kg/m3]
  double u, v;  //!< [m/s]
  double p;     //!< [Pa]
  double e;     //!< [J/kg]
};

//! Integrals over the active cells (per unit depth of the 2-D domain).
struct GasTotals {
  double mass = 0;             //!< [kg/m]
  double momentum_x = 0;       //!< [kg/s]
  double momentum_y = 0;       //!< [kg/s]
  double internal_energy = 0;  //!< [J/m]
  double kinetic_energy = 0;   //!< [J/m], from cell-centred (face-averaged) velocities
  double total_energy() const { return internal_energy + kinetic_energy; }
};

//! Cell-centred copy of the state on the host (i fastest), for output.
struct HostGasFields {
  int nx = 0, ny = 0;
  std::vector<double> rho, u, v, p, e;
  std::vector<std::uint8_t> active;  //!< 1 where the cell is advanced, 0 where inactive (immersed solid)
};

}  // namespace blastsim::cip
