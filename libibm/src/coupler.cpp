//! \file coupler.cpp
//! \brief GasRockCoupler: rock-to-gas masks and velocities, gas-to-rock edge pressures, the coupled step.
#include "blastsim/ibm/coupler.hpp"

#include "blastsim/ibm/coupling_step_kernels.hpp"
#include "blastsim/core/backend.hpp"
#include "blastsim/core/checkpoint.hpp"
#include "blastsim/core/error.hpp"

#include <thrust/fill.h>
#include <thrust/sequence.h>
#include <thrust/sort.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace blastsim::ibm {

namespace {
//! The cells i0..i1, j0..j1 (inclusive, clipped to the grid) whose centres may lie within r [m] of c.
struct CellBox {
  int i0, i1, j0, j1;
  index_t count() const { return static_cast<index_t>(i1 - i0 + 1) * (j1 - j0 + 1); }
};
CellBox cells_around(const cip::GasGrid& g, const std::array<double, 2>& c, double r) {
  return {std::max(0, static_cast<int>(std::floor((c[0] - r - g.x_min) / g.dx))),
          std::min(g.nx - 1, static_cast<int>(std::ceil((c[0] + r - g.x_min) / g.dx))),
          std::max(0, static_cast<int>(std::floor((c[1] - r - g.y_min) / g.dy))),
          std::min(g.ny - 1, static_cast<int>(std::ceil((c[1] + r - g.y_min) / g.dy)))};
}
}  // namespace


namespace detail {
//! The coupler's device arrays.
struct CouplerArrays {
  DeviceVector<int> u_owner, v_owner;  // padded shape: triangle covering each x-face / y-face point, -1: none
  DeviceVector<std::uint8_t> new_active, changed;  // padded shape: mask being built, cells whose gas moved
  DeviceVector<double> rho_next, e_next;           // padded shape: density and specific energy after the move
  DeviceVector<double> alpha_next, m1_next;        // padded shape: products fields after the move (two materials)
  DeviceVector<double> ledger;  // 4 per cell: covered, uncovered, mass created [kg/m], energy created [J/m]
  // crack gas: per junction (mesh vertex) its place on the mesh outline and its mouth cell; per segment
  // (joint) the gas it handed to the grid in this step and that cell; the sort of all deposits by cell
  DeviceVector<std::uint8_t> outline;
  DeviceVector<int> junction_cell, handover_cell, keys, order;
  DeviceVector<ChannelConserved> handover;
  DeviceVector<double> load_factor;  // per segment: crack_width()'s dw_dopening
  // charges (set_charges): per cell (i + nx j) its charge or -1 and its lighting time (params), and its ledger
  // (4 per cell: products mass, detonation energy, replaced mass and energy). A cell has burnt when its
  // lighting time is at most burnt_until_.
  DeviceVector<int> charge_of_cell;
  DeviceVector<double> burn_time, charge_ledger;
};
}  // namespace detail

GasRockCoupler::GasRockCoupler(cip::GasSolver& gas, fdem::RockSolver& rock, const cip::GasPoint& ambient)
    : gas_(gas), rock_(rock), ambient_(ambient), a_(std::make_unique<detail::CouplerArrays>()) {
  const index_t n = gas_.grid().padded_shape().size();
  a_->u_owner.assign(n, -1);
  a_->v_owner.assign(n, -1);
  a_->new_active.assign(n, 1);
  a_->changed.assign(n, 0);
  a_->rho_next.assign(n, 0.0);
  a_->e_next.assign(n, 0.0);
  a_->alpha_next.assign(gas.materials().two ? n : 0, 0.0);
  a_->m1_next.assign(gas.materials().two ? n : 0, 0.0);
  a_->ledger.assign(4 * static_cast<index_t>(gas_.grid().nx) * gas_.grid().ny, 0.0);
}

GasRockCoupler::~GasRockCoupler() = default;

const char* gas_load_name(GasLoad load) { return load == GasLoad::face_forces ? "faces" : "edges"; }

