//! \file input_charge.cpp
//! \brief [[charge]]: explosive charges in the rock's holes (coupled cases; docs/input.md, docs/coupling.md
//! "Charges"): their holes go first among the mesh's, and the damage zone is measured around them by default.
#include "blastsim/core/error.hpp"
#include "case.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace blastsim::app {

void read_charges(TableReader& root, Case& c) {
  std::vector<fdem::Circle> holes;
  std::vector<std::string> labels;
  const cip::GasGrid& g = c.gas.grid;
  CouplingSettings& k = c.coupling;
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
    t.allow({"initiation_point"});
    t.finish();
    if (q.center[0] - q.hole_radius < g.x_min || q.center[0] + q.hole_radius > g.x_min + g.nx * g.dx ||
        q.center[1] - q.hole_radius < g.y_min || q.center[1] + q.hole_radius > g.y_min + g.ny * g.dy)
      throw InputError(fmt::format("{}: its hole (centre [{}, {}] m, radius {} m) leaves the gas domain", key, q.center[0],
                                   q.center[1], q.hole_radius));
    if (q.radius < 0.5 * std::min(g.dx, g.dy))
      throw InputError(fmt::format("{}.radius = {} m: below half a gas cell ({} m); the grid cannot hold the charge",
                                   key, q.radius, 0.5 * std::min(g.dx, g.dy)));
    k.charges.push_back(q);
    holes.push_back({q.center, q.hole_radius});
    labels.push_back(key);
  }
  fdem::MeshSpec& mesh = c.rock.model.mesh;
  for (std::size_t h = 0; h < mesh.holes.size(); ++h) labels.push_back(fmt::format("rock.mesh.hole.{}", h));
  if (!k.charges.empty()) {
    if (!mesh.has_holes() && mesh.shape != fdem::MeshShape::file)
      throw InputError(fmt::format("charge.0: the rock needs holes for its charges: use rock.mesh.shape = "
                                   "\"rectangle_with_holes\" or \"disc_with_holes\" (the charges' holes are cut from it), "
                                   "or a mesh file with the holes (this mesh is \"{}\")", fdem::mesh_shape_name(mesh.shape)));
    if (c.gas.solver.transport != cip::Transport::conservative)
      throw InputError("gas.transport = \"paper\": the paper's transport carries one gas; charges (their detonation "
                       "products) need \"conservative\"");
    c.gas.charges = true;
    k.charge_products = {c.gas.explosive->jwl.rho0, c.gas.detonation_energy};
    mesh.holes.insert(mesh.holes.begin(), holes.begin(), holes.end());
    if (!c.analysis.holes_given) {  // the damage zone around every hole, the charges' first
      std::vector<AnalysisSettings::Hole> all;
      for (const fdem::Circle& h : holes) all.push_back({h.center, h.radius});
      all.insert(all.end(), c.analysis.holes.begin(), c.analysis.holes.end());
      c.analysis.holes = all;
    }
  }
  if (mesh.has_holes() && mesh.holes.empty())
    throw InputError(fmt::format("rock.mesh.shape = \"{}\": needs at least one hole ([[rock.mesh.hole]], or the holes of "
                                 "[[charge]])", fdem::mesh_shape_name(mesh.shape)));
  fdem::check_mesh_holes(mesh, labels);
}

}  // namespace blastsim::app
