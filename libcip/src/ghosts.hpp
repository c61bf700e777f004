//! \file ghosts.hpp
//! \brief Internal: the ghost-fill launcher shared by the gas solver's phases.
#pragma once

#include "blastsim/cip/boundary.hpp"
#include "blastsim/cip/gas_state.hpp"
#include "blastsim/cip/grid.hpp"

namespace blastsim::cip {

void fill_ghosts(const GasStateView& s, const GasGrid& grid, const BoundaryConditions& bc);

}  // namespace blastsim::cip
