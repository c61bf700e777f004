//! \file coupler.hpp
//! \brief The immersed-boundary coupling of a GasSolver and a RockSolver through their device arrays
//! (docs/coupling.md): an ordered list of coupling processes (coupling_process.hpp) - the immersed boundary
//! (rock -> gas), the gas's load on the rock (gas -> rock), and, when enabled, the gas in the cracks and the
//! explosive charges - called at each stage of a coupled step. Nothing leaves the device inside a step but
//! one reduction at its end.
#pragma once

#include "blastsim/cip/gas_solver.hpp"
#include "blastsim/fdem/rock_solver.hpp"
#include "blastsim/ibm/charges.hpp"
#include "blastsim/ibm/coupling_options.hpp"
#include "blastsim/ibm/coupling_process.hpp"
#include "blastsim/ibm/crack_gas_coupling.hpp"
#include "blastsim/ibm/gas_loading.hpp"
#include "blastsim/ibm/immersed_boundary.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace blastsim::ibm {

//! Rock steps that fill a gas step of dt [s] without exceeding the rock step rock_dt [s] (rock subcycling;
//! a small relative allowance keeps a dt equal to rock_dt up to rounding at one substep).
inline int rock_substeps(double dt, double rock_dt) {
  return std::max(1, static_cast<int>(std::ceil(dt / rock_dt * (1 - 1e-12))));
}

//! One coupled step: its dt [s] and the number of rock steps that fill it.
struct CoupledStep {
  double dt;
  int rock_substeps;
};

//! The coupled step's dt policy (docs/coupling.md), from time t [s]: the gas's Courant limit gas_dt [s] and,
//! unless the rock subcycles, the rock's step rock_dt [s] (the paper's single dt), shortened to land on
//! `until` [s] (an output time); with subcycling the rock fills the step with rock_substeps(dt, rock_dt) steps.
inline CoupledStep plan_coupled_step(double t, double gas_dt, double rock_dt, bool subcycling, double until) {
  double dt = subcycling ? gas_dt : std::min(gas_dt, rock_dt);
  if (t + dt > until) dt = until - t;
  return {dt, subcycling ? rock_substeps(dt, rock_dt) : 1};
}


class GasRockCoupler {
 public:
  //! The immersed boundary and the gas load as its first processes. `ambient`: the state an inactive cell holds,
  //! and the one an uncovered cell starts from (the paper: 1.2 kg/m3, 2.09e5 J/kg, at rest).
  GasRockCoupler(cip::GasSolver& gas, fdem::RockSolver& rock, const cip::GasPoint& ambient,
                 const CouplerOptions& options = {});
  ~GasRockCoupler();

  // --- processes (add before the first step and before read_checkpoint()) ---
  //! Gives every broken joint its own gas (CrackGasCoupling; docs/coupling.md "Gas in the cracks"); walls at the
  //! ambient air's temperature unless options.wall_theta says otherwise.
  CrackGasCoupling& enable_crack_gas(const CrackGasOptions& options);
  //! Places explosive charges in the gas (Charges; docs/coupling.md "Charges").
  Charges& set_charges(const std::vector<Charge>& charges, const ChargeProducts& products);
  //! Any other process, after the ones already there: it joins the schedule of each stage it declares.
  CouplingProcess& add(std::unique_ptr<CouplingProcess> process);
  //! The schedule: per stage, in the order they run, the processes that run it ("cover: immersed boundary,
  //! crack gas"), one line a stage; a stage no process runs is left out.
  std::string schedule() const;
  const CrackGasCoupling* crack_gas() const { return crack_; }  //!< null unless enabled
  CrackGasCoupling* crack_gas() { return crack_; }
  const Charges* charges() const { return charges_; }           //!< null without charges

  // --- stepping ---
  //! Rock -> gas: every process's cover(), update_cells() and after_cells(), then the gas's ghosts. The first
  //! call sets the run's initial masks (cells under rock take the ambient state, nothing is counted); a run
  //! makes it before its first outputs.
  void rock_to_gas();
  //! Gas -> rock: every process's load_rock(), for the rock's next steps.
  void gas_to_rock();
  //! The next step toward `until` [s] (an output time): charges lit by now burn first (a rock_to_gas(): at
  //! t = 0 after the run's first outputs, so that the products' sound speed sets the first dt); then dt is
  //! the fixed dt, or the Courant limit at the gas's signal rate (signal_rate()) and, without subcycling, the
  //! rock's step, shortened to land on `until` and on the next process event (a charge's initiation).
  CoupledStep plan_step(double until);
  //! One coupled step of dt [s]: rock_to_gas(), before_gas(), the gas step, after_gas(), gas_to_rock(), then
  //! `rock_substeps` rock steps of dt / rock_substeps (1: the paper's single dt; more: the rock subcycles,
  //! docs/coupling.md), then the charges lit by the new time burn. The host waits once, at the end, for the
  //! gas's signal rate and the rock's largest speed in one reduction (with crack gas more: the two sorts of
  //! its deposit records, and the channels' stable step before each rock substep). Throws InstabilityError on a non-finite rock.
  void step(double dt, int rock_substeps = 1);
  //! The gas's largest signal rate [1/s] for the next dt (+infinity on an invalid gas state): read with the
  //! rock's speed after step(), or by plan_step(); NaN before either.
  double signal_rate() const { return signal_rate_; }
  //! Largest dt [s] that both solvers accept: min(gas Courant limit at `courant`, rock stable step).
  double stable_dt(double courant) const;
  //! [-] the Courant number plan_step() uses: CouplerOptions::courant, or recommended_courant() of the gas's
  //! transport and the gas load.
  double courant() const {
    return options_.courant.value_or(recommended_courant(gas_.options().transport, options_.gas_load));
  }

  // --- diagnostics (device reductions) ---
  //! What every process reports, summed into one record (coupling_process.hpp).
  CouplingDiagnostics diagnostics() const;
  //! Every process's columns of the coupling's time series from `d` (diagnostics(); zeros in header mode), in
  //! the order the processes were added: a record the caller writes without knowing the processes.
  void report(const CouplingDiagnostics& d, CsvRecord& o) const;
  //! Number of inactive (rock-covered) cells.
  long inactive_cells() const;
  //! Gas mass and energy in the active cells whose centres lie in `region`.
  cip::GasTotals gas_in(const cip::CellRegion& region) const { return gas_.totals(region); }
  //! The ambient state's pressure [Pa].
  double ambient_pressure() const;

  //! Whether the masks are set, and every process's own records; the solvers write theirs separately.
  void write_checkpoint(CheckpointWriter& w) const;
  void read_checkpoint(CheckpointReader& r);

 private:
  CouplingContext context() const;
  void fire_due();  // a rock_to_gas() when a process is due at the gas's time (masks set)
  cip::GasSolver& gas_;
  fdem::RockSolver& rock_;
  cip::GasPoint ambient_;
  CouplerOptions options_;
  std::vector<std::unique_ptr<CouplingProcess>> processes_;  // in the order added
  std::array<std::vector<CouplingProcess*>, kStageCount> schedule_;  // per stage, the processes that run it
  //! Runs `stage` of every process scheduled for it, in order.
  void run(Stage stage, CouplingContext& ctx, const StageStep& step = {});
  ImmersedBoundary* immersed_ = nullptr;  // the first process: its face owners are everyone's
  CrackGasCoupling* crack_ = nullptr;
  Charges* charges_ = nullptr;
  bool masks_set_ = false;
  double signal_rate_ = std::numeric_limits<double>::quiet_NaN();  // the gas's, for the next dt
};

}  // namespace blastsim::ibm
