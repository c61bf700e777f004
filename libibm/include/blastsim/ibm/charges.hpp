//! \file charges.hpp
//! \brief Explosive charges in blastholes as a coupling process (docs/coupling.md "Charges"): the cells whose
//! centres lie in a charge's circle are its cells; until their lighting time (lighting_time()) they are a solid
//! at rest that keeps its volume, then they burn: products at the explosive's density and detonation energy,
//! the change recorded in a ledger (the energy budget).
#pragma once

#include "blastsim/ibm/charge_types.hpp"
#include "blastsim/ibm/coupling_process.hpp"

#include <array>
#include <memory>
#include <vector>

namespace blastsim::ibm {

namespace detail {
struct ChargeArrays;
}

//! A coupling process (coupling_process.hpp).
class Charges : public CouplingProcess {
 public:
  //! Throws InputError: the gas has no products material, a charge larger than its hole or without a cell
  //! centre inside it, two charges sharing a cell, a point initiation without a positive detonation velocity, a
  //! bad products state.
  Charges(const cip::GasSolver& gas, const std::vector<Charge>& charges, const ChargeProducts& products);
  ~Charges() override;
  const char* name() const override { return "charges"; }

  const std::vector<Charge>& charges() const { return charges_; }
  const ChargeProducts& products() const { return products_; }

  std::vector<Stage> stages() const override { return {Stage::cover, Stage::after_cells}; }
  void run(Stage stage, CouplingContext& ctx, const StageStep& step) override;
  //! A charge has cells lit by t that have not burnt.
  bool due(double t) const override;
  //! The earliest initiation time of a charge later than t [s]: a step lands on it, so that a charge fires at
  //! its time and not up to a step later.
  double next_event(double t) const override;

  //! Per charge: the borehole pressure [Pa], the mean pressure of the active cells whose centres lie within its
  //! hole radius (`ambient_pressure` when none is active).
  std::vector<double> pressures(const cip::GasSolver& gas, double ambient_pressure) const;
  //! Per charge: its detonation energy released so far [J/m] (rho0 e0 times the area of its burnt cells).
  std::vector<double> energies(const cip::GasSolver& gas) const;

  //! What the burnt cells put in; their energy less what the cells held is energy added (the budget).
  void add_diagnostics(const CouplingContext& ctx, CouplingDiagnostics& d) const override;
  //! charge_detonation_energy_J_per_m (all charges).
  void report(const CouplingDiagnostics& d, CsvRecord& o) const override;
  void write_checkpoint(CheckpointWriter& w) const override;
  void read_checkpoint(CheckpointReader& r) override;

 private:
  //! An unburnt charge's cells: every face point of theirs that no triangle covers becomes a wall at rest.
  void cover(CouplingContext& ctx);
  //! The charge cells lit since the last burn burn (from the second rock_to_gas() on: the first sets the run's
  //! initial state, and the budget counts what burning adds).
  void after_cells(CouplingContext& ctx);
  std::vector<Charge> charges_;
  ChargeProducts products_;
  std::vector<std::array<double, 2>> window_;  // per charge: its first and last lighting time [s]
  double burnt_until_;  // gas time of the last burn (every cell lit by then has burnt)
  std::unique_ptr<detail::ChargeArrays> a_;
};

}  // namespace blastsim::ibm
