//! \file coupled_run.cpp
//! \brief The coupled gas-rock time loop of the driver (libibm's GasRockCoupler) and its outputs: the gas's
//! and the rock's files, and coupling_series.csv with the energy budget of the whole system.
#include "coupled_run.hpp"

#include "blastsim/core/error.hpp"
#include "blastsim/ibm/coupler.hpp"
#include "gas_outputs.hpp"
#include "rock_outputs.hpp"

#include <chrono>
#include <optional>

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
  //! initial gas + rock energy + work of non-gas loads + energy the cell transitions created + work of the
  //! rock's face impulses on the gas (GasSolver::immersed_face_work) = gas energy + what left the grid + rock
  //! kinetic + strain + joint work + contact work + damping.
  double write() {
    const cip::GasTotals g = gas_.totals();
    const fdem::RockEnergies e = rock_.energies();
    const ibm::CouplingDiagnostics d = coupler_.diagnostics();
    const double out = gas_.boundary_outflow().energy, other = e.external_work - e.pressure_work;
    const double now = g.total_energy() + out + e.kinetic + e.strain + e.joint_work + e.contact_work + e.damping_dissipated;
    const double face_work = gas_.immersed_face_work();
    const double residual = now - (initial_ + other + d.transitions.energy_created + face_work);
    std::string row = fmt::format("{},{:.9e},{:.9e},{:.9e},{:.9e},{:.9e},{:.9e},{:.9e},{:.9e},{:.9e},{:.9e},{:.9e},{:.9e},{:.9e},"
                         "{:.9e},{:.6e},{:.6e},{:.6e},{:.6e},{},{:.6e},{},{},{:.9e}",
                         gas_.steps(), gas_.time(), g.mass, g.internal_energy, g.kinetic_energy, out, e.kinetic, e.strain,
                         e.joint_work, e.fracture_dissipated, e.contact_work, e.damping_dissipated, d.gas_work_on_rock,
                         other, d.transitions.energy_created, residual, residual / initial_, d.gas_force_on_rock[0],
                         d.gas_force_on_rock[1], e.broken_joints, e.crack_length, d.transitions.covered,
                         d.transitions.uncovered, face_work);
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
                    "gas_force_y_N_per_m,broken_joints,crack_length_m,cells_covered,cells_uncovered,"
                    "immersed_face_work_J_per_m";
    for (const MonitorRegion& r : c.regions) h += fmt::format(",{0}_mass_kg_per_m,{0}_energy_J_per_m", r.name);
    return h;
  }
};

//! Blasthole monitor, for a rock made as a disc with a hole (the single-hole blast): wall_series.csv (gas
//! pressure just inside the hole wall, mean, min and max of 64 points, against the rock's radial stress at the
//! wall, mean, min and max of 8 sector values, and their spread: S1 / the paper's Fig. 4b; the gas at the
//! rock's outer surface) every monitor.interval, and summary.txt with the events the paper
//! reports: the first crack, and the first time detonation gas leaves the outer surface, with its speed.
class BlastholeMonitor {
 public:
  BlastholeMonitor(const CoupledCaseConfig& c, cip::GasSolver& gas, fdem::RockSolver& rock, bool resume)
      : c_(c), gas_(gas), rock_(rock), active_(c.rock.mesh.shape == "disc_with_hole"),
        file_(active_ ? std::optional<CsvSeries>(std::in_place, (make_output_dir(c.gas.output_directory) / "wall_series.csv").string(),
                                                 wall_header(), resume)
                      : std::nullopt) {
    const RockMeshSpec& m = c.rock.mesh;
    const double h = std::min(c.gas.grid.dx, c.gas.grid.dy);
    // Gas at the wall: 1.5 cells inside it, where the bilinear stencil of the samples holds only hole cells
    // (closer in, it reaches the inactive cells under the rock, which hold the ambient state).
    const double r_wall = std::max(0.0, m.hole_radius - 1.5 * std::max(c.gas.grid.dx, c.gas.grid.dy));
    for (int k = 0; k < kWallPoints; ++k) {
      const double th = 2 * M_PI * (k + 0.5) / kWallPoints;
      points_.push_back({m.center[0] + r_wall * std::cos(th), m.center[1] + r_wall * std::sin(th)});
    }
    const int ring = std::max(64, static_cast<int>(2 * M_PI * m.radius / h));  // just outside the outer surface
    for (int k = 0; k < ring; ++k) {
      const double th = 2 * M_PI * (k + 0.5) / ring;
      points_.push_back({m.center[0] + (m.radius + 0.5 * h) * std::cos(th), m.center[1] + (m.radius + 0.5 * h) * std::sin(th)});
      outward_.push_back({std::cos(th), std::sin(th)});
    }
    p_ambient_ = c.gas.eos.pressure(c.gas.ambient.density, c.gas.ambient.internal_energy);
  }

