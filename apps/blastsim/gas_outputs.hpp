//! \file gas_outputs.hpp
//! \brief What a driver run writes about the gas: VTK snapshots, line and point probes, the conservation
//! monitor (gas_totals.csv); shared by gas-only and coupled runs. Include only from kernel sources.
#pragma once

#include "blastsim/cip/balance.hpp"
#include "blastsim/cip/gas_solver.hpp"
#include "blastsim/core/checkpoint.hpp"
#include "blastsim/core/error.hpp"
#include "case_config.hpp"
#include "output_checkpoint.hpp"
#include "run_loop.hpp"
#include "vtk_gas_writer.hpp"

#include <fmt/format.h>
#include <fmt/ostream.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <ostream>
#include <string>
#include <vector>

namespace blastsim::app {

//! Throws InputError when a fixed dt [s] violates the Courant limit at the gas's signal rate [1/s].
inline void check_fixed_dt_courant(double dt, double rate, double courant, const cip::GasSolver& solver) {
  if (dt * rate > courant)
    throw InputError(fmt::format("time.dt = {:g} s violates the Courant limit at step {} (t = {:.6e} s): Courant "
                                 "number {:.4g} > gas.courant = {:g}; the largest stable dt now is {:.4g} s",
                                 dt, solver.steps() + 1, solver.time(), dt * rate, courant, courant / rate));
}

//! The gas's signal rate [1/s] for the next dt; an invalid state (+inf) stops the run with InstabilityError
//! naming the quantity, step and place, before that state is written anywhere.
//! `r`: the rate when the caller has it already (a coupled step reads it with the rock's speed).
inline double checked_signal_rate(cip::GasSolver& solver, const std::string& output_directory, double r) {
  if (!std::isfinite(r))
    throw InstabilityError(fmt::format("gas state invalid after step {} (t = {:.6e} s): {}; the last good output is in {}",
                                       solver.steps(), solver.time(), solver.describe_invalid_cell(), output_directory));
  return r;
}
inline double checked_signal_rate(cip::GasSolver& solver, const std::string& output_directory) {
  return checked_signal_rate(solver, output_directory, solver.max_signal_rate());
}

//! Output state of one run: files, schedules and open CSV streams.
class GasOutputs {
 public:
  //! `gas_alone`: false in a coupled run, where the gas exchanges energy with the rock and cells that the rock
  //! uncovers start with ambient gas: gas_totals.csv is written but not watched (the coupled budget, with
  //! those transitions, is in coupling_series.csv).
  //! `resume`: a restart, whose read_checkpoint() follows (files are kept, not started anew).
  GasOutputs(const CaseConfig& c, cip::GasSolver& solver, std::ostream& log, bool gas_alone = true, bool resume = false)
      : c_(c), solver_(solver), log_(log), gas_alone_(gas_alone), dir_(make_output_dir(c.output_directory)),
        pvd_((dir_ / "gas.pvd").string()),
        totals_((dir_ / "gas_totals.csv").string(),
                "step,time_s,dt_s,mass_kg_per_m,momentum_x_kg_per_s,momentum_y_kg_per_s,internal_energy_J_per_m,"
                "kinetic_energy_J_per_m,total_energy_J_per_m,mass_out_kg_per_m,momentum_x_out_kg_per_s,"
                "momentum_y_out_kg_per_s,energy_out_J_per_m,mass_balance_drift,energy_balance_drift",
                resume) {
    for (const PointProbe& p : c.point_probes) {
      point_files_.emplace_back((dir_ / fmt::format("point_{}.csv", p.name)).string(), "t,x,y,rho,u,v,p,e", resume);
      next_point_.push_back(0.0);
    }
    for (size_t k = 0; k < c.line_probes.size(); ++k) line_done_.emplace_back(c.line_probes[k].times.size(), false);
  }

