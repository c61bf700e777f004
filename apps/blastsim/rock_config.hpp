//! \file rock_config.hpp
//! \brief The driver's rock-only case (mesh, material, loads, time, output); plain data (case_input.hpp reads it).
#pragma once

#include "blastsim/fdem/fragments.hpp"
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
  std::string shape;  //!< rectangle | disc | disc_with_hole | rectangle_with_hole | rectangle_with_holes | disc_with_holes | file
  double element_size = 0;           //!< [m]
  std::array<double, 2> center{};    //!< [m] discs and holes
  double radius = 0, hole_radius = 0;  //!< [m]
  std::array<double, 2> min{}, max{};  //!< [m] rectangles
  std::string file;                  //!< .msh path (shape = file)
  std::string mesher = "gmsh";       //!< gmsh | rings (disc_with_hole without Gmsh: fdem::ring_disc_with_hole)
  std::vector<fdem::Segment> joint_lines;  //!< [m] segments the Gmsh mesh follows: a row of joints along each
  //! [m] holes of rectangle_with_holes / disc_with_holes: the [[charge]] holes first (a coupled case puts them
  //! here), then [[rock.mesh.hole]]; boundary groups hole0, hole1, ... in this order
  std::vector<fdem::Circle> holes;
  double jitter = 0;                 //!< interior vertices moved by up to this fraction of their shortest edge
  long long seed = 1;                //!< of the jitter (one realisation per seed)
  bool is_rectangle() const { return shape.rfind("rectangle", 0) == 0; }
  bool has_holes() const { return shape == "rectangle_with_holes" || shape == "disc_with_holes"; }
};

//! A velocity probe in the rock ([[probe.rock_point]]): follows the material point at `position`.
struct RockProbe {
  std::string name;
  std::array<double, 2> position{};  //!< [m] in the initial mesh
  double until = 1e308;              //!< [s] end of the window in which the peak counts
};

//! A hole around which the damage zone is measured ([[analysis.hole]]).
struct DamageHole {
  std::array<double, 2> center{};  //!< [m]
  double radius = 0;               //!< [m]
  std::array<double, 2> behind{};  //!< direction away from the free face: only the half plane behind counts ([0, 0]: all round)
};

//! What the run reports about fragments and damage at every snapshot ([analysis]).
struct AnalysisSpec {
  bool fragments = true;
  int min_fragment_triangles = fdem::kDefaultMinFragmentTriangles;
  double oversize = 0.5;          //!< [m] sieve size above which a fragment is oversize
  double ring_width = 0;          //!< [m] of the damage-zone rings (0: twice the mean joint length)
  double crushed_fraction = 0.5;  //!< broken share of a ring's joint length that makes it crushed
  std::vector<DamageHole> holes;  //!< (default: the mesh's holes, when it has some)
  bool holes_given = false;       //!< [[analysis.hole]] tables were given (else the defaults above)
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
  //! [[rock.viscous_boundary]]: boundary groups where the model cuts a rock mass that goes on (Lysmer and
  //! Kuhlemeyer's dashpots: waves leave instead of reflecting)
  std::vector<std::string> viscous_boundaries;
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
  AnalysisSpec analysis;
  std::vector<RockProbe> probes;
  std::vector<std::string> echo;
};

}  // namespace blastsim::app
