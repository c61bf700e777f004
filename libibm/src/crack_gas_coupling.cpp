//! \file crack_gas_coupling.cpp
//! \brief CrackGasCoupling: its arrays (crack_coupling_kernels.hpp's lists) and the launches that join the crack
//! gas to the rock and the grid.
#include "blastsim/ibm/crack_gas_coupling.hpp"

#include "blastsim/core/checkpoint.hpp"
#include "blastsim/core/device_groups.hpp"
#include "blastsim/core/error.hpp"
#include "blastsim/ibm/crack_coupling_kernels.hpp"

#include <thrust/sequence.h>
#include <thrust/sort.h>

#include <algorithm>

namespace blastsim::ibm {

namespace detail {
BLASTSIM_CONST_STORAGE(CrackJunctionPlaces, BLASTSIM_CRACK_JUNCTION_PLACES)
BLASTSIM_STATE_STORAGE(CrackMouthCells, BLASTSIM_CRACK_MOUTH_CELLS)
BLASTSIM_STATE_STORAGE(CrackHandovers, BLASTSIM_CRACK_HANDOVERS)
BLASTSIM_STATE_STORAGE(CrackDepositOrder, BLASTSIM_CRACK_DEPOSIT_ORDER)
struct CrackCouplingArrays {
  CrackJunctionPlacesArrays places;   // per junction
  CrackMouthCellsArrays mouth_cells;  // per junction
  CrackHandoversArrays handovers;     // per segment
  CrackDepositOrderArrays order;      // per record: junctions, then segments
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
  a_->mouth_cells.cell.assign(junctions, -1);
  a_->handovers.cell.assign(segments, -1);
  a_->handovers.gas.assign(segments, ChannelConserved{0, 0, 0, 0, 0});
  a_->handovers.load_factor.assign(segments, 1.0);
  a_->order.key.assign(junctions + segments, 0);
  a_->order.record.assign(junctions + segments, 0);
}

CrackGasCoupling::~CrackGasCoupling() = default;

void CrackGasCoupling::before_gas(CouplingContext& ctx, double /*dt*/) {
  for_each_index("ibm.crack.geometry", crack_->segment_count(),
                 CrackGeometryKernel{ctx.rock.view(), ctx.gas.materials(), ctx.gas.grid(),
                                     ctx.gas.immersed_boundary().cell_active, crack_->geometry(), crack_->segments(),
                                     a_->handovers.view(), crack_->options().residual_aperture});
}

void CrackGasCoupling::after_gas(CouplingContext& ctx, double dt) {
  // the mouths, from the cells' new gas
  for_each_index("ibm.crack.mouths", crack_->junction_count(),
                 CrackMouthKernel{ctx.rock.view(), ctx.gas.materials(), ctx.gas.grid(),
                                  ctx.gas.immersed_boundary().cell_active, ctx.gas.cells(), crack_->graph(),
                                  crack_->segments(), a_->places.view(), crack_->mouths(),
                                  a_->mouth_cells.view()});
  crack_->advance(dt);
  // what the mouths gave the cells, and the hand-overs, summed per cell in sorted order
  const int nj = crack_->junction_count(), ns = crack_->segment_count(), records = nj + ns;
  for_each_index("ibm.crack.keys", records,
                 CrackDepositKeyKernel{a_->mouth_cells.read(), a_->handovers.read(), a_->order.view(), nj});
  thrust::sequence(thrust::device, a_->order.record.begin(), a_->order.record.end());
  thrust::stable_sort_by_key(thrust::device, a_->order.key.begin(), a_->order.key.end(), a_->order.record.begin());
  count_host_wait();  // the sequence and the sort block
  const cip::GasGrid g = ctx.gas.grid();
  for_each_index("ibm.crack.deposit", records,
                 CrackDepositKernel{a_->order.read(), crack_->deposit_view(), a_->handovers.read(), nj, records, g.nx,
                                    g.cell_area(), ctx.gas.cells()});
  crack_->clear_deposits();
}

void CrackGasCoupling::load_rock(CouplingContext& ctx) {
  const fdem::RockView rock = ctx.rock.view();
  for_each_index("ibm.crack.face_pressure", rock.joint_count,
                 CrackFacePressureKernel{rock, crack_->segments(), a_->handovers.read()});
}

double CrackGasCoupling::mouth_pressure(const fdem::RockSolver& rock, std::array<double, 2> center, double radius) const {
  const CrackGraph g = crack_->graph();
  const CrackSegments<Access::read> seg = crack_->segments();
  const fdem::RockReadView view = rock.view();
  const fdem::JointNodes* joint = view.joint.nodes;
  const fdem::NodeMotion<Access::read> nodes = view.nodes;
  const std::uint8_t* outline = a_->places.view().outline;
  const double cx = center[0], cy = center[1], r2 = radius * radius;
  return reduce_max("ibm.crack.mouth_pressure", crack_->segment_count(), 0.0, [=] BLAST_HD(index_t si) {
    const int s = static_cast<int>(si);
    if (seg.kind[s] != kSegmentGas) return 0.0;
    const fdem::JointNodes jn = joint[s];
    double p = 0.0;
    for (int e = 0; e < 2; ++e) {
      if (!outline[g.segment_junction[2 * s + e]]) continue;
      const int node = e == 0 ? jn.a0 : jn.a1;
      const double dx = nodes.x[node] - cx, dy = nodes.y[node] - cy;
      if (dx * dx + dy * dy > r2) p = seg.prim[s].p;
    }
    return p;
  });
}

double CrackGasCoupling::front(const fdem::RockSolver& rock, std::array<double, 2> center, double pressure) const {
  const CrackSegments<Access::read> seg = crack_->segments();
  const fdem::RockReadView view = rock.view();
  const fdem::JointNodes* joint = view.joint.nodes;
  const fdem::NodeMotion<Access::read> x = view.nodes;
  const double cx = center[0], cy = center[1];
  return reduce_max("ibm.crack.front", static_cast<index_t>(crack_->segment_count()), 0.0, [=] BLAST_HD(index_t si) {
    const int s = static_cast<int>(si);
    if (seg.kind[s] != kSegmentGas || !(seg.prim[s].p > pressure)) return 0.0;
    const fdem::JointNodes jn = joint[s];
    const double dx = 0.25 * (x.x[jn.a0] + x.x[jn.a1] + x.x[jn.b0] + x.x[jn.b1]) - cx;
    const double dy = 0.25 * (x.y[jn.a0] + x.y[jn.a1] + x.y[jn.b0] + x.y[jn.b1]) - cy;
    return sqrt(dx * dx + dy * dy);
  });
}

void CrackGasCoupling::add_diagnostics(const CouplingContext& ctx, CouplingDiagnostics& d) const {
  d.crack_gas = true;
  d.crack = crack_->totals(ctx.ambient_pressure);
  d.energy_held += d.crack.energy;
}

void CrackGasCoupling::write_checkpoint(CheckpointWriter& w) const { crack_->write_checkpoint(w); }
void CrackGasCoupling::read_checkpoint(CheckpointReader& r) { crack_->read_checkpoint(r); }

}  // namespace blastsim::ibm