  //! The output schedule, the monitor's reference and the sizes of the CSV files, for a restart.
  void write_checkpoint(CheckpointWriter& w) {
    w.value("out.gas.counters", std::array<double, 5>{next_snapshot_, static_cast<double>(snapshot_index_),
                                                      static_cast<double>(mass_warned_), static_cast<double>(energy_warned_),
                                                      static_cast<double>(next_time_)});
    w.value("out.gas.initial", initial_);
    w.host_array("out.gas.next_point", next_point_);
    std::vector<std::uint8_t> done;
    for (const auto& l : line_done_) done.insert(done.end(), l.begin(), l.end());
    w.host_array("out.gas.line_done", done);
    std::vector<std::uint64_t> sizes{totals_.size()};
    for (CsvSeries& f : point_files_) sizes.push_back(f.size());
    w.host_array("out.gas.csv_sizes", sizes);
    write_pvd_checkpoint(w, "out.gas.pvd", pvd_);
  }
  void read_checkpoint(CheckpointReader& r) {
    const std::array<double, 5> k = r.value<std::array<double, 5>>("out.gas.counters");
    if (!std::isfinite(k[0]) || !(k[1] >= 0 && k[1] <= 1e9 && k[1] == std::floor(k[1])) ||
        !(k[4] >= 0 && k[4] <= static_cast<double>(c_.output_times.size()) && k[4] == std::floor(k[4])))
      r.fail("out.gas.counters", "the output schedule is out of range");
    next_snapshot_ = k[0], snapshot_index_ = static_cast<int>(k[1]), mass_warned_ = k[2] != 0, energy_warned_ = k[3] != 0;
    next_time_ = static_cast<size_t>(k[4]);
    initial_ = r.value<cip::GasTotals>("out.gas.initial");
    next_point_ = r.host_array<double>("out.gas.next_point");
    const std::vector<std::uint8_t> done = r.host_array<std::uint8_t>("out.gas.line_done");
    const std::vector<std::uint64_t> sizes = r.host_array<std::uint64_t>("out.gas.csv_sizes");
    size_t at = 0;
    for (auto& l : line_done_)
      for (size_t m = 0; m < l.size(); ++m) l[m] = at < done.size() && done[at++];
    if (next_point_.size() != point_files_.size() || sizes.size() != point_files_.size() + 1 || at != done.size())
      throw InputError("checkpoint " + r.path() + ": its probes differ from this case's");
    for (double t : next_point_)
      if (!std::isfinite(t)) r.fail("out.gas.next_point", "a probe time is not finite");
    totals_.truncate_to(sizes[0]);
    for (size_t p = 0; p < point_files_.size(); ++p) point_files_[p].truncate_to(sizes[p + 1]);
    read_pvd_checkpoint(r, "out.gas.pvd", pvd_);
  }

  //! Earliest pending event time after t (snapshot, line probe, end), for the Courant-mode dt clip.
  double next_event(double t) const {
    double next = c_.end_time;
    if (c_.output_interval > 0) next = std::min(next, next_snapshot_);
    if (next_time_ < c_.output_times.size()) next = std::min(next, c_.output_times[next_time_]);
    for (size_t k = 0; k < c_.line_probes.size(); ++k)
      for (size_t m = 0; m < c_.line_probes[k].times.size(); ++m)
        if (!line_done_[k][m] && c_.line_probes[k].times[m] > t) next = std::min(next, c_.line_probes[k].times[m]);
    return next;
  }

  //! Writes whatever is due at the solver's current time (force: snapshot regardless of schedule).
  //! Returns true when a snapshot was due (and written, when output.vtk).
  bool write_due(double dt, bool force_snapshot) {
    const double t = solver_.time(), tol = 1e-9 * c_.end_time;
    const bool listed_due = next_time_ < c_.output_times.size() && t >= c_.output_times[next_time_] - tol;
    const bool snapshot_due = force_snapshot || listed_due || (c_.output_interval > 0 && t >= next_snapshot_ - tol);
    if (snapshot_due) {
      snapshot();
      if (c_.output_interval > 0)
        advance_schedule(next_snapshot_, c_.output_interval, t + tol);
      while (next_time_ < c_.output_times.size() && c_.output_times[next_time_] <= t + tol) ++next_time_;
    }
    for (size_t k = 0; k < c_.line_probes.size(); ++k)
      for (size_t m = 0; m < c_.line_probes[k].times.size(); ++m)
        if (!line_done_[k][m] && c_.line_probes[k].times[m] <= t + tol) {
          write_line(c_.line_probes[k], m);
          line_done_[k][m] = true;
        }
    sample_points(t);
    if (solver_.steps() % c_.monitor_interval == 0 || force_snapshot) monitor(dt);
    return snapshot_due;
  }

  //! The end of a run, after write_due(dt, false) wrote what the schedule asked for: the snapshot (unless
  //! that call wrote one) and the monitor row (unless the step was a monitor step) that close every run.
  void write_end(double dt, bool snapshot_written) {
    if (!snapshot_written) snapshot();
    if (solver_.steps() % c_.monitor_interval != 0) monitor(dt);
  }