void GasRockCoupler::rock_to_gas() {
  const cip::GasGrid g = gas_.grid();
  const PaddedShape sh = g.padded_shape();
  fill_device("ibm.clear_owner.u", a_->u_owner, -1);
  fill_device("ibm.clear_owner.v", a_->v_owner, -1);
  const fdem::RockView rock = rock_.view();
  const Field2D<int> uo = make_field_view(a_->u_owner, sh), vo = make_field_view(a_->v_owner, sh);
  for_each_index("ibm.cover", rock.triangles, CoverKernel{rock, g, uo, vo});
  const double t = gas_.time();
  const ChargeCells charge_cells{device_ptr(a_->charge_of_cell), device_ptr(a_->burn_time), g.nx, g.ny};
  if (!charges_.empty()) {
    for_each_cell("ibm.charge.cover.u", 0, g.nx + 1, 0, g.ny, ChargeCoverKernel{charge_cells, 0, t, uo});
    for_each_cell("ibm.charge.cover.v", 0, g.nx, 0, g.ny + 1, ChargeCoverKernel{charge_cells, 1, t, vo});
  }
  const cip::ImmersedBoundaryView ib = gas_.immersed_boundary();
  const bool faces = gas_load_ == GasLoad::face_forces;
  for_each_cell("ibm.face_velocity.u", 0, g.nx + 1, 0, g.ny, ImposedVelocityKernel{rock, g, 0, uo, ib.u_prescribed, ib.u_imposed, faces});
  for_each_cell("ibm.face_velocity.v", 0, g.nx, 0, g.ny + 1, ImposedVelocityKernel{rock, g, 1, vo, ib.v_prescribed, ib.v_imposed, faces});
  const Field2D<std::uint8_t> fresh = make_field_view(a_->new_active, sh), changed = make_field_view(a_->changed, sh);
  const Field2D<double> rho_next = make_field_view(a_->rho_next, sh), e_next = make_field_view(a_->e_next, sh);
  for_each_cell("ibm.cells.mask", 0, g.nx, 0, g.ny, NewMaskKernel{uo, vo, fresh});
  const cip::GasStateView s = gas_.state();
  const bool two = gas_.materials().two;
  const cip::MaterialView m = gas_.material_fields();
  const cip::MaterialView next{make_field_view(a_->alpha_next, sh), make_field_view(a_->m1_next, sh)};
  for_each_cell("ibm.cells.transition", 0, g.nx, 0, g.ny,
                TransitionKernel{ib.cell_active, fresh, s.rho.f, s.e.f, s.u.f, s.v.f, rho_next, e_next, two, m, next,
                                 changed, device_ptr(a_->ledger), g.nx, g.ny, g.cell_area(), ambient_.density,
                                 ambient_.internal_energy, !masks_set_});
  for_each_cell("ibm.cells.apply", 0, g.nx, 0, g.ny,
                ApplyTransitionKernel{fresh, changed, rho_next, e_next, ib.u_imposed, ib.v_imposed, ib.cell_active, s,
                                      two, next, m});
  // Charge cells whose lighting time has come burn, from the second call on: the first call's state is the
  // run's initial state, and the budget counts what burning adds.
  if (!charges_.empty() && masks_set_) {
    for_each_cell("ibm.charge.burn", 0, g.nx, 0, g.ny,
                  ChargeBurnKernel{charge_cells, ib.cell_active, device_ptr(a_->charge_ledger), burnt_until_, t,
                                   g.cell_area(), products_, s, m});
    burnt_until_ = t;
  }
  masks_set_ = true;
  gas_.apply_boundaries();
}

void GasRockCoupler::gas_to_rock() {
  const cip::GasGrid g = gas_.grid();
  const cip::GasStateView s = gas_.state();
  const cip::ImmersedBoundaryView ib = gas_.immersed_boundary();
  const fdem::RockView rock = rock_.view();
  const cip::GasMaterials& mat = gas_.materials();
  for_each_index("ibm.edge_pressure", 3 * static_cast<index_t>(rock.triangles),
                 EdgePressureKernel{rock, g, mat, gas_.material_fields(), ib.cell_active, s.rho.f, s.e.f,
                                    mat_ambient_pressure(),
                                    crack_ ? crack_->network().kind : nullptr, crack_ ? crack_->network().prim : nullptr,
                                    crack_ ? device_ptr(a_->load_factor) : nullptr, gas_load_ == GasLoad::face_forces});
  if (gas_load_ == GasLoad::face_forces) {
    const PaddedShape sh = g.padded_shape();
    for_each_index("ibm.face_load", static_cast<index_t>(rock.triangles),
                   FaceLoadKernel{rock, g, mat, gas_.material_fields(), ib.cell_active, s.rho.f, s.e.f,
                                  make_field_view(a_->u_owner, sh), make_field_view(a_->v_owner, sh),
                                  Field2D<const double>{gas_.pressure_with_viscosity().data, sh}, gas_.steps() > 0});
  }
}

