//! \file rock_model.cpp
//! \brief The mesh factory and the rock model's set-up (rock_model.hpp).
#include "blastsim/fdem/rock_model.hpp"

#include "blastsim/core/error.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace blastsim::fdem {

namespace {
std::string num(double v) {
  std::ostringstream os;
  os << v;
  return os.str();
}

//! The vertices that lie on a joint line (kept in place by the mesh jitter: the lines stay straight).
std::vector<int> joint_line_vertices(const TriangleMesh& mesh, const std::vector<Segment>& lines, double h) {
  std::vector<int> out;
  for (size_t v = 0; v < mesh.vertices.size(); ++v)
    for (const Segment& g : lines) {
      const double lx = g.b[0] - g.a[0], ly = g.b[1] - g.a[1], len2 = lx * lx + ly * ly;
      const double px = mesh.vertices[v][0] - g.a[0], py = mesh.vertices[v][1] - g.a[1];
      const double t = std::clamp((px * lx + py * ly) / len2, 0.0, 1.0);
      if (std::hypot(px - t * lx, py - t * ly) < 1e-6 * std::max(h, std::sqrt(len2))) {  // h: 0 for a mesh file
        out.push_back(static_cast<int>(v));
        break;
      }
    }
  return out;
}

NamedMesh mesh_of_shape(const MeshSpec& s) {
  const double h = s.element_size;
  const GmshOptions gmsh{s.algorithm, s.realisation};
  switch (s.shape) {
    case MeshShape::rectangle:
      return gmsh_rectangle(s.min[0], s.min[1], s.max[0], s.max[1], h, s.joint_lines, gmsh);
    case MeshShape::disc: return gmsh_disc(s.center[0], s.center[1], s.radius, h, s.joint_lines, gmsh);
    case MeshShape::disc_with_hole:
      if (s.ring_mesher) return ring_disc_with_hole(s.center[0], s.center[1], s.radius, s.hole_radius, h, s.ring_growth);
      return gmsh_disc_with_hole(s.center[0], s.center[1], s.radius, s.hole_radius, h, s.joint_lines, gmsh);
    case MeshShape::rectangle_with_hole:
      return gmsh_rectangle_with_hole(s.min[0], s.min[1], s.max[0], s.max[1], s.center[0], s.center[1], s.hole_radius, h,
                                      gmsh);
    case MeshShape::rectangle_with_holes:
      return gmsh_rectangle_with_holes(s.min[0], s.min[1], s.max[0], s.max[1], s.holes, h, s.joint_lines, gmsh);
    case MeshShape::disc_with_holes:
      return gmsh_disc_with_holes(s.center[0], s.center[1], s.radius, s.holes, h, s.joint_lines, gmsh);
    case MeshShape::file: break;
  }
  return read_gmsh_file(s.file);
}
}  // namespace

const char* mesh_shape_name(MeshShape shape) {
  switch (shape) {
    case MeshShape::rectangle: return "rectangle";
    case MeshShape::disc: return "disc";
    case MeshShape::disc_with_hole: return "disc_with_hole";
    case MeshShape::rectangle_with_hole: return "rectangle_with_hole";
    case MeshShape::rectangle_with_holes: return "rectangle_with_holes";
    case MeshShape::disc_with_holes: return "disc_with_holes";
    case MeshShape::file: return "file";
  }
  return "?";
}

bool MeshSpec::is_rectangle() const {
  return shape == MeshShape::rectangle || shape == MeshShape::rectangle_with_hole || shape == MeshShape::rectangle_with_holes;
}
bool MeshSpec::has_holes() const { return shape == MeshShape::rectangle_with_holes || shape == MeshShape::disc_with_holes; }
double MeshSpec::area() const {
  if (shape == MeshShape::file) return 0;
  return is_rectangle() ? std::fabs((max[0] - min[0]) * (max[1] - min[1])) : M_PI * radius * radius;
}

