//! \file boundary.cpp
//! \brief The ghost fill of the outer boundaries of the staggered gas grid (its kernels: boundary_kernels.hpp).
#include "ghosts.hpp"

#include "blastsim/core/backend.hpp"

namespace blastsim::cip {

const char* to_string(BoundaryKind k) {
  switch (k) {
    case BoundaryKind::outflow: return "outflow";
    case BoundaryKind::wall: return "wall";
    case BoundaryKind::periodic: return "periodic";
  }
  return "?";
}

bool parse_boundary_kind(const std::string& text, BoundaryKind& out) {
  if (text == "outflow") out = BoundaryKind::outflow;
  else if (text == "wall") out = BoundaryKind::wall;
  else if (text == "periodic") out = BoundaryKind::periodic;
  else return false;
  return true;
}


void fill_material_ghosts(const MaterialView& m, const GasGrid& grid, const BoundaryConditions& bc) {
  const int g = GasGrid::ghost;
  for_each_cell("cip.ghosts.materials_x", 0, 2 * g, 0, grid.ny,
                detail::FillMaterialGhosts{m, 0, grid.nx, bc.kind(left), bc.kind(right)});
  for_each_cell("cip.ghosts.materials_y", 0, 2 * g, -g, grid.nx + g,
                detail::FillMaterialGhosts{m, 1, grid.ny, bc.kind(bottom), bc.kind(top)});
}

//! Fills the ghosts of a state (used on the current and on the starred state).
void fill_ghosts(const GasStateView& s, const GasGrid& grid, const BoundaryContext& ctx) {
  const int g = GasGrid::ghost;
  const BoundaryConditions& bc = ctx.bc;
  for_each_index("cip.ghosts.outflow_faces", 2 * static_cast<index_t>(grid.nx + grid.ny),
                 detail::FillOutflowFaces{s, grid, ctx});
  // x pass over the logical rows [0, ny] (cells 0..ny-1 and y-faces 0..ny).
  for_each_cell("cip.ghosts.x", 0, 2 * g + 2, 0, grid.ny + 1,
                detail::FillGhosts<0>{s, grid.nx, bc.kind(left), bc.kind(right)});
  // y pass over every column of the padded array.
  for_each_cell("cip.ghosts.y", -g, grid.nx + 1 + g, 0, 2 * g + 2,
                detail::FillGhosts<1>{s, grid.ny, bc.kind(bottom), bc.kind(top)});
}

}  // namespace blastsim::cip
