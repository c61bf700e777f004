//! \file rock_run.cpp
//! \brief The rock-only time loop of the driver and its outputs (VTU series, energy series, progress).
#include "rock_run.hpp"

#include "blastsim/core/error.hpp"
#include "rock_outputs.hpp"

#include <fmt/format.h>
#include <fmt/ostream.h>

#include <chrono>
#include <cmath>
#include <ostream>

namespace blastsim::app {

namespace {
double half_cosine_ramp(double t, double T) { return T <= 0 || t >= T ? 1.0 : 0.5 * (1.0 - std::cos(M_PI * t / T)); }
}  // namespace

void run_rock_case(const RockCaseConfig& c, std::ostream& log, const RunOptions& options) {
  RockModel model = make_rock_model(c);
  fdem::RockSolver& solver = *model.solver;
  const double dt = rock_time_step(c, solver);
  log << fmt::format("rock: {} triangles, {} joints, {} boundary edges; stable step {:.4g} s, dt {:.4g} s, {} steps\n",
                     solver.triangle_count(), solver.joint_count(), model.topology.boundary_edges.size(), solver.stable_dt(), dt,
                     static_cast<long long>(std::ceil(c.end_time / dt)));

  RockOutputs out(c, model);
  out.snapshot();
  out.monitor();
  double next_snapshot = c.output_interval > 0 ? c.output_interval : c.end_time;
  size_t next_time = 0;  // output.times: snapshots at the first step at or after each (the rock's dt is fixed)
  const auto start = std::chrono::steady_clock::now();
  auto last_progress = start;
  const double tol = 1e-9 * c.end_time;
  while (solver.time() < c.end_time - tol) {
    const double step = std::min(dt, c.end_time - solver.time());
    if (c.pressure_ramp_time > 0) solver.set_pressure_scale(half_cosine_ramp(solver.time(), c.pressure_ramp_time));
    solver.step(step);
    if (solver.steps() % c.monitor_interval == 0) out.monitor();
    const bool listed = next_time < c.output_times.size() && solver.time() >= c.output_times[next_time] - tol;
    if ((solver.time() >= next_snapshot - tol || listed) && solver.time() < c.end_time - tol) {
      out.snapshot();
      while (c.output_interval > 0 && next_snapshot <= solver.time() + tol) next_snapshot += c.output_interval;
      while (next_time < c.output_times.size() && c.output_times[next_time] <= solver.time() + tol) ++next_time;
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
  const fdem::RockEnergies e = out.monitor();
  out.snapshot();
  log << fmt::format("rock: {} steps to t = {:.4e} s; {} joints broken, crack length {:.4f} m, fracture energy "
                     "{:.4e} J/m\n", solver.steps(), solver.time(), e.broken_joints, e.crack_length,
                     e.fracture_dissipated);
}

}  // namespace blastsim::app
