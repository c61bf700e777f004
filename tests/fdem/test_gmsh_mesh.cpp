//! \file test_gmsh_mesh.cpp
//! \brief Gmsh-built meshes (areas, boundary groups, element size) and .msh reading, good and bad files.
#include "blastsim/core/error.hpp"
#include "blastsim/fdem/gmsh_mesh.hpp"
#include "catch.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <map>
#include <cstdio>
#include <string>
#include <vector>

using namespace blastsim::fdem;

namespace {
double mesh_area(const TriangleMesh& m) {
  double a = 0;
  for (const auto& t : m.triangles) {
    const auto &p = m.vertices[t[0]], &q = m.vertices[t[1]], &r = m.vertices[t[2]];
    a += 0.5 * ((q[0] - p[0]) * (r[1] - p[1]) - (r[0] - p[0]) * (q[1] - p[1]));
  }
  return a;
}
double group_length(const NamedMesh& m, const std::string& name) {
  double l = 0;
  for (const auto& e : m.boundary_groups.at(name))
    l += std::hypot(m.mesh.vertices[e[1]][0] - m.mesh.vertices[e[0]][0], m.mesh.vertices[e[1]][1] - m.mesh.vertices[e[0]][1]);
  return l;
}
double mean_edge(const TriangleMesh& m) {
  double l = 0;
  for (const auto& t : m.triangles)
    for (int k = 0; k < 3; ++k) {
      const auto &p = m.vertices[t[k]], &q = m.vertices[t[(k + 1) % 3]];
      l += std::hypot(q[0] - p[0], q[1] - p[1]);
    }
  return l / (3.0 * m.triangles.size());
}
const std::string data = BLASTSIM_TEST_DATA_DIR;
}  // namespace

TEST_CASE("Gmsh rectangle: area, named sides, element size, FDEM topology", "[fdem][mesh][gmsh]") {
  const NamedMesh m = gmsh_rectangle(0.0, 0.0, 0.2, 0.1, 0.01);
  const FdemTopology topo = build_topology(m.mesh);
  std::printf("Gmsh rectangle 0.2 x 0.1, h 0.01: %zu triangles, %zu joints, mean edge %.4f m\n", m.mesh.triangles.size(),
              topo.joints.size(), mean_edge(m.mesh));
  CHECK_THAT(mesh_area(m.mesh), WithinRel(0.02, 1e-12));
  CHECK_THAT(group_length(m, "left"), WithinRel(0.1, 1e-12));
  CHECK_THAT(group_length(m, "top"), WithinRel(0.2, 1e-12));
  CHECK(mean_edge(m.mesh) > 0.5 * 0.01);
  CHECK(mean_edge(m.mesh) < 1.1 * 0.01);
  // Every boundary edge of the topology is in exactly one named group.
  size_t grouped = 0;
  for (const auto& [name, edges] : m.boundary_groups) grouped += boundary_slots(topo, edges, name).size();
  CHECK(grouped == topo.boundary_edges.size());
}

