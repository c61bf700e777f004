//! \file immersed_boundary.cpp
//! \brief ImmersedBoundary: its arrays (from the field lists of immersed_boundary_kernels.hpp) and the launches
//! of rock -> gas.
#include "blastsim/ibm/immersed_boundary.hpp"

#include "blastsim/core/checkpoint.hpp"
#include "blastsim/core/device_groups.hpp"
#include "blastsim/core/output_files.hpp"

#include <cmath>

namespace blastsim::ibm {

namespace detail {
BLASTSIM_FIELD_STORAGE(FaceOwners, BLASTSIM_IBM_FACE_OWNERS)
BLASTSIM_FIELD_STORAGE(CellUpdate, BLASTSIM_IBM_CELL_UPDATE)
BLASTSIM_FIELD_STORAGE(CellClaims, BLASTSIM_IBM_CELL_CLAIMS)
BLASTSIM_STATE_STORAGE(ImmersedLedger, BLASTSIM_IBM_LEDGER)
struct ImmersedBoundaryArrays {
  FaceOwnersArrays owners;  // padded shape
  CellUpdateArrays update;  // padded shape
  CellClaimsArrays claims;  // padded shape
  ImmersedLedgerArrays ledger;  // per cell
};
}  // namespace detail

ImmersedBoundary::ImmersedBoundary(const cip::GasGrid& grid, FacePointRule rule)
    : grid_(grid), rule_(rule), a_(std::make_unique<detail::ImmersedBoundaryArrays>()) {
  const index_t n = grid.padded_shape().size();
  a_->owners.u.assign(n, kNoOwner);
  a_->owners.v.assign(n, kNoOwner);
  a_->update.active.assign(n, 1);
  a_->update.changed.assign(n, 0);
  a_->update.next.assign(n, cip::CellContent{0, 0, 0, 0});
  a_->claims.claim.assign(n, kNoClaim);
  a_->claims.taken.assign(n, cip::CellContent{0, 0, 0, 0});
  a_->ledger.transitions.assign(static_cast<index_t>(grid.nx) * grid.ny, TransitionLedger{0, 0, 0, 0, 0, 0});
}

ImmersedBoundary::~ImmersedBoundary() = default;

FaceOwners<Access::read_write> ImmersedBoundary::owners() { return a_->owners.view(grid_.padded_shape()); }
CellClaims<Access::read_write> ImmersedBoundary::claims() { return a_->claims.view(grid_.padded_shape()); }

void ImmersedBoundary::run(Stage stage, CouplingContext& ctx, const StageStep& /*step*/) {
  switch (stage) {
    case Stage::cover: return cover(ctx);
    case Stage::update_cells: return update_cells(ctx);
    default: stage_not_run(*this, stage);
  }
}

void ImmersedBoundary::report(const CouplingDiagnostics& d, CsvRecord& o) const {
  o.integer("cells_covered", d.transitions.covered).integer("cells_uncovered", d.transitions.uncovered);
  o.real("transition_energy_J_per_m", d.transitions.energy_created);
}

void ImmersedBoundary::cover(CouplingContext& ctx) {
  fill_device("ibm.clear_owner.u", a_->owners.u, kNoOwner);
  fill_device("ibm.clear_owner.v", a_->owners.v, kNoOwner);
  fill_device("ibm.clear_claim", a_->claims.claim, kNoClaim);
  const fdem::RockView rock = ctx.rock.view();
  for_each_index("ibm.cover", rock.triangle_count, CoverKernel{rock, grid_, ctx.owners});
}

void ImmersedBoundary::update_cells(CouplingContext& ctx) {
  const cip::GasGrid& g = grid_;
  const PaddedShape sh = g.padded_shape();
  const fdem::RockView rock = ctx.rock.view();
  const cip::ImmersedBoundaryView ib = ctx.gas.immersed_boundary();
  const FaceOwners<Access::read> owners = ctx.owners;
  const bool surface = rule_ == FacePointRule::surface_normal;
  for_each_cell("ibm.face_velocity.u", 0, g.nx + 1, 0, g.ny,
                ImposedVelocityKernel{rock, g, 0, owners.u, ib.u_prescribed, ib.u_imposed, surface});
  for_each_cell("ibm.face_velocity.v", 0, g.nx, 0, g.ny + 1,
                ImposedVelocityKernel{rock, g, 1, owners.v, ib.v_prescribed, ib.v_imposed, surface});
  const CellUpdate<Access::read_write> update = a_->update.view(sh);
  for_each_cell("ibm.cells.mask", 0, g.nx, 0, g.ny, NewMaskKernel{owners, update.active});
  for_each_cell("ibm.cells.transition", 0, g.nx, 0, g.ny,
                TransitionKernel{ib.cell_active, update, ctx.gas.cells(), a_->ledger.view(), ctx.claims, g.nx, g.ny, g.cell_area(),
                                 ctx.ambient.density, ctx.ambient.internal_energy, ctx.first});
  for_each_cell("ibm.cells.apply", 0, g.nx, 0, g.ny,
                ApplyTransitionKernel{a_->update.read(sh), ib.u_imposed, ib.v_imposed, ib.cell_active, ctx.gas.cells()});
}

void ImmersedBoundary::add_diagnostics(const CouplingContext& /*ctx*/, CouplingDiagnostics& d) const {
  const TransitionLedger* led = a_->ledger.read().transitions;
  const index_t cells = static_cast<index_t>(a_->ledger.transitions.size());
  auto total = [&](double TransitionLedger::*field) {
    return reduce_sum("ibm.ledger", cells, 0.0, FieldOf<TransitionLedger>{led, field});
  };
  d.transitions.covered = std::lround(total(&TransitionLedger::covered));
  d.transitions.uncovered = std::lround(total(&TransitionLedger::uncovered));
  d.transitions.mass_created = total(&TransitionLedger::mass_created);
  d.transitions.energy_created = total(&TransitionLedger::energy_created);
  d.transitions.mass_lost = total(&TransitionLedger::mass_lost);
  d.transitions.energy_lost = total(&TransitionLedger::energy_lost);
  d.energy_added += d.transitions.energy_created;
}

void ImmersedBoundary::write_checkpoint(CheckpointWriter& w) const {
  write_array(w, "ibm.transitions", a_->ledger.transitions);
}

void ImmersedBoundary::read_checkpoint(CheckpointReader& r) {
  read_array(r, "ibm.transitions", a_->ledger.transitions, a_->ledger.transitions.size());
}

}  // namespace blastsim::ibm
