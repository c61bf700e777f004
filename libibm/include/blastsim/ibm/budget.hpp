//! \file budget.hpp
//! \brief The energy budget of a coupled gas-rock run (docs/validation.md, S4): what the gas and the rock hold
//! and did, against the initial energy and what came in from outside.
#pragma once

#include "blastsim/cip/gas_solver.hpp"
#include "blastsim/fdem/rock_solver.hpp"
#include "blastsim/ibm/coupler.hpp"

namespace blastsim::ibm {

//! Every term of the budget at one moment, per unit thickness [J/m] (forces [N/m]).
struct CoupledBudget {
  cip::GasTotals gas;             //!< gas in the active cells
  double gas_energy_out = 0;      //!< carried out through the grid's outer boundary since the start
  fdem::RockEnergies rock;        //!< the rock's energies and work
  CouplingDiagnostics coupling;   //!< interface force, gas work on the rock, cell-transition ledger
  double other_external_work = 0;  //!< work on the rock of loads other than the gas (supports, gravity)
  double immersed_face_work = 0;  //!< energy the rock's moving faces gave the gas (GasSolver::immersed_face_work)
  double positivity_energy = 0;   //!< energy the gas transport's positivity bound added (GasSolver::positivity_energy)
  double charge_energy = 0;       //!< detonation energy of the burnt charge cells less the gas they held (ChargeTotals)
  //! (gas energy + the energy the coupling processes hold (the cracks' gas) + gas out + rock kinetic + strain +
  //! joint work + contact work + damping) - (initial energy + other external work + the energy the processes
  //! added (cell transitions, burnt charges) + immersed-face work + positivity energy): zero for an exact budget.
  double residual = 0;
  double relative = 0;  //!< [-] residual / (initial energy + charge_energy)
};

//! The energy a budget starts from: gas total energy plus rock kinetic and strain energy [J/m].
double initial_energy(const cip::GasSolver& gas, const fdem::RockSolver& rock);

//! The budget now, against `initial` (initial_energy() at the start of the run).
CoupledBudget coupled_budget(const cip::GasSolver& gas, const fdem::RockSolver& rock, const GasRockCoupler& coupler,
                             double initial);

//! The budget's columns of the coupling's time series (docs/input.md, coupling_series.csv): the gas's and the
//! rock's terms, the residual and its relative value, the broken joints and the crack length; then every
//! process's own columns (GasRockCoupler::report()). In o.header() mode b is not read.
void budget_columns(const CoupledBudget& b, const GasRockCoupler& coupler, CsvRecord& o);

}  // namespace blastsim::ibm
