//! \file coupled_run.cpp
//! \brief A coupled gas-rock case of the driver: the coupled stepper (libibm's GasRockCoupler and its dt
//! policy) and its outputs (the gas's and the rock's files, coupling_series.csv with the energy budget, the
//! blasthole monitor's files, the checkpoint) in the run loop.
#include "run_loop.hpp"

#include "blastsim/core/error.hpp"
#include "blastsim/ibm/blasthole_monitor.hpp"
#include "blastsim/ibm/budget.hpp"
#include "blastsim/ibm/coupler.hpp"
#include "gas_outputs.hpp"
#include "blastsim/cip/vtk_writer.hpp"
#include "rock_outputs.hpp"

#include <fmt/format.h>

#include <cmath>
#include <map>
#include <optional>
#include <set>
#include <vector>

namespace blastsim::app {

namespace {

//! coupling_series.csv: the interface terms and the budget of gas + rock, and the gas in the monitor regions.
class CouplingSeries {
 public:
  CouplingSeries(const Case& c, cip::GasSolver& gas, fdem::RockSolver& rock, ibm::GasRockCoupler& coupler,
                 bool resume)
      : c_(c), gas_(gas), rock_(rock), coupler_(coupler),
        file_((make_output_dir(c.output.directory) / "coupling_series.csv").string(),
              csv_text(CsvRecord::Mode::header, [&](CsvRecord& o) { columns(o); }), resume),
        initial_(ibm::initial_energy(gas, rock)) {}
  void write_checkpoint(CheckpointWriter& w) {
    w.value("out.coupling.initial", initial_);
    file_.write_checkpoint(w, "out.coupling.csv_size");
  }
  void read_checkpoint(CheckpointReader& r) {
    initial_ = r.value<double>("out.coupling.initial");
    if (!std::isfinite(initial_) || initial_ <= 0) r.fail("out.coupling.initial", "not a finite energy > 0");
    file_.read_checkpoint(r, "out.coupling.csv_size");
  }

  //! Writes one row; returns the budget residual relative to the initial energy plus what the charges released.
  double write() {
    double relative = 0;
    file_.row_of([&](CsvRecord& o) { relative = columns(o); });
    return relative;
  }

 private:
  const Case& c_;
  cip::GasSolver& gas_;
  fdem::RockSolver& rock_;
  ibm::GasRockCoupler& coupler_;
  CsvSeries file_;
  double initial_ = 0;

  //! The columns (ibm::budget_columns(): the budget of docs/validation.md S4, then each coupling process's own);
  //! returns the relative budget residual.
  double columns(CsvRecord& o) const {
    const ibm::CoupledBudget b = o.header() ? ibm::CoupledBudget{} : ibm::coupled_budget(gas_, rock_, coupler_, initial_);
    o.integer("step", gas_.steps()).real("time_s", gas_.time());
    ibm::budget_columns(b, coupler_, o);
    for (const MonitorSettings::Region& r : c_.monitor.regions) {
      const cip::GasTotals t = o.header() ? cip::GasTotals{} : coupler_.gas_in(r.where);
      o.real(r.name + "_mass_kg_per_m", t.mass).real(r.name + "_energy_J_per_m", t.total_energy());
    }
    return b.relative;
  }
};

//! The blasthole monitor's files ([monitor.blasthole]; ibm::BlastholeMonitor computes): wall_series.csv every
//! monitor.blasthole.interval, and summary.txt with the events of the blast.
class BlastholeFiles {
 public:
  BlastholeFiles(const Case& c, cip::GasSolver& gas, fdem::RockSolver& rock,
                 const ibm::GasRockCoupler& coupler, bool resume)
      : c_(c), gas_(gas), rock_(rock), coupler_(coupler) {
    if (!c.monitor.blasthole) return;
    monitor_.emplace(c.monitor.blasthole->geometry, c.gas.grid, c.gas.ambient_pressure());
    file_.emplace((make_output_dir(c.output.directory) / "wall_series.csv").string(),
                  csv_text(CsvRecord::Mode::header, [](CsvRecord& o) { wall_columns(o, {}); }), resume);
  }

