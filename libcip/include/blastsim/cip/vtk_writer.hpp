//! \file vtk_writer.hpp
//! \brief The gas's fields as VTK image data (.vti, binary) for ParaView, one file per snapshot; needs the VTK
//! library in the build (vtk_available()).
#pragma once

#include "blastsim/cip/gas_types.hpp"
#include "blastsim/cip/grid.hpp"

#include <string>

namespace blastsim::cip {

//! True when this build can write VTK files (BLASTSIM_ENABLE_VTK and VTK found); the same for libfdem's writers.
bool vtk_available();

//! Writes the cell-centred gas fields (density, pressure, internal_energy, velocity, active) of a grid
//! as a .vti image (cells = gas cells) at `path`, atomically. OutputError on failure; std::runtime_error without VTK.
void write_gas_vti(const std::string& path, const GasGrid& grid, const HostGasFields& fields);

}  // namespace blastsim::cip
