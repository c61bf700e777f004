//! \file coupler.hpp
//! \brief The immersed-boundary coupling of a GasSolver and a RockSolver through their device arrays (docs/coupling.md).
//!
//! Rock -> gas: every staggered velocity point inside a rock triangle takes the velocity interpolated from
//! the triangle's nodes; a cell whose four velocity points are all in rock is inactive and holds the ambient
//! state. Gas -> rock: every exposed rock edge (mesh boundary, faces of broken joints) gets the pressure of
//! the active cell nearest to its midpoint. Nothing leaves the device inside a step.
#pragma once

#include "blastsim/cip/gas_solver.hpp"
#include "blastsim/fdem/rock_solver.hpp"
#include "blastsim/ibm/charges.hpp"
#include "blastsim/ibm/crack_gas.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <memory>

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

//! The coupled energy budget's interface terms, per unit thickness.
struct CouplingDiagnostics {
  std::array<double, 2> gas_force_on_rock{};  //!< [N/m] sum over exposed edges of p L n (inward), last pressures
  double gas_work_on_rock = 0;                //!< [J/m] cumulative work of the edge pressures on the rock
  CellTransitions transitions;
  bool crack_gas = false;  //!< the cracks carry their own gas (enable_crack_gas())
  CrackGasTotals crack;    //!< the gas in the cracks (crack_gas only)
  ChargeTotals charges;    //!< what the charges' burnt cells put into the gas (set_charges())
};

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

//! How the grid gas loads the rock (docs/coupling.md "Gas -> rock"). Crack faces with their own gas (crack gas)
//! take that gas's pressure either way.
enum class GasLoad {
  //! The paper's rule: every exposed edge takes the pressure of the active cell it faces (or the nearest one).
  edge_pressures,
  //! The force the gas's momentum equation applied at each prescribed face, put on the rock surface it stands
  //! for, along the surface normal, with the weights that gave the face its imposed (normal) velocity: the
  //! rock receives exactly the work the gas did on its immersed faces.
  face_forces,
};
//! "edges" or "faces" (the driver's `coupling.gas_load`).
const char* gas_load_name(GasLoad load);

namespace detail {
struct CouplerArrays;
}

class GasRockCoupler {
 public:
  //! `ambient`: the state an inactive cell holds, and the one an uncovered cell starts from (the paper:
  //! 1.2 kg/m3, 2.09e5 J/kg, at rest).
  GasRockCoupler(cip::GasSolver& gas, fdem::RockSolver& rock, const cip::GasPoint& ambient);
  ~GasRockCoupler();

  //! Masks and imposed velocities from the rock's current nodes. Search: each triangle visits only the
  //! velocity points in its bounding box; a point covered by several (overlapping) triangles takes the one
  //! of highest index, found with an order-independent atomic maximum, so the result is deterministic.
  //! The first call sets every covered cell to the ambient state. Later calls keep mass and energy when
  //! cells change state: a covered cell gives its gas in equal shares to its active edge neighbours; an
  //! uncovered cell starts from the ambient state (counted in the transition ledger).
  void rock_to_gas();

  //! The grid gas's load on the rock. GasLoad::edge_pressures: pressure [Pa] on every exposed edge, that of
  //! the active cell the edge faces; where that cell is inactive, a boundary edge takes the nearest active cell
  //! within 2 cells (the paper's rule) and a crack face the ambient pressure (a crack narrower than the grid
  //! holds no gas). GasLoad::face_forces: forces [N/m] on the nodes from the prescribed faces (FaceLoadKernel),
  //! edge pressures 0. Crack faces with their own gas take its pressure in both.
  void gas_to_rock();

  //! Chooses how the grid gas loads the rock (default: GasLoad::edge_pressures, the paper's rule); it also
  //! chooses how the face points take the rock's velocity (face_point_coupling()). Call before the first
  //! step; a checkpoint records it and read_checkpoint() refuses another choice.
  void set_gas_load(GasLoad load) { gas_load_ = load; }
  GasLoad gas_load() const { return gas_load_; }

  //! One coupled step of dt [s]: rock_to_gas(), gas step, gas_to_rock(), then `rock_substeps` rock steps of
  //! dt / rock_substeps under those edge pressures (1: the paper's single dt; more: the rock subcycles a gas
  //! step longer than its stable step, docs/coupling.md), then fire_due_charges(). With crack gas: after rock_to_gas() the cracks'
  //! geometry, after the gas step their mouths (from the cells' new gas), their own steps (as many as their
  //! Courant limit needs) and what they gave to or took from the grid cells. The host waits once, at the end,
  //! for the gas's signal rate and the rock's largest speed in one reduction (signal_rate()); without crack gas
  //! and charges no other value crosses to the host.
  void step(double dt, int rock_substeps = 1);
  //! The gas's largest signal rate [1/s] after the last step() (+infinity on an invalid gas state), as
  //! cip::GasSolver::max_signal_rate() gives it; NaN before the first step.
  double signal_rate() const { return signal_rate_; }