  void sample() {
    if (!monitor_ || gas_.time() < next_ - 1e-12 * c_.time.end) return;
    advance_schedule(next_, c_.monitor.blasthole->interval, gas_.time() + 1e-12 * c_.time.end);
    const ibm::BlastholeSample s = monitor_->sample(gas_, rock_, coupler_.crack_gas());
    file_->row_of([&](CsvRecord& o) { wall_columns(o, s); });
    last_front_ = s.blast_front;
    if (s.blast_front > max_front_) max_front_ = s.blast_front, max_front_time_ = s.time;
  }

  //! summary.txt: the events and how each is measured (docs/single-hole.md sets them beside the paper's), then
  //! `analysis` (the rock analysis, RockOutputs::summary()). Without a blasthole monitor, the analysis alone.
  void write_summary(const fdem::RockEnergies& e, const std::string& analysis) const {
    const std::string path = (std::filesystem::path(c_.output.directory) / "summary.txt").string();
    if (!monitor_) {
      if (!analysis.empty())
        write_atomically(path, [&](std::ostream& out) {
          out << fmt::format("blastsim summary at t = {:.4e} s (step {})\n", gas_.time(), gas_.steps()) << analysis;
        });
      return;
    }
    const ibm::BlastholeEvents& ev = monitor_->events();
    auto when = [](double t) { return t < 0 ? std::string("not reached") : fmt::format("{:.4e} s ({:.3f} ms)", t, 1e3 * t); };
    write_atomically(path, [&](std::ostream& out) {
      out << fmt::format("blastsim single-hole summary at t = {:.4e} s (step {})\n\n", gas_.time(), gas_.steps());
      out << fmt::format("first crack: {}\n  the first sample (every {:g} s) with a broken joint\n", when(ev.first_crack),
                         c_.monitor.blasthole->interval);
      out << fmt::format("gas leaves the rock's outer surface: {}\n", when(ev.ejection));
      out << fmt::format("  the first sample where the gas pressure on the circle half a cell outside the rock's outer\n"
                         "  radius ({:g} m) exceeds twice the ambient pressure ({:.4g} Pa); pressure there then {:.4g} Pa\n",
                         monitor_->geometry().outer_radius, monitor_->ambient_pressure(), ev.ejection_pressure);
      out << fmt::format("nominal gas speed there: {}\n",
                         ev.ejection < 0 ? std::string("-") : fmt::format("{:.1f} m/s at {:.3f} ms", ev.jet_speed, 1e3 * ev.jet_time));
      out << "  the mass-flux-weighted mean outward speed (sum rho u_n^2 / sum rho u_n) over the points of that circle\n"
             "  where the pressure exceeds twice the ambient and the gas flows out; its largest value over the samples\n"
             "  from the first outflow to the end of the run\n";
      out << fmt::format("gas speed at the onset: {}\n  the largest outward speed among those points at the first "
                         "outflow sample\n", ev.ejection < 0 ? std::string("-") : fmt::format("{:.1f} m/s", ev.ejection_speed));
      if (gas_.materials().traced()) {
        out << fmt::format("blast gas reaches the rock's outer surface: {}{}\n",
                           when(ev.blast_arrival), ev.blast_arrival < 0 ? "" : (ev.blast_arrival_crack > 0 ? ", at a crack "
                                                                                "mouth" : ", on the circle outside"));
        out << fmt::format("  the first sample where at least {:g} of the gas is blast gas (the traced gas: {}) at a pressure\n"
                           "  of at least {:g} x the ambient, on the circle half a cell outside the outer radius or in a\n"
                           "  crack at its mouth on the outer surface\n", ibm::BlastholeMonitor::kBlastFraction,
                           gas_.materials().two ? "the detonation products" : "the gas of the [[gas.region]] tables",
                           ibm::BlastholeMonitor::kBlastPressure);
        out << fmt::format("blast gas outflow speed: {}\n",
                           ev.blast_arrival < 0 || ev.blast_speed_time < 0
                               ? std::string("-")
                               : fmt::format("{:.1f} m/s at {:.3f} ms", ev.blast_speed, 1e3 * ev.blast_speed_time));
        out << "  the blast gas's mass-flux-weighted mean outward speed (sum rho Y u_n^2 / sum rho Y u_n, Y its mass\n"
               "  fraction) over the points of that circle where it is blast gas flowing out; its largest value over\n"
               "  the samples from the arrival to the end of the run\n";
        out << fmt::format("blast gas front at the end: {:.4f} m from the hole centre (farthest {:.4f} m at {:.3f} ms)\n"
                           "  the farthest cell centre or crack midpoint inside the outer radius holding blast gas as above\n",
                           last_front_, max_front_, 1e3 * max_front_time_);
      } else {
        out << "blast gas: not traced (no [[gas.region]] with blast_gas = true, no detonation products)\n";
      }
      out << fmt::format("broken joints: {}; crack length {:.4f} m; fracture energy {:.4e} J/m\n", e.broken_joints,
                         e.crack_length, e.fracture_dissipated);
      out << analysis;
    });
  }

