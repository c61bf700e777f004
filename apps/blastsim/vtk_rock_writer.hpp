//! \file vtk_rock_writer.hpp
//! \brief Rock snapshots as VTK unstructured grids (.vtu): the triangles with their fields, and the joints as crack lines.
#pragma once

#include "blastsim/fdem/rock_types.hpp"
#include "blastsim/ibm/crack_gas.hpp"

#include <string>
#include <vector>

namespace blastsim::app {

//! Per-triangle results of the analysis written with the triangles (an empty array is left out).
struct RockCellFields {
  std::vector<int> fragment_id;  //!< fdem::RockSolver::fragment_labels()
  std::vector<double> damage;    //!< fdem::triangle_damage()
};

//! Writes the triangles (points = FDEM nodes at their current positions; point data displacement and
//! velocity; cell data stress [sxx, syy, sxy], principal_max, principal_min (the paper's "PS3"), and the
//! fields of `cells`) to `path`, atomically. Throws std::runtime_error without VTK.
void write_rock_vtu(const std::string& path, const fdem::RockSnapshot& snapshot, const RockCellFields& cells = {});

//! Writes every joint as a line between the mid-points of its two faces' ends, with cell data damage and
//! broken (1: a crack) and the crack gas's aperture, gas_pressure and gas_mass (coupled runs with crack gas;
//! empty arrays are left out), to `path`, atomically.
void write_joints_vtu(const std::string& path, const fdem::RockSnapshot& snapshot, const ibm::CrackSegmentFields& gas = {});

}  // namespace blastsim::app
