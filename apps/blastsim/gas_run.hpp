//! \file gas_run.hpp
//! \brief Runs a gas-only case of the driver: the run loop with the gas stepper (stability guard), snapshots, probes, progress.
#pragma once

#include "case_config.hpp"
#include "run_loop.hpp"

#include <iosfwd>

namespace blastsim::app {

//! Runs the case to its end time, writing into config.output_directory. Throws InputError for a fixed
//! dt above the Courant limit (found at run time) and InstabilityError when the state turns invalid;
//! in both cases the files already written stay valid (the bad state is never written).
void run_gas_case(const CaseConfig& config, std::ostream& log, const RunOptions& options = {});

}  // namespace blastsim::app
