//! \file gmsh_mesh.cpp
//! \brief Gmsh-built specimen meshes and .msh reading (through the Gmsh C++ API), plus boundary-slot lookup.
#include "blastsim/fdem/gmsh_mesh.hpp"

#include "blastsim/core/error.hpp"
#include "splitmix.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <set>
#include <unordered_map>
#include <utility>

#if defined(BLASTSIM_HAVE_GMSH)
#include <gmsh.h>
#if defined(_OPENMP)
#include <omp.h>
#endif
#endif

namespace blastsim::fdem {

std::vector<int> boundary_slots(const FdemTopology& topo, const std::vector<std::array<int, 2>>& edges,
                                const std::string& group) {
  std::map<std::pair<int, int>, int> slot_of;
  for (const BoundaryEdge& b : topo.boundary_edges) {
    const int v0 = topo.node_vertex[b.n0], v1 = topo.node_vertex[b.n1];
    slot_of[{std::min(v0, v1), std::max(v0, v1)}] = b.n0;
  }
  std::vector<int> slots;
  for (const auto& e : edges) {
    const auto it = slot_of.find({std::min(e[0], e[1]), std::max(e[0], e[1])});
    if (it == slot_of.end())
      throw InputError("boundary group '" + group + "': edge between vertices " + std::to_string(e[0]) + " and " +
                       std::to_string(e[1]) + " is not on the mesh boundary");
    slots.push_back(it->second);
  }
  return slots;
}

void check_holes(const std::vector<Circle>& holes, double gap, const std::string& what) {
  for (std::size_t k = 0; k < holes.size(); ++k) {
    if (!(holes[k].radius > 0))
      throw InputError(what + ": hole " + std::to_string(k) + " has radius " + std::to_string(holes[k].radius) +
                       " m; it must be > 0");
    for (std::size_t l = 0; l < k; ++l) {
      const double d = std::hypot(holes[k].center[0] - holes[l].center[0], holes[k].center[1] - holes[l].center[1]);
      if (d < holes[k].radius + holes[l].radius + gap)
        throw InputError(what + ": holes " + std::to_string(l) + " and " + std::to_string(k) + " overlap or touch (centres " +
                         std::to_string(d) + " m apart, radii " + std::to_string(holes[l].radius) + " and " +
                         std::to_string(holes[k].radius) + " m)");
    }
  }
}

#if defined(BLASTSIM_HAVE_GMSH)

bool gmsh_available() { return true; }

namespace {

//! Gmsh session for one call: initialise quietly, single-threaded (deterministic), finalise on exit.
class GmshSession {
 public:
  GmshSession() {
    gmsh::initialize(0, nullptr, false);
    gmsh::option::setNumber("General.Terminal", 0);
    gmsh::option::setNumber("General.NumThreads", 1);  // Gmsh sets the process's OpenMP thread count to this
    gmsh::model::add("blastsim");
  }
  ~GmshSession() {
    gmsh::finalize();
#if defined(_OPENMP)
    omp_set_num_threads(threads_);  // give the solvers back every thread (seen: runs after meshing used one)
#endif
  }

