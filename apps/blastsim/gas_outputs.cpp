//! \file gas_outputs.cpp
//! \brief GasOutputs: the gas's snapshots, probes and conservation monitor.
#include "gas_outputs.hpp"

#include "blastsim/cip/balance.hpp"
#include "blastsim/core/error.hpp"
#include "blastsim/cip/vtk_writer.hpp"

#include <fmt/format.h>

#include <cmath>

namespace blastsim::app {

bool SnapshotSchedule::due(const OutputSettings& o, double t, double tol) const {
  const bool listed_due = listed < o.times.size() && t >= o.times[listed] - tol;
  return listed_due || (o.interval > 0 && t >= next - tol);
}

void SnapshotSchedule::advance(const OutputSettings& o, double t, double tol) {
  if (o.interval > 0) advance_schedule(next, o.interval, t + tol);
  while (listed < o.times.size() && o.times[listed] <= t + tol) ++listed;
}

GasOutputs::GasOutputs(const Case& c, cip::GasSolver& solver, std::ostream& log, bool gas_alone, bool resume)
    : c_(c), solver_(solver), log_(log), gas_alone_(gas_alone), dir_(make_output_dir(c.output.directory)),
      pvd_((dir_ / "gas.pvd").string()),
      totals_((dir_ / "gas_totals.csv").string(),
              csv_text(CsvRecord::Mode::header, [&](CsvRecord& o) { totals_columns(o, 0, {}, {}, {}); }), resume) {
  for (const ProbeSettings::Point& p : c.probes.points) {
    point_files_.emplace_back((dir_ / fmt::format("point_{}.csv", p.name)).string(), "t,x,y,rho,u,v,p,e", resume);
    next_point_.push_back(0.0);
  }
  for (const ProbeSettings::Line& l : c.probes.lines) line_done_.emplace_back(l.times.size(), false);
}

void GasOutputs::write_checkpoint(CheckpointWriter& w) {
  w.value("out.gas.next_snapshot", schedule_.next);
  w.value("out.gas.listed_snapshot", static_cast<std::uint64_t>(schedule_.listed));
  w.value("out.gas.snapshot_index", snapshot_index_);
  w.value("out.gas.warned", std::array<int, 2>{mass_warned_, energy_warned_});
  w.value("out.gas.initial", initial_);
  w.host_array("out.gas.next_point", next_point_);
  std::vector<std::uint8_t> done;
  for (const auto& l : line_done_) done.insert(done.end(), l.begin(), l.end());
  w.host_array("out.gas.line_done", done);
  totals_.write_checkpoint(w, "out.gas.totals_size");
  for (size_t p = 0; p < point_files_.size(); ++p) point_files_[p].write_checkpoint(w, "out.gas.point_size." + c_.probes.points[p].name);
  pvd_.write_checkpoint(w, "out.gas.pvd");
}

void GasOutputs::read_checkpoint(CheckpointReader& r) {
  schedule_.next = r.value<double>("out.gas.next_snapshot");
  if (!std::isfinite(schedule_.next)) r.fail("out.gas.next_snapshot", "not finite");
  const std::uint64_t listed = r.value<std::uint64_t>("out.gas.listed_snapshot");
  if (listed > c_.output.times.size()) r.fail("out.gas.listed_snapshot", "past the end of output.times");
  schedule_.listed = static_cast<size_t>(listed);
  snapshot_index_ = r.value<int>("out.gas.snapshot_index");
  if (snapshot_index_ < 0 || snapshot_index_ > 999999) r.fail("out.gas.snapshot_index", "out of range");
  const std::array<int, 2> warned = r.value<std::array<int, 2>>("out.gas.warned");
  mass_warned_ = warned[0] != 0, energy_warned_ = warned[1] != 0;
  initial_ = r.value<cip::GasTotals>("out.gas.initial");
  next_point_ = r.host_array<double>("out.gas.next_point");
  const std::vector<std::uint8_t> done = r.host_array<std::uint8_t>("out.gas.line_done");
  size_t at = 0;
  for (auto& l : line_done_)
    for (size_t m = 0; m < l.size(); ++m) l[m] = at < done.size() && done[at++];
  if (next_point_.size() != point_files_.size() || at != done.size())
    throw InputError("checkpoint " + r.path() + ": its probes differ from this case's");
  for (double t : next_point_)
    if (!std::isfinite(t)) r.fail("out.gas.next_point", "a probe time is not finite");
  totals_.read_checkpoint(r, "out.gas.totals_size");
  for (size_t p = 0; p < point_files_.size(); ++p) point_files_[p].read_checkpoint(r, "out.gas.point_size." + c_.probes.points[p].name);
  pvd_.read_checkpoint(r, "out.gas.pvd");
}

double GasOutputs::next_event(double t) const {
  const OutputSettings& o = c_.output;
  double next = c_.time.end;
  if (o.interval > 0) next = std::min(next, schedule_.next);
  if (schedule_.listed < o.times.size()) next = std::min(next, o.times[schedule_.listed]);
  for (size_t k = 0; k < c_.probes.lines.size(); ++k)
    for (size_t m = 0; m < c_.probes.lines[k].times.size(); ++m)
      if (!line_done_[k][m] && c_.probes.lines[k].times[m] > t) next = std::min(next, c_.probes.lines[k].times[m]);
  return next;
}

bool GasOutputs::write_due(double dt, bool force_snapshot) {
  const double t = solver_.time(), tol = 1e-9 * c_.time.end;
  const bool snapshot_due = force_snapshot || schedule_.due(c_.output, t, tol);
  if (snapshot_due) {
    snapshot();
    schedule_.advance(c_.output, t, tol);
  }
  for (size_t k = 0; k < c_.probes.lines.size(); ++k)
    for (size_t m = 0; m < c_.probes.lines[k].times.size(); ++m)
      if (!line_done_[k][m] && c_.probes.lines[k].times[m] <= t + tol) {
        write_line(c_.probes.lines[k], m);
        line_done_[k][m] = true;
      }
  sample_points(t);
  if (solver_.steps() % c_.output.monitor_interval == 0 || force_snapshot) monitor(dt);
  return snapshot_due;
}

void GasOutputs::write_end(double dt, bool snapshot_written) {
  if (!snapshot_written) snapshot();
  if (solver_.steps() % c_.output.monitor_interval != 0) monitor(dt);
}

void GasOutputs::snapshot() {
  if (!c_.output.vtk) return;
  const std::string name = fmt::format("gas_{:06d}.vti", snapshot_index_++);
  cip::write_gas_vti((dir_ / name).string(), solver_.grid(), solver_.to_host());
  pvd_.add(solver_.time(), name);
}

void GasOutputs::write_line(const ProbeSettings::Line& l, size_t m) {
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

void GasOutputs::sample_points(double t) {
  std::vector<std::array<double, 2>> pts;
  std::vector<size_t> which;
  for (size_t k = 0; k < c_.probes.points.size(); ++k)
    if (t >= next_point_[k] - 1e-12 * c_.time.end) {
      pts.push_back(c_.probes.points[k].position);
      which.push_back(k);
      advance_schedule(next_point_[k], c_.probes.points[k].interval, t);
    }
  if (pts.empty()) return;
  const std::vector<cip::GasSample> smp = solver_.sample(pts);
  for (size_t m = 0; m < smp.size(); ++m) {
    const cip::GasSample& g = smp[m];
    point_files_[which[m]].row(
        fmt::format("{:.9e},{:.9e},{:.9e},{:.9e},{:.9e},{:.9e},{:.9e},{:.9e}", t, g.x, g.y, g.rho, g.u, g.v, g.p, g.e));
  }
}

void GasOutputs::monitor(double dt) {
  const cip::GasTotals s = solver_.totals();
  const cip::BoundaryOutflow& o = solver_.boundary_outflow();
  if (solver_.steps() == 0) initial_ = s;
  const cip::BalanceDrift drift = cip::balance_drift(s, o, initial_, solver_.positivity_energy());
  totals_.row_of([&](CsvRecord& r) { totals_columns(r, dt, s, o, drift); });
  if (!gas_alone_) return;  // coupled: rock moves gas in and out of cells; coupling_series.csv has the budget
  warn_once(mass_warned_, "mass", drift.mass);
  warn_once(energy_warned_, "energy", drift.energy);
}

void GasOutputs::totals_columns(CsvRecord& r, double dt, const cip::GasTotals& s, const cip::BoundaryOutflow& o,
                                const cip::BalanceDrift& drift) const {
  r.integer("step", solver_.steps()).real("time_s", solver_.time()).real("dt_s", dt, 6).real("mass_kg_per_m", s.mass, 12);
  r.real("momentum_x_kg_per_s", s.momentum_x, 12).real("momentum_y_kg_per_s", s.momentum_y, 12);
  r.real("internal_energy_J_per_m", s.internal_energy, 12).real("kinetic_energy_J_per_m", s.kinetic_energy, 12);
  r.real("total_energy_J_per_m", s.total_energy(), 12).real("mass_out_kg_per_m", o.mass, 12);
  r.real("momentum_x_out_kg_per_s", o.momentum_x, 12).real("momentum_y_out_kg_per_s", o.momentum_y, 12);
  r.real("energy_out_J_per_m", o.energy, 12).real("mass_balance_drift", drift.mass, 6);
  r.real("energy_balance_drift", drift.energy, 6);
}

void GasOutputs::warn_once(bool& warned, const char* what, double drift) {
  if (warned || !(std::fabs(drift) > c_.output.drift_warning)) return;
  warned = true;
  log_ << fmt::format("warning: {} balance drifted by {:+.3e} (> output.drift_warning = {:g}) at step {} "
                      "(t = {:.6e} s); gas_totals.csv has the history\n",
                      what, drift, c_.output.drift_warning, solver_.steps(), solver_.time());
}

}  // namespace blastsim::app
