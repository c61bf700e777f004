//! \file coupled_run.cpp
//! \brief The coupled gas-rock time loop of the driver (libibm's GasRockCoupler) and its outputs: the gas's
//! and the rock's files, and coupling_series.csv with the energy budget of the whole system.
#include "coupled_run.hpp"

#include "blastsim/core/error.hpp"
#include "blastsim/ibm/coupler.hpp"
#include "gas_outputs.hpp"
#include "rock_outputs.hpp"

#include <chrono>

namespace blastsim::app {

namespace {

using Clock = std::chrono::steady_clock;

//! coupling_series.csv: the interface terms and the budget of gas + rock, and the gas in the monitor regions.
class CouplingSeries {
 public:
  CouplingSeries(const CoupledCaseConfig& c, cip::GasSolver& gas, fdem::RockSolver& rock, ibm::GasRockCoupler& coupler,
                 bool resume)
      : c_(c), gas_(gas), rock_(rock), coupler_(coupler),
        file_((make_output_dir(c.gas.output_directory) / "coupling_series.csv").string(), header(c), resume) {
    const cip::GasTotals g = gas_.totals();
    const fdem::RockEnergies e = rock_.energies();
    initial_ = g.total_energy() + e.kinetic + e.strain;
  }
  void write_checkpoint(CheckpointWriter& w) {
    w.value("out.coupling.initial", initial_);
    w.value("out.coupling.csv_size", file_.size());
  }
  void read_checkpoint(CheckpointReader& r) {
    initial_ = r.value<double>("out.coupling.initial");
    file_.truncate_to(r.value<std::uint64_t>("out.coupling.csv_size"));
  }

  //! Writes one row; returns the budget residual relative to the initial energy. Budget (S4 of validation.md):
  //! initial gas + rock energy + work of non-gas loads + energy the cell transitions created = gas energy +
  //! what left the grid + rock kinetic + strain + joint work + contact work + damping.
  double write() {
    const cip::GasTotals g = gas_.totals();
    const fdem::RockEnergies e = rock_.energies();
    const ibm::CouplingDiagnostics d = coupler_.diagnostics();
    const double out = gas_.boundary_outflow().energy, other = e.external_work - e.pressure_work;
    const double now = g.total_energy() + out + e.kinetic + e.strain + e.joint_work + e.contact_work + e.damping_dissipated;
    const double residual = now - (initial_ + other + d.transitions.energy_created);
    std::string row = fmt::format("{},{:.9e},{:.9e},{:.9e},{:.9e},{:.9e},{:.9e},{:.9e},{:.9e},{:.9e},{:.9e},{:.9e},{:.9e},{:.9e},"
                         "{:.9e},{:.6e},{:.6e},{:.6e},{:.6e},{},{:.6e},{},{}",
                         gas_.steps(), gas_.time(), g.mass, g.internal_energy, g.kinetic_energy, out, e.kinetic, e.strain,
                         e.joint_work, e.fracture_dissipated, e.contact_work, e.damping_dissipated, d.gas_work_on_rock,
                         other, d.transitions.energy_created, residual, residual / initial_, d.gas_force_on_rock[0],
                         d.gas_force_on_rock[1], e.broken_joints, e.crack_length, d.transitions.covered,
                         d.transitions.uncovered);
    for (const MonitorRegion& r : c_.regions) {
      const cip::GasTotals t = coupler_.gas_in(r.region);
      row += fmt::format(",{:.9e},{:.9e}", t.mass, t.total_energy());
    }
    file_.row(row);
    return residual / initial_;
  }

 private:
  const CoupledCaseConfig& c_;
  cip::GasSolver& gas_;
  fdem::RockSolver& rock_;
  ibm::GasRockCoupler& coupler_;
  CsvSeries file_;
  double initial_ = 0;

