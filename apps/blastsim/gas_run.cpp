//! \file gas_run.cpp
//! \brief A gas-only case of the driver: the gas stepper (Courant dt, stability guard) and its outputs (VTK
//! series, CSV probes, totals) in the run loop.
#include "blastsim/core/error.hpp"
#include "gas_outputs.hpp"
#include "run_loop.hpp"
#include "blastsim/cip/vtk_writer.hpp"

namespace blastsim::app {

namespace {

//! The gas solver in the run loop: dt from the Courant number (or time.dt, checked against it), landing on
//! output events; every new state checked before anything writes it.
class GasStepper : public Stepper {
 public:
  GasStepper(const Case& c, cip::GasSolver& solver)
      : c_(c), solver_(solver), rate_(checked_signal_rate(solver, c.output.directory, solver.max_signal_rate())) {}
  double time() const override { return solver_.time(); }
  long long steps() const override { return solver_.steps(); }
  double next_dt(double until) override {
    if (c_.time.dt) {
      check_fixed_dt_courant(*c_.time.dt, rate_, c_.gas.courant, solver_);
      return *c_.time.dt;
    }
    double dt = c_.gas.courant / rate_;
    if (solver_.time() + dt > until) dt = until - solver_.time();
    return dt;
  }
  void step(double dt) override {
    solver_.step(dt);
    rate_ = checked_signal_rate(solver_, c_.output.directory, solver_.max_signal_rate());
  }

 private:
  const Case& c_;
  cip::GasSolver& solver_;
  double rate_;  // signal rate [1/s] of the current state
};

class GasRunOutputs : public RunOutputs {
 public:
  explicit GasRunOutputs(GasOutputs& out) : out_(out) {}
  double next_event(double t) const override { return out_.next_event(t); }
  void after_step(double dt, bool last) override {
    const bool snapshot = out_.write_due(dt, false);
    if (last) out_.write_end(dt, snapshot);
  }
  void finish() override {}

 private:
  GasOutputs& out_;
};

}  // namespace

void run_gas_case(const Case& c, std::ostream& log, const RunOptions& options) {
  if (c.output.vtk && !cip::vtk_available())
    throw InputError("output.vtk = true, but this build has no VTK: set output.vtk = false (CSV output still works)");
  cip::GasSolver solver(c.gas.grid, c.gas.materials(), c.gas.solver);
  solver.initialise([&](double x, double y) { return c.gas.initial_state(x, y); });
  GasOutputs out(c, solver, log);
  out.write_due(0.0, true);
  GasStepper stepper(c, solver);
  GasRunOutputs outputs(out);
  run_loop(stepper, outputs, RunControl{c.time.end, c.time.max_steps, c.output.progress_interval}, log, options);
}

}  // namespace blastsim::app