  //! Gives every broken joint its own gas (docs/coupling.md "Gas in the cracks"): a 1-D channel network on the
  //! broken joints, joined at the mesh vertices, opening into the grid gas where a junction lies in an active
  //! cell or on the mesh outline beside one; each crack face is loaded by its channel's pressure. Call before
  //! the first step (and before read_checkpoint()). Throws InputError on bad options, or if the rock was
  //! built without mesh vertices (FdemTopology::node_vertex).
  void enable_crack_gas(const CrackGasOptions& options);
  const CrackGas* crack_gas() const { return crack_.get(); }
  //! Largest gas pressure [Pa] of the cracks at their mouths on the mesh outline farther than `radius` [m]
  //! from `center` (e.g. on the outer free face of a disc around a hole); 0 without crack gas (a device
  //! reduction).
  double crack_mouth_pressure(std::array<double, 2> center, double radius) const;
  //! The crack gas's front [m]: the largest distance from `center` of the midpoint of a crack that holds its
  //! own gas above `pressure` [Pa] (e.g. a quarter of the blasthole's pressure: how far the hole's gas has gone
  //! through the crack network); 0 when none does or without crack gas (a device reduction).
  double crack_gas_front(std::array<double, 2> center, double pressure) const;
  CrackGas* crack_gas() { return crack_.get(); }

  //! Places explosive charges in the gas (docs/coupling.md "Charges"): the cells whose centres lie in a charge's
  //! circle are its cells; until their lighting time (lighting_time()) they are a solid at rest that keeps its
  //! volume, then rock_to_gas() burns them: products at `products`' density and energy, the change recorded in
  //! the charge ledger (diagnostics().charges, the energy budget). Call before the first rock_to_gas() and
  //! before read_checkpoint(). Throws InputError: the gas has no products material, a charge larger than its
  //! hole or without a cell centre inside it, two charges sharing a cell, a point initiation without a positive
  //! detonation velocity, a bad products state.
  void set_charges(const std::vector<Charge>& charges, const ChargeProducts& products);
  const std::vector<Charge>& charges() const { return charges_; }
  //! Per charge: the borehole pressure [Pa], the mean pressure of the active cells whose centres lie within
  //! its hole radius (the ambient pressure when none is active).
  std::vector<double> charge_pressures() const;
  //! Per charge: its detonation energy released so far [J/m] (rho0 e0 times the area of its burnt cells).
  std::vector<double> charge_energies() const;
  //! The earliest initiation time of a charge later than t [s] (infinity when none): a stepper lands a step
  //! on it, so that a charge fires at its time and not up to a step later.
  double next_initiation(double t) const;
  //! Burns the charge cells lit by now (a rock_to_gas() when any charge has cells due), so that the next dt
  //! sees the products. step() calls it at its end; call it once after the first rock_to_gas() (and after the
  //! run's initial outputs) when a charge fires at t = 0, before the first dt is chosen.
  void fire_due_charges();

  //! Largest dt [s] that both solvers accept: min(gas Courant limit at `courant`, rock stable step).
  double stable_dt(double courant) const;

  //! Number of inactive (rock-covered) cells, for diagnostics and tests.
  long inactive_cells() const;
  //! Force of the gas on the rock, its cumulative work and the cell-transition ledger (device reductions).
  CouplingDiagnostics diagnostics() const;
  //! The coupler's own state (whether the masks are set, the transition ledger) in a checkpoint; the solvers
  //! write theirs separately.
  void write_checkpoint(CheckpointWriter& w) const;
  void read_checkpoint(CheckpointReader& r);

  //! Gas mass and energy in the active cells whose centres lie in `region`.
  cip::GasTotals gas_in(const cip::CellRegion& region) const { return gas_.totals(region); }

 private:
  cip::GasSolver& gas_;
  fdem::RockSolver& rock_;
  cip::GasPoint ambient_;
  bool masks_set_ = false;
  GasLoad gas_load_ = GasLoad::edge_pressures;
  std::unique_ptr<CrackGas> crack_;
  std::vector<Charge> charges_;
  ChargeProducts products_;
  std::vector<std::array<double, 2>> charge_window_;  // per charge: its first and last lighting time [s]
  double burnt_until_ = 0;  // gas time of the last rock_to_gas() that burnt (every cell lit by then is burnt)
  double signal_rate_ = std::numeric_limits<double>::quiet_NaN();  // the gas's, read with the rock's speed
  bool charges_due(double t) const;
  void crack_geometry();
  void crack_mouths();
  void apply_crack_deposits();
  double mat_ambient_pressure() const;  // the ambient state's pressure [Pa]
  // Padded-shape work arrays (owners of the face points, the mask being built, the moved gas) and the
  // transition ledger, behind the class (coupler.cpp).
  std::unique_ptr<detail::CouplerArrays> a_;
};

}  // namespace blastsim::ibm