  void write_checkpoint(CheckpointWriter& w) {
    w.value("out.blasthole.next", next_);
    w.value("out.blasthole.events", monitor_ ? monitor_->events() : ibm::BlastholeEvents{});
    w.value("out.blasthole.front", std::array<double, 3>{last_front_, max_front_, max_front_time_});
    if (file_) file_->write_checkpoint(w, "out.blasthole.csv_size");
  }
  void read_checkpoint(CheckpointReader& r) {
    next_ = r.value<double>("out.blasthole.next");
    if (!std::isfinite(next_)) r.fail("out.blasthole.next", "not finite");
    const ibm::BlastholeEvents ev = r.value<ibm::BlastholeEvents>("out.blasthole.events");
    const std::array<double, 3> front = r.value<std::array<double, 3>>("out.blasthole.front");
    for (const double v : front)
      if (!std::isfinite(v)) r.fail("out.blasthole.front", "not finite");
    last_front_ = front[0], max_front_ = front[1], max_front_time_ = front[2];
    if (!monitor_) return;
    monitor_->restore(ev);
    file_->read_checkpoint(r, "out.blasthole.csv_size");
  }

 private:
  const Case& c_;
  cip::GasSolver& gas_;
  fdem::RockSolver& rock_;
  const ibm::GasRockCoupler& coupler_;
  std::optional<ibm::BlastholeMonitor> monitor_;  // only with [monitor.blasthole]
  std::optional<CsvSeries> file_;
  double next_ = 0;  // time of the next sample [s]
  double last_front_ = 0, max_front_ = 0, max_front_time_ = 0;  // the blast gas's front [m], its farthest and when