  void sample() {
    if (!active_ || gas_.time() < next_ - 1e-12 * c_.gas.end_time) return;
    while (next_ <= gas_.time() + 1e-12 * c_.gas.end_time) next_ += c_.monitor_interval;
    const std::vector<cip::GasSample> g = gas_.sample(points_);
    double pm = 0, pmin = 1e300, pmax = -1e300;
    for (int k = 0; k < kWallPoints; ++k) pm += g[k].p / kWallPoints, pmin = std::min(pmin, g[k].p), pmax = std::max(pmax, g[k].p);
    // Rock: radial stress at the hole wall per 45-degree sector, from a least-squares fit of Lame's form
    // sigma_rr = A + B / r^2 to the triangles centred within three hole radii, evaluated at the wall (one
    // constant-strain triangle at the wall is too coarse a sample; test I4 uses the same estimate).
    const fdem::RockSnapshot snap = rock_.snapshot();
    const RockMeshSpec& m = c_.rock.mesh;
    std::array<std::array<double, 5>, kSectors> fit{};  // sums of 1, q, q^2, s, s q with q = 1/r^2
    for (size_t t = 0; t < snap.stress.size() / 3; ++t) {
      const double cx = (snap.x[3 * t] + snap.x[3 * t + 1] + snap.x[3 * t + 2]) / 3 - m.center[0];
      const double cy = (snap.y[3 * t] + snap.y[3 * t + 1] + snap.y[3 * t + 2]) / 3 - m.center[1];
      const double r = std::hypot(cx, cy);
      if (r > 3 * m.hole_radius) continue;
      const double cs = cx / r, sn = cy / r, q = 1 / (r * r);
      const double srr = snap.stress[3 * t] * cs * cs + 2 * snap.stress[3 * t + 1] * sn * cs + snap.stress[3 * t + 2] * sn * sn;
      std::array<double, 5>& f = fit[static_cast<int>(std::floor((std::atan2(cy, cx) + M_PI) / (2 * M_PI) * kSectors)) % kSectors];
      f[0] += 1, f[1] += q, f[2] += q * q, f[3] += srr, f[4] += srr * q;
    }
    double sm = 0, smin = 1e300, smax = -1e300;
    int n = 0;
    for (const std::array<double, 5>& f : fit) {
      const double det = f[0] * f[2] - f[1] * f[1];
      if (f[0] < 3 || det <= 0) continue;
      const double A = (f[3] * f[2] - f[4] * f[1]) / det, B = (f[0] * f[4] - f[1] * f[3]) / det;
      const double wall = A + B / (m.hole_radius * m.hole_radius);
      sm += wall, smin = std::min(smin, wall), smax = std::max(smax, wall), ++n;
    }
    if (n > 0) sm /= n;
    const double spread = n > 0 && sm != 0 ? (smax - smin) / std::fabs(sm) : 0.0;  // symmetry (S1)
    // Gas at the outer surface: detonation gas is taken to have left the rock where the pressure just outside
    // the original surface exceeds twice the ambient (the air pushed by the rock stays within a few kPa).
    // The outflow's speed: the mass-flux-weighted mean outward speed, sum rho u_n^2 / sum rho u_n, over the
    // points where such gas flows out (u_n > 0), and the largest single outward speed there.
    double out_p = 0, out_speed = 0, flux = 0, momentum_flux = 0;
    for (size_t k = kWallPoints; k < g.size(); ++k) {
      out_p = std::max(out_p, g[k].p);
      const std::array<double, 2>& o = outward_[k - kWallPoints];
      const double un = g[k].u * o[0] + g[k].v * o[1];
      if (g[k].p > 2 * p_ambient_ && un > 0) {
        out_speed = std::max(out_speed, un);
        flux += g[k].rho * un, momentum_flux += g[k].rho * un * un;
      }
    }
    const double flux_speed = flux > 0 ? momentum_flux / flux : 0.0;
    const fdem::RockEnergies e = rock_.energies();
    file_->row(fmt::format("{:.9e},{:.6e},{:.6e},{:.6e},{:.6e},{:.6e},{:.6e},{:.4e},{},{:.6e},{:.6e},{:.6e},{:.6e}", gas_.time(),
                          pm, pmin, pmax, sm, smin, smax, spread, e.broken_joints, e.crack_length, out_p, out_speed, flux_speed));
    if (first_crack_ < 0 && e.broken_joints > 0) first_crack_ = gas_.time();
    if (ejection_ < 0 && out_p > 2 * p_ambient_) ejection_ = gas_.time(), ejection_speed_ = out_speed, ejection_p_ = out_p;
    if (ejection_ >= 0 && flux_speed > jet_speed_) jet_speed_ = flux_speed, jet_time_ = gas_.time();
  }