 private:
#if defined(_OPENMP)
  int threads_ = omp_get_max_threads();  // taken before gmsh::initialize()
#endif
};

//! The current model's triangles and 1-D physical groups as a NamedMesh (vertices renumbered from 0).
NamedMesh extract_model(const std::string& source) {
  NamedMesh out;
  std::vector<std::size_t> node_tags, tri_tags, tri_nodes;
  std::vector<double> coords, params;
  gmsh::model::mesh::getNodes(node_tags, coords, params, -1, -1, true, false);
  std::unordered_map<std::size_t, std::size_t> where;  // node tag -> position in node_tags
  for (std::size_t k = 0; k < node_tags.size(); ++k) where[node_tags[k]] = k;
  gmsh::model::mesh::getElementsByType(2, tri_tags, tri_nodes);  // type 2: 3-node triangle
  if (tri_tags.empty()) throw InputError(source + ": no 3-node triangles in the mesh");
  std::unordered_map<std::size_t, int> index;  // node tag -> vertex index
  auto vertex = [&](std::size_t tag) {
    const auto it = index.find(tag);
    if (it != index.end()) return it->second;
    const auto w = where.find(tag);
    if (w == where.end()) throw InputError(source + ": element refers to missing node " + std::to_string(tag));
    const int v = static_cast<int>(out.mesh.vertices.size());
    out.mesh.vertices.push_back({coords[3 * w->second], coords[3 * w->second + 1]});
    index[tag] = v;
    return v;
  };
  int clockwise = 0;
  for (std::size_t e = 0; e < tri_tags.size(); ++e) {
    std::array<int, 3> t{vertex(tri_nodes[3 * e]), vertex(tri_nodes[3 * e + 1]), vertex(tri_nodes[3 * e + 2])};
    const auto& a = out.mesh.vertices[t[0]];
    const auto& b = out.mesh.vertices[t[1]];
    const auto& c = out.mesh.vertices[t[2]];
    if ((b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1]) < 0) ++clockwise;
    out.mesh.triangles.push_back(t);
  }
  // A surface meshed with its normal along -z gives clockwise triangles throughout: turn them all.
  // A mix is left alone so that check_mesh() reports the inverted ones.
  if (clockwise == static_cast<int>(tri_tags.size()))
    for (auto& t : out.mesh.triangles) std::swap(t[1], t[2]);
  gmsh::vectorpair groups;
  gmsh::model::getPhysicalGroups(groups, 1);
  for (const auto& [dim, tag] : groups) {
    std::string name;
    gmsh::model::getPhysicalName(dim, tag, name);
    if (name.empty()) name = "group" + std::to_string(tag);
    std::vector<int> entities;
    gmsh::model::getEntitiesForPhysicalGroup(dim, tag, entities);
    auto& edges = out.boundary_groups[name];
    for (int entity : entities) {
      std::vector<std::size_t> line_tags, line_nodes;
      gmsh::model::mesh::getElementsByType(1, line_tags, line_nodes, entity);  // type 1: 2-node line
      for (std::size_t e = 0; e < line_tags.size(); ++e)
        edges.push_back({vertex(line_nodes[2 * e]), vertex(line_nodes[2 * e + 1])});
    }
  }
  check_mesh(out.mesh);
  return out;
}

//! u_k of GmshOptions: a number in [-1, 1) from the square (i, j) and realisation k (SplitMix64 of the three
//! combined), the same on every machine.
double realisation_noise(double i, double j, unsigned k) {
  using detail::splitmix64;
  const std::uint64_t z = splitmix64(splitmix64(splitmix64(k) ^ static_cast<std::uint64_t>(static_cast<std::int64_t>(i))) ^
                                     static_cast<std::uint64_t>(static_cast<std::int64_t>(j)));
  return 2 * detail::unit_interval(z) - 1;
}

void require_size(double h, const char* what) {
  if (!(h > 0) || !std::isfinite(h))
    throw InputError(std::string(what) + ": element size h = " + std::to_string(h) + " m must be > 0");
}

//! Names the boundary curves of the surfaces in the model by `classify(x, y)` of a point on each (the middle of
//! its parameter range) and meshes. A point, not the curve's extent: an embedded line that ends on a boundary
//! circle or side splits it into pieces, and every piece lies on the one curve it was cut from, however short.
template <class Classify>
NamedMesh mesh_shape(double h, GmshOptions options, Classify classify, const std::string& source) {
  gmsh::model::occ::synchronize();
  gmsh::vectorpair surfaces, curves;
  gmsh::model::getEntities(surfaces, 2);
  gmsh::model::getBoundary(surfaces, curves, true, false, false);
  std::map<std::string, std::vector<int>> named;
  for (const auto& [dim, tag] : curves) {
    std::vector<double> lo, hi, point;
    gmsh::model::getParametrizationBounds(dim, std::abs(tag), lo, hi);
    gmsh::model::getValue(dim, std::abs(tag), {0.5 * (lo.at(0) + hi.at(0))}, point);
    named[classify(point.at(0), point.at(1))].push_back(std::abs(tag));
  }
  for (const auto& [name, tags] : named) {
    const int g = gmsh::model::addPhysicalGroup(1, tags);
    gmsh::model::setPhysicalName(1, g, name);
  }
  std::vector<int> surface_tags;
  for (const auto& dt : surfaces) surface_tags.push_back(dt.second);
  gmsh::model::addPhysicalGroup(2, surface_tags);
  const double noise = options.realisation > 0 ? kRealisationSizeNoise : 0.0;
  gmsh::option::setNumber("Mesh.MeshSizeMin", 0.5 * h);
  gmsh::option::setNumber("Mesh.MeshSizeMax", h * (1 + noise));
  gmsh::option::setNumber("Mesh.Algorithm", options.algorithm == GmshAlgorithm::frontal ? 6 : 5);  // gmsh_mesh.hpp
  if (options.realisation > 0) {
    const unsigned k = options.realisation;
    gmsh::model::mesh::setSizeCallback([h, k, noise](int, int, double x, double y, double) {
      return h * (1 + noise * realisation_noise(std::floor(x / h), std::floor(y / h), k));
    });
  }
  gmsh::model::mesh::generate(2);
  return extract_model(source);
}

//! Names the side of a rectangle [x0, x1] x [y0, y1] that the boundary point (x, y) lies on (else "hole").
std::string rectangle_side(double x, double y, double x0, double y0, double x1, double y1) {
  const double tol = 1e-5 * std::max(x1 - x0, y1 - y0);
  if (std::fabs(x - x0) < tol) return "left";
  if (std::fabs(x - x1) < tol) return "right";
  if (std::fabs(y - y0) < tol) return "bottom";
  if (std::fabs(y - y1) < tol) return "top";
  return "hole";
}

//! Embeds straight segments in the surfaces: the meshes on the two sides of each share its nodes, so
//! joints lie along it (a chord, a pre-cut crack).
void embed_segments(const gmsh::vectorpair& surfaces, const std::vector<Segment>& embedded) {
  if (embedded.empty()) return;
  gmsh::vectorpair tools, out;
  std::vector<gmsh::vectorpair> map;
  for (const Segment& g : embedded) {
    const int p0 = gmsh::model::occ::addPoint(g.a[0], g.a[1], 0), p1 = gmsh::model::occ::addPoint(g.b[0], g.b[1], 0);
    tools.push_back({1, gmsh::model::occ::addLine(p0, p1)});
  }
  gmsh::model::occ::fragment(surfaces, tools, out, map);
}

template <class Build>
NamedMesh guarded(const std::string& what, Build build) {
  try {
    GmshSession session;
    return build();
  } catch (const InputError&) {
    throw;
  } catch (const std::exception& e) {
    throw InputError(what + ": Gmsh failed: " + e.what());
  } catch (...) {
    throw InputError(what + ": Gmsh failed");
  }
}

}  // namespace

