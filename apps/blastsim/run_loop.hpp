//! \file run_loop.hpp
//! \brief The driver's one time loop, for gas, rock and coupled cases alike: a Stepper (the solvers: the next
//! stable dt, one step) and RunOutputs (what the run writes, and the times it must land on). Host code only.
#pragma once

#include <iosfwd>
#include <string>

namespace blastsim::app {

struct RunOptions {
  bool quiet = false;    //!< no progress lines
  bool restart = false;  //!< continue from the output folder's checkpoint.bin (coupled cases)
};

//! What the loop advances. The stepper chooses and checks its dt (the solvers know their limits).
class Stepper {
 public:
  virtual ~Stepper() = default;
  virtual double time() const = 0;      //!< [s]
  virtual long long steps() const = 0;
  //! dt [s] of the next step from time() toward `until` [s] (the next output event): a stepper whose dt
  //! follows the solution lands on `until`; a fixed-step one only on the end time.
  virtual double next_dt(double until) = 0;
  virtual void step(double dt) = 0;
  //! Relative tolerance of "the end time is reached": t >= end (1 - tolerance).
  virtual double end_tolerance() const { return 1e-12; }
  //! Extra text for the progress line (cracks, substeps).
  virtual std::string progress_note() const { return ""; }
};

//! What the run writes.
class RunOutputs {
 public:
  virtual ~RunOutputs() = default;
  //! Earliest pending output event after t [s] (the end time when none).
  virtual double next_event(double t) const = 0;
  //! After each step of dt [s]; `last`: the end time is reached.
  virtual void after_step(double dt, bool last) = 0;
  //! Once after the loop (also after a time.max_steps stop).
  virtual void finish() = 0;
};

//! Time controls the loop reads once from the case.
struct RunControl {
  double end_time = 0;           //!< [s]
  long long max_steps = 0;       //!< 0: no limit
  double progress_interval = 2;  //!< [s of wall time] between progress lines
};

//! Steps until the end time (or time.max_steps), calling outputs.after_step() after each step and printing
//! a progress line every progress_interval seconds of wall time and at the end (unless options.quiet).
void run_loop(Stepper& stepper, RunOutputs& outputs, const RunControl& control, std::ostream& log,
              const RunOptions& options);

//! One progress line: step, time, dt, fraction done, elapsed and estimated remaining wall time, `extra`.
std::string progress_line(long long step, double t, double dt, double end, double elapsed, const std::string& extra);

}  // namespace blastsim::app