  //! summary.txt: the events, how each is measured, and where the paper puts them.
  void write_summary(const fdem::RockEnergies& e) const {
    if (!active_) return;
    const RockMeshSpec& m = c_.rock.mesh;
    auto when = [](double t) { return t < 0 ? std::string("not reached") : fmt::format("{:.4e} s ({:.3f} ms)", t, 1e3 * t); };
    write_atomically((std::filesystem::path(c_.gas.output_directory) / "summary.txt").string(), [&](std::ostream& out) {
      out << fmt::format("blastsim single-hole summary at t = {:.4e} s (step {})\n\n", gas_.time(), gas_.steps());
      out << fmt::format("first crack: {}\n  the first sample (every {:g} s) with a broken joint\n", when(first_crack_),
                         c_.monitor_interval);
      out << fmt::format("gas leaves the rock's outer surface: {} (paper: about 3.14 ms)\n", when(ejection_));
      out << fmt::format("  the first sample where the gas pressure on the circle half a cell outside the rock's outer\n"
                         "  radius ({:g} m) exceeds twice the ambient pressure ({:.4g} Pa); pressure there then {:.4g} Pa\n",
                         m.radius, p_ambient_, ejection_p_);
      out << fmt::format("nominal gas speed there: {} (paper: about 214 m/s)\n",
                         ejection_ < 0 ? std::string("-") : fmt::format("{:.1f} m/s at {:.3f} ms", jet_speed_, 1e3 * jet_time_));
      out << "  the mass-flux-weighted mean outward speed (sum rho u_n^2 / sum rho u_n) over the points of that circle\n"
             "  where the pressure exceeds twice the ambient and the gas flows out; its largest value over the samples\n"
             "  from the first outflow to the end of the run\n";
      out << fmt::format("gas speed at the onset: {}\n  the largest outward speed among those points at the first "
                         "outflow sample\n", ejection_ < 0 ? std::string("-") : fmt::format("{:.1f} m/s", ejection_speed_));
      out << fmt::format("broken joints: {}; crack length {:.4f} m; fracture energy {:.4e} J/m\n", e.broken_joints,
                         e.crack_length, e.fracture_dissipated);
    });
  }

  void write_checkpoint(CheckpointWriter& w) {
    w.value("out.blasthole.events",
            std::array<double, 7>{next_, first_crack_, ejection_, ejection_speed_, ejection_p_, jet_speed_, jet_time_});
    w.value("out.blasthole.csv_size", active_ ? file_->size() : std::uint64_t{0});
  }
  void read_checkpoint(CheckpointReader& r) {
    const std::array<double, 7> v = r.value<std::array<double, 7>>("out.blasthole.events");
    next_ = v[0], first_crack_ = v[1], ejection_ = v[2], ejection_speed_ = v[3], ejection_p_ = v[4];
    jet_speed_ = v[5], jet_time_ = v[6];
    const std::uint64_t size = r.value<std::uint64_t>("out.blasthole.csv_size");
    if (active_) file_->truncate_to(size);
  }

 private:
  static constexpr int kWallPoints = 64, kSectors = 8;
  const CoupledCaseConfig& c_;
  cip::GasSolver& gas_;
  fdem::RockSolver& rock_;
  bool active_;
  std::optional<CsvSeries> file_;  // only for a disc with a hole