TEST_CASE("Gmsh disc with a hole: area and hole perimeter converge to the circle's", "[fdem][mesh][gmsh]") {
  const double R = 0.1, r = 0.02, h = 0.005;
  const NamedMesh m = gmsh_disc_with_hole(0.0, 0.0, R, r, h);
  const double exact = M_PI * (R * R - r * r);
  std::printf("Gmsh disc with hole: %zu triangles, area %.6f vs %.6f m2, hole perimeter %.5f vs %.5f m\n",
              m.mesh.triangles.size(), mesh_area(m.mesh), exact, group_length(m, "hole"), 2 * M_PI * r);
  // A polygon with edges of about h inscribed in a circle of radius r loses about h^2 / (12 r^2) of its
  // perimeter's length fraction: bounds 1 % here.
  CHECK_THAT(mesh_area(m.mesh), WithinRel(exact, 0.01));
  CHECK_THAT(group_length(m, "hole"), WithinRel(2 * M_PI * r, 0.01));
  CHECK_THAT(group_length(m, "outer"), WithinRel(2 * M_PI * R, 0.01));
  const NamedMesh d = gmsh_disc(0.0, 0.0, R, h);
  CHECK_THAT(mesh_area(d.mesh), WithinRel(M_PI * R * R, 0.01));
  // A chord embedded along the y axis: a row of joints covers it, and it is not a boundary.
  const NamedMesh c = gmsh_disc(0.0, 0.0, R, h, {{{0.0, -R}, {0.0, R}}});
  const FdemTopology topo = build_topology(c.mesh);
  double on_chord = 0;
  for (const Joint& j : topo.joints) {
    const auto& p = topo.node_positions[j.a0];
    const auto& q = topo.node_positions[j.a1];
    if (std::fabs(p[0]) < 1e-12 && std::fabs(q[0]) < 1e-12) on_chord += std::fabs(q[1] - p[1]);
  }
  CHECK_THAT(on_chord, WithinRel(2 * R, 1e-9));
  CHECK_THAT(group_length(c, "outer"), WithinRel(2 * M_PI * R, 0.01));
  const NamedMesh rh = gmsh_rectangle_with_hole(-0.1, -0.1, 0.1, 0.1, 0.0, 0.0, 0.03, h);
  CHECK_THAT(mesh_area(rh.mesh), WithinRel(0.04 - M_PI * 0.03 * 0.03, 0.01));
  CHECK(rh.boundary_groups.count("hole") == 1);
}

namespace {
//! Bond-orientational order of a mesh's edges (Nelson & Halperin 1979, Phys. Rev. B 19:2457): psi_n = |mean of
//! exp(i n theta)|, theta each edge's direction, over the edges whose midpoints lie in the annulus [r0, r1]
//! (`annulus`) and in each of `sectors` equal angular sectors of it (`sector`). A lattice of equilateral
//! triangles has |psi_6| = 1; edges of every direction alike give 0 (to the sampling noise, about
//! 1 / sqrt(edges)).
struct EdgeOrder {
  double annulus = 0;
  std::vector<double> sector;
};
EdgeOrder edge_order(const TriangleMesh& m, int n, double r0, double r1, int sectors) {
  std::vector<std::complex<double>> sum(sectors, 0.0);
  std::vector<long> count(sectors, 0);
  for (const auto& t : m.triangles)
    for (int k = 0; k < 3; ++k) {  // each interior edge twice: the same direction modulo pi
      const auto &p = m.vertices[t[k]], &q = m.vertices[t[(k + 1) % 3]];
      const double mx = 0.5 * (p[0] + q[0]), my = 0.5 * (p[1] + q[1]);
      const double r = std::hypot(mx, my);
      if (r < r0 || r > r1) continue;
      const int s = std::min(sectors - 1, static_cast<int>((std::atan2(my, mx) + M_PI) / (2 * M_PI) * sectors));
      sum[s] += std::polar(1.0, n * std::atan2(q[1] - p[1], q[0] - p[0]));
      ++count[s];
    }
  EdgeOrder out;
  std::complex<double> total = 0;
  long edges = 0;
  for (int s = 0; s < sectors; ++s) {
    out.sector.push_back(count[s] ? std::abs(sum[s]) / count[s] : 0.0);
    total += sum[s], edges += count[s];
  }
  out.annulus = edges ? std::abs(total) / edges : 0.0;
  return out;
}
}  // namespace

