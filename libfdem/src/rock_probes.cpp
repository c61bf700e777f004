//! \file rock_probes.cpp
//! \brief RockProbes: where each probe sits, its peaks on the device, its samples and its checkpoint record.
#include "blastsim/fdem/rock_probes.hpp"

#include "blastsim/core/checkpoint.hpp"
#include "blastsim/core/device_groups.hpp"
#include "blastsim/core/error.hpp"
#include "blastsim/fdem/probe_kernels.hpp"

#include <cmath>
#include <sstream>
#include <string>

namespace blastsim::fdem {

namespace detail {
BLASTSIM_STATE_STORAGE(RockProbeArrays, BLASTSIM_ROCK_PROBES)
struct ProbeArrays : RockProbeArraysArrays {};
}  // namespace detail

RockProbes::RockProbes() : a_(std::make_unique<detail::ProbeArrays>()) {}
RockProbes::~RockProbes() = default;
RockProbes::RockProbes(RockProbes&&) noexcept = default;
RockProbes& RockProbes::operator=(RockProbes&&) noexcept = default;

void RockProbes::set(const std::vector<std::array<double, 2>>& points, const std::vector<double>& until,
                     const std::vector<double>& px, const std::vector<double>& py) {
  if (!until.empty() && until.size() != points.size())
    throw InputError("set_probes: " + std::to_string(until.size()) + " window ends for " + std::to_string(points.size()) +
                     " probes");
  const int triangles = static_cast<int>(px.size() / 3);
  std::vector<ProbeStation> stations;
  for (size_t k = 0; k < points.size(); ++k) {
    const double x = points[k][0], y = points[k][1];
    int found = -1;
    double w[3] = {0, 0, 0};
    for (int t = 0; t < triangles && found < 0; ++t) {  // barycentric weights (counter-clockwise triangles)
      const int n = 3 * t;
      const double det = (px[n + 1] - px[n]) * (py[n + 2] - py[n]) - (px[n + 2] - px[n]) * (py[n + 1] - py[n]);
      const double w1 = ((x - px[n]) * (py[n + 2] - py[n]) - (px[n + 2] - px[n]) * (y - py[n])) / det;
      const double w2 = ((px[n + 1] - px[n]) * (y - py[n]) - (x - px[n]) * (py[n + 1] - py[n])) / det;
      const double tol = -1e-12;
      if (w1 >= tol && w2 >= tol && 1 - w1 - w2 >= tol) found = t, w[0] = 1 - w1 - w2, w[1] = w1, w[2] = w2;
    }
    if (found < 0) {
      std::ostringstream os;
      os << "rock probe " << k << " at (" << x << ", " << y << ") m lies in no triangle of the rock mesh";
      throw InputError(os.str());
    }
    stations.push_back(ProbeStation{found, {w[0], w[1], w[2]}, until.empty() ? 1e308 : until[k]});
  }
  count_ = static_cast<int>(stations.size());
  copy_from_host(a_->station, stations);
  a_->peak.assign(count_, ProbePeak{0, 0, 0, 0});
}

void RockProbes::record(const NodeMotion<Access::read>& nodes, double time) {
  for_each_index("fdem.probes", count_, ProbePeakKernel{nodes, a_->view(), time});
}

std::vector<ProbeSample> RockProbes::samples(const NodeMotion<Access::read>& nodes) const {
  // The current velocity at each probe, interpolated on the device (one thread per probe) and copied once.
  a_->velocity.resize(count_);
  for_each_index("fdem.probes.velocity", count_, ProbeVelocityKernel{nodes, a_->view()});
  const std::vector<Vec2> v = to_host(a_->velocity);
  const std::vector<ProbePeak> peaks = to_host(a_->peak);
  std::vector<ProbeSample> out(v.size());
  for (size_t k = 0; k < v.size(); ++k)
    out[k] = ProbeSample{v[k].x, v[k].y, peaks[k].speed, peaks[k].time, peaks[k].vx, peaks[k].vy};
  return out;
}

void RockProbes::clear_peaks() { a_->peak.assign(count_, ProbePeak{0, 0, 0, 0}); }

void RockProbes::write_checkpoint(CheckpointWriter& w) const { write_array(w, "rock.probes.peak", a_->peak); }

void RockProbes::read_checkpoint(CheckpointReader& r) {
  read_array(r, "rock.probes.peak", a_->peak);
  if (a_->peak.size() != static_cast<size_t>(count_))
    r.fail("rock.probes.peak", "holds " + std::to_string(a_->peak.size()) + " probes, this case has " +
                                   std::to_string(count_));
  for (const ProbePeak& p : to_host(a_->peak))
    if (!(std::isfinite(p.speed) && p.speed >= 0 && std::isfinite(p.time) && std::isfinite(p.vx) && std::isfinite(p.vy)))
      r.fail("rock.probes.peak", "a peak is not finite or negative");
}

}  // namespace blastsim::fdem
