//! \file gas_solver.hpp
//! \brief The CIP compressible-gas solver of the paper's eqs. (1)-(5) with a device-array interface.
#pragma once

#include "blastsim/cip/boundary.hpp"
#include "blastsim/cip/cip_kernels.hpp"
#include "blastsim/cip/eos.hpp"
#include "blastsim/cip/gas_state.hpp"
#include "blastsim/cip/grid.hpp"

#include <array>
#include <functional>
#include <string>
#include <vector>

namespace blastsim::cip {

struct BoundaryContext;

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

//! One gas solver on one grid. The state lives in device memory; state() and immersed_boundary() expose
//! views of it so a coupler can read pressures and impose solid velocities without host copies.
class GasSolver {
 public:
  GasSolver(const GasGrid& grid, const EquationOfState& eos, const GasSolverOptions& options = {});

  const GasGrid& grid() const { return grid_; }
  const EquationOfState& eos() const { return eos_; }
  const GasSolverOptions& options() const { return options_; }
  double time() const { return time_; }          //!< [s] simulated time
  long long steps() const { return steps_; }     //!< steps taken

  //! Sets rho, e at cell centres and u, v at their faces from a host function of position [m]; the
  //! derivatives from limited centred differences (zero in uniform regions and beside jumps between
  //! them, as in the paper's Table 1); fills the ghosts. Also takes the outflow reference state.
  void initialise(const std::function<GasPoint(double x, double y)>& state_at);

  GasStateView state() { return state_.view(grid_.padded_shape()); }
  ImmersedBoundaryView immersed_boundary() { return immersed_.view(grid_.padded_shape()); }
  //! Cell-centred pressure p + q of the last step's non-advection phase [Pa] (padded shape).
  Field2D<double> pressure_with_viscosity() { return make_field_view(pressure_, grid_.padded_shape()); }

  //! Fills ghost values from the outer boundary conditions.
  void apply_boundaries();

  //! max over active cells of max((|u_c| + c)/dx, (|v_c| + c)/dy) [1/s]; +infinity when any active cell
  //! holds a non-finite or non-positive density or internal energy (see describe_invalid_cell()).
  double max_signal_rate();
  //! Largest dt [s] with Courant number `courant`: courant / max_signal_rate().
  double courant_dt(double courant) { return courant / max_signal_rate(); }

  //! Advances one step of dt [s]: ghosts, P = p + q, non-advection, derivative update, CIP advection.
  void step(double dt);

  GasTotals totals();
  //! Samples the gas at host points [m] (a device gather; cost independent of the grid size).
  std::vector<GasSample> sample(const std::vector<std::array<double, 2>>& points);
  HostGasFields to_host();
  //! Describes the first active cell with a non-finite or non-positive density or energy ("" if none).
  std::string describe_invalid_cell();

 private:
  BoundaryContext boundary_context() const;
  GasGrid grid_;
  EquationOfState eos_;
  GasSolverOptions options_;
  GasState state_;      // current state (n)
  GasState starred_;    // after the non-advection phase (*)
  ImmersedBoundaryArrays immersed_;
  DeviceVector<double> pressure_;  // P = p + q
  DeviceVector<double> outflow_pressure_, outflow_velocity_;  // OutflowReference, set by initialise()
  double time_ = 0.0;
  long long steps_ = 0;
};

//! Marks a fixed solid through the immersed-boundary input: faces whose point lies inside get velocity 0,
//! cells whose four faces all lie inside become inactive. `inside` is evaluated on the host.
void mark_static_solid(GasSolver& solver, const std::function<bool(double x, double y)>& inside);

}  // namespace blastsim::cip
