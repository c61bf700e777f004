//! \file input_rock.cpp
//! \brief [rock]: the rock's material, options, mesh and loads (docs/input.md), into an fdem::RockModelSpec.
#include "blastsim/core/error.hpp"
#include "case.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace blastsim::app {

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

fdem::MeshSpec read_mesh(TableReader& t) {
  using fdem::MeshShape;
  fdem::MeshSpec s;
  s.label = "rock.mesh";
  const std::vector<std::string> shapes{"rectangle", "disc", "disc_with_hole", "rectangle_with_hole",
                                        "rectangle_with_holes", "disc_with_holes", "file"};
  const std::string shape = t.text("shape", shapes);
  s.shape = static_cast<MeshShape>(std::find(shapes.begin(), shapes.end(), shape) - shapes.begin());
  s.jitter = t.number("jitter", "", Range{0.0, 0.25, false, false}, 0.0);
  s.seed = t.integer("seed", "", 0, 1);
  // Read only when given: a case without it resolves (and checkpoints) as before the key existed.
  if (t.has("rotation")) {
    s.rotation = t.number("rotation", "deg", Range{-360.0, 360.0, false, false}) * M_PI / 180;
    t.same_as_absent("rotation", s.rotation == 0);
  }
  if (s.shape == MeshShape::file) {
    if (t.has("realisation"))
      throw InputError(t.key_path("realisation") + ": picks one of Gmsh's meshes of a built shape; a mesh file is "
                       "meshed already (remove the key, or give a shape)");
    s.file = t.text("file", {});
    return s;
  }
  s.element_size = t.number("element_size", "m", Range::positive());
  s.ring_mesher = t.text("mesher", {"gmsh", "rings"}, std::string("gmsh")) == "rings";
  if (s.ring_mesher && s.shape != MeshShape::disc_with_hole)
    throw InputError(fmt::format("{}.mesher = \"rings\" meshes only shape = \"disc_with_hole\" (this mesh is \"{}\"): use "
                                 "mesher = \"gmsh\"", t.path(), shape));
  if (t.has("growth") && !s.ring_mesher)
    throw InputError(t.key_path("growth") + ": the ring mesher's grading; only with mesher = \"rings\"");
  if (t.has("algorithm") && s.ring_mesher)
    throw InputError(t.key_path("algorithm") + ": Gmsh's meshing algorithm; only with mesher = \"gmsh\"");
  if (t.has("realisation") && s.ring_mesher)
    throw InputError(t.key_path("realisation") + ": picks one of Gmsh's meshes; only with mesher = \"gmsh\" (the ring "
                     "mesher has one mesh per size: use jitter and seed there)");
  // Read only when given: a case without it resolves (and checkpoints) as before the key existed.
  if (t.has("realisation")) {
    s.realisation = static_cast<unsigned>(t.integer("realisation", "", 0, std::nullopt, 1000000));
    t.same_as_absent("realisation", s.realisation == 0);
  }
  if (!s.ring_mesher)
    s.algorithm = t.text("algorithm", {"delaunay", "frontal"}, std::string("delaunay")) == "frontal"
                      ? fdem::GmshAlgorithm::frontal
                      : fdem::GmshAlgorithm::delaunay;
  // Read only when given: a case without it resolves (and checkpoints) as before the key existed.
  if (s.ring_mesher && t.has("growth")) {
    const double absent = s.ring_growth;
    s.ring_growth = t.number("growth", "", Range{1.0, 2.0, false, false});
    t.same_as_absent("growth", s.ring_growth == absent);
  }
  for (TableReader& h : t.table_array("hole")) {
    if (!s.has_holes())
      throw InputError(fmt::format("{}: holes are cut from shape = \"rectangle_with_holes\" or \"disc_with_holes\" "
                                   "(this mesh is \"{}\")", h.path(), shape));
    s.holes.push_back({h.pair("center", "m"), h.number("radius", "m", Range::positive())});
    h.finish();
  }
  if (s.is_rectangle()) {
    s.min = t.pair("min", "m");
    s.max = t.pair("max", "m");
    if (!(s.max[0] > s.min[0]) || !(s.max[1] > s.min[1]))
      throw InputError(fmt::format("{}: max must exceed min in x and y", t.path()));
  } else {
    s.center = t.pair("center", "m", std::array<double, 2>{0.0, 0.0});
    s.radius = t.number("radius", "m", Range::positive());
  }
  if (s.shape == MeshShape::disc_with_hole || s.shape == MeshShape::rectangle_with_hole) {
    if (s.shape == MeshShape::rectangle_with_hole) s.center = t.pair("center", "m");
    s.hole_radius = t.number("hole_radius", "m", Range::positive());
  }
  // Memory before meshing: about 2.3 area / h^2 triangles, each about 2 kB in mesh, topology and solver.
  const double triangles = 2.3 * s.area() / (s.element_size * s.element_size);
  check_memory_need(fmt::format("rock.mesh.element_size = {:g} m on this {} (about {:.3g} triangles)", s.element_size,
                                shape, triangles),
                    triangles * 2048.0);
  for (TableReader& l : t.table_array("joint_line")) {
    s.joint_lines.push_back({l.pair("from", "m"), l.pair("to", "m")});
    l.finish();
  }
  fdem::check_joint_lines(s);
  return s;
}