  static std::string wall_header() {
    return "time_s,gas_pressure_wall_mean_Pa,gas_pressure_wall_min_Pa,gas_pressure_wall_max_Pa,"
           "rock_radial_stress_wall_mean_Pa,rock_radial_stress_wall_min_Pa,rock_radial_stress_wall_max_Pa,"
           "rock_radial_stress_wall_sector_spread,broken_joints,crack_length_m,outer_surface_gas_pressure_max_Pa,"
           "outer_surface_gas_speed_max_m_per_s,outer_surface_gas_speed_flux_mean_m_per_s";
  }
  std::vector<std::array<double, 2>> points_, outward_;
  double p_ambient_ = 0, next_ = 0, first_crack_ = -1, ejection_ = -1, ejection_speed_ = 0, ejection_p_ = 0;
  double jet_speed_ = 0, jet_time_ = -1;  // largest flux-weighted outflow speed [m/s] since the first outflow, and when
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
  RockModel model = make_rock_model(c.rock);
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
  RockOutputs rock_out(c.rock, model, resume);
  CouplingSeries series(c, gas, rock, coupler, resume);
  BlastholeMonitor blasthole(c, gas, rock, resume);
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
    blasthole.write_checkpoint(w);
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
    blasthole.read_checkpoint(r);
    warned = r.value<int>("run.warned") != 0;
    log << fmt::format("restarted from {} at step {} (t = {:.6e} s)\n", checkpoint_path, gas.steps(), gas.time());
  } else {
    gas_out.write_due(0.0, true);
    rock_out.snapshot();
    rock_out.monitor();
    series.write();
    blasthole.sample();
    if (c.checkpoint) write_checkpoint();
  }

  const auto wall_start = Clock::now();
  auto last_progress = wall_start;
  double rate = checked_signal_rate(gas, gc.output_directory);
  int substeps = 1;
  while (gas.time() < gc.end_time * (1 - 1e-12)) {
    if (gc.max_steps > 0 && gas.steps() >= gc.max_steps) {
      log << fmt::format("stopping at time.max_steps = {} (t = {:.6e} s)\n", gc.max_steps, gas.time());
      break;
    }
    double dt = 0;
    if (gc.fixed_dt) {
      dt = *gc.fixed_dt;
      check_fixed_dt_courant(dt, rate, gc.courant, gas);
    } else {  // the gas Courant limit, and the rock's step unless the rock subcycles (docs/coupling.md)
      dt = c.rock_subcycling ? gc.courant / rate : std::min(gc.courant / rate, rock_dt);
      const double next = gas_out.next_event(gas.time());
      if (gas.time() + dt > next) dt = next - gas.time();
    }
    substeps = c.rock_subcycling ? ibm::rock_substeps(dt, rock_dt) : 1;
    coupler.step(dt, substeps);  // rock -> gas, gas, gas -> rock, rock (throws InstabilityError on a non-finite rock)
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
    blasthole.sample();
    if (snapshot) blasthole.write_summary(rock.energies());
    if (snapshot && c.checkpoint) write_checkpoint();
    const auto now = Clock::now();
    if (!options.quiet && (std::chrono::duration<double>(now - last_progress).count() >= gc.progress_interval || last)) {
      const fdem::RockEnergies e = rock.energies();
      log << progress_line(gas.steps(), gas.time(), dt, gc.end_time, std::chrono::duration<double>(now - wall_start).count(),
                           fmt::format("{}  broken joints {}  crack length {:.3f} m",
                                       c.rock_subcycling ? fmt::format("  rock substeps {}", substeps) : std::string(),
                                       e.broken_joints, e.crack_length))
          << std::flush;
      last_progress = now;
    }
  }
  const fdem::RockEnergies e = rock.energies();
  const ibm::CouplingDiagnostics d = coupler.diagnostics();
  blasthole.write_summary(e);
  log << fmt::format("coupled: {} steps to t = {:.4e} s; {} joints broken, crack length {:.4f} m; gas work on the rock "
                     "{:.4e} J/m\n", gas.steps(), gas.time(), e.broken_joints, e.crack_length, d.gas_work_on_rock);
}

}  // namespace blastsim::app
