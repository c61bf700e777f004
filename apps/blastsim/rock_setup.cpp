//! \file rock_setup.cpp
//! \brief The rock of a case before its run: the model built and checked against the case, and its time step.
#include "rock_setup.hpp"

#include "blastsim/core/error.hpp"
#include "blastsim/fdem/rock_analysis.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <limits>

namespace blastsim::app {

fdem::RockModel make_rock_model(const Case& c, bool restart, std::ostream* log) {
  fdem::RockModelSpec spec = c.rock.model;
  if (restart && spec.in_situ) spec.in_situ->equilibrate = false;
  if (spec.in_situ && log) {
    const double tolerance = spec.in_situ->equilibrium.tolerance;
    spec.in_situ->equilibrium.progress = [log, tolerance](long steps, double ratio) {
      *log << fmt::format("  relaxing: {} steps, kinetic / elastic energy {:.3e} (at rest below {:g} for two P-wave "
                          "crossings)\n", steps, ratio, tolerance)
           << std::flush;
    };
  }
  for (size_t k = 0; k < c.probes.rock_points.size(); ++k) {
    const ProbeSettings::RockPoint& p = c.probes.rock_points[k];
    spec.probes.push_back({fmt::format("probe.rock_point.{}", k), p.position, p.until});
  }
  fdem::RockModel model = fdem::build_rock_model(spec);
  check_against_mesh(c, model.mesh.mesh);
  return model;
}

void check_rock_model(const Case& c, std::ostream& out) {
  const fdem::RockModel model = make_rock_model(c, true);
  out << fmt::format("rock model: {} triangles, {} joints, built and checked (the in-situ relaxation, if any, runs "
                     "with the case)\n", model.solver->triangle_count(), model.solver->joint_count());
}

void check_against_mesh(const Case& c, const fdem::TriangleMesh& mesh) {
  std::array<double, 2> lo{1e308, 1e308}, hi{-1e308, -1e308};
  for (const auto& v : mesh.vertices)
    for (int d = 0; d < 2; ++d) lo[d] = std::min(lo[d], v[d]), hi[d] = std::max(hi[d], v[d]);
  auto in_box = [&](const std::array<double, 2>& p) { return p[0] >= lo[0] && p[0] <= hi[0] && p[1] >= lo[1] && p[1] <= hi[1]; };
  const std::string box = fmt::format("[{:g}, {:g}] x [{:g}, {:g}] m", lo[0], hi[0], lo[1], hi[1]);
  for (size_t k = 0; k < c.analysis.holes.size() && c.analysis.holes_given; ++k)
    if (!in_box(c.analysis.holes[k].center))
      throw InputError(fmt::format("analysis.hole.{}.center = [{:g}, {:g}] m: outside the rock (its mesh spans {})", k,
                                   c.analysis.holes[k].center[0], c.analysis.holes[k].center[1], box));
  const double extent = std::max(hi[0] - lo[0], hi[1] - lo[1]);
  if (c.analysis.ring_width > extent)
    throw InputError(fmt::format("analysis.damage_ring_width = {:g} m: wider than the rock ({:g} m across, {})",
                                 c.analysis.ring_width, extent, box));
  // A charge fills a hole of the mesh: no rock within half its hole's radius of its centre (a polygon of three or
  // more sides inscribed in the hole's circle keeps at least that much clear), and rock within 1.5 radii around it.
  for (size_t k = 0; k < c.coupling.charges.size(); ++k) {
    const ibm::Charge& q = c.coupling.charges[k];
    auto vec = [](const std::array<double, 2>& p) { return fdem::Vec2{p[0], p[1]}; };
    double nearest = std::numeric_limits<double>::infinity();
    for (const std::array<int, 3>& t : mesh.triangles)
      nearest = std::min(nearest, fdem::distance_to_triangle(vec(q.center), vec(mesh.vertices[t[0]]),
                                                             vec(mesh.vertices[t[1]]), vec(mesh.vertices[t[2]])));
    if (nearest < 0.5 * q.hole_radius)
      throw InputError(fmt::format("charge.{}: no hole in the rock's mesh at its centre [{:g}, {:g}] m (rock lies {:g} m "
                                   "from it, within half of charge.{}.hole_radius = {:g} m); a charge fills a hole of "
                                   "the mesh", k, q.center[0], q.center[1], nearest, k, q.hole_radius));
    if (!(nearest <= 1.5 * q.hole_radius))
      throw InputError(fmt::format("charge.{}: no rock around its hole (centre [{:g}, {:g}] m, hole_radius {:g} m; the "
                                   "nearest rock lies {:g} m away); a charge fills a hole of the rock's mesh", k,
                                   q.center[0], q.center[1], q.hole_radius, nearest));
  }
}

double rock_time_step(const Case& c, const fdem::RockSolver& solver) {
  const bool fixed = c.time.dt && !(c.kind == CaseKind::coupled && c.time.rock_subcycling);
  if (!fixed) return c.time.step_fraction * solver.stable_dt();
  if (*c.time.dt > solver.stable_dt())
    throw InputError(fmt::format("time.dt = {} s exceeds the rock's stable step {:.4g} s for this mesh and these "
                                 "penalties: give time.dt <= {:.4g} s or leave it out", *c.time.dt, solver.stable_dt(),
                                 solver.stable_dt()));
  return *c.time.dt;
}


std::string joint_sets_line(const Case& c, const fdem::RockModel& model) {
  const std::vector<fdem::JointSetSpec>& sets = c.rock.model.joint_sets;
  if (sets.empty()) return "";
  std::string line = "joint sets:";
  for (std::size_t k = 0; k < sets.size(); ++k)
    line += fmt::format("{} {} {} joints ({})", k ? ";" : "", sets[k].label, model.set_joints[k].size(),
                        sets[k].open ? std::string("open: broken at the start")
                                     : fmt::format("closed: f_t {:g} Pa, c {:g} Pa", sets[k].properties.tensile_strength,
                                                   sets[k].properties.cohesion));
  return line + "\n";
}

std::string in_situ_line(const Case& c, const fdem::RockModel& model) {
  if (!c.rock.model.in_situ) return "";
  const fdem::InSituSpec& is = *c.rock.model.in_situ;
  const fdem::InSituStress& s = is.stress;
  std::string held;
  for (const std::string& b : is.held_boundaries) held += (held.empty() ? "" : ", ") + b;
  std::string line = fmt::format("in-situ stress: sigma_xx {:g}, sigma_yy {:g}, tau_xy {:g} Pa at y = {:g} m (per metre up: "
                                 "{:g}, {:g}, {:g} Pa/m), held on {}",
                                 s.at_reference[0], s.at_reference[1], s.at_reference[2], s.reference_y, s.gradient[0],
                                 s.gradient[1], s.gradient[2], held);
  if (const auto& e = model.equilibrium)
    line += fmt::format("; at rest after {} relaxation steps ({} undamped checks, kinetic / elastic energy at most {:.2e} "
                        "over the last), elastic energy {:.6g} J/m, {} joints broken",
                        e->steps, e->checks, e->kinetic_ratio, e->elastic_energy, e->broken_joints);
  else if (is.equilibrate)
    line += " (equilibrium state from the checkpoint)";
  else
    line += " (not equilibrated: equilibrate = false)";
  return line + "\n";
}

}  // namespace blastsim::app
