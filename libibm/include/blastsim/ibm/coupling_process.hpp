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
#include "blastsim/ibm/crack_gas_types.hpp"
#include "blastsim/ibm/immersed_boundary_kernels.hpp"

#include <array>
#include <limits>
#include <vector>

namespace blastsim {
class CsvRecord;  // core/output_files.hpp
}

namespace blastsim::ibm {

//! Cumulative effect of cells changing state (covered by rock, or uncovered) since the first rock_to_gas().
//! A covered cell's gas moves to its active neighbours (docs/coupling.md); the ambient gas given to uncovered
//! cells, and the gas of a covered cell with no active neighbour left, are the mass and energy counted here.
struct CellTransitions {
  long covered = 0;             //!< cells that became inactive
  long uncovered = 0;           //!< cells that became active
  double mass_created = 0;      //!< [kg/m] net mass added by these exceptions (negative: removed)
  double energy_created = 0;    //!< [J/m] net internal energy added by them
  double mass_lost = 0;         //!< [kg/m] of that, the gas of covered cells that had nowhere to go (>= 0)
  double energy_lost = 0;       //!< [J/m] likewise
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
  //! Which cells a process claims (ImmersedBoundary::claims()): the gas of a claimed cell covered with no
  //! stable cell beside it goes to `taken` instead of being lost
  CellClaims<Access::read_write> claims;
  bool first;  //!< this rock_to_gas() sets the run's initial masks: nothing moves, nothing is counted
  //! [m] how far from a triangle with a crack face the face points it owns may lie (the gaps of the cracks
  //! that keep their own gas: CouplingProcess::owner_margin()); 0 when every owned point lies in its triangle
  double owner_margin;
};

//! The stages of a coupled step, in the order GasRockCoupler runs them (docs/coupling.md "The coupled step").
//! rock -> gas (GasRockCoupler::rock_to_gas()): cover, update_cells, after_cells; around the gas step:
//! before_gas, after_gas; gas -> rock (gas_to_rock()): load_rock; the rock's substeps: before_rock_step before
//! each, after_rock after the last.
enum class Stage : int { cover, update_cells, after_cells, before_gas, after_gas, load_rock, before_rock_step, after_rock };
inline constexpr int kStageCount = 8;
//! "cover", "update_cells", ... (the schedule's listing).
const char* stage_name(Stage s);

//! The step a stage runs in: dt [s] is the coupled step's, except in Stage::before_rock_step, where it is the
//! rock substep's; substep: that substep (0 .. rock_substeps - 1).
struct StageStep {
  double dt = 0;
  int substep = 0;
  int rock_substeps = 1;
};

//! The interface of a process: it declares the stages it runs (data: GasRockCoupler builds its schedule from
//! them once, when the process is added, and can print it), and runs each in run().
class CouplingProcess {
 public:
  virtual ~CouplingProcess() = default;
  //! Short name (messages, the schedule).
  virtual const char* name() const = 0;
  //! The stages this process runs, each once per occurrence in a step (GasRockCoupler::schedule()).
  virtual std::vector<Stage> stages() const = 0;
  //! Runs `stage`, one of stages().
  virtual void run(Stage stage, CouplingContext& ctx, const StageStep& step) = 0;

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
  //! Adds its part to the coupling's diagnostics (device reductions).
  virtual void add_diagnostics(const CouplingContext& /*ctx*/, CouplingDiagnostics& /*d*/) const {}
  //! Its columns of the coupling's time series, named with their units, from its part of `d` (a record the caller
  //! writes without knowing the process: GasRockCoupler::report()); in o.header() mode d is all zeros.
  virtual void report(const CouplingDiagnostics& /*d*/, CsvRecord& /*o*/) const {}
  virtual void write_checkpoint(CheckpointWriter& /*w*/) const {}
  virtual void read_checkpoint(CheckpointReader& /*r*/) {}
};

//! Throws std::logic_error naming the process and the stage: run() was given a stage the process does not
//! declare (a process's run() ends its switch with it).
[[noreturn]] void stage_not_run(const CouplingProcess& process, Stage stage);

}  // namespace blastsim::ibm
