//! \file vtk_writer.hpp
//! \brief Rock snapshots as VTK unstructured grids (.vtu) for ParaView: the triangles with their fields, and the
//! joints as crack lines; needs the VTK library in the build (cip::vtk_available()).
#pragma once

#include "blastsim/fdem/rock_types.hpp"

#include <string>
#include <vector>

namespace blastsim::fdem {

//! Per-triangle results of the analysis written with the triangles (an empty array is left out).
struct RockCellFields {
  std::vector<int> fragment_id;  //!< fragment_labels() (fragments.hpp)
  std::vector<double> damage;    //!< triangle_damage()
};

//! Writes the triangles (points = FDEM nodes at their current positions; point data displacement and
//! velocity; cell data stress [sxx, syy, sxy], principal_max, principal_min (the paper's "PS3"), and the
//! fields of `cells`) to `path`, atomically. OutputError on failure; std::runtime_error without VTK.
void write_rock_vtu(const std::string& path, const RockSnapshot& snapshot, const RockCellFields& cells = {});

//! A value per joint written with the joints (e.g. the crack gas's pressure); one of another length is left out.
struct JointField {
  std::string name;
  std::vector<double> values;
};
//! Writes every joint as a line between the mid-points of its two faces' ends, with cell data damage and
//! broken (1: a crack) and `fields`, to `path`, atomically.
void write_joints_vtu(const std::string& path, const RockSnapshot& snapshot, const std::vector<JointField>& fields = {});

}  // namespace blastsim::fdem
