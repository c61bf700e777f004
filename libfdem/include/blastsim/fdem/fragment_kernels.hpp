//! \file fragment_kernels.hpp
//! \brief Kernels of the rock analysis on the device: fragment labels (connected components of triangles
//! through joints that still hold) and velocity probes (a material point followed through the run).
#pragma once

#include "blastsim/core/macros.hpp"

#include <cstdint>

namespace blastsim::fdem {

//! What joins a triangle to its neighbours: per edge slot the triangle across it and the joint between
//! them (-1 on the mesh boundary), and per joint whether it has broken.
struct FragmentLinks {
  const int* neighbour;         //!< per edge slot
  const int* joint;             //!< per edge slot
  const std::uint8_t* broken;   //!< per joint
  //! The triangle joined to the owner of `slot` by a joint that still holds, or -1.
  BLAST_HD int held_neighbour(int slot) const {
    const int j = joint[slot];
    return j >= 0 && !broken[j] ? neighbour[slot] : -1;
  }
};

//! One Jacobi sweep of label propagation with pointer jumping, one thread per triangle t:
//! m = min(label[t], label of each neighbour held by a joint), then label_out[t] = label[m].
//! Invariant: label[t] <= t and label[t] lies in t's fragment, so labels only fall; at the fixed point
//! every fragment carries the smallest triangle index it holds, whatever the sweep order (the sweep reads
//! only `label_in`, so the bytes do not depend on the thread schedule either).
struct LabelSweepKernel {
  FragmentLinks links;
  const int* label_in;
  int* label_out;
  BLAST_HD void operator()(index_t tl) const {
    const int t = static_cast<int>(tl);
    int m = label_in[t];
    for (int k = 0; k < 3; ++k) {
      const int n = links.held_neighbour(3 * t + k);
      if (n >= 0 && label_in[n] < m) m = label_in[n];
    }
    label_out[t] = label_in[m];
  }
};

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

//! Velocity [m/s] at a probe from its triangle's node velocities.
BLAST_HD inline void probe_velocity(const ProbeStation& p, const double* vx, const double* vy, double& ux, double& uy) {
  ux = 0, uy = 0;
  for (int k = 0; k < 3; ++k) ux += p.weight[k] * vx[3 * p.triangle + k], uy += p.weight[k] * vy[3 * p.triangle + k];
}

//! Updates each probe's peak with the current velocity within its window (one thread per probe; called after
//! every step).
struct ProbePeakKernel {
  const ProbeStation* station;
  const double* vx;
  const double* vy;
  ProbePeak* peak;
  double time;
  BLAST_HD void operator()(index_t k) const {
    double ux, uy;
    probe_velocity(station[k], vx, vy, ux, uy);
    const double s = sqrt(ux * ux + uy * uy);
    if (s > peak[k].speed && time <= station[k].until) peak[k] = ProbePeak{s, time, ux, uy};
  }
};

}  // namespace blastsim::fdem
