//! \file coupler_kernels.hpp
//! \brief The one reduction of a coupled step (GasRockCoupler::step()): the gas's signal rate and the rock's
//! largest speed read together, so that the host waits once a step. Plain header: no backend dependency.
#pragma once

#include "blastsim/cip/gas_step_kernels.hpp"
#include "blastsim/fdem/rock_step_kernels.hpp"

namespace blastsim::ibm {

//! 1 for cell k (i + nx j) that the rock covers (inactive), 0 for an open one (GasRockCoupler::inactive_cells()).
struct InactiveCell {
  Field2D<const std::uint8_t> active;
  int nx;
  BLAST_HD double operator()(index_t k) const {
    return active(static_cast<int>(k % nx), static_cast<int>(k / nx)) ? 0.0 : 1.0;
  }
};

//! The two values the host reads after a coupled step (GasRockCoupler::step()): the gas's largest signal rate
//! [1/s] (the next dt) and the rock's largest node speed over the step's substeps [m/s] (contact rebuild,
//! instability check), in one reduction, so the host waits once a step.
struct StepScalars {
  double signal_rate, rock_speed;
};
struct StepScalarsOf {
  cip::SignalRate gas;
  fdem::NodeSpeedPeak rock;
  index_t cells;
  BLAST_HD StepScalars operator()(index_t k) const {
    return k < cells ? StepScalars{gas(k), 0.0} : StepScalars{0.0, rock(k - cells)};
  }
};
//! Componentwise maximum (order-independent: the same bits on any reduction tree; the flags for a non-finite
//! state, +infinity and 1e308, win as they do in each solver's own reduction).
struct MaxOfStepScalars {
  BLAST_HD StepScalars operator()(const StepScalars& a, const StepScalars& b) const {
    return {a.signal_rate > b.signal_rate ? a.signal_rate : b.signal_rate,
            a.rock_speed > b.rock_speed ? a.rock_speed : b.rock_speed};
  }
};

}  // namespace blastsim::ibm