NamedMesh gmsh_rectangle(double x0, double y0, double x1, double y1, double h, const std::vector<Segment>& embedded,
                         GmshOptions options) {
  require_size(h, "rectangle mesh");
  if (!(x1 > x0) || !(y1 > y0)) throw InputError("rectangle mesh: need x1 > x0 and y1 > y0");
  return guarded("rectangle mesh", [&] {
    embed_segments({{2, gmsh::model::occ::addRectangle(x0, y0, 0, x1 - x0, y1 - y0)}}, embedded);
    return mesh_shape(h, options, [&](double x, double y) { return rectangle_side(x, y, x0, y0, x1, y1); },
                      "rectangle mesh");
  });
}

NamedMesh gmsh_disc(double cx, double cy, double r, double h, const std::vector<Segment>& embedded,
                    GmshOptions options) {
  require_size(h, "disc mesh");
  if (!(r > 0)) throw InputError("disc mesh: radius " + std::to_string(r) + " m must be > 0");
  return guarded("disc mesh", [&] {
    embed_segments({{2, gmsh::model::occ::addDisk(cx, cy, 0, r, r)}}, embedded);
    return mesh_shape(h, options, [](double, double) { return std::string("outer"); }, "disc mesh");
  });
}

NamedMesh gmsh_disc_with_hole(double cx, double cy, double r, double r_hole, double h,
                              const std::vector<Segment>& embedded, GmshOptions options) {
  require_size(h, "disc-with-hole mesh");
  if (!(r_hole > 0) || !(r > r_hole))
    throw InputError("disc-with-hole mesh: need 0 < hole radius (" + std::to_string(r_hole) + " m) < radius (" +
                     std::to_string(r) + " m)");
  return guarded("disc-with-hole mesh", [&] {
    const int outer = gmsh::model::occ::addDisk(cx, cy, 0, r, r);
    const int hole = gmsh::model::occ::addDisk(cx, cy, 0, r_hole, r_hole);
    gmsh::vectorpair out;
    std::vector<gmsh::vectorpair> map;
    gmsh::model::occ::cut({{2, outer}}, {{2, hole}}, out, map);
    embed_segments(out, embedded);
    return mesh_shape(h, options, [&](double x, double y) {
      return std::hypot(x - cx, y - cy) > 0.5 * (r + r_hole) ? std::string("outer") : std::string("hole");
    }, "disc-with-hole mesh");
  });
}

