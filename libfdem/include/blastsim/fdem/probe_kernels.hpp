//! \file probe_kernels.hpp
//! \brief Velocity probes of the rock (fdem::RockProbes): a material point followed through the run, its
//! velocity from its triangle's nodes and its peak particle velocity; the field list of their arrays and their
//! kernels (one thread a probe).
#pragma once

#include "blastsim/core/access.hpp"
#include "blastsim/core/macros.hpp"
#include "blastsim/fdem/rock_fields.hpp"

namespace blastsim::fdem {

//! A velocity probe: the triangle holding the point in the initial mesh and its barycentric weights there,
//! so the probe moves with the rock (a geophone fixed to it).
struct ProbeStation {
  int triangle;
  double weight[3];
  double until;  //!< [s] the peak counts up to this time only (a window: e.g. the first arrival)
};

//! Peak particle velocity of a probe so far: the largest speed |v| (the peak vector sum), the time of it,
//! and the velocity components then.
struct ProbePeak {
  double speed;  //!< [m/s]
  double time;   //!< [s]
  double vx, vy;  //!< [m/s]
};

//! The probes' arrays, one entry a probe.
#define BLASTSIM_ROCK_PROBES(X)                                                       \
  X(ProbeStation, station, "where the probe sits (fixed once set)")                   \
  X(ProbePeak, peak, "its peak so far (checkpointed as rock.probes.peak)")            \
  X(Vec2, velocity, "its velocity [m/s] when last sampled (a work array of the samples)")
BLASTSIM_VIEW_GROUP(RockProbeArrays, BLASTSIM_ROCK_PROBES)

//! Velocity [m/s] at a probe from its triangle's node velocities.
BLAST_HD inline Vec2 probe_velocity(const ProbeStation& p, const NodeMotion<Access::read>& nodes) {
  double ux = 0, uy = 0;
  for (int k = 0; k < 3; ++k)
    ux += p.weight[k] * nodes.vx[3 * p.triangle + k], uy += p.weight[k] * nodes.vy[3 * p.triangle + k];
  return {ux, uy};
}

//! Updates each probe's peak with the current velocity within its window (called after every step).
struct ProbePeakKernel {
  NodeMotion<Access::read> nodes;
  RockProbeArrays<Access::read_write> probes;  //!< reads station; updates peak
  double time;                                 //!< [s] now
  BLAST_HD void operator()(index_t k) const {
    const Vec2 u = probe_velocity(probes.station[k], nodes);
    const double s = sqrt(u.x * u.x + u.y * u.y);
    if (s > probes.peak[k].speed && time <= probes.station[k].until) probes.peak[k] = ProbePeak{s, time, u.x, u.y};
  }
};

//! Each probe's current velocity into its `velocity` entry (for a sample read by the host).
struct ProbeVelocityKernel {
  NodeMotion<Access::read> nodes;
  RockProbeArrays<Access::read_write> probes;  //!< reads station; writes velocity
  BLAST_HD void operator()(index_t k) const { probes.velocity[k] = probe_velocity(probes.station[k], nodes); }
};

}  // namespace blastsim::fdem
