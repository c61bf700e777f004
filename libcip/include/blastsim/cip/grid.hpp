//! \file grid.hpp
//! \brief Geometry of the staggered gas grid (paper sec. 2): cell centres, x-faces and y-faces.
#pragma once

#include "blastsim/core/field2d.hpp"

namespace blastsim::cip {

//! Uniform Cartesian grid of nx x ny cells over [x_min, x_min + nx dx] x [y_min, y_min + ny dy].
//!
//! Index conventions (every staggered array uses the same padded shape, see padded_shape()):
//! - cell (i, j), 0 <= i < nx, 0 <= j < ny: centre (x_min + (i + 1/2) dx, y_min + (j + 1/2) dy);
//! - x-face u(i, j), 0 <= i <= nx: the left face of cell (i, j), at (x_min + i dx, cell-centre y);
//! - y-face v(i, j), 0 <= j <= ny: the bottom face of cell (i, j), at (cell-centre x, y_min + j dy).
struct GasGrid {
  int nx = 0;          //!< cells along x
  int ny = 0;          //!< cells along y
  double x_min = 0.0;  //!< [m] left edge of the domain
  double y_min = 0.0;  //!< [m] bottom edge of the domain
  double dx = 0.0;     //!< [m] cell width
  double dy = 0.0;     //!< [m] cell height

  //! Ghost layers on every side: two cover the CIP upwind block and the centred derivative stencils.
  static constexpr int ghost = 2;

  //! One padded shape (nx + 1) x (ny + 1) logical points plus ghosts serves cells and both face sets.
  BLAST_HD PaddedShape padded_shape() const { return PaddedShape{nx + 1, ny + 1, ghost}; }

  BLAST_HD double cell_x(int i) const { return x_min + (i + 0.5) * dx; }
  BLAST_HD double cell_y(int j) const { return y_min + (j + 0.5) * dy; }
  BLAST_HD double face_x(int i) const { return x_min + i * dx; }
  BLAST_HD double face_y(int j) const { return y_min + j * dy; }
  BLAST_HD double x_max() const { return x_min + nx * dx; }
  BLAST_HD double y_max() const { return y_min + ny * dy; }
  BLAST_HD double cell_area() const { return dx * dy; }

  //! A grid over [x0, x1] x [y0, y1]; throws InputError when nx, ny < 3 or the box is empty.
  static GasGrid from_box(int nx, int ny, double x0, double x1, double y0, double y1);
};

}  // namespace blastsim::cip
