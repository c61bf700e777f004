//! \file rock_outputs.cpp
//! \brief Rock model set-up from a case, and the rock's output files (VTU series, energy series).
#include "rock_outputs.hpp"

#include "blastsim/core/error.hpp"
#include "blastsim/fdem/rock_analysis.hpp"
#include "vtk_rock_writer.hpp"

#include <fmt/format.h>

#include <cmath>

namespace blastsim::app {

namespace {

fdem::NamedMesh make_mesh(const RockMeshSpec& s) {
  const double h = s.element_size;
  if (s.shape == "rectangle") return fdem::gmsh_rectangle(s.min[0], s.min[1], s.max[0], s.max[1], h, s.joint_lines);
  if (s.shape == "disc") return fdem::gmsh_disc(s.center[0], s.center[1], s.radius, h, s.joint_lines);
  if (s.mesher == "rings")  // read_mesh allows it for disc_with_hole only
    return fdem::ring_disc_with_hole(s.center[0], s.center[1], s.radius, s.hole_radius, h);
  if (s.shape == "disc_with_hole")
    return fdem::gmsh_disc_with_hole(s.center[0], s.center[1], s.radius, s.hole_radius, h, s.joint_lines);
  if (s.shape == "rectangle_with_hole")
    return fdem::gmsh_rectangle_with_hole(s.min[0], s.min[1], s.max[0], s.max[1], s.center[0], s.center[1],
                                          s.hole_radius, h);
  return fdem::read_gmsh_file(s.file);
}

//! Nodes whose initial position lies in the load's box.
std::vector<int> nodes_in_box(const fdem::FdemTopology& topo, const VelocityLoad& l) {
  std::vector<int> nodes;
  for (size_t n = 0; n < topo.node_positions.size(); ++n) {
    const auto& p = topo.node_positions[n];
    if (p[0] >= l.min[0] && p[0] <= l.max[0] && p[1] >= l.min[1] && p[1] <= l.max[1]) nodes.push_back(static_cast<int>(n));
  }
  return nodes;
}

}  // namespace

RockModel make_rock_model(const RockCaseConfig& c) {
  RockModel m;
  m.mesh = make_mesh(c.mesh);
  m.topology = fdem::build_topology(m.mesh.mesh);
  m.solver = std::make_unique<fdem::RockSolver>(m.topology, c.material, c.options);
  fdem::RockSolver& solver = *m.solver;
  const fdem::FdemTopology& topo = m.topology;
  const fdem::NamedMesh& mesh = m.mesh;
  // Loads. Initial velocities first: prescribed velocities then override them on their nodes.
  if (c.initial_velocity[0] != 0 || c.initial_velocity[1] != 0) {
    std::vector<double> v(2 * solver.node_count());
    for (int n = 0; n < solver.node_count(); ++n) v[2 * n] = c.initial_velocity[0], v[2 * n + 1] = c.initial_velocity[1];
    solver.set_velocities(v);
  }
  for (size_t k = 0; k < c.velocities.size(); ++k) {
    const VelocityLoad& l = c.velocities[k];
    const std::vector<int> nodes = nodes_in_box(topo, l);
    if (nodes.empty())
      throw InputError(fmt::format("rock.velocity.{}: no mesh node lies in the box [{}, {}] x [{}, {}] m", k, l.min[0],
                                   l.max[0], l.min[1], l.max[1]));
    solver.prescribe_velocity(nodes, l.along_x, l.along_y, l.velocity[0], l.velocity[1]);
    m.velocity_nodes.push_back(nodes);
  }
  for (size_t k = 0; k < c.pressures.size(); ++k) {
    const PressureLoad& l = c.pressures[k];
    const auto group = mesh.boundary_groups.find(l.boundary);
    if (group == mesh.boundary_groups.end()) {
      std::string names;
      for (const auto& [name, edges] : mesh.boundary_groups) names += (names.empty() ? "" : ", ") + name;
      throw InputError(fmt::format("rock.pressure.{}.boundary = \"{}\": the mesh has no such boundary group (it has: {})",
                                   k, l.boundary, names));
    }
    solver.set_edge_pressure(fdem::boundary_slots(topo, group->second, l.boundary), l.pressure);
  }
  return m;
}

double rock_time_step(const RockCaseConfig& c, const fdem::RockSolver& solver) {
  double dt = c.step_fraction * solver.stable_dt();
  if (c.fixed_dt) {
    if (*c.fixed_dt > solver.stable_dt())
      throw InputError(fmt::format("time.dt = {} s exceeds the rock's stable step {:.4g} s for this mesh and these "
                                   "penalties: give time.dt <= {:.4g} s or leave it out", *c.fixed_dt,
                                   solver.stable_dt(), solver.stable_dt()));
    dt = *c.fixed_dt;
  }
  return dt;
}

RockOutputs::RockOutputs(const RockCaseConfig& c, const RockModel& model, bool resume)
    : c_(c), solver_(*model.solver), velocity_nodes_(model.velocity_nodes), dir_(make_output_dir(c.output_directory)),
      rock_pvd_((dir_ / "rock.pvd").string()), joints_pvd_((dir_ / "joints.pvd").string()),
      series_((dir_ / "rock_series.csv").string(),
              [&] {
                std::string h = "step,time_s,kinetic_J_per_m,strain_J_per_m,joint_work_J_per_m,"
                                "fracture_dissipated_J_per_m,contact_work_J_per_m,friction_dissipated_J_per_m,"
                                "damping_dissipated_J_per_m,external_work_J_per_m,energy_balance_J_per_m,"
                                "broken_joints,crack_length_m";
                for (size_t k = 0; k < model.velocity_nodes.size(); ++k)
                  h += fmt::format(",velocity{0}_reaction_x_N_per_m,velocity{0}_reaction_y_N_per_m", k);
                return h;
              }(),
              resume),
      e0_(solver_.energies()) {}

void RockOutputs::write_checkpoint(CheckpointWriter& w) {
  w.value("out.rock.index", index_);
  w.value("out.rock.initial", e0_);
  w.value("out.rock.csv_size", series_.size());
  write_pvd_checkpoint(w, "out.rock.pvd", rock_pvd_);
  write_pvd_checkpoint(w, "out.joints.pvd", joints_pvd_);
}

void RockOutputs::read_checkpoint(CheckpointReader& r) {
  index_ = r.value<int>("out.rock.index");
  if (index_ < 0) r.fail("out.rock.index", "negative");
  e0_ = r.value<fdem::RockEnergies>("out.rock.initial");
  series_.truncate_to(r.value<std::uint64_t>("out.rock.csv_size"));
  read_pvd_checkpoint(r, "out.rock.pvd", rock_pvd_);
  read_pvd_checkpoint(r, "out.joints.pvd", joints_pvd_);
}

void RockOutputs::snapshot() {
  if (!c_.vtk) return;
  const fdem::RockSnapshot s = solver_.snapshot();
  const std::string rock_name = fmt::format("rock_{:06d}.vtu", index_);
  const std::string joints_name = fmt::format("joints_{:06d}.vtu", index_++);
  write_rock_vtu((dir_ / rock_name).string(), s);
  write_joints_vtu((dir_ / joints_name).string(), s);
  rock_pvd_.add(solver_.time(), rock_name);
  joints_pvd_.add(solver_.time(), joints_name);
}

fdem::RockEnergies RockOutputs::monitor() {
  const fdem::RockEnergies e = solver_.energies();
  const double balance = fdem::energy_residual(e, e0_);
  std::string reactions;  // of the supports on the loaded nodes: the platen force, with the sign of the axes
  for (const std::array<double, 2>& f : solver_.support_reactions(velocity_nodes_))
    reactions += fmt::format(",{:.9e},{:.9e}", f[0], f[1]);
  series_.row(fmt::format("{},{:.9e},{:.9e},{:.9e},{:.9e},{:.9e},{:.9e},{:.9e},{:.9e},{:.9e},{:.6e},{},{:.6e}",
                         solver_.steps(), solver_.time(), e.kinetic, e.strain, e.joint_work, e.fracture_dissipated,
                         e.contact_work, e.friction_dissipated, e.damping_dissipated, e.external_work, balance,
                         e.broken_joints, e.crack_length) +
              reactions);
  return e;
}

}  // namespace blastsim::app
