//! \file rock_run.cpp
//! \brief A rock-only case of the driver: the rock stepper (fixed dt, load ramp) and its outputs (VTU series,
//! rock_series.csv) in the run loop.
#include "rock_run.hpp"

#include "blastsim/core/error.hpp"
#include "blastsim/fdem/rock_analysis.hpp"
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
  RockStepper(const RockCaseConfig& c, fdem::RockSolver& solver, double dt) : c_(c), solver_(solver), dt_(dt) {}
  double time() const override { return solver_.time(); }
  long long steps() const override { return solver_.steps(); }
  double next_dt(double) override { return std::min(dt_, c_.end_time - solver_.time()); }
  void step(double dt) override {
    if (c_.pressure_ramp_time > 0) solver_.set_pressure_scale(fdem::half_cosine_ramp(solver_.time(), c_.pressure_ramp_time));
    solver_.step(dt);
  }
  double end_tolerance() const override { return 1e-9; }  // fixed steps land on the end within rounding
  std::string progress_note() const override {
    const fdem::RockEnergies e = solver_.energies();
    return fmt::format("  broken joints {}  kinetic {:.3e} J/m", e.broken_joints, e.kinetic);
  }

 private:
  const RockCaseConfig& c_;
  fdem::RockSolver& solver_;
  double dt_;
};

//! Snapshots at the first step at or after each output time (the rock's dt is fixed), a row of
//! rock_series.csv every output.monitor_interval steps, and both at the end.
class RockRunOutputs : public RunOutputs {
 public:
  RockRunOutputs(const RockCaseConfig& c, fdem::RockSolver& solver, RockOutputs& out, std::ostream& log)
      : c_(c), solver_(solver), out_(out), log_(log),
        next_snapshot_(c.output_interval > 0 ? c.output_interval : c.end_time) {}
  double next_event(double) const override { return c_.end_time; }
  void after_step(double, bool) override {
    const double tol = 1e-9 * c_.end_time;
    if (solver_.steps() % c_.monitor_interval == 0) out_.monitor();
    const bool listed = next_time_ < c_.output_times.size() && solver_.time() >= c_.output_times[next_time_] - tol;
    if ((solver_.time() >= next_snapshot_ - tol || listed) && solver_.time() < c_.end_time - tol) {
      out_.snapshot();
      if (c_.output_interval > 0) advance_schedule(next_snapshot_, c_.output_interval, solver_.time() + tol);
      while (next_time_ < c_.output_times.size() && c_.output_times[next_time_] <= solver_.time() + tol) ++next_time_;
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
  const RockCaseConfig& c_;
  fdem::RockSolver& solver_;
  RockOutputs& out_;
  std::ostream& log_;
  double next_snapshot_;
  size_t next_time_ = 0;  // first of output.times not yet written
};

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
  RockStepper stepper(c, solver, dt);
  RockRunOutputs outputs(c, solver, out, log);
  run_loop(stepper, outputs, RunControl{c.end_time, c.max_steps, c.progress_interval}, log, options);
}

}  // namespace blastsim::app
