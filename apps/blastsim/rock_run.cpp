//! \file rock_run.cpp
//! \brief A rock-only case of the driver: the rock stepper (fixed dt, load ramp) and its outputs (VTU series,
//! rock_series.csv) in the run loop.
#include "blastsim/fdem/rock_analysis.hpp"
#include "gas_outputs.hpp"
#include "rock_outputs.hpp"
#include "run_loop.hpp"

#include <fmt/format.h>
#include <fmt/ostream.h>

#include <algorithm>
#include <cmath>
#include <ostream>

namespace blastsim::app {

namespace {

//! The rock solver in the run loop: a fixed dt (rock_time_step()), shortened only to land on the end time;
//! edge pressures ramped in over rock.pressure_ramp_time.
class RockStepper : public Stepper {
 public:
  RockStepper(const Case& c, fdem::RockSolver& solver, double dt) : c_(c), solver_(solver), dt_(dt) {}
  double time() const override { return solver_.time(); }
  long long steps() const override { return solver_.steps(); }
  double next_dt(double) override { return std::min(dt_, c_.time.end - solver_.time()); }
  void step(double dt) override {
    const double ramp = c_.rock.pressure_ramp_time;
    if (ramp > 0) solver_.set_pressure_scale(fdem::half_cosine_ramp(solver_.time(), ramp));
    solver_.step(dt);
  }
  double end_tolerance() const override { return 1e-9; }  // fixed steps land on the end within rounding
  std::string progress_note() const override {
    const fdem::RockEnergies e = solver_.energies();
    return fmt::format("  broken joints {}  kinetic {:.3e} J/m", e.broken_joints, e.kinetic);
  }

 private:
  const Case& c_;
  fdem::RockSolver& solver_;
  double dt_;
};

//! Snapshots at the first step at or after each output time (the rock's dt is fixed), a row of
//! rock_series.csv every output.monitor_interval steps, and both at the end.
class RockRunOutputs : public RunOutputs {
 public:
  RockRunOutputs(const Case& c, fdem::RockSolver& solver, RockOutputs& out, std::ostream& log)
      : c_(c), solver_(solver), out_(out), log_(log), schedule_{c.output.interval > 0 ? c.output.interval : c.time.end} {}
  double next_event(double) const override { return c_.time.end; }
  void after_step(double, bool) override {
    const double tol = 1e-9 * c_.time.end, t = solver_.time();
    if (solver_.steps() % c_.output.monitor_interval == 0) out_.monitor();
    if (schedule_.due(c_.output, t, tol) && t < c_.time.end - tol) {
      out_.snapshot();
      schedule_.advance(c_.output, t, tol);
    }
  }
  void finish() override {
    const fdem::RockEnergies e = out_.monitor();
    out_.snapshot();
    out_.write_summary();
    log_ << fmt::format("rock: {} steps to t = {:.4e} s; {} joints broken, crack length {:.4f} m, fracture energy "
                        "{:.4e} J/m\n", solver_.steps(), solver_.time(), e.broken_joints, e.crack_length,
                        e.fracture_dissipated);
    log_ << out_.cost_note();
  }

 private:
  const Case& c_;
  fdem::RockSolver& solver_;
  RockOutputs& out_;
  std::ostream& log_;
  SnapshotSchedule schedule_;
};

}  // namespace

void run_rock_case(const Case& c, std::ostream& log, const RunOptions& options) {
  if (c.rock.model.in_situ && c.rock.model.in_situ->equilibrate)
    log << fmt::format("in-situ stress: relaxing the rock to rest before t = 0 (at most {} steps)\n",
                       c.rock.model.in_situ->equilibrium.max_steps)
        << std::flush;
  fdem::RockModel model = make_rock_model(c, false, &log);
  fdem::RockSolver& solver = *model.solver;
  const double dt = rock_time_step(c, solver);
  log << fmt::format("rock: {} triangles, {} joints, {} boundary edges; stable step {:.4g} s, dt {:.4g} s, {} steps\n",
                     solver.triangle_count(), solver.joint_count(), model.topology.boundary_edges.size(), solver.stable_dt(), dt,
                     static_cast<long long>(std::ceil(c.time.end / dt)));
  log << joint_sets_line(c, model);
  log << in_situ_line(c, model);
  RockOutputs out(c, model);
  out.snapshot();
  out.monitor();
  RockStepper stepper(c, solver, dt);
  RockRunOutputs outputs(c, solver, out, log);
  run_loop(stepper, outputs, RunControl{c.time.end, c.time.max_steps, c.output.progress_interval}, log, options);
}

}  // namespace blastsim::app