NamedMesh gmsh_rectangle_with_hole(double x0, double y0, double x1, double y1, double cx, double cy, double r_hole,
                                   double h, GmshOptions options) {
  require_size(h, "rectangle-with-hole mesh");
  if (!(x1 > x0) || !(y1 > y0) || !(r_hole > 0) || cx - r_hole <= x0 || cx + r_hole >= x1 || cy - r_hole <= y0 ||
      cy + r_hole >= y1)
    throw InputError("rectangle-with-hole mesh: the hole must lie strictly inside the rectangle");
  return guarded("rectangle-with-hole mesh", [&] {
    const int rect = gmsh::model::occ::addRectangle(x0, y0, 0, x1 - x0, y1 - y0);
    const int hole = gmsh::model::occ::addDisk(cx, cy, 0, r_hole, r_hole);
    gmsh::vectorpair out;
    std::vector<gmsh::vectorpair> map;
    gmsh::model::occ::cut({{2, rect}}, {{2, hole}}, out, map);
    return mesh_shape(h, options, [&](double x, double y) { return rectangle_side(x, y, x0, y0, x1, y1); },
                      "rectangle-with-hole mesh");
  });
}

namespace {
//! Cuts `holes` out of the surface `outer`, embeds `embedded` and meshes; curves named by `outer_name` (of a point
//! on the curve) unless they lie on the rim of hole k, named "hole<k>".
template <class OuterName>
NamedMesh mesh_with_holes(int outer, const std::vector<Circle>& holes, double h, const std::vector<Segment>& embedded,
                          GmshOptions options, OuterName outer_name, const std::string& what) {
  gmsh::vectorpair tools, out;
  for (const Circle& c : holes) tools.push_back({2, gmsh::model::occ::addDisk(c.center[0], c.center[1], 0, c.radius, c.radius)});
  std::vector<gmsh::vectorpair> map;
  gmsh::model::occ::cut({{2, outer}}, tools, out, map);
  embed_segments(out, embedded);
  return mesh_shape(h, options, [&](double x, double y) {
    for (std::size_t k = 0; k < holes.size(); ++k)  // holes lie half an element apart: a rim point is one hole's
      if (std::fabs(std::hypot(x - holes[k].center[0], y - holes[k].center[1]) - holes[k].radius) <
          1e-3 * holes[k].radius + 1e-9)
        return "hole" + std::to_string(k);
    return outer_name(x, y);
  }, what);
}
}  // namespace