TEST_CASE("Gmsh's default mesh is isotropic: no edge direction preferred, where the frontal mesh is a lattice",
          "[fdem][mesh][gmsh]") {
  // Cracks run along element edges, so a mesh whose edges prefer some directions prefers those crack paths.
  // Reference: edges of every direction alike give psi_2 = psi_6 = 0 up to sampling noise; a lattice gives
  // |psi_6| = 1. The annulus leaves three elements next to each rim, where the edges follow the circles. With
  // independent edges the noise would be about 1 / sqrt(54,000) = 0.004 over the annulus and 1 / sqrt(4,500) =
  // 0.015 in a sector of 30 degrees; neighbouring edges are not independent (a Delaunay mesh has small ordered
  // patches), so the bounds are 0.03 over the annulus and, in each sector, a fifth of a lattice's order.
  const double R = 0.3, a = 0.03, h = 0.006, r0 = a + 3 * h, r1 = R - 3 * h;
  const NamedMesh iso = gmsh_disc_with_hole(0.0, 0.0, R, a, h);
  const NamedMesh lattice = gmsh_disc_with_hole(0.0, 0.0, R, a, h, {}, GmshAlgorithm::frontal);
  const EdgeOrder i6 = edge_order(iso.mesh, 6, r0, r1, 12), i2 = edge_order(iso.mesh, 2, r0, r1, 12);
  const EdgeOrder l6 = edge_order(lattice.mesh, 6, r0, r1, 12);
  const double iso6 = *std::max_element(i6.sector.begin(), i6.sector.end());
  const double iso2 = *std::max_element(i2.sector.begin(), i2.sector.end());
  const double lat6 = *std::min_element(l6.sector.begin(), l6.sector.end());
  const double all6 = i6.annulus, all2 = i2.annulus;
  std::printf("edge order, disc R %.2f m with hole %.2f m, h %.3f m: delaunay (%zu triangles) |psi_6| %.4f, |psi_2| %.4f "
              "over the annulus, largest of 12 sectors %.4f / %.4f; frontal (%zu triangles) smallest sector |psi_6| %.4f\n",
              R, a, h, iso.mesh.triangles.size(), all6, all2, iso6, iso2, lattice.mesh.triangles.size(), lat6);
  CHECK(all6 < 0.03);
  CHECK(all2 < 0.03);
  CHECK(iso6 < 0.2);
  CHECK(iso2 < 0.2);
  CHECK(lat6 > 0.5);  // the measure sees the frontal algorithm's lattice in every sector
}

namespace {
//! The smallest altitude [m] of a mesh's triangles (twice the area over the longest edge).
double smallest_altitude(const TriangleMesh& m) {
  double out = 1e300;
  for (const auto& t : m.triangles) {
    const auto &p = m.vertices[t[0]], &q = m.vertices[t[1]], &r = m.vertices[t[2]];
    const double two_area = std::fabs((q[0] - p[0]) * (r[1] - p[1]) - (r[0] - p[0]) * (q[1] - p[1]));
    const double longest = std::max({std::hypot(q[0] - p[0], q[1] - p[1]), std::hypot(r[0] - q[0], r[1] - q[1]),
                                     std::hypot(p[0] - r[0], p[1] - r[1])});
    out = std::min(out, two_area / longest);
  }
  return out;
}
//! The fraction of a's vertices with r0 < |x| < r1 that lie within tol of one of b's (a grid of cells tol wide).
double shared_vertices(const TriangleMesh& a, const TriangleMesh& b, double r0, double r1, double tol) {
  std::map<std::pair<long, long>, std::vector<int>> cells;
  auto cell = [tol](double x) { return static_cast<long>(std::floor(x / tol)); };
  for (std::size_t v = 0; v < b.vertices.size(); ++v) cells[{cell(b.vertices[v][0]), cell(b.vertices[v][1])}].push_back(int(v));
  long inside = 0, shared = 0;
  for (const auto& p : a.vertices) {
    const double r = std::hypot(p[0], p[1]);
    if (r < r0 || r > r1) continue;
    ++inside;
    bool found = false;
    for (long i = cell(p[0]) - 1; i <= cell(p[0]) + 1 && !found; ++i)
      for (long j = cell(p[1]) - 1; j <= cell(p[1]) + 1 && !found; ++j)
        if (const auto it = cells.find({i, j}); it != cells.end())
          for (int v : it->second)
            if (std::hypot(b.vertices[v][0] - p[0], b.vertices[v][1] - p[1]) < tol) found = true;
    shared += found;
  }
  return inside ? static_cast<double>(shared) / inside : 0.0;
}
}  // namespace

