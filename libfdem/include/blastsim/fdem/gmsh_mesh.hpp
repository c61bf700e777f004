//! \file gmsh_mesh.hpp
//! \brief Triangle meshes from Gmsh: the usual specimen shapes built through the Gmsh API, and .msh files read.
//!
//! Every function returns the mesh (counter-clockwise triangles) with its boundary edges grouped by name:
//! the built shapes name theirs ("left", "right", "bottom", "top", "outer", "hole"); a .msh file's
//! 1-D physical groups give theirs. Without Gmsh in the build (BLASTSIM_HAVE_GMSH undefined) each function
//! throws InputError saying so.
#pragma once

#include "blastsim/fdem/mesh.hpp"

#include <array>
#include <string>
#include <vector>

namespace blastsim::fdem {

//! A straight segment [m] from a to b.
struct Segment {
  std::array<double, 2> a, b;
};

//! True when this build can call Gmsh.
bool gmsh_available();

//! Gmsh's 2-D meshing algorithm for the built shapes.
//! - delaunay (Gmsh's "Delaunay", Mesh.Algorithm 5): an unstructured mesh whose edges take every direction
//!   alike; what a fracture mesh needs, since cracks run along element edges.
//! - frontal (Gmsh's "Frontal-Delaunay", Mesh.Algorithm 6): nearly equilateral triangles, but away from the
//!   boundaries they settle into one lattice whose edges run in three directions 60 degrees apart (measured:
//!   85 % of a 9.5 mm disc's edges within 5 degrees of one direction modulo 60), so cracks run along those three
//!   directions, and the lattice turns with the element size. Kept to reproduce results made with it.
enum class GmshAlgorithm { delaunay, frontal };

//! How Gmsh meshes the built shapes: the algorithm, and which of a family of independent meshes of the same
//! shape and element size.
//! - realisation 0: Gmsh's own mesh (the size field is h everywhere).
//! - realisation k > 0: the size field is h (1 + a u_k(x)), a = kRealisationSizeNoise, with u_k a pseudo-random
//!   number in [-1, 1] per square of side h (a hash of the square's indices and k, so the same k gives the same
//!   mesh on every machine). Gmsh's refinement inserts its points in another order, and the interior shares
//!   almost no vertex with realisation 0 or another k (measured on a 6 mm disc: 0.03-0.05 % of the interior
//!   vertices within 1 % of h of one of the other mesh's; the circles keep their vertex counts), while the
//!   element size changes by at most a: sampled mesh realisations for a spread of results, whose triangle count
//!   stays within about 2 % (docs/fdem-solver.md, "Mesh realisations").
struct GmshOptions {
  GmshAlgorithm algorithm = GmshAlgorithm::delaunay;
  unsigned realisation = 0;
  // Implicit from an algorithm: gmsh_disc(..., GmshAlgorithm::frontal) asks for Gmsh's own frontal mesh.
  GmshOptions(GmshAlgorithm algorithm_ = GmshAlgorithm::delaunay, unsigned realisation_ = 0)  // NOLINT
      : algorithm(algorithm_), realisation(realisation_) {}
};
//! The relative amplitude a of a realisation's size-field noise (GmshOptions).
inline constexpr double kRealisationSizeNoise = 0.01;

//! Rectangle [x0, x1] x [y0, y1], target element size h [m]; groups left, right, bottom, top. `embedded`:
//! segments the mesh must follow (e.g. a plane at the Mohr-Coulomb angle across a compression specimen).
NamedMesh gmsh_rectangle(double x0, double y0, double x1, double y1, double h,
                         const std::vector<Segment>& embedded = {},
                         GmshOptions options = {});
//! Disc of radius r centred at (cx, cy); group outer. `embedded`: segments (chords, with their ends on the
//! circle) that the mesh must follow, so that a row of joints lies exactly along each.
NamedMesh gmsh_disc(double cx, double cy, double r, double h, const std::vector<Segment>& embedded = {},
                    GmshOptions options = {});
//! Disc of radius r with a concentric circular hole of radius r_hole; groups outer, hole. `embedded`
//! segments (e.g. a pre-cut radial crack from the hole) become lines of the mesh.
NamedMesh gmsh_disc_with_hole(double cx, double cy, double r, double r_hole, double h,
                              const std::vector<Segment>& embedded = {},
                              GmshOptions options = {});
//! Rectangle with a circular hole (centre (cx, cy), radius r_hole) inside it; groups left, right, bottom,
//! top, hole.
NamedMesh gmsh_rectangle_with_hole(double x0, double y0, double x1, double y1, double cx, double cy, double r_hole,
                                   double h, GmshOptions options = {});
//! A circle [m]: a blasthole of a multi-hole mesh.
struct Circle {
  std::array<double, 2> center;
  double radius;
};
//! Throws InputError naming the first hole that is not strictly inside `inside` (a predicate on a circle) or that
//! overlaps another (their rims closer than `gap` [m]); `what` names the mesh in the message.
void check_holes(const std::vector<Circle>& holes, double gap, const std::string& what);
//! Rectangle [x0, x1] x [y0, y1] with any number of circular holes (a bench section with its blastholes);
//! groups left, right, bottom, top and hole0, hole1, ... in the order given. `embedded`: segments the mesh
//! follows (pre-existing joints). Throws InputError for a hole that leaves the rectangle or overlaps another.
NamedMesh gmsh_rectangle_with_holes(double x0, double y0, double x1, double y1, const std::vector<Circle>& holes,
                                    double h, const std::vector<Segment>& embedded = {},
                                    GmshOptions options = {});
//! Disc of radius r centred at (cx, cy) with any number of circular holes; groups outer and hole0, hole1, ...
NamedMesh gmsh_disc_with_holes(double cx, double cy, double r, const std::vector<Circle>& holes, double h,
                               const std::vector<Segment>& embedded = {},
                               GmshOptions options = {});
//! Reads a Gmsh mesh file as data (read_msh_file()); refuses Gmsh scripts (.geo), which could run commands.
//! Needs no Gmsh. Throws InputError for a missing, unreadable or malformed file, or one with no triangles.
NamedMesh read_gmsh_file(const std::string& path);
//! Parser of MSH 4.1 ASCII files (3-node triangles; 2-node lines of 1-D physical groups name boundary edges);
//! nothing in the file is run, and errors give the line number.
NamedMesh read_msh_file(const std::string& path);

//! Boundary slots (see RockSolver) of the edges in `edges` (vertex pairs), looked up in the topology.
//! Throws InputError naming the group if an edge is not a boundary edge of the topology.
std::vector<int> boundary_slots(const FdemTopology& topology, const std::vector<std::array<int, 2>>& edges,
                                const std::string& group);

}  // namespace blastsim::fdem