  static std::string header(const CoupledCaseConfig& c) {
    std::string h = "step,time_s,gas_mass_kg_per_m,gas_internal_J_per_m,gas_kinetic_J_per_m,gas_energy_out_J_per_m,"
                    "rock_kinetic_J_per_m,rock_strain_J_per_m,joint_work_J_per_m,fracture_dissipated_J_per_m,"
                    "contact_work_J_per_m,damping_dissipated_J_per_m,gas_work_on_rock_J_per_m,other_external_work_J_per_m,"
                    "transition_energy_J_per_m,budget_residual_J_per_m,budget_relative,gas_force_x_N_per_m,"
                    "gas_force_y_N_per_m,broken_joints,crack_length_m,cells_covered,cells_uncovered";
    for (const MonitorRegion& r : c.regions) h += fmt::format(",{0}_mass_kg_per_m,{0}_energy_J_per_m", r.name);
    return h;
  }
};

//! The case as the checkpoint records it: the resolved input, less the keys a restart may change.
std::string checkpoint_case_text(const CoupledCaseConfig& c) {
  std::string text;
  for (const std::string& line : c.echo) {
    const bool may_change = line.rfind("time.end ", 0) == 0 || line.rfind("time.max_steps ", 0) == 0 ||
                            line.rfind("output.progress_interval ", 0) == 0 || line.rfind("output.directory ", 0) == 0;
    if (!may_change) text += line + "\n";
  }
  return text;
}

//! Throws InputError naming the first line where the checkpoint's case and this one differ.
void check_same_case(const std::string& saved, const std::string& now, const std::string& path) {
  if (saved == now) return;
  size_t a = 0;
  while (a < saved.size() && a < now.size() && saved[a] == now[a]) ++a;
  const size_t start = saved.rfind('\n', a == 0 ? 0 : a - 1);
  const size_t from = start == std::string::npos ? 0 : start + 1;
  auto line_at = [&](const std::string& s) { return s.substr(from, s.find('\n', from) - from); };
  throw InputError(fmt::format("--restart: {} was written for another case: it has \"{}\" where this input has \"{}\" "
                               "(a restart may change only time.end, time.max_steps, output.progress_interval and output.directory)",
                               path, line_at(saved), line_at(now)));
}

}  // namespace

void run_coupled_case(const CoupledCaseConfig& c, std::ostream& log, const RunOptions& options) {
  const CaseConfig& gc = c.gas;
  if (gc.vtk && !vtk_available())
    throw InputError("output.vtk = true, but this build has no VTK: set output.vtk = false (CSV output still works)");
  RockModel model = make_rock_model(c.rock, false);
  fdem::RockSolver& rock = *model.solver;
  const double rock_dt = rock_time_step(c.rock, rock);  // checks a fixed dt against the rock's stable step
  cip::GasSolver gas(gc.grid, gc.eos, gc.solver);
  gas.initialise([&](double x, double y) { return gc.initial_state(x, y); });
  ibm::GasRockCoupler coupler(gas, rock, gc.ambient);
  const bool resume = options.restart;
  if (!resume) coupler.rock_to_gas();  // masks first: cells under rock take the ambient state before any output
  log << fmt::format("coupled: gas {} x {} cells of {:.4g} x {:.4g} m ({} covered by rock); rock {} triangles, {} joints, "
                     "stable step {:.4g} s\n",
                     gc.grid.nx, gc.grid.ny, gc.grid.dx, gc.grid.dy, coupler.inactive_cells(), rock.triangle_count(),
                     rock.joint_count(), rock.stable_dt());

  GasOutputs gas_out(gc, gas, log, false, resume);
  RockOutputs rock_out(c.rock, rock, resume);
  CouplingSeries series(c, gas, rock, coupler, resume);
  bool warned = false;
  // Checkpoint: everything a run needs to go on bit for bit, written with every snapshot (atomically).
  const std::string checkpoint_path = (std::filesystem::path(gc.output_directory) / "checkpoint.bin").string();
  auto write_checkpoint = [&] {
    CheckpointWriter w(checkpoint_path);
    w.text("case", checkpoint_case_text(c));
    gas.write_checkpoint(w);
    rock.write_checkpoint(w);
    coupler.write_checkpoint(w);
    gas_out.write_checkpoint(w);
    rock_out.write_checkpoint(w);
    series.write_checkpoint(w);
    w.value("run.warned", static_cast<int>(warned));
    w.commit();
  };
  if (resume) {
    CheckpointReader r(checkpoint_path);
    check_same_case(r.text("case"), checkpoint_case_text(c), checkpoint_path);
    gas.read_checkpoint(r);
    rock.read_checkpoint(r);
    coupler.read_checkpoint(r);
    gas_out.read_checkpoint(r);
    rock_out.read_checkpoint(r);
    series.read_checkpoint(r);
    warned = r.value<int>("run.warned") != 0;
    log << fmt::format("restarted from {} at step {} (t = {:.6e} s)\n", checkpoint_path, gas.steps(), gas.time());
  } else {
    gas_out.write_due(0.0, true);
    rock_out.snapshot();
    rock_out.monitor();
    series.write();
    if (c.checkpoint) write_checkpoint();
  }

  const auto wall_start = Clock::now();
  auto last_progress = wall_start;
  double rate = checked_signal_rate(gas, gc.output_directory);
  while (gas.time() < gc.end_time * (1 - 1e-12)) {
    if (gc.max_steps > 0 && gas.steps() >= gc.max_steps) {
      log << fmt::format("stopping at time.max_steps = {} (t = {:.6e} s)\n", gc.max_steps, gas.time());
      break;
    }
    double dt = 0;
    if (gc.fixed_dt) {
      dt = *gc.fixed_dt;
      check_fixed_dt_courant(dt, rate, gc.courant, gas);
    } else {  // one dt for both solvers: the gas Courant limit and the rock's step (docs/coupling.md)
      dt = std::min(gc.courant / rate, rock_dt);
      const double next = gas_out.next_event(gas.time());
      if (gas.time() + dt > next) dt = next - gas.time();
    }
    coupler.step(dt);  // rock -> gas, gas, gas -> rock, rock (throws InstabilityError on a non-finite rock)
    rate = checked_signal_rate(gas, gc.output_directory);
    const bool last = gas.time() >= gc.end_time * (1 - 1e-12);
    const bool snapshot = gas_out.write_due(dt, last);
    if (snapshot) rock_out.snapshot();
    if (gas.steps() % gc.monitor_interval == 0 || last) {
      rock_out.monitor();
      const double drift = series.write();
      if (!warned && std::fabs(drift) > gc.drift_warning) {
        warned = true;
        log << fmt::format("warning: the gas + rock energy budget is off by {:+.3e} of the initial energy (> "
                           "output.drift_warning = {:g}) at step {} (t = {:.6e} s); coupling_series.csv has the history\n",
                           drift, gc.drift_warning, gas.steps(), gas.time());
      }
    }
    if (snapshot && c.checkpoint) write_checkpoint();
    const auto now = Clock::now();
    if (!options.quiet && (std::chrono::duration<double>(now - last_progress).count() >= gc.progress_interval || last)) {
      const fdem::RockEnergies e = rock.energies();
      log << progress_line(gas.steps(), gas.time(), dt, gc.end_time, std::chrono::duration<double>(now - wall_start).count(),
                           fmt::format("  broken joints {}  crack length {:.3f} m", e.broken_joints, e.crack_length))
          << std::flush;
      last_progress = now;
    }
  }
  const fdem::RockEnergies e = rock.energies();
  const ibm::CouplingDiagnostics d = coupler.diagnostics();
  log << fmt::format("coupled: {} steps to t = {:.4e} s; {} joints broken, crack length {:.4f} m; gas work on the rock "
                     "{:.4e} J/m\n", gas.steps(), gas.time(), e.broken_joints, e.crack_length, d.gas_work_on_rock);
}

}  // namespace blastsim::app
