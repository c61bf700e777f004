//! \file immersed_boundary.hpp
//! \brief The immersed boundary, rock -> gas (the paper's Fig. 1a; docs/coupling.md "Rock -> gas"): every staggered
//! velocity point inside a rock triangle takes the velocity interpolated from the triangle's nodes; a cell whose
//! four velocity points are all in rock is inactive and holds the ambient state; cells that change state hand
//! their gas on or start from the ambient state, counted in a ledger.
#pragma once

#include "blastsim/ibm/coupling_options.hpp"
#include "blastsim/ibm/coupling_process.hpp"

#include <memory>

namespace blastsim::ibm {


namespace detail {
struct ImmersedBoundaryArrays;
}

//! A coupling process (coupling_process.hpp); the first of GasRockCoupler's. Its arrays: the face points'
//! owners (shared with the other processes through CouplingContext), the cell update, the transition ledger.
class ImmersedBoundary : public CouplingProcess {
 public:
  ImmersedBoundary(const cip::GasGrid& grid, FacePointRule rule);
  ~ImmersedBoundary() override;
  const char* name() const override { return "immersed boundary"; }

  //! Face-point owners of the grid's padded shape (for CouplingContext).
  FaceOwners<Access::read_write> owners();
  //! The cells' claims (for CouplingContext): cleared in cover(); a process may claim cells then, and collect
  //! in after_cells the gas of those covered with nowhere to go.
  CellClaims<Access::read_write> claims();
  FacePointRule rule() const { return rule_; }

  std::vector<Stage> stages() const override { return {Stage::cover, Stage::update_cells}; }
  void run(Stage stage, CouplingContext& ctx, const StageStep& step) override;

  //! The transitions so far, and the energy they added (device reductions).
  void add_diagnostics(const CouplingContext& ctx, CouplingDiagnostics& d) const override;
  //! cells_covered, cells_uncovered, transition_energy_J_per_m.
  void report(const CouplingDiagnostics& d, CsvRecord& o) const override;
  void write_checkpoint(CheckpointWriter& w) const override;
  void read_checkpoint(CheckpointReader& r) override;

 private:
  //! Clears the owners, then rasterises every triangle over the face points of its bounding box; a point
  //! covered by several (overlapping) triangles takes the one of highest index, found with an
  //! order-independent atomic maximum, so the result is deterministic.
  void cover(CouplingContext& ctx);
  //! Imposed velocities, the new mask and the cells that change state: the first call (ctx.first) sets every
  //! covered cell to the ambient state; later calls keep mass and energy when cells change state: a covered cell
  //! gives its gas in equal shares to its active edge neighbours; an uncovered cell starts from the ambient
  //! state (counted in the ledger).
  void update_cells(CouplingContext& ctx);

  cip::GasGrid grid_;
  FacePointRule rule_;
  std::unique_ptr<detail::ImmersedBoundaryArrays> a_;
};

}  // namespace blastsim::ibm
