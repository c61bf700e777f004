//! \file gas_run.hpp
//! \brief Runs a gas-only case of the driver: time loop, stability guard, snapshots, probes, progress.
#pragma once

#include "case_config.hpp"

#include <iosfwd>

namespace blastsim::app {

struct RunOptions {
  bool quiet = false;    //!< no progress lines
  bool restart = false;  //!< continue from the output folder's checkpoint.bin (coupled cases)
};

//! Runs the case to its end time, writing into config.output_directory. Throws InputError for a fixed
//! dt above the Courant limit (found at run time) and InstabilityError when the state turns invalid;
//! in both cases the files already written stay valid (the bad state is never written).
void run_gas_case(const CaseConfig& config, std::ostream& log, const RunOptions& options = {});

}  // namespace blastsim::app
