//! \file rock_model.hpp
//! \brief A rock model from its description: the mesh (a Gmsh shape, the ring mesher, or a .msh file read as
//! data, with an optional jitter of its interior vertices), its FDEM topology, and the solver with its
//! initial velocity, prescribed velocities, boundary pressures, viscous boundaries and velocity probes.
//! Host code; every error is an InputError that names the part through its `label` (what the caller calls
//! it, e.g. an input key).
#pragma once

#include "blastsim/fdem/gmsh_mesh.hpp"
#include "blastsim/fdem/joint_sets.hpp"
#include "blastsim/fdem/material.hpp"
#include "blastsim/fdem/mesh.hpp"
#include "blastsim/fdem/rock_solver.hpp"
#include "blastsim/fdem/rock_types.hpp"

#include <array>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace blastsim::fdem {

//! The shapes a mesh can have.
enum class MeshShape { rectangle, disc, disc_with_hole, rectangle_with_hole, rectangle_with_holes, disc_with_holes, file };
//! The shape's name ("rectangle", "disc_with_holes", "file", ...), as the input spells it.
const char* mesh_shape_name(MeshShape shape);

//! How a mesh is made.
struct MeshSpec {
  std::string label = "mesh";  //!< how messages name the spec; its fields follow as label.field
  MeshShape shape = MeshShape::rectangle;
  double element_size = 0;           //!< [m] target edge length (built shapes)
  std::array<double, 2> center{};    //!< [m] of discs and of a single hole
  double radius = 0;                 //!< [m] of a disc
  double hole_radius = 0;            //!< [m] of a single hole
  std::array<double, 2> min{}, max{};  //!< [m] corners of a rectangle
  std::string file;                  //!< .msh path (MeshShape::file)
  bool ring_mesher = false;          //!< disc_with_hole by ring_disc_with_hole() instead of Gmsh
  GmshAlgorithm algorithm = GmshAlgorithm::delaunay;  //!< of the Gmsh-built shapes (gmsh_mesh.hpp)
  unsigned realisation = 0;  //!< of the Gmsh-built shapes: 0 Gmsh's own mesh, k > 0 another (GmshOptions)
  double ring_growth = 1.0;          //!< of the ring mesher: width ratio of neighbouring rings, in [1, 2]
  std::vector<Segment> joint_lines;  //!< [m] segments the Gmsh mesh follows: a row of joints along each
  //! [m] holes of rectangle_with_holes / disc_with_holes; boundary groups hole0, hole1, ... in this order
  std::vector<Circle> holes;
  double jitter = 0;  //!< interior vertices moved by up to this fraction of their shortest edge (0: none)
  long long seed = 1;  //!< of the jitter (one realisation per seed)
  //! [rad] a disc or disc_with_hole mesh turned by this angle about `center` (counter-clockwise), its joint lines
  //! kept where they are: the same rock, its circles' polygons placed differently (0: as Gmsh makes it)
  double rotation = 0;
  bool is_rectangle() const;
  bool has_holes() const;  //!< rectangle_with_holes or disc_with_holes
  //! [m2] the rock's area before the holes (0 for a file).
  double area() const;
};

//! Throws InputError unless every hole of a rectangle_with_holes / disc_with_holes spec lies inside the rock
//! with half an element to spare and at least half an element of rock lies between any two; `labels[k]`
//! names hole k in the message. A spec with such a shape needs at least one hole.
void check_mesh_holes(const MeshSpec& spec, const std::vector<std::string>& labels);

//! Throws InputError naming joint line k as label.joint_line.k unless every joint line lies in the rock (both
//! ends inside or on its boundary), is at least half an element long, and the mesh is one Gmsh can make lines
//! in (not rectangle_with_hole, not the ring mesher).
void check_joint_lines(const MeshSpec& spec);
//! The same for one segment named `label` that a built shape is to follow (a pre-cut crack).
void check_mesh_segment(const MeshSpec& spec, const Segment& segment, const std::string& label);

//! A segment a built mesh is to follow, with the name an error gives it and, for a joint set's generated
//! traces, the set's index (-1: a segment the input gave, a crack, a [[rock.joint]], a joint line).
struct LabelledSegment {
  std::string label;
  Segment segment;
  int set = -1;
};
//! Throws InputError naming the segments unless the lines a built mesh must follow leave it room for elements
//! of spec.element_size h: any two either meet (cross or touch) or stay at least h / 2 apart, every end that is
//! not on the outline or a hole's rim lies at least h / 2 from them, and a chord of a circle (both ends on it)
//! leaves at least h / 2 between its middle and the circle. Closer lines make Gmsh mesh the strip between them
//! at its width: elements (and a stable step) shrinking with the gap, a million triangles at 50 um. Two generated
//! traces are not checked against each other (joint_sets_traces() places them by its own clearance rules); a
//! mesh file is not checked (its edges are given).
void check_segment_clearance(const MeshSpec& spec, const std::vector<LabelledSegment>& segments);

//! The mesh of `spec`, jittered when spec.jitter > 0 (the vertices on joint lines stay, so the lines stay
//! straight), turned by spec.rotation. Throws InputError when Gmsh or the file fails, when the jittered mesh is
//! invalid, or when a rotation is asked of a shape other than "disc" or "disc_with_hole".
NamedMesh build_mesh(const MeshSpec& spec);