 private:
  void snapshot() {
    if (!c_.vtk) return;
    const std::string name = fmt::format("gas_{:06d}.vti", snapshot_index_++);
    write_gas_vti((dir_ / name).string(), solver_.grid(), solver_.to_host());
    pvd_.add(solver_.time(), name);
  }
  void write_line(const LineProbe& l, size_t m) {
    std::vector<std::array<double, 2>> pts(l.points);
    for (int k = 0; k < l.points; ++k) {
      const double s = static_cast<double>(k) / (l.points - 1);
      pts[k] = {l.start[0] + s * (l.end[0] - l.start[0]), l.start[1] + s * (l.end[1] - l.start[1])};
    }
    const std::vector<cip::GasSample> smp = solver_.sample(pts);
    write_atomically((dir_ / fmt::format("line_{}_{:03d}.csv", l.name, m)).string(), [&](std::ostream& out) {
      out << "x,y,rho,u,v,p,e\n";
      for (const cip::GasSample& g : smp)
        out << fmt::format("{:.9e},{:.9e},{:.9e},{:.9e},{:.9e},{:.9e},{:.9e}\n", g.x, g.y, g.rho, g.u, g.v, g.p, g.e);
    });
  }
  void sample_points(double t) {
    std::vector<std::array<double, 2>> pts;
    std::vector<size_t> which;
    for (size_t k = 0; k < c_.point_probes.size(); ++k)
      if (t >= next_point_[k] - 1e-12 * c_.end_time) {
        pts.push_back(c_.point_probes[k].position);
        which.push_back(k);
        advance_schedule(next_point_[k], c_.point_probes[k].interval, t);
      }
    if (pts.empty()) return;
    const std::vector<cip::GasSample> smp = solver_.sample(pts);
    for (size_t m = 0; m < smp.size(); ++m) {
      const cip::GasSample& g = smp[m];
      point_files_[which[m]].row(fmt::format("{:.9e},{:.9e},{:.9e},{:.9e},{:.9e},{:.9e},{:.9e},{:.9e}", t, g.x, g.y, g.rho,
                                             g.u, g.v, g.p, g.e));
    }
  }
  //! The conservation monitor: totals in the domain, what crossed the outer boundary, and the relative
  //! drift of the balance (in domain + out - initial) / initial; a warning when it exceeds the threshold.
  void monitor(double dt) {
    const cip::GasTotals s = solver_.totals();
    const cip::BoundaryOutflow& o = solver_.boundary_outflow();
    if (solver_.steps() == 0) initial_ = s;
    const cip::BalanceDrift drift = cip::balance_drift(s, o, initial_, solver_.positivity_energy());
    const double mass_drift = drift.mass, energy_drift = drift.energy;
    totals_.row(fmt::format("{},{:.9e},{:.6e},{:.12e},{:.12e},{:.12e},{:.12e},{:.12e},{:.12e},{:.12e},{:.12e},{:.12e},"
                           "{:.12e},{:.6e},{:.6e}",
                           solver_.steps(), solver_.time(), dt, s.mass, s.momentum_x, s.momentum_y, s.internal_energy,
                           s.kinetic_energy, s.total_energy(), o.mass, o.momentum_x, o.momentum_y, o.energy,
                           mass_drift, energy_drift));
    if (!gas_alone_) return;  // coupled: rock moves gas in and out of cells; coupling_series.csv has the budget
    warn_once(mass_warned_, "mass", mass_drift);
    warn_once(energy_warned_, "energy", energy_drift);
  }
  void warn_once(bool& warned, const char* what, double drift) {
    if (warned || !(std::fabs(drift) > c_.drift_warning)) return;
    warned = true;
    log_ << fmt::format("warning: {} balance drifted by {:+.3e} (> output.drift_warning = {:g}) at step {} "
                        "(t = {:.6e} s); gas_totals.csv has the history\n",
                        what, drift, c_.drift_warning, solver_.steps(), solver_.time());
  }

  const CaseConfig& c_;
  cip::GasSolver& solver_;
  std::ostream& log_;
  bool gas_alone_;
  cip::GasTotals initial_;
  bool mass_warned_ = false, energy_warned_ = false;
  std::filesystem::path dir_;
  PvdSeries pvd_;
  CsvSeries totals_;
  std::vector<CsvSeries> point_files_;
  std::vector<double> next_point_;
  std::vector<std::vector<bool>> line_done_;
  double next_snapshot_ = 0.0;
  size_t next_time_ = 0;  // first of c_.output_times not yet written
  int snapshot_index_ = 0;
};

}  // namespace blastsim::app
