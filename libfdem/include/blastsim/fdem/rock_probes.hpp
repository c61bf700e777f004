//! \file rock_probes.hpp
//! \brief fdem::RockProbes: velocity probes fixed to the rock (geophones), their peak particle velocities and
//! their checkpoint record; a room of the rock solver of its own. Host-safe: the arrays sit behind a pointer
//! (probe_kernels.hpp declares them).
#pragma once

#include "blastsim/core/checkpoint_fwd.hpp"
#include "blastsim/fdem/rock_fields.hpp"
#include "blastsim/fdem/rock_types.hpp"

#include <array>
#include <memory>
#include <vector>

namespace blastsim::fdem {

namespace detail {
struct ProbeArrays;
}

//! The probes of one RockSolver: each follows the material point it was set at (the triangle holding it in the
//! initial mesh, by barycentric weights), and keeps the largest speed it sees up to the time `until` of its window.
class RockProbes {
 public:
  RockProbes();
  ~RockProbes();
  RockProbes(RockProbes&&) noexcept;
  RockProbes& operator=(RockProbes&&) noexcept;

  //! Sets probes at `points` [m] of the initial mesh (node positions x0, y0, 3 per triangle, counter-clockwise),
  //! replacing any earlier set, their peaks zero; `until` [s], when not empty, one window end per probe (empty: no
  //! end). Throws InputError naming a point that lies in no triangle, or a count of windows that does not match.
  void set(const std::vector<std::array<double, 2>>& points, const std::vector<double>& until,
           const std::vector<double>& x0, const std::vector<double>& y0);
  int count() const { return count_; }
  //! Updates every probe's peak with its velocity now, at `time` [s] (after each step; a kernel, no wait).
  void record(const NodeMotion<Access::read>& nodes, double time);
  //! Per probe: its velocity now and its peak so far (host copies).
  std::vector<ProbeSample> samples(const NodeMotion<Access::read>& nodes) const;
  //! Every peak back to zero (a run's start after the in-situ relaxation).
  void clear_peaks();
  //! The peaks, as the record rock.probes.peak.
  void write_checkpoint(CheckpointWriter& w) const;
  //! Reads the peaks back: one a probe of this set (set() came first, as when it was written), finite and not
  //! negative, else the record is refused by name.
  void read_checkpoint(CheckpointReader& r);

 private:
  std::unique_ptr<detail::ProbeArrays> a_;
  int count_ = 0;
};

}  // namespace blastsim::fdem