NamedMesh gmsh_rectangle_with_holes(double x0, double y0, double x1, double y1, const std::vector<Circle>& holes,
                                    double h, const std::vector<Segment>& embedded, GmshOptions options) {
  const std::string what = "rectangle-with-holes mesh";
  require_size(h, what.c_str());
  if (!(x1 > x0) || !(y1 > y0)) throw InputError(what + ": need x1 > x0 and y1 > y0");
  check_holes(holes, 0.5 * h, what);
  for (std::size_t k = 0; k < holes.size(); ++k) {
    const Circle& c = holes[k];
    if (c.center[0] - c.radius < x0 + 0.5 * h || c.center[0] + c.radius > x1 - 0.5 * h ||
        c.center[1] - c.radius < y0 + 0.5 * h || c.center[1] + c.radius > y1 - 0.5 * h)
      throw InputError(what + ": hole " + std::to_string(k) + " (centre " + std::to_string(c.center[0]) + ", " +
                       std::to_string(c.center[1]) + " m, radius " + std::to_string(c.radius) +
                       " m) does not lie inside the rectangle with half an element to spare");
  }
  return guarded(what, [&] {
    return mesh_with_holes(gmsh::model::occ::addRectangle(x0, y0, 0, x1 - x0, y1 - y0), holes, h, embedded, options,
                           [&](double x, double y) { return rectangle_side(x, y, x0, y0, x1, y1); }, what);
  });
}

NamedMesh gmsh_disc_with_holes(double cx, double cy, double r, const std::vector<Circle>& holes, double h,
                               const std::vector<Segment>& embedded, GmshOptions options) {
  const std::string what = "disc-with-holes mesh";
  require_size(h, what.c_str());
  if (!(r > 0)) throw InputError(what + ": radius " + std::to_string(r) + " m must be > 0");
  check_holes(holes, 0.5 * h, what);
  for (std::size_t k = 0; k < holes.size(); ++k)
    if (std::hypot(holes[k].center[0] - cx, holes[k].center[1] - cy) + holes[k].radius > r - 0.5 * h)
      throw InputError(what + ": hole " + std::to_string(k) + " does not lie inside the disc with half an element to spare");
  return guarded(what, [&] {
    return mesh_with_holes(gmsh::model::occ::addDisk(cx, cy, 0, r, r), holes, h, embedded, options,
                           [](double, double) { return std::string("outer"); }, what);
  });
}

#else  // no Gmsh in this build

bool gmsh_available() { return false; }

namespace {
[[noreturn]] void no_gmsh(const std::string& what) {
  throw InputError(what + " needs Gmsh, and this build has none (install libgmsh-dev and reconfigure)");
}
}  // namespace

NamedMesh gmsh_rectangle(double, double, double, double, double, const std::vector<Segment>&, GmshOptions) {
  no_gmsh("rectangle mesh");
}
NamedMesh gmsh_disc(double, double, double, double, const std::vector<Segment>&, GmshOptions) { no_gmsh("disc mesh"); }
NamedMesh gmsh_disc_with_hole(double, double, double, double, double, const std::vector<Segment>&, GmshOptions) {
  no_gmsh("disc-with-hole mesh");
}
NamedMesh gmsh_rectangle_with_hole(double, double, double, double, double, double, double, double, GmshOptions) {
  no_gmsh("rectangle-with-hole mesh");
}
NamedMesh gmsh_rectangle_with_holes(double, double, double, double, const std::vector<Circle>&, double,
                                    const std::vector<Segment>&, GmshOptions) {
  no_gmsh("rectangle-with-holes mesh");
}
NamedMesh gmsh_disc_with_holes(double, double, double, const std::vector<Circle>&, double, const std::vector<Segment>&,
                               GmshOptions) {
  no_gmsh("disc-with-holes mesh");
}

#endif

// Gmsh's own reader (gmsh::open) interprets a file as a script: a .msh can carry commands such as SystemCall.
// Mesh files are read by read_msh_file() as data instead, with or without Gmsh in the build.
NamedMesh read_gmsh_file(const std::string& path) {
  const std::string ext = path.size() >= 4 ? path.substr(path.size() - 4) : "";
  if (ext == ".geo")
    throw InputError("mesh file '" + path + "': a Gmsh script (.geo); blastsim reads meshes as data only (MSH 4.1 "
                     "ASCII): mesh the script with gmsh first (gmsh -2 -format msh41 FILE.geo)");
  return read_msh_file(path);
}

}  // namespace blastsim::fdem
