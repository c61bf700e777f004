//! \file test_topology.cpp
//! \brief FDEM topology from a mesh (owned nodes, joints, boundary edges) and the bad-mesh errors.
#include "blastsim/core/error.hpp"
#include "blastsim/fdem/gmsh_mesh.hpp"
#include "blastsim/fdem/mesh.hpp"
#include "blastsim/fdem/rock_model.hpp"
#include "catch.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

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

TEST_CASE("Ring mesh of a disc with a hole (no Gmsh): area, boundary groups, element shape", "[fdem][mesh]") {
  const double R = 0.93, a = 0.05;
  for (double h : {0.03, 0.0095}) {
    const NamedMesh m = ring_disc_with_hole(0.0, 0.0, R, a, h);
    const FdemTopology topo = build_topology(m.mesh);
    double area = 0, worst_angle = M_PI, longest = 0;
    for (const auto& t : m.mesh.triangles) {
      std::array<std::array<double, 2>, 3> p{m.mesh.vertices[t[0]], m.mesh.vertices[t[1]], m.mesh.vertices[t[2]]};
      area += 0.5 * ((p[1][0] - p[0][0]) * (p[2][1] - p[0][1]) - (p[1][1] - p[0][1]) * (p[2][0] - p[0][0]));
      for (int k = 0; k < 3; ++k) {
        const auto& o = p[k];
        const auto& b = p[(k + 1) % 3];
        const auto& c = p[(k + 2) % 3];
        const double ux = b[0] - o[0], uy = b[1] - o[1], vx = c[0] - o[0], vy = c[1] - o[1];
        worst_angle = std::min(worst_angle, std::acos((ux * vx + uy * vy) / std::hypot(ux, uy) / std::hypot(vx, vy)));
        longest = std::max(longest, std::hypot(ux, uy));
      }
    }
    // Inscribed polygons of n sides lose pi r^2 (1 - sin(2 pi / n) n / (2 pi)) ~ (2 pi^2 / 3) r^2 / n^2 each.
    const double exact = M_PI * (R * R - a * a);
    std::printf("ring mesh h = %.4f m: %zu triangles, %zu joints, area %.6f vs %.6f m2 (%+.3f %%), smallest angle "
                "%.1f deg, longest edge %.4f m; %zu hole and %zu outer edges\n", h, m.mesh.triangles.size(),
                topo.joints.size(), area, exact, 100 * (area / exact - 1), worst_angle * 180 / M_PI, longest,
                m.boundary_groups.at("hole").size(), m.boundary_groups.at("outer").size());
    CHECK(std::fabs(area / exact - 1) < 2e-3);
    CHECK(worst_angle > 30 * M_PI / 180);
    CHECK(longest < 1.8 * h);  // a diagonal between circles whose arcs are staggered
    CHECK(topo.boundary_edges.size() == m.boundary_groups.at("hole").size() + m.boundary_groups.at("outer").size());
    CHECK(boundary_slots(topo, m.boundary_groups.at("hole"), "hole").size() == m.boundary_groups.at("hole").size());
  }
  CHECK_THROWS_WITH(ring_disc_with_hole(0, 0, 0.05, 0.1, 0.01), Catch::Contains("hole radius < radius"));
}

TEST_CASE("Mesh jitter: interior vertices move within the bound, boundary and fixed ones stay, same seed same mesh",
          "[fdem][mesh][jitter]") {
  const TriangleMesh base = structured_rectangle(10, 8, 0.0, 1.0, 0.0, 0.8);  // edges 0.1 m (diagonals longer)
  TriangleMesh a = base, b = base, c = base;
  const int centre = 5 * 11 + 4;  // vertex (4, 5), interior
  perturb_mesh(a, 0.05, 7, {centre});
  perturb_mesh(b, 0.05, 7, {centre});
  perturb_mesh(c, 0.05, 8);
  int moved = 0;
  double largest = 0;
  for (size_t v = 0; v < base.vertices.size(); ++v) {
    const double d = std::hypot(a.vertices[v][0] - base.vertices[v][0], a.vertices[v][1] - base.vertices[v][1]);
    const double x = base.vertices[v][0], y = base.vertices[v][1];
    const bool boundary = x < 1e-12 || x > 1 - 1e-12 || y < 1e-12 || y > 0.8 - 1e-12;
    if (boundary || static_cast<int>(v) == centre) CHECK(d == 0.0);
    if (d > 0) ++moved;
    largest = std::max(largest, d);
  }
  std::printf("mesh jitter 0.05: %d of %zu vertices moved, largest offset %.4f m (bound 0.05 x 0.1 m)\n", moved,
              base.vertices.size(), largest);
  CHECK(moved == 9 * 7 - 1);  // every interior vertex but the fixed one
  CHECK(largest <= 0.05 * 0.1 + 1e-15);
  CHECK(a.vertices == b.vertices);
  CHECK(a.vertices != c.vertices);
  CHECK_THROWS_AS(perturb_mesh(a, 0.3, 1), blastsim::InputError);
}

