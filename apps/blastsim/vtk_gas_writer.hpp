//! \file vtk_gas_writer.hpp
//! \brief Gas fields as VTK image data (.vti, binary), one file per snapshot; needs the VTK library.
#pragma once

#include "blastsim/cip/gas_types.hpp"
#include "blastsim/cip/grid.hpp"

#include <string>

namespace blastsim::app {

//! True when this build can write VTK files (BLASTSIM_ENABLE_VTK and VTK found).
bool vtk_available();

//! Writes the cell-centred gas fields (density, pressure, internal_energy, velocity, active) of a grid
//! as a .vti image (cells = gas cells) at `path`, atomically. Throws std::runtime_error without VTK.
void write_gas_vti(const std::string& path, const cip::GasGrid& grid, const cip::HostGasFields& fields);

}  // namespace blastsim::app