void check_mesh_holes(const MeshSpec& s, const std::vector<std::string>& labels) {
  if (!s.has_holes()) return;
  const double h = s.element_size;
  for (std::size_t k = 0; k < s.holes.size(); ++k) {
    const Circle& c = s.holes[k];
    const bool inside = s.is_rectangle()
                            ? c.center[0] - c.radius >= s.min[0] + 0.5 * h && c.center[0] + c.radius <= s.max[0] - 0.5 * h &&
                                  c.center[1] - c.radius >= s.min[1] + 0.5 * h && c.center[1] + c.radius <= s.max[1] - 0.5 * h
                            : std::hypot(c.center[0] - s.center[0], c.center[1] - s.center[1]) + c.radius <=
                                  s.radius - 0.5 * h;
    if (!(c.radius >= 0.5 * h))  // Gmsh cannot mesh a circle much smaller than its elements
      throw InputError(labels[k] + ".radius = " + num(c.radius) + " m: a hole needs a radius of at least half an element (" +
                       s.label + ".element_size = " + num(h) + " m); use smaller elements or a larger hole");
    if (!inside)
      throw InputError(labels[k] + ": the hole (centre [" + num(c.center[0]) + ", " + num(c.center[1]) + "] m, radius " +
                       num(c.radius) + " m) is not inside the rock's " + mesh_shape_name(s.shape) +
                       " with half an element (" + num(0.5 * h) + " m) to spare");
    for (std::size_t l = 0; l < k; ++l) {
      const Circle& o = s.holes[l];
      const double d = std::hypot(c.center[0] - o.center[0], c.center[1] - o.center[1]);
      if (d < c.radius + o.radius + 0.5 * h)
        throw InputError(labels[k] + ": its hole overlaps that of " + labels[l] + " (centres " + num(d) +
                         " m apart, radii " + num(c.radius) + " and " + num(o.radius) +
                         " m; at least half an element, " + num(0.5 * h) + " m, of rock must lie between them)");
    }
  }
}

void check_joint_lines(const MeshSpec& s) {
  for (std::size_t k = 0; k < s.joint_lines.size(); ++k)
    check_mesh_segment(s, s.joint_lines[k], s.label + ".joint_line." + std::to_string(k));
}

void check_mesh_segment(const MeshSpec& s, const Segment& g, const std::string& label) {
  {
    auto point = [](const std::array<double, 2>& p) { return "(" + num(p[0]) + ", " + num(p[1]) + ") m"; };
    if (s.shape == MeshShape::rectangle_with_hole || s.ring_mesher)
      throw InputError(label + ": joint lines are made by Gmsh for shape = \"rectangle\", \"disc\", \"disc_with_hole\", "
                       "\"rectangle_with_holes\" or \"disc_with_holes\" (this mesh: shape \"" + mesh_shape_name(s.shape) +
                       "\", mesher \"" + (s.ring_mesher ? "rings" : "gmsh") + "\")");
    if (std::hypot(g.b[0] - g.a[0], g.b[1] - g.a[1]) < 0.5 * s.element_size)
      throw InputError(label + ": from " + point(g.a) + " to " + point(g.b) + " is shorter than half an element (" +
                       num(0.5 * s.element_size) + " m)");
    for (const auto& p : {g.a, g.b}) {
      const double tol = 1e-9 * std::max({s.max[0] - s.min[0], s.max[1] - s.min[1], s.radius});
      const double r = std::hypot(p[0] - s.center[0], p[1] - s.center[1]);
      const bool inside = s.is_rectangle() ? p[0] >= s.min[0] - tol && p[0] <= s.max[0] + tol && p[1] >= s.min[1] - tol &&
                                                 p[1] <= s.max[1] + tol
                                           : r <= s.radius + tol && (s.shape != MeshShape::disc_with_hole || r >= s.hole_radius - tol);
      for (std::size_t k = 0; k < s.holes.size() && inside; ++k)
        if (std::hypot(p[0] - s.holes[k].center[0], p[1] - s.holes[k].center[1]) < s.holes[k].radius - tol)
          throw InputError(label + ": the end " + point(p) + " lies inside hole " + std::to_string(k) +
                           " (centre [" + num(s.holes[k].center[0]) + ", " + num(s.holes[k].center[1]) + "] m, radius " +
                           num(s.holes[k].radius) + " m); both ends must lie in the rock or on its boundary");
      if (!inside)
        throw InputError(label + ": the end " + point(p) + " lies outside the rock; both ends must lie in the " +
                         mesh_shape_name(s.shape) + " or on its boundary");
    }
  }
}

