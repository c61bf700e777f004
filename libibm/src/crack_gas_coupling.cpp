//! \file crack_gas_coupling.cpp
//! \brief CrackGasCoupling: its arrays (crack_coupling_kernels.hpp's lists) and the launches that join the crack
//! gas to the rock and the grid.
#include "blastsim/ibm/crack_gas_coupling.hpp"

#include "blastsim/core/checkpoint.hpp"
#include "blastsim/core/device_groups.hpp"
#include "blastsim/core/error.hpp"
#include "blastsim/core/output_files.hpp"
#include "blastsim/ibm/crack_coupling_kernels.hpp"


#include <algorithm>
#include <cmath>
#include <string>
#include <type_traits>

namespace blastsim::ibm {

namespace detail {
BLASTSIM_CONST_STORAGE(CrackJunctionPlaces, BLASTSIM_CRACK_JUNCTION_PLACES)
BLASTSIM_CONST_STORAGE(CrackSegmentParams, BLASTSIM_CRACK_SEGMENT_PARAMS)
BLASTSIM_STATE_STORAGE(CrackMouthCells, BLASTSIM_CRACK_MOUTH_CELLS)
BLASTSIM_STATE_STORAGE(CrackHandovers, BLASTSIM_CRACK_HANDOVERS)
BLASTSIM_STATE_STORAGE(CrackHandoverCells, BLASTSIM_CRACK_HANDOVER_CELLS)
BLASTSIM_STATE_STORAGE(CrackCushion, BLASTSIM_CRACK_CUSHION)
BLASTSIM_STATE_STORAGE(CrackDepositOrder, BLASTSIM_CRACK_DEPOSIT_ORDER)
BLASTSIM_STATE_STORAGE(CrackExchangeLedger, BLASTSIM_CRACK_EXCHANGE_LEDGER)
BLASTSIM_STATE_STORAGE(CrackWallLedger, BLASTSIM_CRACK_WALL_LEDGER)
struct CrackCouplingArrays {
  CrackJunctionPlacesArrays places;   // per junction
  CrackSegmentParamsArrays params;    // per segment
  CrackMouthCellsArrays mouth_cells;  // kMouthSamples per junction
  CrackHandoversArrays handovers;     // per segment
  CrackHandoverCellsArrays handover_cells;  // kHandoverSamples per segment
  CrackCushionArrays cushion;         // per segment
  CrackDepositOrderArrays order;      // per record: the mouths' samples, then the hand-overs' points
  CrackExchangeLedgerArrays exchange; // per record
  CrackWallLedgerArrays walls;        // per segment
};
}  // namespace detail

namespace {
//! The channel network of a rock's joints: per joint its two end vertices.
CrackGas network_of(const fdem::RockSolver& rock, const cip::GasMaterials& materials, const CrackGasOptions& options) {
  const std::vector<int>& vertex = rock.node_vertex();
  if (vertex.size() != static_cast<std::size_t>(rock.node_count()))
    throw InputError("crack gas: the rock was built without its mesh vertices (FdemTopology::node_vertex)");
  const int junctions = vertex.empty() ? 0 : *std::max_element(vertex.begin(), vertex.end()) + 1;
  std::vector<std::array<int, 2>> ends;
  ends.reserve(rock.joint_nodes().size());
  for (const fdem::JointNodes& j : rock.joint_nodes()) ends.push_back({vertex[j.a0], vertex[j.a1]});
  return CrackGas(junctions, ends, materials, options);
}
}  // namespace

CrackGasCoupling::CrackGasCoupling(const fdem::RockSolver& rock, const cip::GasMaterials& materials,
                                   const CrackGasOptions& options)
    : crack_(std::make_unique<CrackGas>(network_of(rock, materials, options))),
      a_(std::make_unique<detail::CrackCouplingArrays>()) {
  const int junctions = crack_->junction_count(), segments = crack_->segment_count();
  const std::vector<int>& vertex = rock.node_vertex();
  std::vector<std::uint8_t> outline(junctions, 0);
  for (const fdem::BoundaryEdge& b : rock.boundary_edges()) outline[vertex[b.n0]] = outline[vertex[b.n1]] = 1;
  copy_from_host(a_->places.outline, outline);
  a_->params.initial_aperture.assign(segments, 0.0);
  a_->params.closure_stiffness.assign(segments, 0.0);
  a_->params.max_closure.assign(segments, 0.0);
  a_->mouth_cells.cell.assign(kMouthSamples * static_cast<std::size_t>(junctions), -1);
  a_->mouth_cells.sharers.assign(kMouthSamples * static_cast<std::size_t>(junctions), 0);
  a_->mouth_cells.share.assign(kMouthSamples * static_cast<std::size_t>(junctions), ChannelConserved{0, 0, 0, 0, 0});
  a_->handovers.pending.assign(segments, 0);
  a_->handovers.samples.assign(segments, 0);
  a_->handovers.reverted.assign(segments, 0);
  a_->handover_cells.cell.assign(kHandoverSamples * static_cast<std::size_t>(segments), -1);
  a_->handovers.gas.assign(segments, ChannelConserved{0, 0, 0, 0, 0});
  a_->cushion.for_each([&](const char*, auto& v) { v.assign(segments, typename std::decay_t<decltype(v)>::value_type{}); });
  const std::size_t records = record_count();
  a_->exchange.for_each([&](const char*, auto& v) { v.assign(records, typename std::decay_t<decltype(v)>::value_type{}); });
  a_->walls.for_each([&](const char*, auto& v) { v.assign(segments, 0.0); });
  a_->order.key.assign(records, 0);
  a_->order.record.assign(records, 0);
}

CrackGasCoupling::~CrackGasCoupling() = default;

void CrackGasCoupling::set_initial_apertures(const std::vector<int>& joints, double aperture) {
  if (!(aperture >= 0) || !std::isfinite(aperture))
    throw InputError("crack gas: initial aperture " + std::to_string(aperture) + " m: must be >= 0");
  const std::optional<JointClosure>& law = crack_->options().joint_closure;
  const bool closes = law && aperture > 0;
  if (closes && !(law->max_closure < aperture))
    throw InputError("crack gas: joint_max_closure = " + std::to_string(law->max_closure) +
                     " m: must be below the initial aperture of the joints it closes (" + std::to_string(aperture) + " m)");
  std::vector<double> a = to_host(a_->params.initial_aperture), k = to_host(a_->params.closure_stiffness),
                      vm = to_host(a_->params.max_closure);
  for (const int j : joints) {
    if (j < 0 || j >= crack_->segment_count())
      throw InputError("crack gas: joint " + std::to_string(j) + " out of range for an initial aperture");
    a[j] = aperture;
    k[j] = closes ? law->stiffness : 0.0;
    vm[j] = closes ? law->max_closure : 0.0;
  }
  copy_from_host(a_->params.initial_aperture, a);
  copy_from_host(a_->params.closure_stiffness, k);
  copy_from_host(a_->params.max_closure, vm);
}

HandoverGaps CrackGasCoupling::handover_gaps(const cip::GasGrid& g) const {
  const double gap = crack_->options().handover_width * std::max(g.dx, g.dy);
  return {gap, 0.5 * gap};
}

void CrackGasCoupling::run(Stage stage, CouplingContext& ctx, const StageStep& step) {
  switch (stage) {
    case Stage::cover: return cover(ctx);
    case Stage::after_cells: return after_cells(ctx);
    case Stage::after_gas: return after_gas(ctx, step.dt);
    case Stage::before_rock_step: return before_rock_step(ctx, step.substep, step.dt);
    case Stage::after_rock: return after_rock(ctx);
    default: stage_not_run(*this, stage);
  }
}

void CrackGasCoupling::report(const CouplingDiagnostics& d, CsvRecord& o) const {
  o.real("crack_gas_mass_kg_per_m", d.crack.mass).real("crack_gas_energy_J_per_m", d.crack.energy);
  o.integer("crack_gas_segments", d.crack.gas_segments).integer("crack_wet_segments", d.crack.wet_segments);
  o.real("crack_gas_pressure_max_Pa", d.crack.max_pressure, 6);
  o.real("crack_gas_to_grid_J_per_m", d.crack.to_grid_energy).real("crack_gas_wall_work_J_per_m", d.crack.wall_work);
  o.real("crack_gas_unpaid_work_J_per_m", d.crack.unpaid_work).real("crack_gas_wall_heat_J_per_m", d.crack.wall_heat);
}

void CrackGasCoupling::cover(CouplingContext& ctx) {
  update_geometry(ctx);
  for_each_index("ibm.crack.gap_cover", crack_->segment_count(),
                 CrackGapCoverKernel{ctx.rock.view(), ctx.gas.grid(), crack_->segments(), a_->handovers.read(),
                                     ctx.owners, ctx.claims.claim});
}

void CrackGasCoupling::after_cells(CouplingContext& ctx) {
  for_each_index("ibm.crack.claimed_gas", crack_->segment_count(),
                 CrackClaimedGasKernel{ctx.rock.view(), ctx.gas.grid(), crack_->segments(), a_->handovers.view(), a_->walls.view(),
                                       ctx.claims.claim, ctx.claims.taken});
}

void CrackGasCoupling::update_geometry(CouplingContext& ctx) {
  for_each_index("ibm.crack.geometry", crack_->segment_count(),
                 CrackGeometryKernel{ctx.rock.view(), ctx.gas.materials(), a_->params.view(), crack_->geometry(),
                                     crack_->segments(), a_->handovers.view(), a_->cushion.view(), a_->walls.view(),
                                     crack_->options().residual_aperture,
                                     handover_gaps(ctx.gas.grid()), 0.5 * ctx.rock.last_step(),
                                     crack_->vacuum_density()});
}

int CrackGasCoupling::record_count() const {
  return kMouthSamples * crack_->junction_count() + kHandoverSamples * crack_->segment_count();
}

void CrackGasCoupling::sort_records(int records, int mouth_records) {
  for_each_index("ibm.crack.keys", records,
                 CrackDepositKeyKernel{a_->mouth_cells.read(), a_->handover_cells.read(), a_->order.view(), mouth_records});
  fill_indices("ibm.crack.records", a_->order.record);
  stable_sort_by_key("ibm.crack.sort", a_->order.key, a_->order.record, static_cast<index_t>(records));
}

void CrackGasCoupling::after_gas(CouplingContext& ctx, double dt) {
  const int mouth_records = kMouthSamples * crack_->junction_count();
  const int records = mouth_records;  // the mouths' samples alone: no hand-over has a cell before after_rock
  const cip::GasGrid g = ctx.gas.grid();
  // the mouths from the cells' new gas; the cells they share, sorted, set what each may draw over the step
  for_each_index("ibm.crack.mouths", crack_->junction_count(),
                 CrackMouthKernel{ctx.rock.view(), ctx.gas.materials(), g, ctx.gas.immersed_boundary().cell_active,
                                  ctx.gas.cells(), crack_->graph(), crack_->segments(), a_->places.view(),
                                  crack_->mouths(), a_->mouth_cells.view(), crack_->vacuum_density()});
  sort_records(records, mouth_records);
  for_each_index("ibm.crack.mouth_sharers", records,
                 MouthSharersKernel{a_->order.read(), a_->mouth_cells.view(), mouth_records, records});
  for_each_index("ibm.crack.mouth_gas", crack_->junction_count(),
                 MouthHeldGasKernel{g, ctx.gas.cells(), a_->mouth_cells.read(), crack_->mouths()});
  interval_ = dt;
}

void CrackGasCoupling::before_rock_step(CouplingContext& ctx, int k, double dt) {
  if (k > 0) update_geometry(ctx);  // substep 0: cover() set it from the rock as it stands
  crack_->advance(dt, std::max(dt, interval_));
  const fdem::RockView rock = ctx.rock.view();
  for_each_index("ibm.crack.cushion", rock.joint_count,
                 CrackCushionKernel{rock, a_->params.view(), crack_->segments(), a_->cushion.view(),
                                    crack_->options().residual_aperture, 0.5 * ctx.rock.last_step()});
}

void CrackGasCoupling::after_rock(CouplingContext& ctx) {
  const int ns = crack_->segment_count(), mouth_records = kMouthSamples * crack_->junction_count();
  const int records = record_count();
  const cip::GasGrid g = ctx.gas.grid();
  // the hand-overs' cells; what the mouths gave the cells over the substeps and the hand-overs, summed per cell
  // in sorted order, put in the cells with its momentum (cip::CellDeposits)
  for_each_index("ibm.crack.handover_cells", ns,
                 HandoverCellKernel{ctx.rock.view(), g, ctx.gas.immersed_boundary().cell_active, crack_->segments(),
                                    a_->handovers.view(), a_->handover_cells.view()});
  sort_records(records, mouth_records);
  if (!deposits_) deposits_ = std::make_unique<cip::CellDeposits>(g);
  for_each_index("ibm.crack.deposit", records,
                 CrackDepositKernel{a_->order.read(), a_->mouth_cells.read(), crack_->deposit_view(), a_->handovers.read(),
                                    crack_->geometry(), a_->exchange.view(), deposits_->entries(records), mouth_records,
                                    records});
  deposits_->apply(ctx.gas);
  for_each_index("ibm.crack.refused", records,
                 CrackRefusedKernel{a_->order.read(), deposits_->list(), deposits_->last(), a_->exchange.view()});
  crack_->clear_deposits();
  for_each_index("ibm.crack.handover_clear", ns, HandoverClearKernel{a_->handovers.view()});
}

double CrackGasCoupling::outer_blast_fraction(const fdem::RockSolver& rock, std::array<double, 2> center, double radius,
                                              double min_pressure) const {
  const fdem::RockReadView view = rock.view();
  return reduce_max("ibm.crack.outer_blast", crack_->segment_count(), 0.0,
                    OuterBlastFraction{crack_->graph(), crack_->segments(), view.joint, view.nodes, a_->places.view(),
                                       center[0], center[1], radius * radius, min_pressure});
}

double CrackGasCoupling::blast_front(const fdem::RockSolver& rock, std::array<double, 2> center, double min_fraction,
                                     double min_pressure) const {
  const fdem::RockReadView view = rock.view();
  return reduce_max("ibm.crack.blast_front", static_cast<index_t>(crack_->segment_count()), 0.0,
                    BlastFrontOf{crack_->segments(), view.joint, view.nodes, center[0], center[1], min_fraction,
                                 min_pressure});
}

void CrackGasCoupling::add_diagnostics(const CouplingContext& ctx, CouplingDiagnostics& d) const {
  d.crack_gas = true;
  d.crack = crack_->totals(ctx.ambient_pressure);
  // Gas handed to the grid and not yet in a cell (a hand-over in the rock -> gas update that ends a step)
  auto pending = [&](const char* label, double ChannelConserved::*field) {
    return reduce_sum(label, crack_->segment_count(), 0.0, PendingHandoverOf{a_->handovers.read(), field});
  };
  d.crack.mass += pending("ibm.crack.pending_mass", &ChannelConserved::m);
  d.crack.energy += pending("ibm.crack.pending_energy", &ChannelConserved::E);
  d.crack.products_mass += pending("ibm.crack.pending_products", &ChannelConserved::m1);
  const ChannelConserved* given = a_->exchange.read().to_grid;
  const index_t records = static_cast<index_t>(a_->exchange.to_grid.size());
  d.crack.to_grid_mass = reduce_sum("ibm.crack.to_grid_mass", records, 0.0,
                                    FieldOf<ChannelConserved>{given, &ChannelConserved::m});
  d.crack.to_grid_energy = reduce_sum("ibm.crack.to_grid_energy", records, 0.0,
                                      FieldOf<ChannelConserved>{given, &ChannelConserved::E});
  auto walls = [&](const char* label, WallLedgerOf::Entry e) {
    return reduce_sum(label, crack_->segment_count(), 0.0, WallLedgerOf{a_->walls.read(), e});
  };
  d.crack.wall_work = walls("ibm.crack.wall_work", WallLedgerOf::Entry::wall_work);
  d.crack.unpaid_work = walls("ibm.crack.unpaid_work", WallLedgerOf::Entry::unpaid_work);
  d.crack.from_cells_mass = walls("ibm.crack.taken_mass", WallLedgerOf::Entry::taken_mass);
  d.crack.from_cells_energy = walls("ibm.crack.taken_energy", WallLedgerOf::Entry::taken_energy);
  d.energy_held += d.crack.energy + d.crack.wall_heat;  // the walls' heat went into the rock (not modelled there)
}

void CrackGasCoupling::write_checkpoint(CheckpointWriter& w) const {
  crack_->write_checkpoint(w);
  write_array(w, "crack.handover_pending", a_->handovers.pending);
  write_array(w, "crack.handover_gas", a_->handovers.gas);
  write_array(w, "crack.handover_reverted", a_->handovers.reverted);
  a_->cushion.for_each([&](const char* name, const auto& v) { write_array(w, std::string("crack.cushion.") + name, v); });
  a_->exchange.for_each([&](const char* name, const auto& v) { write_array(w, std::string("crack.exchange.") + name, v); });
  a_->walls.for_each([&](const char* name, const auto& v) { write_array(w, std::string("crack.") + name, v); });
}
void CrackGasCoupling::read_checkpoint(CheckpointReader& r) {
  crack_->read_checkpoint(r);
  const auto n = static_cast<std::size_t>(crack_->segment_count());
  read_array(r, "crack.handover_pending", a_->handovers.pending, n);
  read_array(r, "crack.handover_gas", a_->handovers.gas, n);
  read_array(r, "crack.handover_reverted", a_->handovers.reverted, n);
  a_->cushion.for_each([&](const char* name, auto& v) { read_array(r, std::string("crack.cushion.") + name, v, n); });
  a_->exchange.for_each([&](const char* name, auto& v) { read_array(r, std::string("crack.exchange.") + name, v, record_count()); });
  a_->walls.for_each([&](const char* name, auto& v) { read_array(r, std::string("crack.") + name, v, n); });
  for (const std::uint8_t p : to_host(a_->handovers.pending))
    if (p > 1) r.fail("crack.handover_pending", "holds a flag other than 0 or 1");
  for (const std::uint8_t p : to_host(a_->handovers.reverted))
    if (p > 1) r.fail("crack.handover_reverted", "holds a flag other than 0 or 1");
}

}  // namespace blastsim::ibm
