//! \file crack_gas.cpp
//! \brief CrackGas: the crack graph's arrays, the channel step (crack_gas_kernels.hpp) and its host interface.
#include "blastsim/ibm/crack_gas.hpp"

#include "blastsim/core/device_groups.hpp"
#include "blastsim/core/checkpoint.hpp"
#include "blastsim/core/csr.hpp"
#include "blastsim/core/error.hpp"

#include <sstream>
#include <stdexcept>
#include <cmath>
#include <limits>
#include <string>

namespace blastsim::ibm {

void CrackGasOptions::validate() const {
  auto bad = [](const char* key, double v, const char* allowed) {
    throw InputError(std::string("crack gas: ") + key + " = " + std::to_string(v) + ": " + allowed);
  };
  if (!(residual_aperture > 0) || !std::isfinite(residual_aperture)) bad("residual_aperture", residual_aperture, "must be > 0 [m]");
  if (friction_factor && (!(*friction_factor >= 0) || !std::isfinite(*friction_factor)))
    bad("friction_factor", *friction_factor, "must be >= 0");
  if (roughness && (!(*roughness > 0) || !std::isfinite(*roughness))) bad("roughness", *roughness, "must be > 0 [m]");
  if (!(viscosity >= 0) || !std::isfinite(viscosity)) bad("viscosity", viscosity, "must be >= 0 [Pa s]");
  if (!(courant >= kMinCourant && courant <= 1)) bad("courant", courant, "must be in [0.01, 1]");
  if (!(handover_width >= 1) || !std::isfinite(handover_width))
    bad("handover_width", handover_width, "must be >= 1 [cells]");
  if (!(vacuum_fraction >= 0 && vacuum_fraction < 1)) bad("vacuum_fraction", vacuum_fraction, "must be in [0, 1)");
  if (!(prandtl > 0) || !std::isfinite(prandtl)) bad("prandtl", prandtl, "must be > 0");
  if (wall_theta && (!(*wall_theta > 0) || !std::isfinite(*wall_theta)))
    bad("wall_theta", *wall_theta, "must be > 0 [J/kg]");
  if (joint_closure && (!(joint_closure->stiffness > 0) || !std::isfinite(joint_closure->stiffness)))
    bad("joint_closure_stiffness", joint_closure->stiffness, "must be > 0 [Pa/m]");
  if (joint_closure && (!(joint_closure->max_closure > 0) || !std::isfinite(joint_closure->max_closure)))
    bad("joint_max_closure", joint_closure->max_closure, "must be > 0 [m]");
  if (walls != WallHeat::adiabatic && !wall_theta)
    throw InputError(std::string("crack gas: walls = ") + wall_heat_name(walls) +
                     " needs the walls' temperature (wall_theta = R T_wall [J/kg]; a coupled run sets the ambient air's)");
}

const char* wall_heat_name(WallHeat walls) {
  switch (walls) {
    case WallHeat::adiabatic: return "adiabatic";
    case WallHeat::isothermal: return "isothermal";
    case WallHeat::exchange: return "exchange";
  }
  return "?";
}

ChannelFlowParams CrackGasOptions::flow() const {
  return {friction_factor.value_or(-1.0), roughness.value_or(residual_aperture), viscosity, walls,
          wall_theta.value_or(0.0), prandtl, std::pow(prandtl, -2.0 / 3.0)};
}

namespace detail {
BLASTSIM_CONST_STORAGE(CrackGraph, BLASTSIM_CRACK_GRAPH)
BLASTSIM_STATE_STORAGE(CrackGeometry, BLASTSIM_CRACK_GEOMETRY)
BLASTSIM_STATE_STORAGE(CrackSegments, BLASTSIM_CRACK_SEGMENTS)
BLASTSIM_STATE_STORAGE(CrackEndStates, BLASTSIM_CRACK_END_STATES)
BLASTSIM_STATE_STORAGE(CrackEndFluxes, BLASTSIM_CRACK_END_FLUXES)
BLASTSIM_STATE_STORAGE(CrackMouths, BLASTSIM_CRACK_MOUTHS)
BLASTSIM_STATE_STORAGE(CrackDeposits, BLASTSIM_CRACK_DEPOSITS)
//! The network's arrays: the graph (fixed), per segment its geometry and state, per end the step's work
//! arrays, per junction its mouth and deposit.
struct CrackArrays {
  CrackGraphArrays graph;
  CrackGeometryArrays geometry;
  CrackSegmentsArrays segments;
  CrackEndStatesArrays end_states;
  CrackEndFluxesArrays end_fluxes;
  CrackMouthsArrays mouths;
  CrackDepositsArrays deposits;
};
}  // namespace detail

CrackGas::CrackGas(int junctions, const std::vector<std::array<int, 2>>& segment_ends, const cip::GasMaterials& materials,
                   const CrackGasOptions& options)
    : segments_(static_cast<int>(segment_ends.size())), junctions_(junctions), mat_(materials), options_(options),
      a_(std::make_unique<detail::CrackArrays>()) {
  options_.validate();
  if (junctions < 0) throw InputError("crack gas: negative junction count");
  std::vector<int> sj(2 * static_cast<std::size_t>(segments_));
  for (int s = 0; s < segments_; ++s)
    for (int e = 0; e < 2; ++e) {
      const int J = segment_ends[s][e];
      if (J < 0 || J >= junctions)
        throw InputError("crack gas: segment " + std::to_string(s) + " ends at junction " + std::to_string(J) +
                         ", outside [0, " + std::to_string(junctions) + ")");
      sj[2 * s + e] = J;
    }
  const HostCsr ends = group_by_key(sj, junctions);  // each junction's segment ends, ascending
  for (int J = 0; J < junctions; ++J) {
    const int degree = ends.offset[J + 1] - ends.offset[J];
    if (degree > kCrackMaxDegree)
      throw InputError("crack gas: junction " + std::to_string(J) + " joins " + std::to_string(degree) +
                       " segment ends, at most " + std::to_string(kCrackMaxDegree) + " are supported");
  }
  detail::CrackArrays& a = *a_;
  copy_from_host(a.graph.segment_junction, sj);
  copy_from_host(a.graph.junction_offset, ends.offset);
  copy_from_host(a.graph.junction_entry, ends.entry);
  a.geometry.length.assign(segments_, 1.0);
  a.geometry.aperture.assign(segments_, options_.residual_aperture);
  a.geometry.axis_x.assign(segments_, 0.0);
  a.geometry.axis_y.assign(segments_, 0.0);
  a.segments.volume.assign(segments_, options_.residual_aperture);
  a.segments.kind.assign(segments_, kSegmentNone);
  a.segments.cons.assign(segments_, ChannelConserved{0, 0, 0, 0, 0});
  a.segments.prim.assign(segments_, ChannelPrimitive{0, 0, 0, 0, 0, 0, 0});
  a.segments.wall_heat.assign(segments_, 0.0);
  a.end_states.face.assign(2 * static_cast<std::size_t>(segments_), ChannelPrimitive{0, 0, 0, 0, 0, 0, 0});
  a.end_fluxes.out.assign(2 * static_cast<std::size_t>(segments_), ChannelFlux{0, 0, 0, 0, 0});
  a.end_fluxes.end_area.assign(2 * static_cast<std::size_t>(segments_), 0.0);
  a.mouths.open.assign(junctions_, 0);
  a.mouths.reservoir.assign(junctions_, ChannelPrimitive{0, 0, 0, 0, 0, 0, 0});
  a.mouths.reservoir_mass.assign(junctions_, std::numeric_limits<double>::infinity());
  a.deposits.deposit.assign(junctions_, ChannelConserved{0, 0, 0, 0, 0});
  a.deposits.drawn.assign(junctions_, ChannelConserved{0, 0, 0, 0, 0});
  a.deposits.momentum_x.assign(junctions_, 0.0);
  a.deposits.momentum_y.assign(junctions_, 0.0);
}

CrackGas::~CrackGas() = default;
CrackGas::CrackGas(CrackGas&&) noexcept = default;
CrackGas& CrackGas::operator=(CrackGas&&) noexcept = default;

void CrackGas::set_geometry(const std::vector<double>& length, const std::vector<double>& aperture) {
  if (length.size() != static_cast<std::size_t>(segments_) || aperture.size() != length.size())
    throw InputError("crack gas: set_geometry needs one length and one aperture per segment");
  copy_from_host(a_->geometry.length, length);
  copy_from_host(a_->geometry.aperture, aperture);
}

void CrackGas::set_gas(const std::vector<std::uint8_t>& kind, const std::vector<ChannelConserved>& gas,
                       const std::vector<double>& volume) {
  const auto n = static_cast<std::size_t>(segments_);
  if (kind.size() != n || gas.size() != n || volume.size() != n)
    throw InputError("crack gas: set_gas needs one kind, state and volume per segment");
  copy_from_host(a_->segments.kind, kind);
  copy_from_host(a_->segments.cons, gas);
  copy_from_host(a_->segments.volume, volume);
  update_primitives();
}

void CrackGas::set_reservoirs(const std::vector<int>& junctions, const std::vector<ChannelPrimitive>& states) {
  if (junctions.size() != states.size()) throw InputError("crack gas: one reservoir state per junction");
  std::vector<std::uint8_t> mouth(junctions_, 0);
  std::vector<ChannelPrimitive> res(junctions_, ChannelPrimitive{0, 0, 0, 0, 0, 0, 0});
  for (std::size_t k = 0; k < junctions.size(); ++k) {
    if (junctions[k] < 0 || junctions[k] >= junctions_) throw InputError("crack gas: reservoir junction out of range");
    mouth[junctions[k]] = 1;
    res[junctions[k]] = states[k];
  }
  copy_from_host(a_->mouths.open, mouth);
  copy_from_host(a_->mouths.reservoir, res);
}

CrackGraph CrackGas::graph() const { return a_->graph.view(); }
CrackGeometry<Access::read_write> CrackGas::geometry() { return a_->geometry.view(); }
CrackGeometry<Access::read> CrackGas::geometry() const { return a_->geometry.read(); }
CrackSegments<Access::read_write> CrackGas::segments() { return a_->segments.view(); }
CrackSegments<Access::read> CrackGas::segments() const { return a_->segments.read(); }
CrackMouths<Access::read_write> CrackGas::mouths() { return a_->mouths.view(); }
CrackMouths<Access::read> CrackGas::mouths() const { return a_->mouths.read(); }
CrackDeposits<Access::read> CrackGas::deposit_view() const { return a_->deposits.read(); }

void CrackGas::update_primitives() {
  for_each_index("crack.primitive", segments_, SegmentPrimitiveKernel{mat_, a_->segments.view(), vacuum_density_});
}

void CrackGas::update_vacuum_density() {
  const index_t n = static_cast<index_t>(segments_) + junctions_;
  vacuum_density_ = options_.vacuum_fraction *
                    reduce_max("crack.densest", n, 0.0, DensestGasOf{a_->segments.read(), a_->mouths.read(), segments_});
}

double CrackGas::stable_dt() const {
  const detail::CrackArrays& a = *a_;
  const CrackGeometry<Access::read> geo = a.geometry.read();
  const CrackSegments<Access::read> seg = a.segments.read();
  double rate = reduce_max("crack.rate", segments_, 0.0, SegmentRateOf{mat_, geo, seg});
  // A mouth's reservoir gas enters at up to its vacuum front speed.
  rate = std::max(rate, reduce_max("crack.mouth_rate", junctions_, 0.0,
                                   MouthRateOf{mat_, a.graph.view(), geo, seg, a.mouths.read()}));
  if (rate >= kInvalidSegmentRate) return 0.0;  // a segment's state is not valid (SegmentRateOf)
  return rate > 0 ? options_.courant / rate : std::numeric_limits<double>::infinity();
}

void CrackGas::step(double dt) {
  update_primitives();
  step_from_primitives(dt, dt);
}

void CrackGas::step_from_primitives(double dt, double interval) {
  detail::CrackArrays& a = *a_;
  const CrackGraph g = a.graph.view();
  const CrackGeometry<Access::read> geo = a.geometry.read();
  const CrackMouths<Access::read> mouths = a.mouths.read();
  for_each_index("crack.faces", segments_,
                 FaceStateKernel{mat_, g, geo, a.segments.read(), mouths, a.end_states.view(), options_.second_order,
                                 vacuum_density_, dt});
  for_each_index("crack.junctions", junctions_,
                 JunctionFluxKernel{mat_, g, geo, a.segments.read(), mouths, a.end_states.read(), a.end_fluxes.view(),
                                    a.deposits.view(), options_.flow(), dt, interval});
  for_each_index("crack.update", segments_,
                 SegmentUpdateKernel{mat_, geo, a.segments.view(), a.end_fluxes.read(),
                                     options_.flow(), vacuum_density_, dt});
}

int CrackGas::advance(double dt, double interval) {
  if (!(dt > 0)) return 0;
  if (!(interval >= dt)) throw std::invalid_argument("CrackGas::advance: the interval must be at least dt");
  update_vacuum_density();
  update_primitives();
  const double limit = stable_dt();
  if (!(limit > 0))
    throw InstabilityError("crack gas state not valid: " + describe_invalid_segment());
  // The count in floating point first: dt / limit can exceed any int (a tiny limit), and must not wrap.
  const double wanted = std::isfinite(limit) ? std::max(1.0, std::ceil(dt / limit * (1 - 1e-12))) : 1.0;
  if (!(wanted <= kMaxSubsteps)) {
    std::ostringstream os;
    os << "the crack gas needs " << wanted << " substeps of " << limit << " s in one step of " << dt
       << " s (at most " << kMaxSubsteps << "): its signal crosses a segment far faster than the step allows";
    throw InstabilityError(os.str());
  }
  const int steps = static_cast<int>(wanted);
  for (int k = 0; k < steps; ++k) {  // each substep starts from the primitives just computed
    step_from_primitives(dt / steps, interval);
    update_primitives();
  }
  return steps;
}

std::string CrackGas::describe_invalid_segment() const {
  const std::vector<std::uint8_t> kind = kinds();
  const std::vector<ChannelConserved> c = gas();
  const std::vector<double> volume = volumes(), w = apertures();
  for (std::size_t s = 0; s < kind.size(); ++s) {
    if (kind[s] != kSegmentGas || segment_state_valid(c[s], volume[s])) continue;
    std::ostringstream os;
    os << "segment (joint) " << s << ": mass " << c[s].m << " kg/m, momentum " << c[s].q << " kg/s, energy " << c[s].E
       << " J/m, volume " << volume[s] << " m2/m, aperture " << w[s] << " m";
    return os.str();
  }
  return "a mouth's reservoir (the grid cell a crack opens into) holds no valid gas";
}

CrackGasTotals CrackGas::totals(double reference_pressure) const {
  CrackGasTotals t;
  const CrackSegments<Access::read> seg = a_->segments.read();
  const double wet = 1.5 * reference_pressure;
  auto sum = [&](const char* label, GasSegmentValue::What what) {
    return reduce_sum(label, segments_, 0.0, GasSegmentValue{seg, what, wet});
  };
  t.mass = sum("crack.mass", GasSegmentValue::mass);
  t.energy = sum("crack.energy", GasSegmentValue::energy);
  t.products_mass = sum("crack.products", GasSegmentValue::products_mass);
  t.volume = sum("crack.volume", GasSegmentValue::volume);
  t.gas_segments = std::lround(sum("crack.count", GasSegmentValue::count));
  t.wet_segments = std::lround(sum("crack.wet", GasSegmentValue::wet_count));
  t.max_pressure = reduce_max("crack.max_p", segments_, 0.0, GasSegmentValue{seg, GasSegmentValue::pressure, wet});
  t.wall_heat = reduce_sum("crack.wall_heat", segments_, 0.0, WallHeatOf{seg});
  return t;
}

std::vector<ChannelConserved> CrackGas::gas() const { return to_host(a_->segments.cons); }
std::vector<ChannelPrimitive> CrackGas::primitives() const { return to_host(a_->segments.prim); }
std::vector<std::uint8_t> CrackGas::kinds() const { return to_host(a_->segments.kind); }
std::vector<double> CrackGas::apertures() const { return to_host(a_->geometry.aperture); }
std::vector<double> CrackGas::volumes() const { return to_host(a_->segments.volume); }
CrackSegmentFields CrackGas::segment_fields() const {
  const std::vector<std::uint8_t> kind = kinds();
  const std::vector<double> w = apertures();
  const std::vector<ChannelPrimitive> p = primitives();
  const std::vector<ChannelConserved> m = gas();
  const std::size_t n = kind.size();
  CrackSegmentFields f{std::vector<double>(n, 0.0), std::vector<double>(n, 0.0), std::vector<double>(n, 0.0),
                       std::vector<double>(n, 0.0)};
  for (std::size_t j = 0; j < n; ++j) {
    if (kind[j] != kSegmentNone) f.aperture[j] = w[j];
    if (kind[j] == kSegmentGas) f.gas_pressure[j] = p[j].p, f.gas_mass[j] = m[j].m, f.blast_gas_fraction[j] = p[j].Y;
  }
  return f;
}

std::vector<ChannelConserved> CrackGas::deposits() const { return to_host(a_->deposits.deposit); }
void CrackGas::clear_deposits() {
  for_each_index("crack.clear_deposits", junctions_, ClearDepositsKernel{a_->deposits.view()});
}

//! The checkpoint holds the segments' state and geometry (the graph comes from the mesh; the ends and the
//! mouths are recomputed every step).
void CrackGas::write_checkpoint(CheckpointWriter& w) const {
  w.value("crack.vacuum_density", vacuum_density_);
  a_->segments.for_each([&](const char* name, const auto& v) { write_array(w, std::string("crack.") + name, v); });
  a_->geometry.for_each([&](const char* name, const auto& v) { write_array(w, std::string("crack.") + name, v); });
}

void CrackGas::check_kinds(const CheckpointReader& r) const {
  for (const std::uint8_t k : to_host(a_->segments.kind))
    if (k != kSegmentNone && k != kSegmentGas && k != kSegmentGrid) r.fail("crack.kind", "not a segment kind (0, 1 or 2)");
}

void CrackGas::read_checkpoint(CheckpointReader& r) {
  const auto n = static_cast<std::size_t>(segments_);
  vacuum_density_ = r.value<double>("crack.vacuum_density");
  if (!(vacuum_density_ >= 0) || !std::isfinite(vacuum_density_)) r.fail("crack.vacuum_density", "not a density >= 0");
  a_->segments.for_each([&](const char* name, auto& v) { read_array(r, std::string("crack.") + name, v, n); });
  a_->geometry.for_each([&](const char* name, auto& v) { read_array(r, std::string("crack.") + name, v, n); });
  check_kinds(r);
  for (const double q : to_host(a_->segments.wall_heat))
    if (!std::isfinite(q)) r.fail("crack.wall_heat", "not finite");
  update_primitives();
}

}  // namespace blastsim::ibm
