//! \file run_loop.cpp
//! \brief The driver's time loop and its progress lines.
#include "run_loop.hpp"

#include "blastsim/cip/gas_solver.hpp"
#include "blastsim/core/error.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ostream>

namespace blastsim::app {

namespace {
//! "hh:mm:ss" of a duration in seconds.
std::string hms(double seconds) {
  const long s = static_cast<long>(std::lround(std::max(seconds, 0.0)));
  return fmt::format("{:02d}:{:02d}:{:02d}", s / 3600, (s / 60) % 60, s % 60);
}
}  // namespace

std::string progress_line(long long step, double t, double dt, double end, double elapsed, const std::string& extra) {
  const double frac = t / end;
  return fmt::format("step {:>8}  t = {:.4e} s  dt = {:.3e} s  {:5.1f} %  elapsed {}  left {}{}\n", step, t, dt,
                     100 * frac, hms(elapsed), hms(elapsed * (1 - frac) / frac), extra);
}

double checked_signal_rate(const cip::GasSolver& solver, const std::string& output_directory, double rate) {
  if (!std::isfinite(rate))
    throw InstabilityError(fmt::format("gas state invalid after step {} (t = {:.6e} s): {}; the last good output is in {}",
                                       solver.steps(), solver.time(), solver.describe_invalid_cell(), output_directory));
  return rate;
}

void check_fixed_dt_courant(double dt, double rate, double courant, const cip::GasSolver& solver) {
  if (dt * rate > courant)
    throw InputError(fmt::format("time.dt = {:g} s violates the Courant limit at step {} (t = {:.6e} s): Courant "
                                 "number {:.4g} > gas.courant = {:g}; the largest stable dt now is {:.4g} s",
                                 dt, solver.steps() + 1, solver.time(), dt * rate, courant, courant / rate));
}

std::filesystem::path make_output_dir(const std::string& d) {
  std::error_code ec;
  std::filesystem::create_directories(d, ec);
  if (ec || !std::filesystem::is_directory(d))
    throw OutputError("output.directory = \"" + d + "\": cannot be created (" +
                      (ec ? ec.message() : std::string("a file of that name is in the way")) + ")");
  return d;
}

void run_loop(Stepper& stepper, RunOutputs& outputs, const RunControl& control, std::ostream& log,
              const RunOptions& options) {
  using Clock = std::chrono::steady_clock;
  const auto wall_start = Clock::now();
  auto last_progress = wall_start;
  const double end = control.end_time * (1 - stepper.end_tolerance());
  while (stepper.time() < end) {
    if (control.max_steps > 0 && stepper.steps() >= control.max_steps) {
      log << fmt::format("stopping at time.max_steps = {} (t = {:.6e} s)\n", control.max_steps, stepper.time());
      break;
    }
    const double dt = stepper.next_dt(outputs.next_event(stepper.time()));
    if (!(dt >= 1e-12 * control.end_time))  // also NaN
      throw InstabilityError(fmt::format("the time step collapsed to dt = {:g} s at step {} (t = {:.6e} s), below 1e-12 x "
                                         "time.end: the run could not finish; the last good output is kept",
                                         dt, stepper.steps(), stepper.time()));
    stepper.step(dt);
    const bool last = stepper.time() >= end;
    outputs.after_step(dt, last);
    const auto now = Clock::now();
    if (!options.quiet &&
        (std::chrono::duration<double>(now - last_progress).count() >= control.progress_interval || last)) {
      log << progress_line(stepper.steps(), stepper.time(), dt, control.end_time,
                           std::chrono::duration<double>(now - wall_start).count(), stepper.progress_note())
          << std::flush;
      last_progress = now;
    }
  }
  outputs.finish();
}

}  // namespace blastsim::app
