//! \file budget.cpp
//! \brief The coupled energy budget from the solvers' and the coupler's totals (host reductions).
#include "blastsim/ibm/budget.hpp"

#include "blastsim/core/output_files.hpp"

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
  b.relative = b.residual / (initial + b.charge_energy);
  return b;
}

void budget_columns(const CoupledBudget& b, const GasRockCoupler& coupler, CsvRecord& o) {
  const cip::GasTotals& g = b.gas;
  const fdem::RockEnergies& e = b.rock;
  o.real("gas_mass_kg_per_m", g.mass).real("gas_internal_J_per_m", g.internal_energy);
  o.real("gas_kinetic_J_per_m", g.kinetic_energy).real("gas_energy_out_J_per_m", b.gas_energy_out);
  o.real("rock_kinetic_J_per_m", e.kinetic).real("rock_strain_J_per_m", e.strain).real("joint_work_J_per_m", e.joint_work);
  o.real("fracture_dissipated_J_per_m", e.fracture_dissipated).real("contact_work_J_per_m", e.contact_work);
  o.real("damping_dissipated_J_per_m", e.damping_dissipated).real("other_external_work_J_per_m", b.other_external_work);
  o.real("immersed_face_work_J_per_m", b.immersed_face_work).real("budget_residual_J_per_m", b.residual, 6);
  o.real("budget_relative", b.relative, 6).integer("broken_joints", e.broken_joints);
  o.real("crack_length_m", e.crack_length, 6);
  coupler.report(b.coupling, o);
}

}  // namespace blastsim::ibm
