//! \file input_domain.cpp
//! \brief [domain]: the gas grid (docs/input.md).
#include "case.hpp"

#include <fmt/format.h>

namespace blastsim::app {

void read_domain(TableReader& root, Case& c) {
  TableReader domain = root.table("domain", true);
  const long long nx = domain.integer("nx", "cells", 3, {}, 1000000), ny = domain.integer("ny", "cells", 3, {}, 1000000);
  // The gas arrays hold about 45 doubles a cell (state and derivatives twice, work arrays, coupling).
  check_memory_need(fmt::format("domain.nx x domain.ny = {} x {} cells", nx, ny),
                    45.0 * 8.0 * static_cast<double>(nx + 5) * static_cast<double>(ny + 5));
  const double x0 = domain.number("x_min", "m", Range::any()), x1 = domain.number("x_max", "m", Range::above(x0));
  const double y0 = domain.number("y_min", "m", Range::any()), y1 = domain.number("y_max", "m", Range::above(y0));
  domain.finish();
  c.gas.grid = cip::GasGrid::from_box(static_cast<int>(nx), static_cast<int>(ny), x0, x1, y0, y1);
}

}  // namespace blastsim::app