void GasRockCoupler::enable_crack_gas(const CrackGasOptions& options) {
  const std::vector<int>& vertex = rock_.node_vertex();
  if (vertex.size() != static_cast<std::size_t>(rock_.node_count()))
    throw InputError("crack gas: the rock was built without its mesh vertices (FdemTopology::node_vertex)");
  const int junctions = vertex.empty() ? 0 : *std::max_element(vertex.begin(), vertex.end()) + 1;
  std::vector<std::array<int, 2>> ends;
  ends.reserve(rock_.joint_nodes().size());
  for (const fdem::JointNodes& j : rock_.joint_nodes()) ends.push_back({vertex[j.a0], vertex[j.a1]});
  crack_ = std::make_unique<CrackGas>(junctions, ends, gas_.materials(), options);
  std::vector<std::uint8_t> outline(junctions, 0);
  for (const fdem::BoundaryEdge& b : rock_.boundary_edges()) outline[vertex[b.n0]] = outline[vertex[b.n1]] = 1;
  copy_from_host(a_->outline, outline);
  a_->junction_cell.assign(junctions, -1);
  const auto segments = ends.size();
  a_->handover_cell.assign(segments, -1);
  a_->handover.assign(segments, ChannelConserved{0, 0, 0, 0, 0});
  a_->load_factor.assign(segments, 1.0);
  a_->keys.assign(junctions + segments, 0);
  a_->order.assign(junctions + segments, 0);
}

void GasRockCoupler::set_charges(const std::vector<Charge>& charges, const ChargeProducts& products) {
  if (!gas_.materials().two)
    throw InputError("charges: the gas has no detonation products (GasMaterials::two is off); give the explosive");
  if (!(products.density > 0) || !std::isfinite(products.specific_energy))
    throw InputError("charges: the products' state needs a positive density and a finite energy");
  const cip::GasGrid g = gas_.grid();
  const index_t cells = static_cast<index_t>(g.nx) * g.ny;
  std::vector<int> owner(cells, -1);
  std::vector<double> burn(cells, 0.0);
  std::vector<std::array<double, 2>> windows;
  for (std::size_t k = 0; k < charges.size(); ++k) {
    const Charge& c = charges[k];
    const std::string name = "charge " + std::to_string(k);
    if (!(c.radius > 0) || !(c.radius <= c.hole_radius))
      throw InputError(name + ": radius " + std::to_string(c.radius) + " m must be > 0 and <= the hole radius " +
                       std::to_string(c.hole_radius) + " m");
    if (c.initiation == Initiation::point && !(c.detonation_velocity > 0))
      throw InputError(name + ": a point initiation needs a detonation velocity > 0");
    if (!(c.initiation_time >= 0)) throw InputError(name + ": initiation time must be >= 0 s");
    int count = 0;
    std::array<double, 2> window{std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()};
    const CellBox box = cells_around(g, c.center, c.radius);
    for (int j = box.j0; j <= box.j1; ++j)
      for (int i = box.i0; i <= box.i1; ++i) {
        const double x = g.x_min + (i + 0.5) * g.dx, y = g.y_min + (j + 0.5) * g.dy;
        if (std::hypot(x - c.center[0], y - c.center[1]) > c.radius) continue;
        const index_t cell = static_cast<index_t>(j) * g.nx + i;
        if (owner[cell] >= 0)
          throw InputError(name + " and charge " + std::to_string(owner[cell]) + " overlap (they share cell " +
                           std::to_string(i) + ", " + std::to_string(j) + ")");
        owner[cell] = static_cast<int>(k);
        burn[cell] = lighting_time(c, x, y);
        window[0] = std::min(window[0], burn[cell]), window[1] = std::max(window[1], burn[cell]);
        ++count;
      }
    if (count == 0)
      throw InputError(name + ": radius " + std::to_string(c.radius) + " m holds no cell centre of the gas grid (cells " +
                       std::to_string(g.dx) + " m): refine the grid");
    windows.push_back(window);
  }
  charges_ = charges;
  charge_window_ = windows;
  burnt_until_ = -std::numeric_limits<double>::infinity();
  products_ = products;
  copy_from_host(a_->charge_of_cell, owner);
  copy_from_host(a_->burn_time, burn);
  a_->charge_ledger.assign(4 * cells, 0.0);
}

