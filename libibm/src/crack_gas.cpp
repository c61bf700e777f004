//! \file crack_gas.cpp
//! \brief CrackGas: the crack graph's arrays, the channel step (crack_gas_kernels.hpp) and its host interface.
#include "blastsim/ibm/crack_gas.hpp"

#include "blastsim/core/backend.hpp"
#include "blastsim/core/checkpoint.hpp"
#include "blastsim/core/error.hpp"

#include <thrust/fill.h>

#include <cmath>
#include <limits>
#include <string>

namespace blastsim::ibm {

void CrackGasOptions::validate() const {
  auto bad = [](const char* key, double v, const char* allowed) {
    throw InputError(std::string("crack gas: ") + key + " = " + std::to_string(v) + ": " + allowed);
  };
  if (!(residual_aperture > 0) || !std::isfinite(residual_aperture)) bad("residual_aperture", residual_aperture, "must be > 0 [m]");
  if (!(friction_factor >= 0) || !std::isfinite(friction_factor)) bad("friction_factor", friction_factor, "must be >= 0");
  if (!(viscosity >= 0) || !std::isfinite(viscosity)) bad("viscosity", viscosity, "must be >= 0 [Pa s]");
  if (!(courant > 0 && courant <= 1)) bad("courant", courant, "must be in (0, 1]");
}

namespace detail {
struct CrackArrays {
  DeviceVector<int> segment_junction, junction_offset, junction_entry;  // the graph (fixed)
  DeviceVector<double> length, aperture, volume;                        // per segment
  DeviceVector<std::uint8_t> kind;
  DeviceVector<ChannelConserved> cons;
  DeviceVector<ChannelPrimitive> prim, face;  // per segment, per end
  DeviceVector<ChannelFlux> out;              // per end
  DeviceVector<double> end_area;              // per end
  DeviceVector<std::uint8_t> mouth;           // per junction
  DeviceVector<ChannelPrimitive> reservoir;   // per junction
  DeviceVector<ChannelConserved> deposit;     // per junction
};
}  // namespace detail

CrackGas::CrackGas(int junctions, const std::vector<std::array<int, 2>>& segment_ends, const cip::GasMaterials& materials,
                   const CrackGasOptions& options)
    : segments_(static_cast<int>(segment_ends.size())), junctions_(junctions), mat_(materials), options_(options),
      a_(std::make_unique<detail::CrackArrays>()) {
  options_.validate();
  if (junctions < 0) throw InputError("crack gas: negative junction count");
  std::vector<int> sj(2 * static_cast<std::size_t>(segments_)), offset(junctions + 1, 0);
  for (int s = 0; s < segments_; ++s)
    for (int e = 0; e < 2; ++e) {
      const int J = segment_ends[s][e];
      if (J < 0 || J >= junctions)
        throw InputError("crack gas: segment " + std::to_string(s) + " ends at junction " + std::to_string(J) +
                         ", outside [0, " + std::to_string(junctions) + ")");
      sj[2 * s + e] = J;
      ++offset[J + 1];
    }
  for (int J = 0; J < junctions; ++J) {
    if (offset[J + 1] > kCrackMaxDegree)
      throw InputError("crack gas: junction " + std::to_string(J) + " joins " + std::to_string(offset[J + 1]) +
                       " segment ends, at most " + std::to_string(kCrackMaxDegree) + " are supported");
    offset[J + 1] += offset[J];
  }
  std::vector<int> entry(offset[junctions]), fill(offset.begin(), offset.end() - 1);
  for (int end = 0; end < 2 * segments_; ++end) entry[fill[sj[end]]++] = end;  // ascending within a junction
  detail::CrackArrays& a = *a_;
  copy_from_host(a.segment_junction, sj);
  copy_from_host(a.junction_offset, offset);
  copy_from_host(a.junction_entry, entry);
  a.length.assign(segments_, 1.0);
  a.aperture.assign(segments_, options_.residual_aperture);
  a.volume.assign(segments_, options_.residual_aperture);
  a.kind.assign(segments_, kSegmentNone);
  a.cons.assign(segments_, ChannelConserved{0, 0, 0, 0, 0});
  a.prim.assign(segments_, ChannelPrimitive{0, 0, 0, 0, 0, 0, 0});
  a.face.assign(2 * static_cast<std::size_t>(segments_), ChannelPrimitive{0, 0, 0, 0, 0, 0, 0});
  a.out.assign(2 * static_cast<std::size_t>(segments_), ChannelFlux{0, 0, 0, 0, 0});
  a.end_area.assign(2 * static_cast<std::size_t>(segments_), 0.0);
  a.mouth.assign(junctions_, 0);
  a.reservoir.assign(junctions_, ChannelPrimitive{0, 0, 0, 0, 0, 0, 0});
  a.deposit.assign(junctions_, ChannelConserved{0, 0, 0, 0, 0});
}

CrackGas::~CrackGas() = default;
CrackGas::CrackGas(CrackGas&&) noexcept = default;
CrackGas& CrackGas::operator=(CrackGas&&) noexcept = default;

void CrackGas::set_geometry(const std::vector<double>& length, const std::vector<double>& aperture) {
  if (length.size() != static_cast<std::size_t>(segments_) || aperture.size() != length.size())
    throw InputError("crack gas: set_geometry needs one length and one aperture per segment");
  copy_from_host(a_->length, length);
  copy_from_host(a_->aperture, aperture);
}

void CrackGas::set_gas(const std::vector<std::uint8_t>& kind, const std::vector<ChannelConserved>& gas,
                       const std::vector<double>& volume) {
  const auto n = static_cast<std::size_t>(segments_);
  if (kind.size() != n || gas.size() != n || volume.size() != n)
    throw InputError("crack gas: set_gas needs one kind, state and volume per segment");
  copy_from_host(a_->kind, kind);
  copy_from_host(a_->cons, gas);
  copy_from_host(a_->volume, volume);
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
  copy_from_host(a_->mouth, mouth);
  copy_from_host(a_->reservoir, res);
}

CrackNetworkView CrackGas::network() {
  detail::CrackArrays& a = *a_;
  return {device_ptr(a.length), device_ptr(a.aperture), device_ptr(a.kind),     device_ptr(a.cons),
          device_ptr(a.volume), device_ptr(a.prim),     device_ptr(a.face),     device_ptr(a.out),
          device_ptr(a.end_area), device_ptr(a.mouth),  device_ptr(a.reservoir), device_ptr(a.deposit)};
}

CrackGraphView CrackGas::graph() const {
  const detail::CrackArrays& a = *a_;
  return {device_ptr(a.segment_junction), device_ptr(a.junction_offset), device_ptr(a.junction_entry), segments_,
          junctions_};
}

CrackGas::Boundary CrackGas::boundary() {
  return {device_ptr(a_->length), device_ptr(a_->aperture), device_ptr(a_->mouth), device_ptr(a_->reservoir)};
}

void CrackGas::update_primitives() {
  for_each_index("crack.primitive", segments_, SegmentPrimitiveKernel{mat_, network()});
}

double CrackGas::stable_dt() const {
  CrackNetworkView n = const_cast<CrackGas*>(this)->network();
  double rate = reduce_max("crack.rate", segments_, 0.0, SegmentRateOf{mat_, n});
  // A mouth's reservoir gas enters at up to its vacuum front speed.
  const CrackGraphView g = graph();
  const cip::GasMaterials mat = mat_;
  rate = std::max(rate, reduce_max("crack.mouth_rate", junctions_, 0.0, [=] BLAST_HD(index_t ji) {
                    const int J = static_cast<int>(ji);
                    if (!n.mouth[J]) return 0.0;
                    const ChannelPrimitive r = n.reservoir[J];
                    const double speed = r.c * fmax(1.0, 2.0 / mixture_gruneisen(mat, r.alpha));
                    double best = 0.0;
                    for (int k = g.junction_offset[J]; k < g.junction_offset[J + 1]; ++k) {
                      const int s = g.junction_entry[k] / 2;
                      if (n.kind[s] == kSegmentGas) best = fmax(best, speed / n.length[s]);
                    }
                    return best;
                  }));
  return rate > 0 ? options_.courant / rate : std::numeric_limits<double>::infinity();
}

void CrackGas::step(double dt) {
  update_primitives();
  step_from_primitives(dt);
}

void CrackGas::step_from_primitives(double dt) {
  const CrackNetworkView n = network();
  const CrackGraphView g = graph();
  for_each_index("crack.faces", segments_, FaceStateKernel{mat_, g, n, options_.second_order, dt});
  for_each_index("crack.junctions", junctions_, JunctionFluxKernel{mat_, g, n, dt});
  for_each_index("crack.update", segments_,
                 SegmentUpdateKernel{n, ChannelFlowParams{options_.friction_factor, options_.viscosity}, dt});
}

int CrackGas::advance(double dt) {
  if (!(dt > 0)) return 0;
  update_primitives();
  const double limit = stable_dt();
  const int steps = std::isfinite(limit) ? std::max(1, static_cast<int>(std::ceil(dt / limit * (1 - 1e-12)))) : 1;
  for (int k = 0; k < steps; ++k) {  // each substep starts from the primitives just computed
    step_from_primitives(dt / steps);
    update_primitives();
  }
  return steps;
}

CrackGasTotals CrackGas::totals(double reference_pressure) const {
  CrackGasTotals t;
  const ChannelConserved* c = device_ptr(a_->cons);
  const ChannelPrimitive* p = device_ptr(a_->prim);
  const std::uint8_t* kind = device_ptr(a_->kind);
  const double* vol = device_ptr(a_->volume);
  auto sum = [&](const char* label, auto f) { return reduce_sum(label, segments_, 0.0, f); };
  t.mass = sum("crack.mass", [=] BLAST_HD(index_t s) { return kind[s] == kSegmentGas ? c[s].m : 0.0; });
  t.energy = sum("crack.energy", [=] BLAST_HD(index_t s) { return kind[s] == kSegmentGas ? c[s].E : 0.0; });
  t.products_mass = sum("crack.products", [=] BLAST_HD(index_t s) { return kind[s] == kSegmentGas ? c[s].m1 : 0.0; });
  t.volume = sum("crack.volume", [=] BLAST_HD(index_t s) { return kind[s] == kSegmentGas ? vol[s] : 0.0; });
  t.gas_segments = std::lround(sum("crack.count", [=] BLAST_HD(index_t s) { return kind[s] == kSegmentGas ? 1.0 : 0.0; }));
  const double wet = 1.5 * reference_pressure;
  t.wet_segments = std::lround(
      sum("crack.wet", [=] BLAST_HD(index_t s) { return kind[s] == kSegmentGas && p[s].p > wet ? 1.0 : 0.0; }));
  t.max_pressure = reduce_max("crack.max_p", segments_, 0.0,
                              [=] BLAST_HD(index_t s) { return kind[s] == kSegmentGas ? p[s].p : 0.0; });
  return t;
}

std::vector<ChannelConserved> CrackGas::gas() const { return to_host(a_->cons); }
std::vector<ChannelPrimitive> CrackGas::primitives() const { return to_host(a_->prim); }
std::vector<std::uint8_t> CrackGas::kinds() const { return to_host(a_->kind); }
std::vector<double> CrackGas::apertures() const { return to_host(a_->aperture); }
std::vector<double> CrackGas::volumes() const { return to_host(a_->volume); }
std::vector<ChannelConserved> CrackGas::deposits() const { return to_host(a_->deposit); }
void CrackGas::clear_deposits() {
  fill_device("crack.clear_deposits", a_->deposit, ChannelConserved{0, 0, 0, 0, 0});
}

void CrackGas::write_checkpoint(CheckpointWriter& w) const {
  w.array("crack.kind", a_->kind);
  w.array("crack.gas", a_->cons);
  w.array("crack.volume", a_->volume);
  w.array("crack.length", a_->length);
  w.array("crack.aperture", a_->aperture);
}

void CrackGas::read_checkpoint(CheckpointReader& r) {
  const auto n = static_cast<std::size_t>(segments_);
  r.array("crack.kind", a_->kind, n);
  r.array("crack.gas", a_->cons, n);
  r.array("crack.volume", a_->volume, n);
  r.array("crack.length", a_->length, n);
  r.array("crack.aperture", a_->aperture, n);
  update_primitives();
}

}  // namespace blastsim::ibm
