//! \file gas_loading.hpp
//! \brief The grid gas's load on the rock, gas -> rock (docs/coupling.md "Gas -> rock", "Face forces"): the
//! paper's edge pressures, or the forces of the prescribed faces.
#pragma once

#include "blastsim/ibm/coupling_options.hpp"
#include "blastsim/ibm/coupling_process.hpp"
#include "blastsim/ibm/immersed_boundary.hpp"

#include <memory>

namespace blastsim::ibm {


namespace detail {
struct LoadWorkArrays;
struct EdgeWorkArrays;
}

//! A coupling process (coupling_process.hpp): the edge pressures [Pa] on every exposed edge (edge_pressures),
//! or the face forces [N/m] on the nodes with all edge pressures 0 (face_forces), for the rock's next steps.
class GasLoading : public CouplingProcess {
 public:
  explicit GasLoading(GasLoad load);
  ~GasLoading() override;
  const char* name() const override { return "gas load"; }
  GasLoad load() const { return load_; }

  std::vector<Stage> stages() const override { return {Stage::before_gas, Stage::load_rock, Stage::after_rock}; }
  void run(Stage stage, CouplingContext& ctx, const StageStep& step) override;

  //! The force of the gas on the rock (a device reduction) and its cumulative work (the rock's ledger).
  void add_diagnostics(const CouplingContext& ctx, CouplingDiagnostics& d) const override;
  //! gas_work_on_rock_J_per_m, gas_force_x_N_per_m, gas_force_y_N_per_m.
  void report(const CouplingDiagnostics& d, CsvRecord& o) const override;
  //! The checkpoint records the load; read_checkpoint() refuses another.
  void write_checkpoint(CheckpointWriter& w) const override;
  void read_checkpoint(CheckpointReader& r) override;

 private:
  //! GasLoad::edge_pressures: pressure on every exposed edge, that of the active cell the edge faces; where
  //! that cell is inactive, a boundary edge takes the nearest active cell within 2 cells (the paper's rule) and
  //! a crack face the ambient pressure. GasLoad::face_forces: forces on the nodes from the prescribed faces
  //! (FaceLoadKernel), edge pressures 0.
  void load_rock(CouplingContext& ctx);
  //! GasLoad::face_forces and edge_pressures_paid: keeps the face velocities the gas step starts from (the energy
  //! equation's).
  void before_gas(CouplingContext& ctx);
  //! GasLoad::face_forces: the gas pays the work the rock received from the face forces over the step, which
  //! its energy equation counted at the faces' velocities instead of the rock's motion (FaceWorkLagKernel).
  //! GasLoad::edge_pressures_paid: each active cell takes back what its energy equation paid at its prescribed
  //! faces (PrescribedFaceRefundKernel) and pays the work of the edges it loaded (EdgeWorkKernel,
  //! EdgeWorkChargeKernel).
  void after_rock(CouplingContext& ctx, double dt, int rock_substeps);
  void keep_nodes(CouplingContext& ctx);  // the rock's nodes and previous step before its substeps
  GasLoad load_;
  // GasLoad::face_forces, within one coupled step (nothing to checkpoint): the gas's face velocities at the
  // step's start, the coupling of each face point loaded, the rock's nodes at the load (gas_loading.cpp)
  std::unique_ptr<detail::LoadWorkArrays> a_;  // the face work and the nodes at the step's start
  std::unique_ptr<detail::EdgeWorkArrays> edge_work_;  // GasLoad::edge_pressures_paid: per slot, within one step
  double dt_prev_ = 0;   // [s] the rock's last step at the load
  double stamp_ = -1;    // the load's mark in the face records (the gas's step count then)
  bool started_ = false;  // before_gas() of this step ran (u_old, v_old set)
  bool loaded_ = false;   // load_rock() of this step ran after a gas step (the records and nodes set)
};

}  // namespace blastsim::ibm
