//! \file run_loop.hpp
//! \brief The driver's one time loop, for gas, rock and coupled cases alike: a Stepper (the solvers: the next
//! stable dt, one step) and RunOutputs (what the run writes, and the times it must land on); the three kinds of
//! run (gas_run.cpp, rock_run.cpp, coupled_run.cpp). Host code only.
#pragma once

#include <filesystem>
#include <iosfwd>
#include <string>

namespace blastsim::cip {
class GasSolver;
}

namespace blastsim::app {

struct Case;

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

//! The gas's signal rate `rate` [1/s] for the next dt; an invalid state (+inf) stops the run with
//! InstabilityError naming the quantity, step and place, before that state is written anywhere.
double checked_signal_rate(const cip::GasSolver& solver, const std::string& output_directory, double rate);
//! InputError when a fixed dt [s] violates the Courant limit at the gas's signal rate [1/s].
void check_fixed_dt_courant(double dt, double rate, double courant, const cip::GasSolver& solver);

//! Creates the output folder (output.directory); returns its path. OutputError naming the key when it cannot.
std::filesystem::path make_output_dir(const std::string& directory);

//! Runs a case of each kind (the outputs in its output folder, progress and notes in `log`).
void run_gas_case(const Case& c, std::ostream& log, const RunOptions& options = {});
void run_rock_case(const Case& c, std::ostream& log, const RunOptions& options = {});
//! A coupled case; with options.restart, from output.directory/checkpoint.bin.
void run_coupled_case(const Case& c, std::ostream& log, const RunOptions& options = {});

}  // namespace blastsim::app
