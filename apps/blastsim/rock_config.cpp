//! \file rock_config.cpp
//! \brief Reads a rock-only case from TOML into a RockCaseConfig; docs/input.md documents every key read here.
#include "blastsim/core/error.hpp"
#include "case_input.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>

namespace blastsim::app {

CaseKind case_kind(const toml::table& input) {
  const bool rock = input.contains("rock"), gas = input.contains("gas");
  return rock && gas ? CaseKind::coupled : (rock ? CaseKind::rock : CaseKind::gas);
}

namespace {

fdem::RockMaterial read_material(TableReader& r) {
  const std::string preset = r.text("preset", {"paper_table2", "none"}, std::string("paper_table2"));
  fdem::RockMaterial m = preset == "paper_table2" ? fdem::RockMaterial::paper_table2() : fdem::RockMaterial{};
  auto value = [&](const char* key, const char* unit, double preset_value, Range range) {
    return preset == "none" ? r.number(key, unit, range) : r.number(key, unit, range, preset_value);
  };
  m.density = value("density", "kg/m3", m.density, Range::positive());
  m.youngs_modulus = value("youngs_modulus", "Pa", m.youngs_modulus, Range::positive());
  m.poisson_ratio = value("poisson_ratio", "", m.poisson_ratio, Range{0.0, 0.5, false, true});
  m.tensile_strength = value("tensile_strength", "Pa", m.tensile_strength, Range::positive());
  m.cohesion = value("cohesion", "Pa", m.cohesion, Range::positive());
  m.friction_angle =
      value("friction_angle", "deg", m.friction_angle * 180 / M_PI, Range{0.0, 90.0, false, true}) * M_PI / 180;
  m.fracture_energy_mode1 = value("fracture_energy_mode1", "J/m2", m.fracture_energy_mode1, Range::positive());
  m.fracture_energy_mode2 = value("fracture_energy_mode2", "J/m2", m.fracture_energy_mode2, Range::positive());
  m.contact_friction = value("contact_friction", "", m.contact_friction, Range::non_negative());
  return m;
}

RockMeshSpec read_mesh(TableReader& t) {
  RockMeshSpec s;
  s.shape = t.text("shape", {"rectangle", "disc", "disc_with_hole", "rectangle_with_hole", "rectangle_with_holes",
                             "disc_with_holes", "file"});
  s.jitter = t.number("jitter", "", Range{0.0, 0.25, false, false}, 0.0);
  s.seed = t.integer("seed", "", 0, 1);
  if (s.shape == "file") {
    s.file = t.text("file", {});
    return s;
  }
  s.element_size = t.number("element_size", "m", Range::positive());
  s.mesher = t.text("mesher", {"gmsh", "rings"}, std::string("gmsh"));
  if (s.mesher == "rings" && s.shape != "disc_with_hole")
    throw InputError(fmt::format("{}.mesher = \"rings\" meshes only shape = \"disc_with_hole\" (this mesh is \"{}\"): use "
                                 "mesher = \"gmsh\"", t.path(), s.shape));
  for (TableReader& h : t.table_array("hole")) {
    if (!s.has_holes())
      throw InputError(fmt::format("{}: holes are cut from shape = \"rectangle_with_holes\" or \"disc_with_holes\" "
                                   "(this mesh is \"{}\")", h.path(), s.shape));
    s.holes.push_back({h.pair("center", "m"), h.number("radius", "m", Range::positive())});
    h.finish();
  }
  if (s.shape == "rectangle" || s.shape == "rectangle_with_hole" || s.shape == "rectangle_with_holes") {
    s.min = t.pair("min", "m");
    s.max = t.pair("max", "m");
    if (!(s.max[0] > s.min[0]) || !(s.max[1] > s.min[1]))
      throw InputError(fmt::format("{}: max must exceed min in x and y", t.path()));
  }
  if (s.shape == "disc" || s.shape == "disc_with_hole" || s.shape == "disc_with_holes") {
    s.center = t.pair("center", "m", std::array<double, 2>{0.0, 0.0});
    s.radius = t.number("radius", "m", Range::positive());
  }
  if (s.shape == "disc_with_hole" || s.shape == "rectangle_with_hole") {
    if (s.shape == "rectangle_with_hole") s.center = t.pair("center", "m");
    s.hole_radius = t.number("hole_radius", "m", Range::positive());
  }
  // Memory before meshing: about 2.3 area / h^2 triangles, each about 2 kB in mesh, topology and solver.
  if (s.shape != "file") {
    const double area = s.is_rectangle() ? std::fabs((s.max[0] - s.min[0]) * (s.max[1] - s.min[1]))
                            : M_PI * s.radius * s.radius;
    check_memory_need(fmt::format("rock.mesh.element_size = {:g} m on this {} (about {:.3g} triangles)", s.element_size,
                                  s.shape, 2.3 * area / (s.element_size * s.element_size)),
                      2.3 * area / (s.element_size * s.element_size) * 2048.0);
  }
  for (TableReader& l : t.table_array("joint_line")) {
    const fdem::Segment g{l.pair("from", "m"), l.pair("to", "m")};
    l.finish();
    if (s.shape == "rectangle_with_hole" || s.mesher != "gmsh")
      throw InputError(fmt::format("{}: joint lines are made by Gmsh for shape = \"rectangle\", \"disc\", "
                                   "\"disc_with_hole\", \"rectangle_with_holes\" or \"disc_with_holes\" (this mesh: "
                                   "shape \"{}\", mesher \"{}\")",
                                   l.path(), s.shape, s.mesher));
    if (std::hypot(g.b[0] - g.a[0], g.b[1] - g.a[1]) < 0.5 * s.element_size)
      throw InputError(fmt::format("{}: from ({}) m to ({}) m is shorter than half an element ({} m)", l.path(),
                                   fmt::join(g.a, ", "), fmt::join(g.b, ", "), 0.5 * s.element_size));
    for (const auto& p : {g.a, g.b}) {
      const double tol = 1e-9 * std::max({s.max[0] - s.min[0], s.max[1] - s.min[1], s.radius});
      const double r = std::hypot(p[0] - s.center[0], p[1] - s.center[1]);
      const bool inside = s.is_rectangle()
                              ? p[0] >= s.min[0] - tol && p[0] <= s.max[0] + tol && p[1] >= s.min[1] - tol &&
                                    p[1] <= s.max[1] + tol
                              : r <= s.radius + tol && (s.shape != "disc_with_hole" || r >= s.hole_radius - tol);
      if (!inside)
        throw InputError(fmt::format("{}: the end ({}) m lies outside the rock; both ends must lie in the {} or on its "
                                     "boundary", l.path(), fmt::join(p, ", "), s.shape));
    }
    s.joint_lines.push_back(g);
  }
  return s;
}

}  // namespace

void read_rock_section(TableReader& root, RockCaseConfig& c) {
  TableReader rock = root.table("rock", true);
  c.material = read_material(rock);
  c.options.joint_penalty_factor = rock.number("joint_penalty_factor", "", Range::positive(), 10.0);
  c.options.contact_penalty_factor = rock.number("contact_penalty_factor", "", Range::positive(), 10.0);
  c.options.damping_ratio = rock.number("damping_ratio", "", Range{0.0, 1.0, false, true}, 0.0);
  c.options.contact = rock.boolean("contact", true);
  c.options.gravity = rock.pair("gravity", "m/s2", std::array<double, 2>{0.0, 0.0});
  c.initial_velocity = rock.pair("initial_velocity", "m/s", std::array<double, 2>{0.0, 0.0});
  c.pressure_ramp_time = rock.number("pressure_ramp_time", "s", Range::non_negative(), 0.0);
  TableReader mesh = rock.table("mesh", true);
  c.mesh = read_mesh(mesh);
  mesh.finish();
  for (TableReader& v : rock.table_array("velocity")) {
    VelocityLoad l;
    l.min = v.pair("min", "m");
    l.max = v.pair("max", "m");
    l.velocity = v.pair("velocity", "m/s");
    const std::string comp = v.text("components", {"x", "y", "xy"}, std::string("xy"));
    l.along_x = comp != "y";
    l.along_y = comp != "x";
    v.finish();
    c.velocities.push_back(l);
  }
  for (TableReader& p : rock.table_array("pressure")) {
    PressureLoad l;
    l.boundary = p.text("boundary", {});
    l.pressure = p.number("pressure", "Pa", Range::any());
    p.finish();
    c.pressures.push_back(l);
  }
  for (TableReader& v : rock.table_array("viscous_boundary")) {
    c.viscous_boundaries.push_back(v.text("boundary", {}));
    v.finish();
  }
  rock.finish();
  c.material.validate();
  c.options.validate();
  read_analysis_section(root, c);
}

void check_mesh_holes(const RockMeshSpec& s, const std::vector<std::string>& names) {
  if (!s.has_holes()) return;
  if (s.holes.empty())
    throw InputError(fmt::format("rock.mesh.shape = \"{}\": needs at least one hole ([[rock.mesh.hole]], or the holes "
                                 "of [[charge]] in a coupled case)", s.shape));
  const double h = s.element_size;
  for (std::size_t k = 0; k < s.holes.size(); ++k) {
    const fdem::Circle& c = s.holes[k];
    const bool inside = s.is_rectangle()
                            ? c.center[0] - c.radius >= s.min[0] + 0.5 * h && c.center[0] + c.radius <= s.max[0] - 0.5 * h &&
                                  c.center[1] - c.radius >= s.min[1] + 0.5 * h && c.center[1] + c.radius <= s.max[1] - 0.5 * h
                            : std::hypot(c.center[0] - s.center[0], c.center[1] - s.center[1]) + c.radius <=
                                  s.radius - 0.5 * h;
    if (!inside)
      throw InputError(fmt::format("{}: the hole (centre [{}, {}] m, radius {} m) is not inside the rock's {} with half an "
                                   "element ({} m) to spare", names[k], c.center[0], c.center[1], c.radius, s.shape,
                                   0.5 * h));
    for (std::size_t l = 0; l < k; ++l) {
      const fdem::Circle& o = s.holes[l];
      const double d = std::hypot(c.center[0] - o.center[0], c.center[1] - o.center[1]);
      if (d < c.radius + o.radius + 0.5 * h)
        throw InputError(fmt::format("{}: its hole overlaps that of {} (centres {} m apart, radii {} and {} m; at least half "
                                     "an element, {} m, of rock must lie between them)", names[k], names[l], d, c.radius,
                                     o.radius, 0.5 * h));
    }
  }
}

void read_analysis_section(TableReader& root, RockCaseConfig& c) {
  TableReader a = root.table("analysis");
  AnalysisSpec& s = c.analysis;
  s.fragments = a.boolean("fragments", true);
  s.min_fragment_triangles =
      static_cast<int>(a.integer("min_fragment_triangles", "", 1, fdem::kDefaultMinFragmentTriangles, 1000000));
  s.oversize = a.number("oversize", "m", Range::positive(), 0.5);
  s.ring_width = a.number("damage_ring_width", "m", Range::non_negative(), 0.0);
  s.crushed_fraction = a.number("crushed_fraction", "", Range{0.0, 1.0, true, false}, 0.5);
  for (TableReader& h : a.table_array("hole")) {
    s.holes_given = true;
    DamageHole d;
    d.center = h.pair("center", "m");
    d.radius = h.number("radius", "m", Range::positive());
    d.behind = h.pair("behind", "", std::array<double, 2>{0.0, 0.0});
    h.finish();
    s.holes.push_back(d);
  }
  a.finish();
  const RockMeshSpec& m = c.mesh;
  if (s.holes.empty() && (m.shape == "disc_with_hole" || m.shape == "rectangle_with_hole"))
    s.holes.push_back({m.center, m.hole_radius});
  if (!s.holes_given)
    for (const fdem::Circle& h : m.holes) s.holes.push_back({h.center, h.radius});
}

void read_rock_probes(TableReader& probe, RockCaseConfig& c) {
  std::vector<std::string> names;
  for (TableReader& p : probe.table_array("rock_point")) {
    RockProbe q;
    q.name = p.text("name", {});
    q.position = p.pair("position", "m");
    if (p.has("until")) q.until = p.number("until", "s", Range::positive());
    p.finish();
    check_output_name("probe.rock_point", q.name);
    names.push_back(q.name);
    c.probes.push_back(q);
  }
  check_unique_names("probe.rock_point", names);
}

void read_charges(TableReader& root, CoupledCaseConfig& c) {
  std::vector<fdem::Circle> holes;
  std::vector<std::string> names;
  const cip::GasGrid& g = c.gas.grid;
  for (TableReader& t : root.table_array("charge")) {
    const std::string key = t.path();
    if (!c.gas.explosive)
      throw InputError(fmt::format("{}: a charge needs the explosive: give [gas.explosive] (a preset or JWL parameters)",
                                   key));
    ibm::Charge q;
    q.center = t.pair("center", "m");
    q.hole_radius = t.number("hole_radius", "m", Range::positive());
    q.radius = t.number("radius", "m", Range::positive(), q.hole_radius);
    if (q.radius > q.hole_radius)
      throw InputError(fmt::format("{}.radius = {} m: the charge is larger than its hole ({}.hole_radius = {} m); a "
                                   "charge must fit its hole (equal: fully coupled; smaller: the gap holds air)",
                                   key, q.radius, key, q.hole_radius));
    q.initiation_time = t.number("initiation_time", "s", Range::non_negative(), 0.0);
    const std::string how = t.text("initiation", {"constant_volume", "point"}, std::string("constant_volume"));
    if (how == "point") {
      q.initiation = ibm::Initiation::point;
      q.point = t.pair("initiation_point", "m", q.center);
      if (std::hypot(q.point[0] - q.center[0], q.point[1] - q.center[1]) > q.radius)
        throw InputError(fmt::format("{}.initiation_point = [{}, {}] m: outside the charge (radius {} m around [{}, {}] m)",
                                     key, q.point[0], q.point[1], q.radius, q.center[0], q.center[1]));
      q.detonation_velocity = c.gas.detonation_velocity;
    } else if (t.has("initiation_point")) {
      throw InputError(fmt::format("{}.initiation_point: only with initiation = \"point\" (this charge detonates at "
                                   "constant volume)", key));
    }
    t.finish();
    if (q.center[0] - q.hole_radius < g.x_min || q.center[0] + q.hole_radius > g.x_min + g.nx * g.dx ||
        q.center[1] - q.hole_radius < g.y_min || q.center[1] + q.hole_radius > g.y_min + g.ny * g.dy)
      throw InputError(fmt::format("{}: its hole (centre [{}, {}] m, radius {} m) leaves the gas domain", key, q.center[0],
                                   q.center[1], q.hole_radius));
    if (q.radius < 0.5 * std::min(g.dx, g.dy))
      throw InputError(fmt::format("{}.radius = {} m: below half a gas cell ({} m); the grid cannot hold the charge",
                                   key, q.radius, 0.5 * std::min(g.dx, g.dy)));
    c.charges.push_back(q);
    holes.push_back({q.center, q.hole_radius});
    names.push_back(key);
  }
  RockMeshSpec& mesh = c.rock.mesh;
  for (std::size_t k = 0; k < mesh.holes.size(); ++k) names.push_back(fmt::format("rock.mesh.hole.{}", k));
  if (c.charges.empty()) {
    check_mesh_holes(mesh, names);
    return;
  }
  if (!mesh.has_holes() && mesh.shape != "file")
    throw InputError(fmt::format("charge.0: the rock needs holes for its charges: use rock.mesh.shape = "
                                 "\"rectangle_with_holes\" or \"disc_with_holes\" (the charges' holes are cut from it), "
                                 "or a mesh file with the holes (this mesh is \"{}\")", mesh.shape));
  if (c.gas.solver.transport != cip::Transport::conservative)
    throw InputError("gas.transport = \"paper\": the paper's transport carries one gas; charges (their detonation "
                     "products) need \"conservative\"");
  c.gas.charges = true;
  c.charge_products = {c.gas.explosive->jwl.rho0, c.gas.detonation_energy};
  mesh.holes.insert(mesh.holes.begin(), holes.begin(), holes.end());
  check_mesh_holes(mesh, names);
  if (!c.rock.analysis.holes_given) {  // the damage zone around every hole, the charges' first
    std::vector<DamageHole> all;
    for (const fdem::Circle& h : holes) all.push_back({h.center, h.radius});
    all.insert(all.end(), c.rock.analysis.holes.begin(), c.rock.analysis.holes.end());
    c.rock.analysis.holes = all;
  }
}

RockCaseConfig read_rock_case(const toml::table& input) {
  RockCaseConfig c;
  TableReader root(input, "", c.echo);
  read_rock_section(root, c);
  std::vector<std::string> hole_names;
  for (std::size_t k = 0; k < c.mesh.holes.size(); ++k) hole_names.push_back(fmt::format("rock.mesh.hole.{}", k));
  check_mesh_holes(c.mesh, hole_names);

  const TimeKeys time = read_time_keys(root, CaseKind::rock);
  c.end_time = time.end;
  c.fixed_dt = time.dt;
  c.max_steps = time.max_steps;
  c.step_fraction = time.step_fraction;

  TableReader out = root.table("output");
  assign_output_basics(read_output_basics(out, 10), c);
  out.finish();
  check_interval("output.interval", c.output_interval, c.end_time, true);
  TableReader probe = root.table("probe");
  read_rock_probes(probe, c);
  probe.finish();
  root.finish();
  return c;
}

CoupledCaseConfig read_coupled_case(const toml::table& input) {
  CoupledCaseConfig c;
  TableReader root(input, "", c.echo);
  read_gas_sections(root, c.gas, &c.rock);
  read_rock_section(root, c.rock);
  if (!c.rock.pressures.empty())
    throw InputError("rock.pressure: a coupled case loads the rock with the gas only; remove the [[rock.pressure]] "
                     "tables (or run the rock alone)");
  if (c.rock.pressure_ramp_time > 0)
    throw InputError("rock.pressure_ramp_time: not used in a coupled case (the gas loads the rock); remove it");
  read_charges(root, c);

  const TimeKeys time = read_time_keys(root, CaseKind::coupled);
  c.gas.end_time = c.rock.end_time = time.end;
  c.gas.fixed_dt = c.rock.fixed_dt = time.dt;
  c.rock.step_fraction = time.step_fraction;
  c.gas.max_steps = c.rock.max_steps = time.max_steps;
  c.rock_subcycling = time.rock_subcycling;
  if (c.rock_subcycling) c.rock.fixed_dt.reset();  // time.dt is the gas step; the rock divides it (docs/coupling.md)

  TableReader out = root.table("output");
  const OutputBasics basics = read_output_basics(out, 10);
  assign_output_basics(basics, c.gas);
  assign_output_basics(basics, c.rock);
  c.gas.drift_warning = out.number("drift_warning", "", Range::positive(), 0.01);
  c.checkpoint = out.boolean("checkpoint", true);
  out.finish();

  TableReader monitor = root.table("monitor");
  if (monitor.has("interval"))
    throw InputError("monitor.interval: moved to monitor.blasthole.interval [s]; the blasthole monitor (wall_series.csv, "
                     "summary.txt) now runs when the input has a [monitor.blasthole] table with center, hole_radius, "
                     "outer_radius and interval (docs/input.md)");
  if (monitor.has("blasthole")) {
    TableReader b = monitor.table("blasthole");
    CoupledCaseConfig::Blasthole spec;
    spec.geometry.center = b.pair("center", "m");
    spec.geometry.hole_radius = b.number("hole_radius", "m", Range::positive());
    spec.geometry.outer_radius = b.number("outer_radius", "m", Range::positive());
    if (!(spec.geometry.outer_radius > spec.geometry.hole_radius))
      throw InputError(fmt::format("monitor.blasthole.outer_radius = {} m: must exceed monitor.blasthole.hole_radius = {} m",
                                   spec.geometry.outer_radius, spec.geometry.hole_radius));
    spec.interval = b.number("interval", "s", Range::positive(), 1e-6);
    b.finish();
    c.blasthole = spec;
  }
  for (TableReader& r : monitor.table_array("region")) {
    MonitorRegion m;
    m.name = r.text("name", {});
    const std::string shape = r.text("shape", {"box", "circle"});
    if (shape == "circle") {
      const std::array<double, 2> centre = r.pair("center", "m");
      m.region = cip::CellRegion::circle(centre[0], centre[1], r.number("radius", "m", Range::positive()));
    } else {
      const std::array<double, 2> lo = r.pair("min", "m"), hi = r.pair("max", "m");
      if (!(hi[0] > lo[0]) || !(hi[1] > lo[1])) throw InputError(fmt::format("{}: box needs max > min in x and y", r.path()));
      m.region = cip::CellRegion::box(lo[0], lo[1], hi[0], hi[1]);
    }
    r.finish();
    check_output_name("monitor.region", m.name);
    c.regions.push_back(m);
  }
  monitor.finish();
  TableReader coupling = root.table("coupling");
  c.gas_load = coupling.text("gas_load", {"edges", "faces"}, std::string("edges")) == "faces" ? ibm::GasLoad::face_forces
                                                                                              : ibm::GasLoad::edge_pressures;
  coupling.finish();
  TableReader crack = root.table("crack_gas");
  c.crack_gas = crack.boolean("enabled", false);
  ibm::CrackGasOptions& o = c.crack_gas_options;
  o.residual_aperture = crack.number("residual_aperture", "m", Range::positive(), o.residual_aperture);
  o.friction_factor = crack.number("friction_factor", "", Range::non_negative(), o.friction_factor);
  o.viscosity = crack.number("viscosity", "Pa s", Range::non_negative(), o.viscosity);
  o.courant = crack.number("courant", "", Range::half_open(0, 1), o.courant);
  o.second_order = crack.boolean("second_order", o.second_order);
  crack.finish();
  std::vector<std::string> region_names;
  for (const MonitorRegion& m : c.regions) region_names.push_back(m.name);
  check_unique_names("monitor.region", region_names);
  check_gas_intervals(c.gas);
  if (c.blasthole) check_interval("monitor.blasthole.interval", c.blasthole->interval, c.gas.end_time, false);
  root.finish();
  return c;
}

}  // namespace blastsim::app