TEST_CASE("Gmsh mesh realisations: independent meshes of one shape, as isotropic and as fine as Gmsh's own",
          "[fdem][mesh][gmsh]") {
  // References. Independent: a mesh whose vertices were placed independently of another's puts a vertex within
  // 1 % of h of one of the other's with probability about pi (0.01 h)^2 / (area per vertex, ~0.43 h^2) = 0.07 %;
  // the same mesh turned back or jittered by 3 % keeps every vertex's neighbours, and the same realisation built
  // twice is the same mesh. Size: the size field stays within h (1 +- a), so the triangle density differs from
  // Gmsh's own mesh by at most (1 -+ a)^-2 - 1 = 2 % (a = 1 %); 1 % more is allowed for the count's own
  // variation between Delaunay meshes of one size (0.3 % over turned discs). Isotropy as in the test above.
  // Quality: the rock's stable step scales with the smallest altitude (rock_solver.hpp), Gmsh's own mesh has
  // 0.40 h here; a realisation must keep at least 0.3 h (at most a third more steps).
  const double R = 0.3, a = 0.03, h = 0.006, r0 = a + 3 * h, r1 = R - 3 * h;
  const NamedMesh own = gmsh_disc_with_hole(0.0, 0.0, R, a, h);
  const NamedMesh k1 = gmsh_disc_with_hole(0.0, 0.0, R, a, h, {}, GmshOptions{GmshAlgorithm::delaunay, 1});
  const NamedMesh k2 = gmsh_disc_with_hole(0.0, 0.0, R, a, h, {}, GmshOptions{GmshAlgorithm::delaunay, 2});
  const NamedMesh k1_again = gmsh_disc_with_hole(0.0, 0.0, R, a, h, {}, GmshOptions{GmshAlgorithm::delaunay, 1});
  const double s10 = shared_vertices(k1.mesh, own.mesh, r0, r1, 0.01 * h);
  const double s12 = shared_vertices(k1.mesh, k2.mesh, r0, r1, 0.01 * h);
  const double n0 = own.mesh.triangles.size();
  std::printf("realisations of a disc R %.2f m with hole %.2f m, h %.3f m: triangles %zu / %zu / %zu (own / 1 / 2), "
              "vertices of 1 within 1 %% of h of one of the own mesh's %.4f, of 2's %.4f; smallest altitude %.3f / "
              "%.3f / %.3f h; realisation 1 |psi_6| %.4f |psi_2| %.4f\n",
              R, a, h, own.mesh.triangles.size(), k1.mesh.triangles.size(), k2.mesh.triangles.size(), s10, s12,
              smallest_altitude(own.mesh) / h, smallest_altitude(k1.mesh) / h, smallest_altitude(k2.mesh) / h,
              edge_order(k1.mesh, 6, r0, r1, 1).annulus, edge_order(k1.mesh, 2, r0, r1, 1).annulus);
  CHECK(k1_again.mesh.vertices == k1.mesh.vertices);  // a realisation is reproducible
  CHECK(k1_again.mesh.triangles == k1.mesh.triangles);
  CHECK(s10 < 0.01);
  CHECK(s12 < 0.01);
  CHECK(shared_vertices(own.mesh, own.mesh, r0, r1, 0.01 * h) == 1.0);  // the measure finds a mesh's own vertices
  for (const NamedMesh* m : {&k1, &k2}) {
    CHECK(std::fabs(m->mesh.triangles.size() / n0 - 1) < 0.03);
    CHECK(smallest_altitude(m->mesh) > 0.3 * h);
    CHECK(m->boundary_groups.at("hole").size() > 0);
    CHECK(std::fabs(group_length(*m, "outer") - 2 * M_PI * R) < 1e-3 * 2 * M_PI * R);
  }
  CHECK(edge_order(k1.mesh, 6, r0, r1, 1).annulus < 0.03);
  CHECK(edge_order(k1.mesh, 2, r0, r1, 1).annulus < 0.03);
}

