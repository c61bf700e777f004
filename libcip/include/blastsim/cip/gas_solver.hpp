//! \file gas_solver.hpp
//! \brief The CIP compressible-gas solver of the paper's eqs. (1)-(5) with a device-array interface.
#pragma once

#include "blastsim/core/checkpoint_fwd.hpp"
#include "blastsim/cip/eos.hpp"
#include "blastsim/cip/gas_state.hpp"
#include "blastsim/cip/gas_step_kernels.hpp"
#include "blastsim/cip/gas_types.hpp"
#include "blastsim/cip/grid.hpp"

#include <array>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace blastsim::cip {

struct BoundaryContext;
struct StepViews;
namespace detail {
struct GasArrays;
}

//! One gas solver on one grid. The state lives in device memory behind the class (this header needs no
//! backend headers); state() and immersed_boundary() expose views of it so a coupler can read pressures and
//! impose solid velocities without host copies.
class GasSolver {
 public:
  //! One material, the gas `eos` everywhere.
  GasSolver(const GasGrid& grid, const EquationOfState& eos, const GasSolverOptions& options = {});
  //! Two materials when materials.two (air and detonation products, eos.hpp GasMaterials); needs the
  //! conservative transport (InputError otherwise).
  GasSolver(const GasGrid& grid, const GasMaterials& materials, const GasSolverOptions& options = {});
  ~GasSolver();
  GasSolver(GasSolver&&) noexcept;
  GasSolver& operator=(GasSolver&&) noexcept;

  const GasGrid& grid() const { return grid_; }
  //! The air's equation of state (the only one in a one-material run).
  const EquationOfState& eos() const { return materials_.air; }
  const GasMaterials& materials() const { return materials_; }
  const GasSolverOptions& options() const { return options_; }
  double time() const { return time_; }          //!< [s] simulated time
  long long steps() const { return steps_; }     //!< steps taken

  //! Sets rho, e at cell centres and u, v at their faces from a host function of position [m]; the
  //! derivatives from limited centred differences (zero in uniform regions and beside jumps between
  //! them, as in the paper's Table 1); fills the ghosts. Also takes the outflow reference state.
  void initialise(const std::function<GasPoint(double x, double y)>& state_at);

  //! Views of the current state; after writing interior values, call apply_boundaries().
  GasStateView state();
  GasStateReadView state() const;  //!< read-only view, for queries
  //! Views of the products' volume fraction and partial density (empty fields in a one-material run); after
  //! writing interior values, call apply_boundaries().
  MaterialView material_fields();
  MaterialReadView material_fields() const;
  //! The cells with their material fields, for a coupler that moves gas between them (gas_state.hpp); after
  //! writing, call apply_boundaries().
  GasCells cells();
  GasCellsRead cells() const;
  ImmersedBoundaryView immersed_boundary();
  ImmersedBoundaryReadView immersed_boundary() const;
  //! Cell-centred pressure p + q of the last step's non-advection phase [Pa] (padded shape).
  Field2D<double> pressure_with_viscosity();

  //! Fills ghost values from the outer boundary conditions. initialise() and step() leave them filled;
  //! call this after writing to the interior through state().
  void apply_boundaries();

  //! max over active cells of max((|u_c| + c)/dx, (|v_c| + c)/dy) [1/s]; +infinity when any active cell
  //! holds a non-finite or non-positive density or internal energy (see describe_invalid_cell()).
  double max_signal_rate() const;
  //! Device functor: the signal rate of cell k (k = j nx + i) as max_signal_rate() reduces it, for callers that
  //! fuse it with a reduction of their own (one wait for the host instead of two).
  SignalRate signal_rate_kernel() const;
  //! Largest dt [s] with Courant number `courant`: courant / max_signal_rate().
  double courant_dt(double courant) const { return courant / max_signal_rate(); }

  //! Advances one step of dt [s]: ghosts, P = p + q, non-advection, derivative update, CIP advection.
  void step(double dt);

  //! Totals over the active cells whose centres lie in `region` (default: the whole grid).
  GasTotals totals(const CellRegion& region = {}) const;
  //! Cumulative flow out through the outer boundary since initialise(): kept per boundary face on the
  //! device every step, summed here (the host waits for the sum).
  BoundaryOutflow boundary_outflow() const;
  //! Cumulative energy [J/m] that immersed (prescribed) faces gave the gas: where setting such a face to the
  //! solid's velocity leaves its dual cell a negative kinetic-energy balance, the deficit is not taken from
  //! the gas's internal energy but counted here (conservative transport; docs/gas-solver.md). A coupled
  //! budget counts it as work of the rock on the gas.
  double immersed_face_work() const;
  //! Cumulative energy [J/m] added to the gas where the kinetic-energy correction of the conservative
  //! transport would have taken more than half a cell's internal energy in one step (near-vacuum
  //! rarefactions; transport_kernels.hpp, kMaxCorrectionFraction). Zero in most runs; a balance counts it as
  //! a source.
  double positivity_energy() const;
  //! The traced gas's reach [m]: the largest distance from `center` of an active cell centre within
  //! `max_radius` [m] that holds at least `min_fraction` of the traced gas (the products, or the tracer's) at
  //! a pressure of at least `min_pressure` [Pa]; 0 when none does or nothing is traced (a device reduction).
  double traced_reach(std::array<double, 2> center, double min_fraction, double min_pressure, double max_radius) const;
  //! Samples the gas at host points [m] (a device gather; cost independent of the grid size).
  std::vector<GasSample> sample(const std::vector<std::array<double, 2>>& points) const;
  HostGasFields to_host() const;
  //! Describes the first active cell with a non-finite or non-positive density or energy ("" if none).
  std::string describe_invalid_cell() const;

  //! Appends the state that carries from one step to the next (fields with derivatives, immersed-boundary
  //! input, outflow reference and balance, time, step count) to a checkpoint; read_checkpoint() restores it
  //! into a solver built with the same grid, so the run continues bit for bit.
  void write_checkpoint(CheckpointWriter& w) const;
  void read_checkpoint(CheckpointReader& r);

 private:
  BoundaryContext boundary_context() const;
  StepViews step_views() const;
  bool fuse_kernels() const;  // options_.fusion resolved for this backend
  void transport_conservatively(double dt);
  void accumulate_boundary_outflow(double dt);
  GasGrid grid_;
  GasMaterials materials_;
  GasSolverOptions options_;
  std::unique_ptr<detail::GasArrays> a_;  // every device array (gas_storage.hpp)
  double time_ = 0.0;
  long long steps_ = 0;
};

//! Marks a fixed solid through the immersed-boundary input: faces whose point lies inside get velocity 0,
//! cells whose four faces all lie inside become inactive. `inside` is evaluated on the host.
void mark_static_solid(GasSolver& solver, const std::function<bool(double x, double y)>& inside);

}  // namespace blastsim::cip
