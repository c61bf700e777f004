//! \file mesh.hpp
//! \brief Triangle meshes and the FDEM topology built from them: nodes owned per triangle, 4-node joints, boundary edges.
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace blastsim::fdem {

//! A conforming triangle mesh as a mesher gives it: shared vertices, triangles by vertex index.
struct TriangleMesh {
  std::vector<std::array<double, 2>> vertices;  //!< [m]
  std::vector<std::array<int, 3>> triangles;    //!< vertex indices, counter-clockwise
};

//! A mesh with named boundary-edge groups (each edge a pair of vertex indices).
struct NamedMesh {
  TriangleMesh mesh;
  std::map<std::string, std::vector<std::array<int, 2>>> boundary_groups;
};

//! Checks a mesh; throws InputError naming the first problem: a vertex index out of range, an inverted
//! (clockwise) or degenerate triangle (area below 1e-12 of its longest edge squared), an edge shared by
//! more than two triangles (non-manifold), or an empty mesh.
void check_mesh(const TriangleMesh& mesh);

//! A cohesive joint between two triangles that share an edge. Its four nodes in the FDEM numbering:
//! the edge of triangle a runs a0 -> a1 (counter-clockwise in a), the coincident edge of b runs b0 -> b1
//! with b0 at a1's position and b1 at a0's.
struct Joint {
  int triangle_a, triangle_b;
  int a0, a1, b0, b1;
};

//! An edge of the original mesh boundary: triangle, and its nodes n0 -> n1 (counter-clockwise in it).
struct BoundaryEdge {
  int triangle;
  int n0, n1;
};

//! FDEM discretisation of a mesh: every triangle owns three nodes (node 3 t + k is vertex k of triangle
//! t), every interior edge becomes a joint, every boundary edge is listed (it will face the gas).
struct FdemTopology {
  std::vector<std::array<double, 2>> node_positions;  //!< [m], 3 per triangle
  std::vector<Joint> joints;
  std::vector<BoundaryEdge> boundary_edges;
  std::vector<int> node_vertex;  //!< the mesh vertex each node came from
  int triangle_count() const { return static_cast<int>(node_positions.size() / 3); }
};

//! Builds the FDEM topology (check_mesh() first). Joints and boundary edges come in a deterministic order.
FdemTopology build_topology(const TriangleMesh& mesh);

//! The midpoint [m] of every joint (of face A's edge, a0 to a1) in the topology's node positions, in joint order.
std::vector<std::array<double, 2>> joint_midpoints(const FdemTopology& topo);

//! A structured mesh of nx x ny squares over [x0, x1] x [y0, y1], each square cut into two triangles
//! along alternating diagonals (for tests and simple specimens).
TriangleMesh structured_rectangle(int nx, int ny, double x0, double x1, double y0, double y1);

//! Moves every vertex that is not on the mesh boundary and not in `fixed` by a random offset, uniform over a
//! disc of radius `fraction` x the length of its shortest edge, for realisations of one case that differ only
//! in the mesh (docs/analysis.md, "Spread over realisations"). The offsets come from a counter-based
//! generator (SplitMix64 of seed and vertex index), so the same seed gives the same mesh on every machine.
//! fraction in [0, 0.25]; the perturbed mesh is checked (check_mesh()).
void perturb_mesh(TriangleMesh& mesh, double fraction, std::uint64_t seed, const std::vector<int>& fixed = {});

//! A disc of radius r centred at (cx, cy) with a concentric hole of radius r_hole, paved in rings without
//! Gmsh (for machines that lack it): round((r - r_hole) / h) rings of equal width, each circle divided into
//! round(2 pi radius / h) equal arcs (every other circle turned by half an arc), neighbouring circles joined
//! by a merge walk in angle, so triangles have sides near h. Groups outer, hole. With `growth` > 1 (at most 2)
//! the rings widen outwards by that ratio each, the first about h wide, and each circle is divided into arcs
//! about as long as the rings beside it are wide: a mesh graded from h at the hole (few elements far out).
NamedMesh ring_disc_with_hole(double cx, double cy, double r, double r_hole, double h, double growth = 1.0);

}  // namespace blastsim::fdem
