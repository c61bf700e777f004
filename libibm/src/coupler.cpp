//! \file coupler.cpp
//! \brief GasRockCoupler: its processes in order at every stage of a coupled step, the dt policy, the step's one
//! reduction, the diagnostics and the checkpoint.
#include "blastsim/ibm/coupler.hpp"

#include "blastsim/core/backend.hpp"
#include "blastsim/core/checkpoint.hpp"
#include "blastsim/core/output_files.hpp"
#include "blastsim/ibm/coupler_kernels.hpp"

#include <stdexcept>

namespace blastsim::ibm {

const char* stage_name(Stage s) {
  static constexpr const char* names[kStageCount] = {"cover",     "update_cells", "after_cells",      "before_gas",
                                                     "after_gas", "load_rock",    "before_rock_step", "after_rock"};
  const int k = static_cast<int>(s);
  return k >= 0 && k < kStageCount ? names[k] : "(no stage)";
}

void stage_not_run(const CouplingProcess& process, Stage stage) {
  throw std::logic_error(std::string("coupling process '") + process.name() + "' was run at stage " + stage_name(stage) +
                         ", which it does not declare");
}

GasRockCoupler::GasRockCoupler(cip::GasSolver& gas, fdem::RockSolver& rock, const cip::GasPoint& ambient,
                               const CouplerOptions& options)
    : gas_(gas), rock_(rock), ambient_(ambient), options_(options) {
  if (!(options_.rock_dt > 0)) options_.rock_dt = rock.stable_dt();
  immersed_ = static_cast<ImmersedBoundary*>(
      &add(std::make_unique<ImmersedBoundary>(gas.grid(), face_point_rule(options.gas_load))));
  add(std::make_unique<GasLoading>(options.gas_load));
}

GasRockCoupler::~GasRockCoupler() = default;

CouplingProcess& GasRockCoupler::add(std::unique_ptr<CouplingProcess> process) {
  for (const Stage s : process->stages()) {
    const int k = static_cast<int>(s);
    if (k < 0 || k >= kStageCount)
      throw std::invalid_argument(std::string("GasRockCoupler::add: ") + process->name() + " declares an unknown stage");
    std::vector<CouplingProcess*>& list = schedule_[k];
    if (std::find(list.begin(), list.end(), process.get()) == list.end()) list.push_back(process.get());
  }
  processes_.push_back(std::move(process));
  return *processes_.back();
}

std::string GasRockCoupler::schedule() const {
  std::string out;
  for (int k = 0; k < kStageCount; ++k) {
    if (schedule_[k].empty()) continue;
    out += stage_name(static_cast<Stage>(k));
    for (std::size_t i = 0; i < schedule_[k].size(); ++i) out += (i ? ", " : ": ") + std::string(schedule_[k][i]->name());
    out += "\n";
  }
  return out;
}

void GasRockCoupler::run(Stage stage, CouplingContext& ctx, const StageStep& step) {
  for (CouplingProcess* p : schedule_[static_cast<int>(stage)]) p->run(stage, ctx, step);
}

CrackGasCoupling& GasRockCoupler::enable_crack_gas(const CrackGasOptions& options) {
  CrackGasOptions o = options;
  if (!o.wall_theta) o.wall_theta = ambient_pressure() / ambient_.density;  // the rock at the ambient air's temperature
  auto p = std::make_unique<CrackGasCoupling>(rock_, gas_.materials(), o);
  crack_ = p.get();
  add(std::move(p));
  return *crack_;
}

Charges& GasRockCoupler::set_charges(const std::vector<Charge>& charges, const ChargeProducts& products) {
  auto p = std::make_unique<Charges>(gas_, charges, products);
  charges_ = p.get();
  add(std::move(p));
  return *charges_;
}

double GasRockCoupler::ambient_pressure() const {
  return gas_.materials().air.pressure(ambient_.density, ambient_.internal_energy);
}

CouplingContext GasRockCoupler::context() const {
  double margin = 0.0;
  for (const auto& p : processes_) margin = std::max(margin, p->owner_margin(gas_.grid()));
  return {gas_, rock_, ambient_, ambient_pressure(), immersed_->owners(), immersed_->claims(), !masks_set_, margin};
}

void GasRockCoupler::rock_to_gas() {
  CouplingContext ctx = context();
  run(Stage::cover, ctx);
  run(Stage::update_cells, ctx);
  run(Stage::after_cells, ctx);
  masks_set_ = true;
  gas_.apply_boundaries();
}

void GasRockCoupler::gas_to_rock() {
  CouplingContext ctx = context();
  run(Stage::load_rock, ctx);
}

void GasRockCoupler::fire_due() {
  if (!masks_set_) return;
  for (const auto& p : processes_)
    if (p->due(gas_.time())) {
      rock_to_gas();
      signal_rate_ = std::numeric_limits<double>::quiet_NaN();  // the new gas sets the next dt
      return;
    }
}

CoupledStep GasRockCoupler::plan_step(double until) {
  fire_due();
  if (std::isnan(signal_rate_)) signal_rate_ = gas_.max_signal_rate();
  if (options_.fixed_dt)
    return {*options_.fixed_dt, options_.rock_subcycling ? rock_substeps(*options_.fixed_dt, options_.rock_dt) : 1};
  const double t = gas_.time();
  for (const auto& p : processes_) until = std::min(until, p->next_event(t));
  return plan_coupled_step(t, courant() / signal_rate_, options_.rock_dt, options_.rock_subcycling, until);
}

void GasRockCoupler::step(double dt, int rock_substeps) {
  if (rock_substeps < 1) throw std::invalid_argument("GasRockCoupler::step: rock_substeps must be at least 1");
  rock_to_gas();
  CouplingContext ctx = context();
  const StageStep whole{dt, 0, rock_substeps};
  run(Stage::before_gas, ctx, whole);
  gas_.step(dt);
  run(Stage::after_gas, ctx, whole);
  gas_to_rock();
  if (schedule_[static_cast<int>(Stage::before_rock_step)].empty()) {  // no process works between the substeps
    rock_.advance(dt / rock_substeps, rock_substeps);
  } else {
    const double substep = dt / rock_substeps;
    rock_.advance(substep, rock_substeps, [&](int k) {
      CouplingContext c = context();
      run(Stage::before_rock_step, c, StageStep{substep, k, rock_substeps});
    });
  }
  {
    CouplingContext c = context();
    run(Stage::after_rock, c, whole);
  }
  fire_due();  // before the next step chooses its dt: the products' sound speed must set it
  const cip::GasGrid& g = gas_.grid();
  const index_t cells = static_cast<index_t>(g.nx) * g.ny;
  const StepScalars s = reduce_with("ibm.step_scalars", cells + rock_.node_count(), StepScalars{0.0, 0.0},
                                    StepScalarsOf{gas_.signal_rate_kernel(), rock_.peak_speed_kernel(), cells},
                                    MaxOfStepScalars{});
  signal_rate_ = s.signal_rate;
  rock_.finish_motion(s.rock_speed);  // throws InstabilityError on a non-finite rock
}

double GasRockCoupler::stable_dt(double courant) const { return std::min(gas_.courant_dt(courant), rock_.stable_dt()); }

CouplingDiagnostics GasRockCoupler::diagnostics() const {
  CouplingDiagnostics d;
  const CouplingContext ctx = context();
  for (const auto& p : processes_) p->add_diagnostics(ctx, d);
  return d;
}

void GasRockCoupler::report(const CouplingDiagnostics& d, CsvRecord& o) const {
  for (const auto& p : processes_) p->report(d, o);
}

long GasRockCoupler::inactive_cells() const {
  const cip::GasGrid g = gas_.grid();
  const Field2D<const std::uint8_t> active = gas_.immersed_boundary().cell_active;
  const int nx = g.nx;
  return static_cast<long>(reduce_sum("ibm.inactive", static_cast<index_t>(g.nx) * g.ny, 0.0, InactiveCell{active, nx}));
}

void GasRockCoupler::write_checkpoint(CheckpointWriter& w) const {
  w.value("ibm.masks_set", static_cast<int>(masks_set_));
  for (const auto& p : processes_) p->write_checkpoint(w);
}

void GasRockCoupler::read_checkpoint(CheckpointReader& r) {
  const int masks = r.value<int>("ibm.masks_set");
  if (masks != 0 && masks != 1) r.fail("ibm.masks_set", "not 0 or 1");
  masks_set_ = masks == 1;
  for (auto& p : processes_) p->read_checkpoint(r);
  signal_rate_ = std::numeric_limits<double>::quiet_NaN();
}

}  // namespace blastsim::ibm
