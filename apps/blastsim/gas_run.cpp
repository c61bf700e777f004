//! \file gas_run.cpp
//! \brief The gas-only time loop of the driver and its outputs (VTK series, CSV probes, totals).
#include "gas_run.hpp"

#include "blastsim/core/error.hpp"
#include "gas_outputs.hpp"

#include <chrono>

namespace blastsim::app {

namespace {
using Clock = std::chrono::steady_clock;
}  // namespace

void run_gas_case(const CaseConfig& c, std::ostream& log, const RunOptions& options) {
  if (c.vtk && !vtk_available())
    throw InputError("output.vtk = true, but this build has no VTK: set output.vtk = false (CSV output still works)");
  cip::GasSolver solver(c.grid, c.eos, c.solver);
  solver.initialise([&](double x, double y) { return c.initial_state(x, y); });
  GasOutputs out(c, solver, log);
  out.write_due(0.0, true);

  const auto wall_start = Clock::now();
  auto last_progress = wall_start;
  double dt = 0.0;
  auto checked_rate = [&] { return checked_signal_rate(solver, c.output_directory); };
  double rate = checked_rate();
  while (solver.time() < c.end_time * (1 - 1e-12)) {
    if (c.max_steps > 0 && solver.steps() >= c.max_steps) {
      log << fmt::format("stopping at time.max_steps = {} (t = {:.6e} s)\n", c.max_steps, solver.time());
      break;
    }
    if (c.fixed_dt) {
      dt = *c.fixed_dt;
      check_fixed_dt_courant(dt, rate, c.courant, solver);
    } else {
      dt = c.courant / rate;
      const double next = out.next_event(solver.time());
      if (solver.time() + dt > next) dt = next - solver.time();
    }
    solver.step(dt);
    rate = checked_rate();
    const bool last = solver.time() >= c.end_time * (1 - 1e-12);
    out.write_due(dt, last);
    const auto now = Clock::now();
    const double since = std::chrono::duration<double>(now - last_progress).count();
    if (!options.quiet && (since >= c.progress_interval || last)) {
      log << progress_line(solver.steps(), solver.time(), dt, c.end_time,
                           std::chrono::duration<double>(now - wall_start).count(), "")
          << std::flush;
      last_progress = now;
    }
  }
}

}  // namespace blastsim::app