TEST_CASE("Gmsh rectangle and disc with several holes: areas, one group per hole, every edge grouped",
          "[fdem][mesh][gmsh]") {
  const double h = 0.005;
  const std::vector<Circle> holes{{{0.05, 0.06}, 0.01}, {{0.12, 0.06}, 0.015}, {{0.19, 0.05}, 0.012}};
  double holes_area = 0;
  for (const Circle& c : holes) holes_area += M_PI * c.radius * c.radius;
  const NamedMesh r = gmsh_rectangle_with_holes(0.0, 0.0, 0.24, 0.12, holes, h, {{{0.0, 0.1}, {0.24, 0.1}}});
  const NamedMesh d = gmsh_disc_with_holes(0.12, 0.06, 0.11, holes, h);
  std::printf("Gmsh rectangle with 3 holes: %zu triangles, area %.6f vs %.6f m2; disc with 3 holes: area %.6f vs "
              "%.6f m2; hole perimeters %.5f %.5f %.5f m\n", r.mesh.triangles.size(), mesh_area(r.mesh),
              0.24 * 0.12 - holes_area, mesh_area(d.mesh), M_PI * 0.11 * 0.11 - holes_area, group_length(r, "hole0"),
              group_length(r, "hole1"), group_length(r, "hole2"));
  // Polygons inscribed in the circles (edges about h, at least 12 per hole): within 1 % as for one hole.
  CHECK_THAT(mesh_area(r.mesh), WithinRel(0.24 * 0.12 - holes_area, 0.01));
  CHECK_THAT(mesh_area(d.mesh), WithinRel(M_PI * 0.11 * 0.11 - holes_area, 0.01));
  for (const NamedMesh* m : {&r, &d}) {
    for (size_t k = 0; k < holes.size(); ++k)
      CHECK_THAT(group_length(*m, "hole" + std::to_string(k)), WithinRel(2 * M_PI * holes[k].radius, 0.01));
    const FdemTopology topo = build_topology(m->mesh);
    size_t grouped = 0;
    for (const auto& [name, edges] : m->boundary_groups) grouped += boundary_slots(topo, edges, name).size();
    CHECK(grouped == topo.boundary_edges.size());
  }
  CHECK_THAT(group_length(r, "top"), WithinRel(0.24, 1e-12));
  CHECK_THAT(group_length(d, "outer"), WithinRel(2 * M_PI * 0.11, 0.01));
}

namespace {
//! Checks that every edge of group `name` is a chord of the circle (c, r) (both ends on it to 1e-9 r) and that the
//! chords go once around it (their angles add up to 2 pi to 1e-9): the group is that whole circle and nothing else.
void check_group_is_circle(const NamedMesh& m, const std::string& name, const std::array<double, 2>& c, double r) {
  INFO("group " << name);
  REQUIRE(m.boundary_groups.count(name) == 1);
  double angle = 0;
  for (const auto& e : m.boundary_groups.at(name)) {
    const auto& p = m.mesh.vertices[e[0]];
    const auto& q = m.mesh.vertices[e[1]];
    CHECK(std::fabs(std::hypot(p[0] - c[0], p[1] - c[1]) - r) < 1e-9 * r);
    CHECK(std::fabs(std::hypot(q[0] - c[0], q[1] - c[1]) - r) < 1e-9 * r);
    angle += 2 * std::asin(std::min(1.0, 0.5 * std::hypot(q[0] - p[0], q[1] - p[1]) / r));
  }
  CHECK_THAT(angle, WithinAbs(2 * M_PI, 1e-9));
}
//! Every boundary edge of the mesh's topology is in exactly one named group.
void check_every_edge_grouped(const NamedMesh& m) {
  const FdemTopology topo = build_topology(m.mesh);
  size_t grouped = 0;
  for (const auto& [name, edges] : m.boundary_groups) grouped += boundary_slots(topo, edges, name).size();
  CHECK(grouped == topo.boundary_edges.size());
}
}  // namespace