  static void wall_columns(CsvRecord& o, const ibm::BlastholeSample& s) {
    o.real("time_s", s.time).real("gas_pressure_wall_mean_Pa", s.wall_pressure_mean, 6);
    o.real("gas_pressure_wall_min_Pa", s.wall_pressure_min, 6).real("gas_pressure_wall_max_Pa", s.wall_pressure_max, 6);
    o.real("rock_radial_stress_wall_mean_Pa", s.wall_stress_mean, 6);
    o.real("rock_radial_stress_wall_min_Pa", s.wall_stress_min, 6).real("rock_radial_stress_wall_max_Pa", s.wall_stress_max, 6);
    o.real("rock_radial_stress_wall_sector_spread", s.wall_stress_spread, 4).integer("broken_joints", s.broken_joints);
    o.real("crack_length_m", s.crack_length, 6).real("outer_surface_gas_pressure_max_Pa", s.outer_pressure_max, 6);
    o.real("outer_surface_gas_speed_max_m_per_s", s.outer_speed_max, 6);
    o.real("outer_surface_gas_speed_flux_mean_m_per_s", s.outer_flux_speed, 6);
    o.real("blast_gas_front_radius_m", s.blast_front, 6).real("blast_gas_front_crack_radius_m", s.blast_front_crack, 6);
    o.real("outer_surface_blast_gas_fraction_max", s.outer_blast_fraction, 6);
    o.real("outer_surface_blast_gas_speed_m_per_s", s.outer_blast_speed, 6);
  }
};

//! The charges' files ([[charge]]): charges.csv (borehole pressure and released energy of every charge) at
//! every row of the coupling series, and their lines of summary.txt.
class ChargeFiles {
 public:
  ChargeFiles(const Case& c, const cip::GasSolver& gas, const ibm::GasRockCoupler& coupler, bool resume)
      : c_(c), gas_(gas), coupler_(coupler), peak_(c.coupling.charges.size(), 0.0), peak_time_(c.coupling.charges.size(), -1.0) {
    if (c.coupling.charges.empty()) return;
    std::string h = "time_s";
    for (std::size_t k = 0; k < c.coupling.charges.size(); ++k)
      h += fmt::format(",charge{0}_pressure_Pa,charge{0}_energy_J_per_m", k);
    file_.emplace((make_output_dir(c.output.directory) / "charges.csv").string(), h, resume);
  }
  void sample(double t) {
    if (!file_) return;
    const std::vector<double> p = coupler_.charges()->pressures(gas_, coupler_.ambient_pressure()),
                              e = coupler_.charges()->energies(gas_);
    std::string row = fmt::format("{:.9e}", t);
    for (std::size_t k = 0; k < p.size(); ++k) {
      row += fmt::format(",{:.6e},{:.9e}", p[k], e[k]);
      if (p[k] > peak_[k]) peak_[k] = p[k], peak_time_[k] = t;
    }
    file_->row(row);
  }
  //! summary.txt lines: per charge its initiation, its peak borehole pressure and the energy it released.
  std::string summary() const {
    if (c_.coupling.charges.empty()) return {};
    const std::vector<double> e = coupler_.charges()->energies(gas_);
    const ibm::ChargeProducts& q = c_.coupling.charge_products;
    std::string out = fmt::format("charges: products start at {:g} kg/m3 and {:.4g} J/kg ({:.4g} Pa); borehole pressure = "
                                  "mean over the hole's active cells (charges.csv)\n",
                                  q.density, q.specific_energy,
                                  c_.gas.explosive->pressure(q.density, q.specific_energy));
    for (std::size_t k = 0; k < c_.coupling.charges.size(); ++k) {
      const ibm::Charge& ch = c_.coupling.charges[k];
      const double nominal = q.density * q.specific_energy * M_PI * ch.radius * ch.radius;
      out += fmt::format("charge {}: hole [{:g}, {:g}] m, radius {:g} m, charge radius {:g} m; initiation {:.4e} s ({}); "
                         "peak borehole pressure {:.4e} Pa at {:.4e} s; energy released {:.4e} J/m ({:.1f} % of rho0 e0 "
                         "pi r^2)\n", k, ch.center[0], ch.center[1], ch.hole_radius, ch.radius, ch.initiation_time,
                         ch.initiation == ibm::Initiation::point
                             ? fmt::format("point at [{:g}, {:g}] m, D {:g} m/s", ch.point[0], ch.point[1],
                                           ch.detonation_velocity)
                             : std::string("constant volume"),
                         peak_[k], peak_time_[k], e[k], 100 * e[k] / nominal);
    }
    return out;
  }
  void write_checkpoint(CheckpointWriter& w) {
    if (file_) file_->write_checkpoint(w, "out.charges.csv_size");
    w.host_array("out.charges.peak", peak_);
    w.host_array("out.charges.peak_time", peak_time_);
  }
  void read_checkpoint(CheckpointReader& r) {
    const std::vector<double> peak = r.host_array<double>("out.charges.peak"),
                              when = r.host_array<double>("out.charges.peak_time");
    if (peak.size() != peak_.size() || when.size() != peak_.size())
      r.fail("out.charges.peak", "not one value per charge (a checkpoint of another case?)");
    peak_ = peak, peak_time_ = when;
    if (file_) file_->read_checkpoint(r, "out.charges.csv_size");
  }