std::vector<double> GasRockCoupler::charge_pressures() const {
  const cip::GasGrid g = gas_.grid();
  const cip::GasMaterials mat = gas_.materials();
  const cip::MaterialReadView m = gas_.material_fields();
  const cip::GasStateView s = gas_.state();
  const Field2D<const std::uint8_t> active = gas_.immersed_boundary().cell_active;
  std::vector<double> out;
  for (const Charge& c : charges_) {
    const CellBox box = cells_around(g, c.center, c.hole_radius);
    const int i0 = box.i0, j0 = box.j0, ni = box.i1 - box.i0 + 1;
    const double cx = c.center[0], cy = c.center[1], r = c.hole_radius;
    const Vec2Sum sum = reduce_sum("ibm.charge.pressure", box.count(), Vec2Sum{0, 0},
                                   [=] BLAST_HD(index_t k) {
                                     const int i = i0 + static_cast<int>(k % ni), j = j0 + static_cast<int>(k / ni);
                                     const double x = g.x_min + (i + 0.5) * g.dx - cx, y = g.y_min + (j + 0.5) * g.dy - cy;
                                     if (!active(i, j) || x * x + y * y > r * r) return Vec2Sum{0, 0};
                                     return Vec2Sum{cip::cell_pressure(mat, m, s.rho.f(i, j), s.e.f(i, j), i, j), 1.0};
                                   });
    out.push_back(sum.y > 0 ? sum.x / sum.y : mat_ambient_pressure());
  }
  return out;
}

std::vector<double> GasRockCoupler::charge_energies() const {
  std::vector<double> out;
  const int* owner = device_ptr(a_->charge_of_cell);
  const double* led = device_ptr(a_->charge_ledger);
  const cip::GasGrid g = gas_.grid();
  const int nx = g.nx;
  for (std::size_t k = 0; k < charges_.size(); ++k) {
    const CellBox box = cells_around(g, charges_[k].center, charges_[k].radius);  // its cells lie in there
    const int kk = static_cast<int>(k), i0 = box.i0, j0 = box.j0, ni = box.i1 - box.i0 + 1;
    out.push_back(reduce_sum("ibm.charge.energy", box.count(), 0.0, [=] BLAST_HD(index_t b) {
      const index_t c = static_cast<index_t>(j0 + b / ni) * nx + i0 + b % ni;
      return owner[c] == kk ? led[4 * c + 1] : 0.0;
    }));
  }
  return out;
}

double GasRockCoupler::next_initiation(double t) const {
  double next = std::numeric_limits<double>::infinity();
  for (const Charge& c : charges_)
    if (c.initiation_time > t) next = std::min(next, c.initiation_time);
  return next;
}

void GasRockCoupler::crack_geometry() {
  const CrackGas::Boundary b = crack_->boundary();
  for_each_index("ibm.crack.geometry", crack_->segments(),
                 CrackGeometryKernel{rock_.view(), gas_.materials(), gas_.grid(), gas_.immersed_boundary().cell_active,
                                     crack_->network(), b.length, b.aperture, device_ptr(a_->handover),
                                     device_ptr(a_->handover_cell), device_ptr(a_->load_factor),
                                     crack_->options().residual_aperture});
}

void GasRockCoupler::crack_mouths() {
  const cip::GasStateView s = gas_.state();
  const CrackGas::Boundary b = crack_->boundary();
  for_each_index("ibm.crack.mouths", crack_->junctions(),
                 CrackMouthKernel{rock_.view(), gas_.materials(), gas_.grid(), gas_.immersed_boundary().cell_active,
                                  s.rho.f, s.e.f, gas_.material_fields(), crack_->graph(), crack_->network(),
                                  device_ptr(a_->outline), b.mouth, b.reservoir, device_ptr(a_->junction_cell)});
}

