//! \file rock_run.cpp
//! \brief The rock-only time loop of the driver and its outputs (VTU series, energy series, progress).
#include "rock_run.hpp"

#include "blastsim/core/error.hpp"
#include "blastsim/fdem/gmsh_mesh.hpp"
#include "blastsim/fdem/rock_solver.hpp"
#include "output_files.hpp"
#include "vtk_rock_writer.hpp"

#include <fmt/format.h>
#include <fmt/ostream.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <ostream>

namespace blastsim::app {

namespace {

fdem::NamedMesh make_mesh(const RockMeshSpec& s) {
  const double h = s.element_size;
  if (s.shape == "rectangle") return fdem::gmsh_rectangle(s.min[0], s.min[1], s.max[0], s.max[1], h);
  if (s.shape == "disc") return fdem::gmsh_disc(s.center[0], s.center[1], s.radius, h);
  if (s.shape == "disc_with_hole") return fdem::gmsh_disc_with_hole(s.center[0], s.center[1], s.radius, s.hole_radius, h);
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

double half_cosine_ramp(double t, double T) { return T <= 0 || t >= T ? 1.0 : 0.5 * (1.0 - std::cos(M_PI * t / T)); }

}  // namespace

void run_rock_case(const RockCaseConfig& c, std::ostream& log, const RunOptions& options) {
  const fdem::NamedMesh mesh = make_mesh(c.mesh);
  const fdem::FdemTopology topo = fdem::build_topology(mesh.mesh);
  fdem::RockSolver solver(topo, c.material, c.options);
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
  double dt = c.step_fraction * solver.stable_dt();
  if (c.fixed_dt) {
    if (*c.fixed_dt > solver.stable_dt())
      throw InputError(fmt::format("time.dt = {} s exceeds the rock's stable step {:.4g} s for this mesh and these "
                                   "penalties: give time.dt <= {:.4g} s or leave it out", *c.fixed_dt,
                                   solver.stable_dt(), solver.stable_dt()));
    dt = *c.fixed_dt;
  }
  log << fmt::format("rock: {} triangles, {} joints, {} boundary edges; stable step {:.4g} s, dt {:.4g} s, {} steps\n",
                     solver.triangle_count(), solver.joint_count(), topo.boundary_edges.size(), solver.stable_dt(), dt,
                     static_cast<long long>(std::ceil(c.end_time / dt)));

  const std::filesystem::path dir(c.output_directory);
  std::filesystem::create_directories(dir);
  PvdSeries rock_pvd((dir / "rock.pvd").string()), joints_pvd((dir / "joints.pvd").string());
  std::ofstream series(dir / "rock_series.csv", std::ios::trunc);
  series << "step,time_s,kinetic_J_per_m,strain_J_per_m,joint_work_J_per_m,fracture_dissipated_J_per_m,"
            "contact_work_J_per_m,friction_dissipated_J_per_m,damping_dissipated_J_per_m,external_work_J_per_m,"
            "energy_balance_J_per_m,broken_joints,crack_length_m\n";
  int snapshot_index = 0;
  auto snapshot = [&] {
    if (!c.vtk) return;
    const fdem::RockSnapshot s = solver.snapshot();
    const std::string rock_name = fmt::format("rock_{:06d}.vtu", snapshot_index);
    const std::string joints_name = fmt::format("joints_{:06d}.vtu", snapshot_index++);
    write_rock_vtu((dir / rock_name).string(), s);
    write_joints_vtu((dir / joints_name).string(), s);
    rock_pvd.add(solver.time(), rock_name);
    joints_pvd.add(solver.time(), joints_name);
  };
  const fdem::RockEnergies e0 = solver.energies();
  auto monitor = [&] {
    const fdem::RockEnergies e = solver.energies();
    const double balance = e.kinetic + e.strain + e.joint_work + e.contact_work + e.damping_dissipated -
                           (e0.kinetic + e0.strain + e.external_work);
    series << fmt::format("{},{:.9e},{:.9e},{:.9e},{:.9e},{:.9e},{:.9e},{:.9e},{:.9e},{:.9e},{:.6e},{},{:.6e}\n",
                          solver.steps(), solver.time(), e.kinetic, e.strain, e.joint_work, e.fracture_dissipated,
                          e.contact_work, e.friction_dissipated, e.damping_dissipated, e.external_work, balance,
                          e.broken_joints, e.crack_length);
    return e;
  };
  snapshot();
  monitor();
  double next_snapshot = c.output_interval > 0 ? c.output_interval : c.end_time;
  const auto start = std::chrono::steady_clock::now();
  auto last_progress = start;
  const double tol = 1e-9 * c.end_time;
  while (solver.time() < c.end_time - tol) {
    const double step = std::min(dt, c.end_time - solver.time());
    if (c.pressure_ramp_time > 0) solver.set_pressure_scale(half_cosine_ramp(solver.time(), c.pressure_ramp_time));
    solver.step(step);
    if (solver.steps() % c.monitor_interval == 0) monitor();
    if (solver.time() >= next_snapshot - tol && solver.time() < c.end_time - tol) {
      snapshot();
      while (next_snapshot <= solver.time() + tol) next_snapshot += c.output_interval;
    }
    const auto now = std::chrono::steady_clock::now();
    if (!options.quiet && std::chrono::duration<double>(now - last_progress).count() >= c.progress_interval) {
      last_progress = now;
      const fdem::RockEnergies e = solver.energies();
      const double wall = std::chrono::duration<double>(now - start).count();
      log << fmt::format("  t = {:.4e} s ({:5.1f} %), step {}, broken joints {}, kinetic {:.3e} J/m, wall {:.1f} s\n",
                         solver.time(), 100 * solver.time() / c.end_time, solver.steps(), e.broken_joints, e.kinetic,
                         wall);
      log.flush();
    }
  }
  const fdem::RockEnergies e = monitor();
  snapshot();
  series.flush();
  log << fmt::format("rock: {} steps to t = {:.4e} s; {} joints broken, crack length {:.4f} m, fracture energy "
                     "{:.4e} J/m\n", solver.steps(), solver.time(), e.broken_joints, e.crack_length,
                     e.fracture_dissipated);
}

}  // namespace blastsim::app