TEST_CASE("Mesh rotation: a turned disc_with_hole is the same rock with its polygons turned, its joint line in place",
          "[fdem][mesh][rotation]") {
  MeshSpec s;
  s.label = "mesh";
  s.shape = MeshShape::disc_with_hole;
  s.center = {0.1, -0.2};
  s.radius = 0.3, s.hole_radius = 0.05, s.element_size = 0.03;
  const double angle = 0.4;  // [rad]
  const double c = std::cos(angle), sn = std::sin(angle);
  const NamedMesh base = build_mesh(s);
  s.rotation = angle;
  const NamedMesh turned = build_mesh(s);
  // Without joint lines Gmsh meshes the same shape: every vertex is the base's turned about the centre.
  REQUIRE(turned.mesh.vertices.size() == base.mesh.vertices.size());
  CHECK(turned.mesh.triangles == base.mesh.triangles);
  double worst = 0;
  for (size_t v = 0; v < base.mesh.vertices.size(); ++v) {
    const double dx = base.mesh.vertices[v][0] - s.center[0], dy = base.mesh.vertices[v][1] - s.center[1];
    const double x = s.center[0] + c * dx - sn * dy, y = s.center[1] + sn * dx + c * dy;
    worst = std::max(worst, std::hypot(turned.mesh.vertices[v][0] - x, turned.mesh.vertices[v][1] - y));
  }
  // The hole's vertices stay on the hole's circle.
  double off_circle = 0;
  for (const auto& e : turned.boundary_groups.at("hole"))
    for (int v : e)
      off_circle = std::max(off_circle, std::fabs(std::hypot(turned.mesh.vertices[v][0] - s.center[0],
                                                             turned.mesh.vertices[v][1] - s.center[1]) - s.hole_radius));
  std::printf("mesh rotation 0.4 rad: %zu vertices, largest distance from the turned base %.2e m, hole vertices "
              "off the circle by at most %.2e m\n", base.mesh.vertices.size(), worst, off_circle);
  CHECK(worst <= 1e-15);
  CHECK(turned.boundary_groups.at("hole").size() == base.boundary_groups.at("hole").size());
  CHECK(off_circle <= 1e-15);
  // A joint line stays where the spec puts it: the vertices along it lie on it, as many as without the turn.
  const Segment line{{0.1 + 0.08, -0.2}, {0.1 + 0.26, -0.2}};
  auto on_line = [&](const TriangleMesh& m) {
    int n = 0;
    for (const auto& p : m.vertices)
      if (std::fabs(p[1] - line.a[1]) <= 1e-12 && p[0] >= line.a[0] - 1e-12 && p[0] <= line.b[0] + 1e-12) ++n;
    return n;
  };
  s.joint_lines = {line};
  const int along_turned = on_line(build_mesh(s).mesh);
  s.rotation = 0;
  const int along_base = on_line(build_mesh(s).mesh);
  std::printf("mesh rotation with a joint line of 0.18 m: %d vertices on it (%d unturned)\n", along_turned, along_base);
  CHECK(along_turned >= 7);  // the line's two ends and at least one vertex per element along it
  CHECK(along_turned == along_base);
  // Only the shapes a turn leaves the same rock.
  MeshSpec box;
  box.label = "rock.mesh";
  box.shape = MeshShape::rectangle;
  box.min = {0.0, 0.0}, box.max = {0.2, 0.1}, box.element_size = 0.02, box.rotation = 0.1;
  CHECK_THROWS_WITH(build_mesh(box), Catch::Contains("rock.mesh.rotation") && Catch::Contains("disc_with_hole"));
}
