//! \file gas_loading.hpp
//! \brief The grid gas's load on the rock, gas -> rock (docs/coupling.md "Gas -> rock", "Face forces"): the
//! paper's edge pressures, or the forces of the prescribed faces.
#pragma once

#include "blastsim/ibm/coupling_process.hpp"
#include "blastsim/ibm/immersed_boundary.hpp"

namespace blastsim::ibm {

//! How the grid gas loads the rock (docs/coupling.md "Gas -> rock"). Crack faces with their own gas (crack gas)
//! take that gas's pressure either way (CrackGasCoupling).
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
//! The face-point rule that goes with a load: face forces need the faces to move with the surface they load.
FacePointRule face_point_rule(GasLoad load);

//! A coupling process (coupling_process.hpp): the edge pressures [Pa] on every exposed edge (edge_pressures),
//! or the face forces [N/m] on the nodes with all edge pressures 0 (face_forces), for the rock's next steps.
class GasLoading : public CouplingProcess {
 public:
  explicit GasLoading(GasLoad load) : load_(load) {}
  const char* name() const override { return "gas load"; }
  GasLoad load() const { return load_; }

  //! GasLoad::edge_pressures: pressure on every exposed edge, that of the active cell the edge faces; where
  //! that cell is inactive, a boundary edge takes the nearest active cell within 2 cells (the paper's rule) and
  //! a crack face the ambient pressure. GasLoad::face_forces: forces on the nodes from the prescribed faces
  //! (FaceLoadKernel), edge pressures 0.
  void load_rock(CouplingContext& ctx) override;
  //! The force of the gas on the rock (a device reduction) and its cumulative work (the rock's ledger).
  void add_diagnostics(const CouplingContext& ctx, CouplingDiagnostics& d) const override;
  //! The checkpoint records the load; read_checkpoint() refuses another.
  void write_checkpoint(CheckpointWriter& w) const override;
  void read_checkpoint(CheckpointReader& r) override;

 private:
  GasLoad load_;
};

}  // namespace blastsim::ibm
