//! \file gas_loading.cpp
//! \brief GasLoading: the launches of gas -> rock (gas_load_kernels.hpp) and the interface force.
#include "blastsim/ibm/gas_loading.hpp"

#include "blastsim/core/checkpoint.hpp"
#include "blastsim/core/device_groups.hpp"
#include "blastsim/core/output_files.hpp"
#include "blastsim/ibm/gas_load_kernels.hpp"

#include <string>
#include <utility>

namespace blastsim::ibm {

namespace detail {
BLASTSIM_FIELD_STORAGE(FaceWork, BLASTSIM_IBM_FACE_WORK)
BLASTSIM_STATE_STORAGE(NodeStart, BLASTSIM_IBM_NODE_START)
BLASTSIM_STATE_STORAGE(EdgeWork, BLASTSIM_IBM_EDGE_WORK)
//! The face work (padded shape; the records marked with the load that wrote them) and the nodes at the start.
struct LoadWorkArrays {
  FaceWorkArrays face;
  NodeStartArrays start;
};
}  // namespace detail

GasLoading::GasLoading(GasLoad load)
    : load_(load), a_(std::make_unique<detail::LoadWorkArrays>()), edge_work_(std::make_unique<detail::EdgeWorkArrays>()) {}
GasLoading::~GasLoading() = default;

const char* gas_load_name(GasLoad load) {
  return load == GasLoad::face_forces ? "faces" : (load == GasLoad::edge_pressures_paid ? "edges_paid" : "edges");
}

FacePointRule face_point_rule(GasLoad load) {
  return load == GasLoad::face_forces ? FacePointRule::surface_normal : FacePointRule::shape_functions;
}

void GasLoading::run(Stage stage, CouplingContext& ctx, const StageStep& step) {
  switch (stage) {
    case Stage::before_gas: return before_gas(ctx);
    case Stage::load_rock: return load_rock(ctx);
    case Stage::after_rock: return after_rock(ctx, step.dt, step.rock_substeps);
    default: stage_not_run(*this, stage);
  }
}

void GasLoading::report(const CouplingDiagnostics& d, CsvRecord& o) const {
  o.real("gas_work_on_rock_J_per_m", d.gas_work_on_rock).real("gas_force_x_N_per_m", d.gas_force_on_rock[0], 6);
  o.real("gas_force_y_N_per_m", d.gas_force_on_rock[1], 6);
}

void GasLoading::load_rock(CouplingContext& ctx) {
  const cip::GasGrid g = ctx.gas.grid();
  const cip::GasStateView s = ctx.gas.state();
  const cip::ImmersedBoundaryView ib = ctx.gas.immersed_boundary();
  const fdem::RockView rock = ctx.rock.view();
  const cip::GasMaterials& mat = ctx.gas.materials();
  const bool faces = load_ == GasLoad::face_forces, paid = load_ == GasLoad::edge_pressures_paid;
  const index_t slots = 3 * static_cast<index_t>(rock.triangle_count);
  detail::EdgeWorkArrays& ew = *edge_work_;
  if (paid) ew.source.resize(slots), ew.loaded.resize(slots);
  for_each_index("ibm.edge_pressure", slots,
                 EdgePressureKernel{rock, g, mat, ctx.gas.material_fields(), ib.cell_active, s.rho.f, s.e.f,
                                    ctx.ambient_pressure, faces, paid, ew.view()});
  if (!faces && !paid) return;
  if (faces) {
    detail::FaceWorkArrays& a = a_->face;
    const PaddedShape sh = g.padded_shape();
    if (a.record_u.size() != static_cast<size_t>(sh.size())) {  // once: every record marked as no load's
      const FaceLoadRecord none{{{0.0, 0.0, 0.0}, 0.0, 0.0}, -1.0};
      a.record_u.assign(sh.size(), none);
      a.record_v.assign(sh.size(), none);
    }
    stamp_ = static_cast<double>(ctx.gas.steps());
    for_each_index("ibm.face_load", static_cast<index_t>(rock.triangle_count),
                   FaceLoadKernel{rock, g, mat, ctx.gas.material_fields(), ib.cell_active, s.rho.f, s.e.f,
                                  ctx.owners, Field2D<const double>{ctx.gas.pressure_with_viscosity().data, sh},
                                  ctx.gas.steps() > 0, ctx.owner_margin, make_field_view(a.record_u, sh),
                                  make_field_view(a.record_v, sh), stamp_});
  }
  // The rock's nodes before its substeps, for the work over the step (after_rock()); only after a gas step,
  // whose P the loads used and whose energy equation counted the faces' velocities.
  loaded_ = started_ && ctx.gas.steps() > 0;
  if (loaded_) keep_nodes(ctx);
}

void GasLoading::keep_nodes(CouplingContext& ctx) {
  const fdem::RockView rock = ctx.rock.view();
  detail::NodeStartArrays& a = a_->start;
  const index_t nodes = 3 * static_cast<index_t>(rock.triangle_count);
  a.for_each([&](const char*, DeviceVector<double>& v) { v.resize(nodes); });
  for_each_index("ibm.face_work.nodes", nodes, NodeStartKernel{rock.nodes, a.view()});
  dt_prev_ = ctx.rock.last_step();
}

void GasLoading::before_gas(CouplingContext& ctx) {
  if (load_ == GasLoad::edge_pressures) return;
  const cip::GasStateView s = ctx.gas.state();
  const PaddedShape sh = ctx.gas.grid().padded_shape();
  detail::FaceWorkArrays& a = a_->face;
  a.u_old.resize(sh.size()), a.v_old.resize(sh.size());  // (the records, empty until load_rock() makes them, unread)
  for_each_index("ibm.face_work.start", sh.size(), FaceStartKernel{s.u.f, s.v.f, a.view(sh)});
  started_ = true;
}

void GasLoading::after_rock(CouplingContext& ctx, double dt, int rock_substeps) {
  if (load_ == GasLoad::edge_pressures || !loaded_) return;
  loaded_ = started_ = false;
  const cip::GasGrid g = ctx.gas.grid();
  const PaddedShape sh = g.padded_shape();
  const detail::FaceWorkArrays& a = a_->face;
  const cip::GasStateView s = ctx.gas.state();
  const cip::ImmersedBoundaryView ib = ctx.gas.immersed_boundary();
  const FaceStepMotion motion{make_field_view(a.u_old, sh), make_field_view(a.v_old, sh), ib.u_imposed, ib.v_imposed, dt};
  const CellPressureWork cell{g, Field2D<const double>{ctx.gas.pressure_with_viscosity().data, sh}, ib.cell_active,
                              s.rho.f, s.e.f};
  if (load_ == GasLoad::edge_pressures_paid) {
    // The cells take back their prescribed faces' work, then pay their edges' (docs/coupling.md).
    for_each_cell("ibm.edge_work.refund", 0, g.nx, 0, g.ny,
                  PrescribedFaceRefundKernel{ib.u_prescribed, ib.v_prescribed, motion, cell});
    detail::EdgeWorkArrays& ew = *edge_work_;
    const fdem::RockView rock = ctx.rock.view();
    const index_t slots = 3 * static_cast<index_t>(rock.triangle_count);
    ew.key.resize(slots), ew.record.resize(slots), ew.work.resize(slots);
    for_each_index("ibm.edge_work", slots,
                   EdgeWorkKernel{rock, a_->start.read(), dt / rock_substeps, dt_prev_, ctx.rock.pressure_scale(),
                                  ew.view()});
    stable_sort_by_key("ibm.edge_work.sort", ew.key, ew.record, slots);
    for_each_index("ibm.edge_work.charge", slots,
                   EdgeWorkChargeKernel{ew.read(), static_cast<int>(slots), g.nx, g.cell_area(), ctx.gas.cells()});
    return;
  }
  for_each_cell("ibm.face_work", 0, g.nx, 0, g.ny,
                FaceWorkLagKernel{ctx.rock.view(), a_->start.read(), dt / rock_substeps, dt_prev_, ctx.owners.u, ctx.owners.v,
                                  make_field_view(a.record_u, sh), make_field_view(a.record_v, sh), stamp_, motion,
                                  cell});
}

void GasLoading::add_diagnostics(const CouplingContext& ctx, CouplingDiagnostics& d) const {
  const Vec2Sum f = reduce_sum("ibm.gas_force", 3 * static_cast<index_t>(ctx.rock.triangle_count()), Vec2Sum{0, 0},
                               EdgeForceOf{ctx.rock.view()});
  d.gas_force_on_rock = {f.x, f.y};
  d.gas_work_on_rock = ctx.rock.energies().pressure_work;
}

void GasLoading::write_checkpoint(CheckpointWriter& w) const { w.value("ibm.gas_load", static_cast<int>(load_)); }

void GasLoading::read_checkpoint(CheckpointReader& r) {
  if (r.value<int>("ibm.gas_load") != static_cast<int>(load_))
    r.fail("ibm.gas_load", std::string("the checkpoint's gas load is not this run's (") + gas_load_name(load_) + ")");
}

}  // namespace blastsim::ibm
