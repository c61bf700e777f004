//! \file rock_run.hpp
//! \brief Runs a rock-only case of the driver: mesh, loads, time loop, .vtu series, energy time series, progress.
#pragma once

#include "run_loop.hpp"
#include "rock_config.hpp"

#include <iosfwd>

namespace blastsim::app {

//! Runs the case to its end time, writing into config.output_directory: rock.pvd / rock_NNNNNN.vtu (triangles),
//! joints.pvd / joints_NNNNNN.vtu (joints, broken ones are the cracks), rock_series.csv (energies, broken
//! joints, crack length). Throws InputError for bad meshes or a fixed dt above the stable step, and
//! InstabilityError when the state turns non-finite (files already written stay valid).
void run_rock_case(const RockCaseConfig& config, std::ostream& log, const RunOptions& options = {});

}  // namespace blastsim::app
