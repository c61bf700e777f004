//! \file budget.cpp
//! \brief The coupled energy budget from the solvers' and the coupler's totals (host reductions).
#include "blastsim/ibm/budget.hpp"

namespace blastsim::ibm {

double initial_energy(const cip::GasSolver& gas, const fdem::RockSolver& rock) {
  const fdem::RockEnergies e = rock.energies();
  return gas.totals().total_energy() + e.kinetic + e.strain;
}

CoupledBudget coupled_budget(const cip::GasSolver& gas, const fdem::RockSolver& rock, const GasRockCoupler& coupler,
                             double initial) {
  CoupledBudget b;
  b.gas = gas.totals();
  b.rock = rock.energies();
  b.coupling = coupler.diagnostics();
  b.gas_energy_out = gas.boundary_outflow().energy;
  b.other_external_work = b.rock.external_work - b.rock.pressure_work;
  const fdem::RockEnergies& e = b.rock;
  const CouplingDiagnostics& d = b.coupling;  // the processes' shares: held (crack gas), added (cells, charges)
  const double now = b.gas.total_energy() + d.energy_held + b.gas_energy_out + e.kinetic + e.strain + e.joint_work +
                     e.contact_work + e.damping_dissipated;
  b.immersed_face_work = gas.immersed_face_work();
  b.positivity_energy = gas.positivity_energy();
  const ChargeTotals& q = d.charges;  // what burning put into the cells, less what they held
  b.charge_energy = q.detonation_energy - q.replaced_energy;
  b.residual = now - (initial + b.other_external_work + d.energy_added + b.immersed_face_work + b.positivity_energy);
  return b;
}

}  // namespace blastsim::ibm