 private:
  const Case& c_;
  const cip::GasSolver& gas_;
  const ibm::GasRockCoupler& coupler_;
  std::optional<CsvSeries> file_;
  std::vector<double> peak_, peak_time_;  // per charge: the largest borehole pressure sampled [Pa] and when [s]
};

//! The case as the checkpoint records it: the resolved input, less the keys a restart may change, and without
//! the echo's "(default)" marks (a default written out is the same input), and without the lines of keys read
//! only when given whose value is what their absence gives (EchoLine::same_as_absent). Keys added since checkpoints were
//! first written are recorded only when their value differs from the one that gives the earlier builds' step
//! (later_keys), so a checkpoint of an earlier build restarts when the input asks for that step, and is refused,
//! naming the key, when it does not.
std::string checkpoint_case_text(const Case& c) {
  std::string text;
  const std::set<std::string> may_change{"time.end", "time.max_steps", "output.progress_interval", "output.directory"};
  const std::map<std::string, std::string> later_keys{{"gas.pressure_predictor", "false"},
                                                      {"rock.mesh.algorithm", "\"frontal\""}};
  const std::string mark = kDefaultMark;
  for (const EchoLine& line : c.echo) {
    if (may_change.count(line.key) || line.same_as_absent) continue;
    const bool marked = line.text.size() >= mark.size() && line.text.compare(line.text.size() - mark.size(), mark.size(), mark) == 0;
    const std::string written = marked ? line.text.substr(0, line.text.size() - mark.size()) : line.text;
    if (const auto k = later_keys.find(line.key); k != later_keys.end() && written == line.key + " = " + k->second)
      continue;
    text += written + "\n";
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

//! The coupled solvers in the run loop: the gas's Courant limit and the rock's step, by the coupler's policy
//! (ibm::plan_coupled_step: one dt for both, or the rock subcycling), or time.dt checked against both.
class CoupledStepper : public Stepper {
 public:
  CoupledStepper(const Case& c, cip::GasSolver& gas, fdem::RockSolver& rock, ibm::GasRockCoupler& coupler)
      : c_(c), gas_(gas), rock_(rock), coupler_(coupler) {}
  double time() const override { return gas_.time(); }
  long long steps() const override { return gas_.steps(); }
  double next_dt(double until) override {
    const ibm::CoupledStep s = coupler_.plan_step(until);  // charges due now burn first
    checked_signal_rate(gas_, c_.output.directory, coupler_.signal_rate());
    if (c_.time.dt) check_fixed_dt_courant(*c_.time.dt, coupler_.signal_rate(), c_.gas.courant, gas_);
    substeps_ = s.rock_substeps;
    return s.dt;
  }
  void step(double dt) override {
    coupler_.step(dt, substeps_);  // rock -> gas, gas, gas -> rock, rock (throws InstabilityError on a non-finite rock)
    checked_signal_rate(gas_, c_.output.directory, coupler_.signal_rate());
  }
  std::string progress_note() const override {
    const fdem::RockEnergies e = rock_.energies();
    return fmt::format("{}  broken joints {}  crack length {:.3f} m",
                       c_.time.rock_subcycling ? fmt::format("  rock substeps {}", substeps_) : std::string(), e.broken_joints,
                       e.crack_length);
  }

 private:
  const Case& c_;
  cip::GasSolver& gas_;
  fdem::RockSolver& rock_;
  ibm::GasRockCoupler& coupler_;
  int substeps_ = 1;  // rock steps in the next (or last) gas step
};

//! Everything a coupled run writes: the gas's and the rock's files, coupling_series.csv, the blasthole
//! monitor's files, and the checkpoint with every snapshot.
class CoupledRunOutputs : public RunOutputs {
 public:
  CoupledRunOutputs(const Case& c, cip::GasSolver& gas, fdem::RockSolver& rock, ibm::GasRockCoupler& coupler,
                    const fdem::RockModel& model, std::ostream& log, bool resume)
      : c_(c), gas_(gas), rock_(rock), coupler_(coupler), log_(log), gas_out_(c, gas, log, false, resume),
        rock_out_(c, model, resume), series_(c, gas, rock, coupler, resume), blasthole_(c, gas, rock, coupler, resume),
        charges_(c, gas, coupler, resume),
        checkpoint_path_((std::filesystem::path(c.output.directory) / "checkpoint.bin").string()) {
    rock_out_.set_crack_gas(coupler.crack_gas() ? &coupler.crack_gas()->crack_gas() : nullptr);
  }

  //! The state at the start of a new run.
  void start() {
    gas_out_.write_due(0.0, true);
    rock_out_.snapshot();
    rock_out_.monitor();
    series_.write();
    charges_.sample(gas_.time());
    blasthole_.sample();
    if (c_.output.checkpoint) write_checkpoint();
  }
  //! Everything a run needs to go on bit for bit, written atomically.
  void write_checkpoint() {
    CheckpointWriter w(checkpoint_path_);
    w.text("case", checkpoint_case_text(c_));
    gas_.write_checkpoint(w);
    rock_.write_checkpoint(w);
    coupler_.write_checkpoint(w);
    gas_out_.write_checkpoint(w);
    rock_out_.write_checkpoint(w);
    series_.write_checkpoint(w);
    blasthole_.write_checkpoint(w);
    charges_.write_checkpoint(w);
    w.value("run.warned", static_cast<int>(warned_));
    w.commit();
  }
  //! Restores everything from a checkpoint; returns true when the run it holds has reached time.end, and
  //! otherwise cuts the CSVs back and rewrites the collections to it (CheckpointReader::finish()).
  bool read_checkpoint(CheckpointReader& r) {
    gas_.read_checkpoint(r);
    rock_.read_checkpoint(r);
    coupler_.read_checkpoint(r);
    gas_out_.read_checkpoint(r);
    rock_out_.read_checkpoint(r);
    series_.read_checkpoint(r);
    blasthole_.read_checkpoint(r);
    charges_.read_checkpoint(r);
    warned_ = r.value<int>("run.warned") != 0;
    const bool finished = gas_.time() >= c_.time.end * (1 - 1e-12);
    r.finish(!finished);
    if (!finished)
      log_ << fmt::format("restarted from {} at step {} (t = {:.6e} s)\n", checkpoint_path_, gas_.steps(), gas_.time());
    return finished;
  }

  double next_event(double t) const override { return gas_out_.next_event(t); }
  //! What the schedule asks for, then the checkpoint with a scheduled snapshot, then (at the end) the snapshot
  //! and the CSV rows that close the run. The checkpoint comes before those closing outputs, so a restart
  //! with a later time.end continues exactly as a run made with that end time from the start.
  void after_step(double dt, bool last) override {
    const bool snapshot = gas_out_.write_due(dt, false);
    if (snapshot) rock_out_.snapshot();
    const bool row = gas_.steps() % c_.output.monitor_interval == 0;
    if (row) write_rows();
    blasthole_.sample();
    if (snapshot) blasthole_.write_summary(rock_.energies(), charges_.summary() + rock_out_.summary());
    if (snapshot && c_.output.checkpoint) write_checkpoint();
    if (!last) return;
    gas_out_.write_end(dt, snapshot);
    if (!snapshot) rock_out_.snapshot();
    if (!row) write_rows();
    if (!snapshot) blasthole_.write_summary(rock_.energies(), charges_.summary() + rock_out_.summary());
  }
  //! One row of rock_series.csv and coupling_series.csv, and the budget warning.
  void write_rows() {
    rock_out_.monitor();
    const double drift = series_.write();
    charges_.sample(gas_.time());
    if (!warned_ && std::fabs(drift) > c_.output.drift_warning) {
      warned_ = true;
      log_ << fmt::format("warning: the gas + rock energy budget is off by {:+.3e} of the initial energy and the charges' (> "
                          "output.drift_warning = {:g}) at step {} (t = {:.6e} s); coupling_series.csv has the history\n",
                          drift, c_.output.drift_warning, gas_.steps(), gas_.time());
    }
  }
  void finish() override {
    const fdem::RockEnergies e = rock_.energies();
    const ibm::CouplingDiagnostics d = coupler_.diagnostics();
    blasthole_.write_summary(e, charges_.summary() + rock_out_.summary());
    log_ << fmt::format("coupled: {} steps to t = {:.4e} s; {} joints broken, crack length {:.4f} m; gas work on the rock "
                        "{:.4e} J/m\n", gas_.steps(), gas_.time(), e.broken_joints, e.crack_length, d.gas_work_on_rock);
    log_ << rock_out_.cost_note();
  }

 private:
  const Case& c_;
  cip::GasSolver& gas_;
  fdem::RockSolver& rock_;
  ibm::GasRockCoupler& coupler_;
  std::ostream& log_;
  GasOutputs gas_out_;
  RockOutputs rock_out_;
  CouplingSeries series_;
  BlastholeFiles blasthole_;
  ChargeFiles charges_;
  std::string checkpoint_path_;
  bool warned_ = false;  // the budget warning was printed
};

//! The log's line on the crack gas: its parameters as they act (the friction law, the hand-over width).
std::string crack_gas_line(const ibm::CrackGasOptions& o, const ibm::CrackGasCoupling& crack, const cip::GasGrid& grid) {
  const ibm::ChannelFlowParams f = o.flow();
  const ibm::HandoverGaps gaps = crack.handover_gaps(grid);
  const std::string friction =
      o.friction_factor ? fmt::format("friction factor {:.3g}", *o.friction_factor)
                        : fmt::format("Louis's friction of the roughness {:.3g} m (f = {:.3g} at an aperture of 10 x it)",
                                      f.roughness, ibm::louis_friction(0.05).turbulent);
  const ibm::CrackGasOptions& acting = crack.crack_gas().options();  // with the walls' temperature the coupler set
  const std::string walls =
      acting.walls == ibm::WallHeat::adiabatic
          ? std::string("adiabatic walls")
          : fmt::format("{} walls at p / rho = {:.4g} J/kg", ibm::wall_heat_name(acting.walls), acting.wall_theta.value_or(0.0));
  const std::string closure =
      o.joint_closure ? fmt::format("open joints close by Barton-Bandis (K_ni {:.4g} Pa/m, V_m {:.4g} m)",
                                    o.joint_closure->stiffness, o.joint_closure->max_closure)
                      : std::string("open joints keep their initial aperture");
  return fmt::format("crack gas on (residual aperture {:.3g} m, {}, {}, {}, hand-over to the grid at {:.3g} m wide, {} "
                     "junctions)",
                     o.residual_aperture, friction, walls, closure, gaps.handover, crack.crack_gas().junction_count());
}

}  // namespace

void run_coupled_case(const Case& c, std::ostream& log, const RunOptions& options) {
  const GasSettings& g = c.gas;
  const CouplingSettings& k = c.coupling;
  if (c.output.vtk && !cip::vtk_available())
    throw InputError("output.vtk = true, but this build has no VTK: set output.vtk = false (CSV output still works)");
  if (c.rock.model.in_situ && c.rock.model.in_situ->equilibrate && !options.restart)
    log << fmt::format("in-situ stress: relaxing the rock to rest before t = 0 (at most {} steps)\n",
                       c.rock.model.in_situ->equilibrium.max_steps)
        << std::flush;
  fdem::RockModel model = make_rock_model(c, options.restart, &log);
  fdem::RockSolver& rock = *model.solver;
  const double rock_dt = rock_time_step(c, rock);  // checks a fixed dt against the rock's stable step
  cip::GasSolver gas(g.grid, g.materials(), g.solver);
  gas.initialise([&](double x, double y) { return g.initial_state(x, y); });
  ibm::CouplerOptions coupling;
  coupling.gas_load = k.gas_load;
  coupling.courant = g.courant;
  coupling.rock_dt = rock_dt;
  coupling.rock_subcycling = c.time.rock_subcycling;
  coupling.fixed_dt = c.time.dt;
  ibm::GasRockCoupler coupler(gas, rock, g.ambient, coupling);
  if (k.crack_gas) {
    ibm::CrackGasCoupling& crack = coupler.enable_crack_gas(k.crack_gas_options);
    for (std::size_t n = 0; n < model.crack_joints.size(); ++n)
      if (c.rock.model.cracks[n].initial_aperture > 0)
        crack.set_initial_apertures(model.crack_joints[n], c.rock.model.cracks[n].initial_aperture);
    for (std::size_t n = 0; n < model.set_joints.size(); ++n)  // open joint sets stand open like pre-cut cracks
      if (c.rock.model.joint_sets[n].open && c.rock.model.joint_sets[n].initial_aperture > 0)
        crack.set_initial_apertures(model.set_joints[n], c.rock.model.joint_sets[n].initial_aperture);
  }
  if (!k.charges.empty()) {
    coupler.set_charges(k.charges, k.charge_products);
    const ibm::ChargeProducts& q = k.charge_products;
    log << fmt::format("charges: {}; products start at rho0 {:g} kg/m3, e0 {:.4g} J/kg: p(rho0, e0) = {:.4g} Pa (rho0 D^2 / 8 = "
                       "{:.4g} Pa with D = {:g} m/s)\n", k.charges.size(), q.density, q.specific_energy,
                       g.explosive->pressure(q.density, q.specific_energy),
                       q.density * g.detonation_velocity * g.detonation_velocity / 8, g.detonation_velocity);
  }
  const bool resume = options.restart;
  if (!resume) coupler.rock_to_gas();  // masks first: cells under rock take the ambient state before any output
  log << fmt::format("coupled: gas {} x {} cells of {:.4g} x {:.4g} m ({} covered by rock); rock {} triangles, {} joints, "
                     "stable step {:.4g} s; gas load on the rock: {}; {}\n",
                     g.grid.nx, g.grid.ny, g.grid.dx, g.grid.dy, coupler.inactive_cells(), rock.triangle_count(),
                     rock.joint_count(), rock.stable_dt(), ibm::gas_load_name(k.gas_load),
                     k.crack_gas ? crack_gas_line(k.crack_gas_options, *coupler.crack_gas(), g.grid)
                                 : std::string("crack gas off"));
  if (!c.rock.model.cracks.empty()) {
    std::size_t joints = 0;
    for (const std::vector<int>& j : model.crack_joints) joints += j.size();
    log << fmt::format("pre-cut cracks: {} ({} joints broken at the start)\n", model.crack_joints.size(), joints);
  }
  log << joint_sets_line(c, model);
  log << in_situ_line(c, model);
  if (g.materials().tracer) log << "blast gas traced: the gas of the [[gas.region]] tables with blast_gas = true\n";
  std::string stages = coupler.schedule();  // a line a stage, made one line: "stage: processes; ..."
  if (!stages.empty() && stages.back() == '\n') stages.pop_back();
  for (std::size_t k = stages.find('\n'); k != std::string::npos; k = stages.find('\n', k)) stages.replace(k, 1, "; ");
  log << "coupling stages: " << stages << "\n";
  // A restart accepts its checkpoint (checksum, structure, the same case) before it touches the output folder.
  const std::string checkpoint_path = (std::filesystem::path(c.output.directory) / "checkpoint.bin").string();
  std::optional<CheckpointReader> reader;
  if (resume) {
    reader.emplace(checkpoint_path);
    check_same_case(reader->text("case"), checkpoint_case_text(c), checkpoint_path);
  }
  CoupledRunOutputs outputs(c, gas, rock, coupler, model, log, resume);
  if (resume) {
    if (outputs.read_checkpoint(*reader)) {  // a finished run: read and checked, nothing changed
      log << fmt::format("--restart: the checkpoint is at t = {:.6e} s, at or past time.end = {:g} s: nothing to do; "
                         "the outputs in {} are left as they are\n", gas.time(), c.time.end, c.output.directory);
      return;
    }
  } else {
    outputs.start();
  }
  CoupledStepper stepper(c, gas, rock, coupler);
  run_loop(stepper, outputs, RunControl{c.time.end, c.time.max_steps, c.output.progress_interval}, log, options);
}

}  // namespace blastsim::app
