//! \file rock_config.hpp
//! \brief The driver's rock-only case (mesh, material, loads, time, output); plain data (case_input.hpp reads it).
#pragma once

#include "blastsim/fdem/gmsh_mesh.hpp"
#include "blastsim/fdem/material.hpp"
#include "blastsim/fdem/rock_types.hpp"

#include <array>
#include <optional>
#include <string>
#include <vector>

namespace blastsim::app {

//! How the rock mesh is made: a Gmsh-built shape or a .msh file.
struct RockMeshSpec {
  std::string shape;                 //!< rectangle | disc | disc_with_hole | rectangle_with_hole | file
  double element_size = 0;           //!< [m]
  std::array<double, 2> center{};    //!< [m] discs and holes
  double radius = 0, hole_radius = 0;  //!< [m]
  std::array<double, 2> min{}, max{};  //!< [m] rectangles
  std::string file;                  //!< .msh path (shape = file)
  std::string mesher = "gmsh";       //!< gmsh | rings (disc_with_hole without Gmsh: fdem::ring_disc_with_hole)
  std::vector<fdem::Segment> joint_lines;  //!< [m] segments the Gmsh mesh follows: a row of joints along each
};

//! Prescribed velocity of every node whose initial position lies in the box [min, max].
struct VelocityLoad {
  std::array<double, 2> min{}, max{};
  std::array<double, 2> velocity{};  //!< [m/s]
  bool along_x = true, along_y = true;
};

//! Pressure on the edges of a named boundary group.
struct PressureLoad {
  std::string boundary;
  double pressure = 0;  //!< [Pa]
};

struct RockCaseConfig {
  fdem::RockMaterial material;
  fdem::RockOptions options;
  RockMeshSpec mesh;
  std::array<double, 2> initial_velocity{};  //!< [m/s]
  std::vector<VelocityLoad> velocities;
  std::vector<PressureLoad> pressures;
  double pressure_ramp_time = 0;   //!< [s] pressures rise as a half cosine over this time (0: at once)
  double end_time = 0;             //!< [s]
  std::optional<double> fixed_dt;  //!< [s]
  long long max_steps = 0;         //!< 0: no limit
  double step_fraction = 0.9;      //!< dt = step_fraction x stable step when no dt is given
  std::string output_directory;
  double output_interval = 0;      //!< [s] between .vtu snapshots (0: start and end)
  std::vector<double> output_times;  //!< [s] extra snapshots (output.times; coupled cases)
  bool vtk = true;
  double progress_interval = 2.0;  //!< [s wall]
  long long monitor_interval = 10;  //!< steps between rows of rock_series.csv
  std::vector<std::string> echo;
};

}  // namespace blastsim::app