//! What a [[rock.joint_set]] or [[rock.joint]] is: open (broken from the start, an optional aperture) or closed
//! with its own strength (the material's where a key is absent).
void read_joint_kind(TableReader& t, const fdem::RockMaterial& material, fdem::JointSetSpec& set) {
  set.open = t.boolean("open", false);
  const fdem::JointProperties rock_joints = fdem::joint_properties_of(material);
  if (set.open) {
    set.initial_aperture = t.number("initial_aperture", "m", Range::non_negative(), 0.0);
    for (const char* key : {"tensile_strength", "cohesion", "friction_angle", "fracture_energy_mode1",
                            "fracture_energy_mode2"})
      if (t.has(key))
        throw InputError(t.key_path(key) + ": an open joint has no strength (it starts broken); remove the key or "
                         "set open = false");
    set.properties = rock_joints;
  } else {
    if (t.has("initial_aperture"))
      throw InputError(t.key_path("initial_aperture") + ": only for open joints (open = true)");
    fdem::JointProperties& q = set.properties;
    q.tensile_strength = t.number("tensile_strength", "Pa", Range::positive(), rock_joints.tensile_strength);
    q.cohesion = t.number("cohesion", "Pa", Range::positive(), rock_joints.cohesion);
    q.friction_angle = t.number("friction_angle", "deg", Range{0.0, 90.0, false, true},
                                rock_joints.friction_angle * 180 / M_PI) * M_PI / 180;
    q.fracture_energy_mode1 =
        t.number("fracture_energy_mode1", "J/m2", Range::positive(), rock_joints.fracture_energy_mode1);
    q.fracture_energy_mode2 =
        t.number("fracture_energy_mode2", "J/m2", Range::positive(), rock_joints.fracture_energy_mode2);
  }
}

//! [rock.in_situ_stress]: the stress, the boundaries that hold it, the equilibration (docs/input.md).
void read_in_situ_stress(TableReader t, fdem::RockModelSpec& m) {
  fdem::InSituSpec is;
  is.label = t.path();
  fdem::InSituStress& s = is.stress;
  s.at_reference = {t.number("sigma_xx", "Pa", Range::any(), 0.0), t.number("sigma_yy", "Pa", Range::any(), 0.0),
                    t.number("tau_xy", "Pa", Range::any(), 0.0)};
  s.reference_y = t.number("reference_y", "m", Range::any(), 0.0);
  // Equilibrium under gravity fixes how sigma_yy and tau_xy change with y; sigma_xx may change at any rate.
  const double rho = m.material.density;
  auto weight = [&](double g) { return g == 0 ? 0.0 : -rho * g; };  // no -0 without gravity
  s.gradient = {t.number("gradient_xx", "Pa/m", Range::any(), 0.0), weight(m.options.gravity[1]), weight(m.options.gravity[0])};
  std::vector<std::string> viscous;  // the default: the viscous boundaries hold the stress
  for (const fdem::ViscousBoundary& v : m.viscous_boundaries) viscous.push_back(v.boundary);
  if (t.has("boundaries")) {
    is.held_boundaries = t.text_list("boundaries");
    t.same_as_absent("boundaries", is.held_boundaries == viscous);
  } else {
    is.held_boundaries = viscous;
    t.allow({"boundaries"});
  }
  is.equilibrate = t.boolean("equilibrate", true);
  is.equilibrium.tolerance = t.number("tolerance", "", Range{0.0, 1e-3, true, false}, 1e-8);
  is.equilibrium.max_steps = t.integer("max_steps", "", 1, 200000);
  t.finish();
  if (is.held_boundaries.empty())
    throw InputError(t.key_path("boundaries") + ": no boundary holds the in-situ stress (none given and no "
                     "[[rock.viscous_boundary]] to take them from); name the boundary groups where the model cuts the "
                     "rock mass, e.g. boundaries = [\"outer\"]");
  const bool stressed = s.at_reference[0] != 0 || s.at_reference[1] != 0 || s.at_reference[2] != 0 ||
                        s.gradient[0] != 0 || s.gradient[1] != 0 || s.gradient[2] != 0;
  if (!stressed)
    throw InputError(t.path() + ": every stress and gradient is zero (and rock.gravity is zero): give sigma_xx, "
                     "sigma_yy or tau_xy, or remove the table");
  m.in_situ = is;
}

}  // namespace

