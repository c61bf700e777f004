//! \file test_topology.cpp
//! \brief FDEM topology from a mesh (owned nodes, joints, boundary edges) and the bad-mesh errors.
#include "blastsim/core/error.hpp"
#include "blastsim/fdem/mesh.hpp"
#include "catch.hpp"

#include <cmath>

using namespace blastsim;
using namespace blastsim::fdem;

TEST_CASE("Topology of a structured rectangle: counts, joint pairing, boundary edges", "[fdem][mesh]") {
  const int nx = 4, ny = 3;
  const FdemTopology t = build_topology(structured_rectangle(nx, ny, 0, 0.4, 0, 0.3));
  const int triangles = 2 * nx * ny;
  CHECK(t.triangle_count() == triangles);
  CHECK(t.node_positions.size() == static_cast<size_t>(3 * triangles));
  // Edges: horizontal nx (ny + 1), vertical (nx + 1) ny, diagonals nx ny; boundary 2 (nx + ny).
  const int edges = nx * (ny + 1) + (nx + 1) * ny + nx * ny;
  CHECK(t.boundary_edges.size() == static_cast<size_t>(2 * (nx + ny)));
  CHECK(t.joints.size() == static_cast<size_t>(edges - 2 * (nx + ny)));
  // Every joint pairs coincident nodes crosswise: a0 with b1 and a1 with b0.
  for (const Joint& j : t.joints) {
    CHECK(t.node_positions[j.a0] == t.node_positions[j.b1]);
    CHECK(t.node_positions[j.a1] == t.node_positions[j.b0]);
    CHECK(j.triangle_a != j.triangle_b);
  }
  // The boundary edges add up to the perimeter.
  double perimeter = 0;
  for (const BoundaryEdge& e : t.boundary_edges)
    perimeter += std::hypot(t.node_positions[e.n1][0] - t.node_positions[e.n0][0],
                            t.node_positions[e.n1][1] - t.node_positions[e.n0][1]);
  CHECK_THAT(perimeter, WithinRel(2 * (0.4 + 0.3), 1e-12));
}

TEST_CASE("Bad meshes are refused with a clear error", "[fdem][mesh][bad]") {
  TriangleMesh square = structured_rectangle(1, 1, 0, 1, 0, 1);
  SECTION("inverted triangle") {
    std::swap(square.triangles[0][1], square.triangles[0][2]);
    CHECK_THROWS_WITH(check_mesh(square), Catch::Contains("triangle 0") && Catch::Contains("inverted"));
  }
  SECTION("degenerate triangle") {
    square.vertices.push_back({2.0, 0.0});
    square.triangles.push_back({1, 4, 1});
    CHECK_THROWS_WITH(check_mesh(square), Catch::Contains("triangle 2") && Catch::Contains("degenerate"));
  }
  SECTION("non-manifold edge") {
    // The unit square is cut along its diagonal 0-3; a third (counter-clockwise) triangle on that diagonal.
    square.vertices.push_back({2.0, -1.0});
    square.triangles.push_back({0, 4, 3});
    CHECK_THROWS_WITH(check_mesh(square), Catch::Contains("non-manifold") && Catch::Contains("shared by 3"));
  }
  SECTION("inconsistent orientation across an edge") {
    // A counter-clockwise triangle that overlaps triangle {0, 3, 2}: it runs the left side 2 -> 0 the same way.
    square.vertices.push_back({0.3, 0.5});
    square.triangles.push_back({4, 2, 0});
    CHECK_THROWS_WITH(check_mesh(square), Catch::Contains("inconsistent orientation"));
  }
  SECTION("vertex index out of range") {
    square.triangles[1][2] = 17;
    CHECK_THROWS_WITH(check_mesh(square), Catch::Contains("vertex index 17"));
  }
  SECTION("empty mesh") { CHECK_THROWS_AS(check_mesh(TriangleMesh{}), InputError); }
}