namespace {
//! Distance [m] between the segments a and b: 0 where they cross or touch.
double segment_distance(const Segment& a, const Segment& b) {
  const Vec2 a0{a.a[0], a.a[1]}, a1{a.b[0], a.b[1]}, b0{b.a[0], b.a[1]}, b1{b.b[0], b.b[1]};
  auto side = [](const Vec2& p, const Vec2& q, const Vec2& r) { return (q.x - p.x) * (r.y - p.y) - (q.y - p.y) * (r.x - p.x); };
  const double d0 = side(a0, a1, b0), d1 = side(a0, a1, b1), d2 = side(b0, b1, a0), d3 = side(b0, b1, a1);
  if (((d0 > 0 && d1 < 0) || (d0 < 0 && d1 > 0)) && ((d2 > 0 && d3 < 0) || (d2 < 0 && d3 > 0))) return 0.0;
  return std::sqrt(std::min({segment_distance2(a0, a1, b0.x, b0.y), segment_distance2(a0, a1, b1.x, b1.y),
                             segment_distance2(b0, b1, a0.x, a0.y), segment_distance2(b0, b1, a1.x, a1.y)}));
}
}  // namespace

void check_segment_clearance(const MeshSpec& s, const std::vector<LabelledSegment>& segments) {
  if (s.shape == MeshShape::file || segments.empty()) return;
  const double clear = 0.5 * s.element_size;
  const double tol = 1e-9 * std::max({s.max[0] - s.min[0], s.max[1] - s.min[1], 2 * s.radius});
  auto point = [](const std::array<double, 2>& p) { return "(" + num(p[0]) + ", " + num(p[1]) + ") m"; };
  const std::string rule = "; lines a built mesh follows must meet or stay at least half an element (" + s.label +
                           ".element_size / 2 = " + num(clear) + " m) apart, or the mesh shrinks to their spacing: move "
                           "them apart, join them, or use smaller elements";
  // The boundary's circles (the outline of a disc, the holes) and the distance to the outline of a rectangle.
  std::vector<Circle> circles = s.holes;
  if (s.shape == MeshShape::disc_with_hole || s.shape == MeshShape::rectangle_with_hole)
    circles.push_back({s.center, s.hole_radius});
  if (!s.is_rectangle()) circles.push_back({s.center, s.radius});
  auto boundary_distance = [&](const std::array<double, 2>& p) {
    double d = 1e308;
    if (s.is_rectangle())
      d = std::min({std::fabs(p[0] - s.min[0]), std::fabs(p[0] - s.max[0]), std::fabs(p[1] - s.min[1]),
                    std::fabs(p[1] - s.max[1])});
    for (const Circle& c : circles) d = std::min(d, std::fabs(std::hypot(p[0] - c.center[0], p[1] - c.center[1]) - c.radius));
    return d;
  };
  for (std::size_t k = 0; k < segments.size(); ++k) {
    const LabelledSegment& a = segments[k];
    for (const auto& p : {a.segment.a, a.segment.b}) {
      const double d = boundary_distance(p);
      if (d > tol && d < clear)
        throw InputError(a.label + ": its end " + point(p) + " lies " + num(d) + " m from the rock's boundary" + rule);
    }
    for (const Circle& c : circles) {  // a shallow chord: both ends on the circle, its middle close to it
      auto on = [&](const std::array<double, 2>& p) {
        return std::fabs(std::hypot(p[0] - c.center[0], p[1] - c.center[1]) - c.radius) <= tol;
      };
      if (!on(a.segment.a) || !on(a.segment.b)) continue;
      const std::array<double, 2> mid{0.5 * (a.segment.a[0] + a.segment.b[0]), 0.5 * (a.segment.a[1] + a.segment.b[1])};
      const double sagitta = c.radius - std::hypot(mid[0] - c.center[0], mid[1] - c.center[1]);
      if (sagitta < clear)
        throw InputError(a.label + ": a chord of the circle of radius " + num(c.radius) + " m whose middle lies " +
                         num(std::max(sagitta, 0.0)) + " m from it" + rule);
    }
    for (std::size_t l = 0; l < k; ++l) {
      const LabelledSegment& b = segments[l];
      if (a.set >= 0 && b.set >= 0) continue;
      const double d = segment_distance(a.segment, b.segment);
      if (d > tol && d < clear)
        throw InputError(a.label + ": runs " + num(d) + " m from " + b.label + rule);
    }
  }
}