void GasRockCoupler::apply_crack_deposits() {
  const int nj = crack_->junctions(), ns = crack_->segments(), records = nj + ns;
  int* keys = device_ptr(a_->keys);
  for_each_index("ibm.crack.keys", records,
                 CrackDepositKeyKernel{device_ptr(a_->junction_cell), device_ptr(a_->handover_cell), keys, nj});
  thrust::sequence(thrust::device, a_->order.begin(), a_->order.end());
  thrust::stable_sort_by_key(thrust::device, a_->keys.begin(), a_->keys.end(), a_->order.begin());
  count_host_wait();  // the sequence and the sort block
  const cip::GasGrid g = gas_.grid();
  for_each_index("ibm.crack.deposit", records,
                 CrackDepositKernel{keys, device_ptr(a_->order), crack_->network().deposit, device_ptr(a_->handover), nj,
                                    records, g.nx, g.cell_area(), gas_.state(), gas_.materials().two,
                                    gas_.material_fields()});
  crack_->clear_deposits();
}

void GasRockCoupler::step(double dt, int rock_substeps) {
  if (rock_substeps < 1) throw std::invalid_argument("GasRockCoupler::step: rock_substeps must be at least 1");
  rock_to_gas();
  if (crack_) crack_geometry();
  gas_.step(dt);
  if (crack_) crack_mouths(), crack_->advance(dt), apply_crack_deposits();
  gas_to_rock();
  rock_.advance(dt / rock_substeps, rock_substeps);
  fire_due_charges();  // before the next step chooses its dt: the products' sound speed must set it
  const cip::GasGrid& g = gas_.grid();
  const index_t cells = static_cast<index_t>(g.nx) * g.ny;
  const StepScalars s = reduce_with("ibm.step_scalars", cells + rock_.node_count(), StepScalars{0.0, 0.0},
                                    StepScalarsOf{gas_.signal_rate_kernel(), rock_.peak_speed_kernel(), cells},
                                    MaxOfStepScalars{});
  signal_rate_ = s.signal_rate;
  rock_.finish_motion(s.rock_speed);  // throws InstabilityError on a non-finite rock
}

bool GasRockCoupler::charges_due(double t) const {
  for (const std::array<double, 2>& w : charge_window_)
    if (w[0] <= t && burnt_until_ < w[1] && burnt_until_ < t) return true;
  return false;
}

void GasRockCoupler::fire_due_charges() {
  if (masks_set_ && charges_due(gas_.time())) rock_to_gas();
}

double GasRockCoupler::stable_dt(double courant) const { return std::min(gas_.courant_dt(courant), rock_.stable_dt()); }


CouplingDiagnostics GasRockCoupler::diagnostics() const {
  CouplingDiagnostics d;
  const Vec2Sum f = reduce_sum("ibm.gas_force", 3 * static_cast<index_t>(rock_.triangle_count()), Vec2Sum{0, 0},
                               EdgeForceOf{rock_.view()});
  d.gas_force_on_rock = {f.x, f.y};
  d.gas_work_on_rock = rock_.energies().pressure_work;
  const double* led = device_ptr(a_->ledger);
  auto total = [&](int c) {
    return reduce_sum("ibm.ledger", static_cast<index_t>(a_->ledger.size() / 4), 0.0,
                      [=] BLAST_HD(index_t k) { return led[4 * k + c]; });
  };
  d.transitions.covered = std::lround(total(0));
  d.transitions.uncovered = std::lround(total(1));
  d.transitions.mass_created = total(2);
  d.transitions.energy_created = total(3);
  if (crack_) d.crack_gas = true, d.crack = crack_->totals(mat_ambient_pressure());
  if (!charges_.empty()) {
    const double* cl = device_ptr(a_->charge_ledger);
    const int* owner = device_ptr(a_->charge_of_cell);
    const double* lit = device_ptr(a_->burn_time);
    const double until = burnt_until_;
    const index_t cells = static_cast<index_t>(a_->charge_of_cell.size());
    auto charge_total = [&](int c) {
      return reduce_sum("ibm.charge.ledger", cells, 0.0, [=] BLAST_HD(index_t k) { return cl[4 * k + c]; });
    };
    d.charges.products_mass = charge_total(0);
    d.charges.detonation_energy = charge_total(1);
    d.charges.replaced_mass = charge_total(2);
    d.charges.replaced_energy = charge_total(3);
    d.charges.burnt_cells = std::lround(
        reduce_sum("ibm.charge.burnt", cells, 0.0, [=] BLAST_HD(index_t k) {
          return owner[k] >= 0 && lit[k] <= until ? 1.0 : 0.0;
        }));
  }
  return d;
}