//! Prescribed velocity [m/s] of every node whose initial position lies in the box [min, max] [m].
struct VelocityLoad {
  std::string label;
  std::array<double, 2> min{}, max{};
  std::array<double, 2> velocity{};
  bool along_x = true, along_y = true;
};
//! A pressure [Pa] on the edges of a named boundary group.
struct PressureLoad {
  std::string label;
  std::string boundary;
  double pressure = 0;
};
//! A viscous (non-reflecting) boundary on a named boundary group (RockSolver::set_viscous_boundary()).
struct ViscousBoundary {
  std::string label;
  std::string boundary;
};
//! A velocity probe at a point of the initial mesh [m], its peak counted up to `until` [s].
struct ProbeSpec {
  std::string label;
  std::array<double, 2> position{};
  double until = 1e308;
};

//! A crack that is there from the start: the joints along a straight segment [m] of the mesh are broken before
//! the first step (RockSolver::break_joints()); `initial_aperture` [m] is the hydraulic opening of a crack whose
//! faces touch in the mesh (used by the crack gas).
struct PreCutCrack {
  std::string label;
  Segment segment;
  double initial_aperture = 0;
};

//! The in-situ stress of a rock model, the boundary groups that hold it (where the model cuts the rock mass) and
//! the equilibration that brings the rock to rest under it before the first step.
struct InSituSpec {
  std::string label = "in_situ_stress";  //!< how messages name it
  InSituStress stress;
  std::vector<std::string> held_boundaries;  //!< boundary groups that carry the in-situ traction
  bool equilibrate = true;
  EquilibriumOptions equilibrium;
};

//! Everything a rock model is made of.
struct RockModelSpec {
  MeshSpec mesh;
  RockMaterial material;
  RockOptions options;
  std::array<double, 2> initial_velocity{};  //!< [m/s] of every node (prescribed velocities override it)
  std::vector<VelocityLoad> velocities;
  std::vector<PressureLoad> pressures;
  std::vector<ViscousBoundary> viscous_boundaries;
  std::vector<ProbeSpec> probes;
  //! Cracks broken before the first step; a built shape follows their segments (as joint lines), a mesh file
  //! must have edges along them.
  std::vector<PreCutCrack> cracks;
  //! Heterogeneous joint strength (heterogeneity.hpp); absent: every joint has the material's.
  std::optional<StrengthHeterogeneity> heterogeneity;
  //! Natural joint sets (joint_sets.hpp): a built shape follows their traces, whose joints take the set's
  //! properties (over the heterogeneous draw) or start broken (open sets).
  std::vector<JointSetSpec> joint_sets;
  //! In-situ stress (set after the joints' properties, equilibrated last); absent: the rock starts unstressed.
  std::optional<InSituSpec> in_situ;
};

//! The mesh, its FDEM topology and the solver, with the nodes of each velocity load.
struct RockModel {
  NamedMesh mesh;
  FdemTopology topology;
  std::unique_ptr<RockSolver> solver;
  std::vector<std::vector<int>> velocity_nodes;
  std::vector<std::vector<int>> crack_joints;  //!< the joints of each pre-cut crack (spec.cracks' order)
  std::vector<std::vector<int>> set_joints;    //!< the joints of each joint set (spec.joint_sets' order)
  //! The set of each joint (-1: none), when spec.joint_sets is not empty.
  std::vector<int> joint_set_of;
  //! How the equilibration under the in-situ stress went (when there was one).
  std::optional<EquilibriumReport> equilibrium;
};
//! Builds the model. Throws InputError: a velocity load's box without nodes, a boundary group the mesh lacks
//! (listing those it has), a probe outside the rock, a pre-cut crack with no joint along its segment, a joint that
//! cannot carry its in-situ traction; InstabilityError: the rock did not come to rest under its in-situ stress.
RockModel build_rock_model(const RockModelSpec& spec);

//! Puts the in-situ stress `s` into `rock` before its first step, after the joints' own properties
//! (docs/fdem-solver.md, "In-situ stress"): each triangle's stress-free shape becomes the one its in-situ stress
//! (at its centroid) stretches to the mesh (prestretch(), so the stress turns with the triangle and a released
//! piece relaxes), each intact joint starts at the opening and slip whose tractions carry sigma n across it (at
//! its middle; joint_preload()), and the boundary edge slots `held` (where the model cuts a rock mass that goes
//! on) carry the traction sigma n as a dead load, half on each node, plus the weight the holes took out under
//! gravity (carry_cut_weight()). A rock without other free surfaces then starts at rest; holes and free faces
//! need equilibrate(). Throws InputError for a held slot that is not a mesh-boundary edge or a joint that cannot
//! carry its traction (naming it), std::logic_error after a step.
void set_in_situ_stress(RockSolver& rock, const InSituStress& s, const std::vector<int>& held);
//! Brings `rock` to rest before its first step under the in-situ stress, gravity and the held boundaries (viscous
//! dynamic relaxation: EquilibriumOptions; edge pressures off, prescribed velocities held at zero), then starts the
//! clock again: time and steps zero, the work ledgers, dissipations and probe peaks cleared (joint damage stays),
//! the pressures, prescribed velocities and the nodes' velocities as they were before. The state reached is the
//! initial state of the run.
EquilibriumReport equilibrate(RockSolver& rock, const EquilibriumOptions& options = {});

//! Mean length [m] of the joints of a topology (0 without joints).
double mean_joint_length(const FdemTopology& topology);

}  // namespace blastsim::fdem