NamedMesh build_mesh(const MeshSpec& s) {
  const bool one_hole = s.shape == MeshShape::disc_with_hole || s.shape == MeshShape::rectangle_with_hole;
  if (one_hole && !(s.hole_radius >= 0.5 * s.element_size))
    throw InputError(s.label + ".hole_radius = " + num(s.hole_radius) + " m: a hole needs a radius of at least half an "
                     "element (" + s.label + ".element_size = " + num(s.element_size) + " m)");
  if (s.rotation != 0 && s.shape != MeshShape::disc && s.shape != MeshShape::disc_with_hole)
    throw InputError(s.label + ".rotation = " + num(s.rotation * 180 / M_PI) + " deg: only a mesh of shape \"disc\" or "
                     "\"disc_with_hole\" can be turned (the rock stays the same; this mesh is \"" +
                     mesh_shape_name(s.shape) + "\"): remove the key");
  // A turned mesh: the joint lines turned back by the angle, the shape meshed, then every vertex turned by it, so
  // the circles' polygons turn and the lines end where the spec puts them.
  const double c = std::cos(s.rotation), sn = std::sin(s.rotation);
  auto turn = [&](std::array<double, 2>& p, double sign) {
    const double dx = p[0] - s.center[0], dy = p[1] - s.center[1];
    p = {s.center[0] + c * dx - sign * sn * dy, s.center[1] + sign * sn * dx + c * dy};
  };
  MeshSpec meshed = s;
  if (s.rotation != 0)
    for (Segment& g : meshed.joint_lines) turn(g.a, -1.0), turn(g.b, -1.0);
  NamedMesh m = mesh_of_shape(meshed);
  if (s.jitter > 0) {
    try {
      perturb_mesh(m.mesh, s.jitter, static_cast<std::uint64_t>(s.seed),
                   joint_line_vertices(m.mesh, meshed.joint_lines, s.element_size));
    } catch (const InputError& e) {
      throw InputError(s.label + ".jitter = " + num(s.jitter) + ": the perturbed mesh is invalid (" + e.what() +
                       "); use a smaller jitter");
    }
  }
  if (s.rotation != 0)
    for (std::array<double, 2>& p : m.mesh.vertices) turn(p, 1.0);
  return m;
}