long GasRockCoupler::inactive_cells() const {
  const cip::GasGrid g = gas_.grid();
  const Field2D<const std::uint8_t> active = gas_.immersed_boundary().cell_active;
  const int nx = g.nx;
  return static_cast<long>(reduce_sum("ibm.inactive", static_cast<index_t>(g.nx) * g.ny, 0.0, [=] BLAST_HD(index_t k) {
    return active(static_cast<int>(k % nx), static_cast<int>(k / nx)) ? 0.0 : 1.0;
  }));
}

double GasRockCoupler::crack_mouth_pressure(std::array<double, 2> center, double radius) const {
  if (!crack_) return 0.0;
  const CrackGraphView g = crack_->graph();
  const CrackNetworkView n = crack_->network();
  const fdem::RockView rock = rock_.view();
  const std::uint8_t* outline = device_ptr(a_->outline);
  const double cx = center[0], cy = center[1], r2 = radius * radius;
  return reduce_max("ibm.crack.mouth_pressure", g.segments, 0.0, [=] BLAST_HD(index_t si) {
    const int s = static_cast<int>(si);
    if (n.kind[s] != kSegmentGas) return 0.0;
    const fdem::JointNodes jn = rock.joint_nodes[s];
    double p = 0.0;
    for (int e = 0; e < 2; ++e) {
      if (!outline[g.segment_junction[2 * s + e]]) continue;
      const int node = e == 0 ? jn.a0 : jn.a1;
      const double dx = rock.x[node] - cx, dy = rock.y[node] - cy;
      if (dx * dx + dy * dy > r2) p = n.prim[s].p;
    }
    return p;
  });
}

double GasRockCoupler::crack_gas_front(std::array<double, 2> center, double pressure) const {
  if (!crack_) return 0.0;
  const CrackNetworkView n = crack_->network();
  const fdem::RockView rock = rock_.view();
  const double cx = center[0], cy = center[1];
  return reduce_max("ibm.crack.front", static_cast<index_t>(rock.joints), 0.0, [=] BLAST_HD(index_t si) {
    const int s = static_cast<int>(si);
    if (n.kind[s] != kSegmentGas || !(n.prim[s].p > pressure)) return 0.0;
    const fdem::JointNodes jn = rock.joint_nodes[s];
    const double dx = 0.25 * (rock.x[jn.a0] + rock.x[jn.a1] + rock.x[jn.b0] + rock.x[jn.b1]) - cx;
    const double dy = 0.25 * (rock.y[jn.a0] + rock.y[jn.a1] + rock.y[jn.b0] + rock.y[jn.b1]) - cy;
    return sqrt(dx * dx + dy * dy);
  });
}

double GasRockCoupler::mat_ambient_pressure() const {
  return gas_.materials().air.pressure(ambient_.density, ambient_.internal_energy);
}

void GasRockCoupler::write_checkpoint(CheckpointWriter& w) const {
  w.value("ibm.masks_set", static_cast<int>(masks_set_));
  w.value("ibm.gas_load", static_cast<int>(gas_load_));
  w.array("ibm.ledger", a_->ledger);
  if (crack_) crack_->write_checkpoint(w);
  if (!charges_.empty()) {
    w.array("ibm.charge.ledger", a_->charge_ledger);
    w.value("ibm.charge.burnt_until", burnt_until_);
  }
}

void GasRockCoupler::read_checkpoint(CheckpointReader& r) {
  const int masks = r.value<int>("ibm.masks_set");
  if (masks != 0 && masks != 1) r.fail("ibm.masks_set", "not 0 or 1");
  masks_set_ = masks == 1;
  const int load = r.value<int>("ibm.gas_load");
  if (load != static_cast<int>(gas_load_))
    r.fail("ibm.gas_load", std::string("the checkpoint's gas load is not this run's (") + gas_load_name(gas_load_) + ")");
  r.array("ibm.ledger", a_->ledger, a_->ledger.size());
  if (crack_) crack_->read_checkpoint(r);
  if (!charges_.empty()) {
    r.array("ibm.charge.ledger", a_->charge_ledger, a_->charge_ledger.size());
    burnt_until_ = r.value<double>("ibm.charge.burnt_until");
    if (std::isnan(burnt_until_)) r.fail("ibm.charge.burnt_until", "not a number");
  }
}

}  // namespace blastsim::ibm
