//! \file coupling_process.hpp
//! \brief A coupling process: one physical exchange between the gas and the rock (the immersed boundary, the
//! gas's load on the rock, the gas in the cracks, the charges), after Celeritas' actions and AMReX's physics
//! modules. A process owns its device arrays, its checkpoint records and its share of the diagnostics and of
//! the energy budget; GasRockCoupler calls its processes, in the order they were added, at each stage of a
//! coupled step (docs/architecture.md "Coupling processes").
#pragma once

#include "blastsim/cip/gas_solver.hpp"
#include "blastsim/fdem/rock_solver.hpp"
#include "blastsim/ibm/charge_types.hpp"
#include "blastsim/ibm/crack_gas.hpp"
#include "blastsim/ibm/immersed_boundary_kernels.hpp"

#include <array>
#include <limits>

namespace blastsim::ibm {

//! Cumulative effect of cells changing state (covered by rock, or uncovered) since the first rock_to_gas().
//! A covered cell's gas moves to its active neighbours (docs/coupling.md); the ambient gas given to uncovered
//! cells, and the gas of a covered cell with no active neighbour left, are the mass and energy counted here.
struct CellTransitions {
  long covered = 0;             //!< cells that became inactive
  long uncovered = 0;           //!< cells that became active
  double mass_created = 0;      //!< [kg/m] net mass added by these exceptions (negative: removed)
  double energy_created = 0;    //!< [J/m] net internal energy added by them
};

//! What the coupling reports, per unit thickness; each process fills its part (add_diagnostics()).
struct CouplingDiagnostics {
  // the gas's load on the rock (GasLoading)
  std::array<double, 2> gas_force_on_rock{};  //!< [N/m] sum over exposed edges of p L n (inward), last loads
  double gas_work_on_rock = 0;                //!< [J/m] cumulative work of the gas's loads on the rock
  // the immersed boundary (ImmersedBoundary)
  CellTransitions transitions;
  // the gas in the cracks (CrackGasCoupling)
  bool crack_gas = false;
  CrackGasTotals crack;
  // the charges (Charges)
  ChargeTotals charges;
  //! The processes' shares of the coupled energy budget [J/m] (budget.hpp): the energy they hold apart from
  //! the grid gas and the rock (the gas in the cracks), and the energy they brought in (the ambient gas of
  //! uncovered cells, less covered gas with nowhere to go; the detonation energy of burnt charge cells, less
  //! the gas those cells held).
  double energy_held = 0;
  double energy_added = 0;
};

//! What the processes work on: the two solvers, the ambient gas, and the face points' owners, which the
//! immersed boundary rasterises from the rock in every rock_to_gas() and other processes may add to (an
//! unburnt charge's walls) or read (the face forces).
struct CouplingContext {
  cip::GasSolver& gas;
  fdem::RockSolver& rock;
  cip::GasPoint ambient;    //!< the state of inactive cells, and of cells the rock uncovers
  double ambient_pressure;  //!< [Pa] of that state
  FaceOwners<Access::read_write> owners;
  bool first;  //!< this rock_to_gas() sets the run's initial masks: nothing moves, nothing is counted
  //! [m] how far from a triangle with a crack face the face points it owns may lie (the gaps of the cracks
  //! that keep their own gas: CouplingProcess::owner_margin()); 0 when every owned point lies in its triangle
  double owner_margin;
};

//! The interface of a process: a hook per stage of GasRockCoupler::step(), each a no-op unless overridden.
class CouplingProcess {
 public:
  virtual ~CouplingProcess() = default;
  //! Short name (messages).
  virtual const char* name() const = 0;

  // --- rock -> gas (GasRockCoupler::rock_to_gas()), in this order ---
  //! Marks the face points the process holds as solid in ctx.owners.
  virtual void cover(CouplingContext& /*ctx*/) {}
  //! The gas's masks, imposed velocities and the cells that change state, from the owners.
  virtual void update_cells(CouplingContext& /*ctx*/) {}
  //! After the new masks are in place (a charge's cells burn).
  virtual void after_cells(CouplingContext& /*ctx*/) {}

  // --- around the gas step of dt [s] ---
  virtual void before_gas(CouplingContext& /*ctx*/, double /*dt*/) {}
  virtual void after_gas(CouplingContext& /*ctx*/, double /*dt*/) {}

  // --- gas -> rock (GasRockCoupler::gas_to_rock()): the loads for the rock's next steps ---
  virtual void load_rock(CouplingContext& /*ctx*/) {}
  //! True when the process works before each of the rock's substeps (before_rock_step()).
  virtual bool updates_rock_steps() const { return false; }
  //! Before rock substep k (0 .. substeps - 1) of dt [s] of a coupled step; load_rock() ran before substep 0.
  virtual void before_rock_step(CouplingContext& /*ctx*/, int /*k*/, double /*dt*/) {}
  //! After the rock's `rock_substeps` steps that fill the coupled step of dt [s].
  virtual void after_rock(CouplingContext& /*ctx*/, double /*dt*/, int /*rock_substeps*/) {}

  // --- events ---
  //! True when the process needs a rock_to_gas() at gas time t [s] before the next dt is chosen (a charge
  //! lit since its last burn).
  virtual bool due(double /*t*/) const { return false; }
  //! The next time after t [s] that a step must land on (infinity: none).
  virtual double next_event(double /*t*/) const { return std::numeric_limits<double>::infinity(); }

  //! [m] how far from a triangle with a crack face the face points the process gives that triangle in cover()
  //! may lie (0: none outside their triangle).
  virtual double owner_margin(const cip::GasGrid& /*grid*/) const { return 0.0; }

  // --- what it reports and keeps ---
  virtual void add_diagnostics(const CouplingContext& /*ctx*/, CouplingDiagnostics& /*d*/) const {}
  virtual void write_checkpoint(CheckpointWriter& /*w*/) const {}
  virtual void read_checkpoint(CheckpointReader& /*r*/) {}
};

}  // namespace blastsim::ibm