TEST_CASE("Gmsh boundary groups stay whole when embedded lines end on the circles and sides they split",
          "[fdem][mesh][gmsh][groups]") {
  // A line that ends on a boundary curve splits it into pieces; each piece keeps the name of the curve it lies on
  // (an outer arc is never "hole", a hole's arc never the outline's).
  const double R = 0.1, r = 0.02, h = 0.01;
  const std::vector<Segment> radial{{{0.0, r}, {0.0, R}}};                           // hole rim to outer circle
  const std::vector<Segment> chords{{{-R, 0.05}, {R, 0.05}}, {{0.05, -R}, {0.05, R}}};  // outer circle to outer circle
  for (const std::vector<Segment>* lines : {&radial, &chords}) {
    std::vector<Segment> ends = *lines;  // chords: their ends on the circle
    for (Segment& g : ends)
      for (auto* p : {&g.a, &g.b}) {
        const double k = std::hypot((*p)[0], (*p)[1]);
        if (k > 0.5 * (R + r)) *p = {(*p)[0] * R / k, (*p)[1] * R / k};
      }
    const NamedMesh m = gmsh_disc_with_hole(0.0, 0.0, R, r, h, ends);
    CHECK(m.boundary_groups.size() == 2);
    check_group_is_circle(m, "outer", {0.0, 0.0}, R);
    check_group_is_circle(m, "hole", {0.0, 0.0}, r);
    check_every_edge_grouped(m);
  }
  // Several holes: a line through hole 0 and one from hole 1 to the outline keep hole0 and hole1 whole.
  const std::vector<Circle> holes{{{0.05, 0.06}, 0.01}, {{0.15, 0.06}, 0.015}};
  const std::vector<Segment> cut{{{0.0, 0.06}, {0.04, 0.06}}, {{0.06, 0.06}, {0.135, 0.06}}, {{0.15, 0.075}, {0.15, 0.12}}};
  const NamedMesh rect = gmsh_rectangle_with_holes(0.0, 0.0, 0.24, 0.12, holes, 0.005, cut);
  check_group_is_circle(rect, "hole0", holes[0].center, holes[0].radius);
  check_group_is_circle(rect, "hole1", holes[1].center, holes[1].radius);
  CHECK_THAT(group_length(rect, "left"), WithinRel(0.12, 1e-12));
  CHECK_THAT(group_length(rect, "top"), WithinRel(0.24, 1e-12));
  CHECK(rect.boundary_groups.count("hole") == 0);
  check_every_edge_grouped(rect);
  const std::vector<Segment> to_rim{{{0.06, 0.06}, {0.135, 0.06}}, {{0.15, 0.075}, {0.15, 0.06 + std::sqrt(0.0121 - 0.0009)}}};
  const NamedMesh disc = gmsh_disc_with_holes(0.12, 0.06, 0.11, holes, 0.005, to_rim);
  check_group_is_circle(disc, "hole0", holes[0].center, holes[0].radius);
  check_group_is_circle(disc, "hole1", holes[1].center, holes[1].radius);
  check_group_is_circle(disc, "outer", {0.12, 0.06}, 0.11);
  check_every_edge_grouped(disc);
}

TEST_CASE(".msh file: triangles and a named boundary group are read", "[fdem][mesh][gmsh]") {
  const NamedMesh m = read_gmsh_file(data + "/square.msh");
  REQUIRE(m.mesh.triangles.size() == 2);
  CHECK(m.mesh.vertices.size() == 4);
  CHECK_THAT(mesh_area(m.mesh), WithinRel(1.0, 1e-14));
  REQUIRE(m.boundary_groups.count("left") == 1);
  CHECK(m.boundary_groups.at("left").size() == 1);
  CHECK_THAT(group_length(m, "left"), WithinRel(1.0, 1e-14));
  const FdemTopology topo = build_topology(m.mesh);
  CHECK(topo.joints.size() == 1);
  CHECK(boundary_slots(topo, m.boundary_groups.at("left"), "left").size() == 1);
}

TEST_CASE("Bad mesh files give clear errors", "[fdem][mesh][gmsh][errors]") {
  CHECK_THROWS_WITH(read_gmsh_file(data + "/no_such_file.msh"), Catch::Contains("not found"));
  CHECK_THROWS_WITH(read_gmsh_file(data + "/inverted.msh"), Catch::Contains("inverted"));
  CHECK_THROWS_AS(gmsh_disc_with_hole(0, 0, 0.1, 0.2, 0.01), blastsim::InputError);
  CHECK_THROWS_WITH(gmsh_rectangle(0, 0, 1, 1, -0.1), Catch::Contains("element size"));
}