void read_rock(TableReader& root, Case& c) {
  fdem::RockModelSpec& m = c.rock.model;
  TableReader rock = root.table("rock", true);
  m.material = read_material(rock);
  m.options.joint_penalty_factor = rock.number("joint_penalty_factor", "", Range::positive(), 10.0);
  m.options.contact_penalty_factor = rock.number("contact_penalty_factor", "", Range::positive(), 10.0);
  m.options.damping_ratio = rock.number("damping_ratio", "", Range{0.0, 1.0, false, true}, 0.0);
  m.options.contact = rock.boolean("contact", true);
  m.options.gravity = rock.pair("gravity", "m/s2", std::array<double, 2>{0.0, 0.0});
  m.initial_velocity = rock.pair("initial_velocity", "m/s", std::array<double, 2>{0.0, 0.0});
  c.rock.pressure_ramp_time = rock.number("pressure_ramp_time", "s", Range::non_negative(), 0.0);
  TableReader mesh = rock.table("mesh", true);
  m.mesh = read_mesh(mesh);
  mesh.finish();
  for (TableReader& v : rock.table_array("velocity")) {
    fdem::VelocityLoad l;
    l.label = v.path();
    l.min = v.pair("min", "m");
    l.max = v.pair("max", "m");
    l.velocity = v.pair("velocity", "m/s");
    const std::string comp = v.text("components", {"x", "y", "xy"}, std::string("xy"));
    l.along_x = comp != "y";
    l.along_y = comp != "x";
    v.finish();
    m.velocities.push_back(l);
  }
  for (TableReader& p : rock.table_array("pressure")) {
    m.pressures.push_back({p.path(), p.text("boundary", {}), p.number("pressure", "Pa", Range::any())});
    p.finish();
  }
  for (TableReader& v : rock.table_array("viscous_boundary")) {
    m.viscous_boundaries.push_back({v.path(), v.text("boundary", {})});
    v.finish();
  }
  for (TableReader& k : rock.table_array("crack")) {
    fdem::PreCutCrack cut{k.path(), {k.pair("from", "m"), k.pair("to", "m")},
                          k.number("initial_aperture", "m", Range::non_negative(), 0.0)};
    if (m.mesh.shape != fdem::MeshShape::file) fdem::check_mesh_segment(m.mesh, cut.segment, cut.label);
    k.finish();
    m.cracks.push_back(cut);
  }
  for (TableReader& t : rock.table_array("joint_set")) {
    fdem::JointSetSpec set;
    set.label = t.path();
    set.angle = t.number("angle", "deg", Range{0.0, 180.0, false, true}) * M_PI / 180;
    set.spacing = t.number("spacing", "m", Range::at_least(m.mesh.element_size));
    set.trace_length = t.number("trace_length", "m", Range::non_negative(), 0.0);
    set.persistence = t.number("persistence", "", Range::half_open(0.0, 1.0), 1.0);
    if (set.persistence < 1 && set.trace_length == 0)
      throw InputError(t.key_path("trace_length") + ": needed when persistence < 1 (the traces' length)");
    if (set.trace_length > 0 && set.trace_length < m.mesh.element_size)
      throw InputError(fmt::format("{} = {:g} m: shorter than rock.mesh.element_size ({:g} m)", t.key_path("trace_length"),
                                   set.trace_length, m.mesh.element_size));
    set.offset = t.number("offset", "m", Range::any(), 0.0);
    set.seed = t.integer("seed", "", 0, 1);
    read_joint_kind(t, m.material, set);
    t.finish();
    if (m.mesh.shape == fdem::MeshShape::file)
      throw InputError(t.path() + ": joint sets need a built mesh shape (a mesh file has its own lines)");
    m.joint_sets.push_back(set);
  }
  for (TableReader& t : rock.table_array("joint")) {
    fdem::JointSetSpec joint;
    joint.label = t.path();
    joint.segments = {{t.pair("from", "m"), t.pair("to", "m")}};
    read_joint_kind(t, m.material, joint);
    t.finish();
    if (m.mesh.shape != fdem::MeshShape::file) fdem::check_mesh_segment(m.mesh, joint.segments[0], joint.label);
    m.joint_sets.push_back(joint);
  }
  const std::vector<std::vector<fdem::Segment>> traces = fdem::joint_sets_traces(m.joint_sets, m.mesh);
  if (m.mesh.shape != fdem::MeshShape::file)  // a mesh file's outline is known once read (fdem::build_rock_model)
    for (std::size_t s = 0; s < traces.size(); ++s)
      for (std::size_t k = 0; k < traces[s].size(); ++k)
        fdem::check_mesh_segment(m.mesh, traces[s][k], fmt::format("{} (trace {})", m.joint_sets[s].label, k));
  if (rock.has("in_situ_stress")) read_in_situ_stress(rock.table("in_situ_stress"), m);
  if (rock.has("heterogeneity")) {
    TableReader h = rock.table("heterogeneity");
    fdem::StrengthHeterogeneity het;
    const std::string dist = h.text("distribution", {"weibull", "lognormal"}, std::string("weibull"));
    if (dist == "weibull") {
      het.distribution = fdem::StrengthDistribution::weibull;
      het.weibull_modulus = h.number("modulus", "", Range{1.0, 1000.0, false, false});
      if (h.has("cov"))
        throw InputError(h.key_path("cov") + ": the log-normal's coefficient of variation; a Weibull distribution "
                         "takes modulus (or set distribution = \"lognormal\")");
    } else {
      het.distribution = fdem::StrengthDistribution::lognormal;
      het.cov = h.number("cov", "", Range{0.0, 2.0, true, false});
      if (h.has("modulus"))
        throw InputError(h.key_path("modulus") + ": the Weibull modulus; a log-normal distribution takes cov (or set "
                         "distribution = \"weibull\")");
    }
    het.seed = static_cast<std::uint64_t>(h.integer("seed", "", 0, 1));
    het.tensile_strength = h.boolean("tensile_strength", true);
    het.cohesion = h.boolean("cohesion", true);
    het.fracture_energy = h.boolean("fracture_energy", true);
    if (h.has("correlation_length")) {  // read only when given: a case without it echoes as before (restart)
      het.correlation_length = h.number("correlation_length", "m", Range::non_negative());
      h.same_as_absent("correlation_length", het.correlation_length == 0);
    }
    h.finish();
    if (!het.tensile_strength && !het.cohesion && !het.fracture_energy)
      throw InputError(h.path() + ": tensile_strength, cohesion and fracture_energy are all false; set one to true "
                       "or remove the table");
    het.validate();
    m.heterogeneity = het;
  }
  rock.finish();
  m.material.validate();
  m.options.validate();
  if (c.kind == CaseKind::coupled && !m.pressures.empty())
    throw InputError("rock.pressure: a coupled case loads the rock with the gas only; remove the [[rock.pressure]] "
                     "tables (or run the rock alone)");
  if (c.kind == CaseKind::coupled && c.rock.pressure_ramp_time > 0)
    throw InputError("rock.pressure_ramp_time: not used in a coupled case (the gas loads the rock); remove it");
}

}  // namespace blastsim::app
