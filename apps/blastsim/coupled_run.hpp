//! \file coupled_run.hpp
//! \brief Runs a coupled gas-rock case of the driver: one dt for both solvers, the coupler's step, outputs.
#pragma once

#include "coupled_config.hpp"
#include "run_loop.hpp"

#include <iosfwd>

namespace blastsim::app {

//! Runs the case to its end time, writing into output.directory the gas files of a gas case (gas.pvd,
//! probes, gas_totals.csv), the rock files of a rock case (rock.pvd, joints.pvd, rock_series.csv) and
//! coupling_series.csv (interface force and work, the energy budget of gas + rock, monitor regions).
//! Throws InputError for bad meshes or a fixed dt above a stability limit, and InstabilityError when either
//! state turns invalid (files already written stay valid).
void run_coupled_case(const CoupledCaseConfig& config, std::ostream& log, const RunOptions& options = {});

}  // namespace blastsim::app
