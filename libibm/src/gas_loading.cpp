//! \file gas_loading.cpp
//! \brief GasLoading: the launches of gas -> rock (gas_load_kernels.hpp) and the interface force.
#include "blastsim/ibm/gas_loading.hpp"

#include "blastsim/core/backend.hpp"
#include "blastsim/core/checkpoint.hpp"
#include "blastsim/ibm/gas_load_kernels.hpp"

#include <string>

namespace blastsim::ibm {

const char* gas_load_name(GasLoad load) { return load == GasLoad::face_forces ? "faces" : "edges"; }

FacePointRule face_point_rule(GasLoad load) {
  return load == GasLoad::face_forces ? FacePointRule::surface_normal : FacePointRule::shape_functions;
}

void GasLoading::load_rock(CouplingContext& ctx) {
  const cip::GasGrid g = ctx.gas.grid();
  const cip::GasStateView s = ctx.gas.state();
  const cip::ImmersedBoundaryView ib = ctx.gas.immersed_boundary();
  const fdem::RockView rock = ctx.rock.view();
  const cip::GasMaterials& mat = ctx.gas.materials();
  const bool faces = load_ == GasLoad::face_forces;
  for_each_index("ibm.edge_pressure", 3 * static_cast<index_t>(rock.triangle_count),
                 EdgePressureKernel{rock, g, mat, ctx.gas.material_fields(), ib.cell_active, s.rho.f, s.e.f,
                                    ctx.ambient_pressure, faces});
  if (!faces) return;
  const PaddedShape sh = g.padded_shape();
  for_each_index("ibm.face_load", static_cast<index_t>(rock.triangle_count),
                 FaceLoadKernel{rock, g, mat, ctx.gas.material_fields(), ib.cell_active, s.rho.f, s.e.f,
                                ctx.owners, Field2D<const double>{ctx.gas.pressure_with_viscosity().data, sh},
                                ctx.gas.steps() > 0, ctx.owner_margin});
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
