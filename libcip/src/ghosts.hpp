//! \file ghosts.hpp
//! \brief Internal: the ghost-fill launcher and the per-step views shared by the gas solver's phases.
#pragma once

#include "blastsim/cip/boundary_kernels.hpp"

namespace blastsim::cip {

void fill_ghosts(const GasStateView& s, const GasGrid& grid, const BoundaryContext& ctx);
//! Ghosts of the products' volume fraction and partial density (zero gradient at walls and outflow sides,
//! wrapped at periodic ones).
void fill_material_ghosts(const MaterialView& m, const GasGrid& grid, const BoundaryConditions& bc);

//! The views every phase of a step works on: the current state (n), the state after the non-advection
//! phase (*) and the immersed-boundary input, read-only.
struct StepViews {
  GasStateView now, starred;
  ImmersedBoundaryReadView ib;
};

}  // namespace blastsim::cip