RockModel build_rock_model(const RockModelSpec& spec) {
  RockModel m;
  MeshSpec mesh = spec.mesh;
  // A built shape follows the pre-cut cracks and the joints; a mesh file has its own edges along them. Either way
  // the mesh jitter keeps the vertices on these lines in place, so that the lines stay straight.
  for (const PreCutCrack& c : spec.cracks) mesh.joint_lines.push_back(c.segment);
  const std::vector<std::vector<Segment>> traces = joint_sets_traces(spec.joint_sets, spec.mesh);  // of each set
  for (const std::vector<Segment>& set : traces) mesh.joint_lines.insert(mesh.joint_lines.end(), set.begin(), set.end());
  {  // room for the elements between the lines, before any meshing
    std::vector<LabelledSegment> lines;
    for (std::size_t k = 0; k < spec.mesh.joint_lines.size(); ++k)
      lines.push_back({spec.mesh.label + ".joint_line." + std::to_string(k), spec.mesh.joint_lines[k]});
    for (const PreCutCrack& c : spec.cracks) lines.push_back({c.label, c.segment});
    for (std::size_t k = 0; k < traces.size(); ++k)
      for (std::size_t t = 0; t < traces[k].size(); ++t)
        lines.push_back(spec.joint_sets[k].segments.empty()
                            ? LabelledSegment{spec.joint_sets[k].label + " (trace " + std::to_string(t) + ")", traces[k][t],
                                              static_cast<int>(k)}
                            : LabelledSegment{spec.joint_sets[k].label, traces[k][t]});
    check_segment_clearance(spec.mesh, lines);
  }
  m.mesh = build_mesh(mesh);
  m.topology = build_topology(m.mesh.mesh);
  if (spec.heterogeneity) check_correlation_length(*spec.heterogeneity, mean_joint_length(m.topology));
  const std::vector<JointProperties> joints =  // a correlated strength field is read at the joints' midpoints
      spec.heterogeneity ? heterogeneous_joints(spec.material, *spec.heterogeneity, joint_midpoints(m.topology))
                         : std::vector<JointProperties>{};
  m.solver = std::make_unique<RockSolver>(m.topology, spec.material, spec.options, joints);
  RockSolver& solver = *m.solver;
  const FdemTopology& topo = m.topology;
  // Initial velocities first: prescribed velocities then override them on their nodes.
  if (spec.initial_velocity[0] != 0 || spec.initial_velocity[1] != 0) {
    std::vector<double> v(2 * solver.node_count());
    for (int n = 0; n < solver.node_count(); ++n) v[2 * n] = spec.initial_velocity[0], v[2 * n + 1] = spec.initial_velocity[1];
    solver.set_velocities(v);
  }
  for (const VelocityLoad& l : spec.velocities) {
    std::vector<int> nodes;
    for (size_t n = 0; n < topo.node_positions.size(); ++n) {
      const auto& p = topo.node_positions[n];
      if (p[0] >= l.min[0] && p[0] <= l.max[0] && p[1] >= l.min[1] && p[1] <= l.max[1]) nodes.push_back(static_cast<int>(n));
    }
    if (nodes.empty())
      throw InputError(l.label + ": no mesh node lies in the box [" + num(l.min[0]) + ", " + num(l.max[0]) + "] x [" +
                       num(l.min[1]) + ", " + num(l.max[1]) + "] m");
    solver.prescribe_velocity(nodes, l.along_x, l.along_y, l.velocity[0], l.velocity[1]);
    m.velocity_nodes.push_back(nodes);
  }
  // The edge slots of a named boundary group; `label` names the part that asked for it.
  auto group_slots = [&](const std::string& key, const std::string& group_name) {
    const auto group = m.mesh.boundary_groups.find(group_name);
    if (group == m.mesh.boundary_groups.end()) {
      std::string names;
      for (const auto& [name, edges] : m.mesh.boundary_groups) names += (names.empty() ? "" : ", ") + name;
      throw InputError(key + " = \"" + group_name + "\": the mesh has no such boundary group (it has: " + names +
                       ")");
    }
    return boundary_slots(topo, group->second, group_name);
  };
  for (const PressureLoad& p : spec.pressures) solver.set_edge_pressure(group_slots(p.label + ".boundary", p.boundary), p.pressure);
  std::vector<int> viscous;
  for (const ViscousBoundary& v : spec.viscous_boundaries) {
    const std::vector<int> slots = group_slots(v.label + ".boundary", v.boundary);
    viscous.insert(viscous.end(), slots.begin(), slots.end());
  }
  if (!viscous.empty()) solver.set_viscous_boundary(viscous);
  // The joints along a segment the input gave (a pre-cut crack, an explicit joint): they must cover it, or part of
  // it lies outside the rock (beyond the outline, in a hole) or, in a mesh file, off the mesh's edges.
  auto joints_along = [&](const std::string& label, const Segment& g) {
    const double length = std::hypot(g.b[0] - g.a[0], g.b[1] - g.a[1]);
    const double tolerance = 1e-6 * std::max(spec.mesh.element_size, length);
    std::vector<int> joints = solver.joints_on_segment(g.a[0], g.a[1], g.b[0], g.b[1], tolerance);
    double covered = 0;
    for (int j : joints) {
      const auto& p = topo.node_positions[topo.joints[j].a0];
      const auto& q = topo.node_positions[topo.joints[j].a1];
      covered += std::hypot(q[0] - p[0], q[1] - p[1]);
    }
    if (!(covered >= (1 - 1e-6) * length))
      throw InputError(label + ": the segment from [" + num(g.a[0]) + ", " + num(g.a[1]) + "] to [" + num(g.b[0]) + ", " +
                       num(g.b[1]) + "] m (" + num(length) + " m) runs along joints of the rock mesh for " + num(covered) +
                       " m only: " + (spec.mesh.shape == MeshShape::file
                                          ? "the rest lies outside the rock, in a hole, or off the mesh file's edges "
                                            "(a mesh file needs edges all along it)"
                                          : "the rest lies outside the rock or in a hole; both ends and the whole "
                                            "segment must lie in the rock"));
    return joints;
  };
  for (const PreCutCrack& c : spec.cracks) {
    std::vector<int> joints = joints_along(c.label, c.segment);
    solver.break_joints(joints);
    m.crack_joints.push_back(std::move(joints));
  }
  if (!spec.joint_sets.empty()) m.joint_set_of.assign(topo.joints.size(), -1);
  for (std::size_t k = 0; k < spec.joint_sets.size(); ++k) {
    const JointSetSpec& set = spec.joint_sets[k];
    std::vector<int> joints;
    for (const Segment& t : traces[k]) {
      const double tolerance = 1e-6 * std::max(spec.mesh.element_size, std::hypot(t.b[0] - t.a[0], t.b[1] - t.a[1]));
      // An explicit joint must lie along the mesh all its length; a set's traces are clipped to the rock.
      for (int j : set.segments.empty() ? solver.joints_on_segment(t.a[0], t.a[1], t.b[0], t.b[1], tolerance)
                                        : joints_along(set.label, t)) {
        joints.push_back(j);
        m.joint_set_of[j] = static_cast<int>(k);  // a later set wins where two meet
      }
    }
    if (set.open) {
      solver.break_joints(joints);
    } else {
      try {
        solver.set_joint_properties(joints, set.properties);
      } catch (const InputError& e) {  // the set's key, not a joint number the user never gave
        throw InputError(set.label + ": its strength cannot be given to the mesh's joints along it (" + e.what() + ")");
      }
    }
    m.set_joints.push_back(std::move(joints));
  }
  if (spec.in_situ) {
    const InSituSpec& is = *spec.in_situ;
    std::vector<int> held;
    for (const std::string& group : is.held_boundaries) {
      const std::vector<int> slots = group_slots(is.label + ".boundaries", group);
      held.insert(held.end(), slots.begin(), slots.end());
    }
    try {
      set_in_situ_stress(solver, is.stress, held);
    } catch (const InputError& e) {
      throw InputError(is.label + ": " + e.what());
    }
  }
  std::vector<std::array<double, 2>> points;
  std::vector<double> until;
  for (const ProbeSpec& p : spec.probes) points.push_back(p.position), until.push_back(p.until);
  try {
    solver.set_probes(points, until);
  } catch (const InputError&) {
    for (const ProbeSpec& p : spec.probes) {  // name the first probe outside the rock
      try {
        solver.set_probes({p.position});
      } catch (const InputError&) {
        throw InputError(p.label + ".position = [" + num(p.position[0]) + ", " + num(p.position[1]) +
                         "] m: lies in no triangle of the rock mesh; a rock probe must lie in the rock");
      }
    }
    throw;
  }
  if (spec.in_situ && spec.in_situ->equilibrate) {
    const InSituSpec& is = *spec.in_situ;
    m.equilibrium = equilibrate(solver, is.equilibrium);
    if (!m.equilibrium->converged)
      throw InstabilityError(is.label + ": the rock did not come to rest under its in-situ stress in max_steps = " +
                             std::to_string(is.equilibrium.max_steps) + " steps (" +
                             std::to_string(m.equilibrium->checks) + " undamped checks failed, " +
                             std::to_string(m.equilibrium->broken_joints) +
                             " joints broken): raise max_steps, or check that the held boundaries and supports hold "
                             "the rock (a free body under unbalanced loads never comes to rest)");
  }
  return m;
}

double mean_joint_length(const FdemTopology& t) {
  double sum = 0;
  for (const Joint& j : t.joints)
    sum += std::hypot(t.node_positions[j.a1][0] - t.node_positions[j.a0][0], t.node_positions[j.a1][1] - t.node_positions[j.a0][1]);
  return t.joints.empty() ? 0.0 : sum / t.joints.size();
}

}  // namespace blastsim::fdem
