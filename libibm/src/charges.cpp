//! \file charges.cpp
//! \brief Charges: the charge cells (charge_kernels.hpp's lists), their walls and burn, the borehole pressures.
#include "blastsim/ibm/charges.hpp"

#include "blastsim/core/checkpoint.hpp"
#include "blastsim/core/device_groups.hpp"
#include "blastsim/core/error.hpp"
#include "blastsim/core/output_files.hpp"
#include "blastsim/ibm/charge_kernels.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace blastsim::ibm {

namespace detail {
BLASTSIM_CONST_STORAGE(ChargeCellParams, BLASTSIM_CHARGE_CELL_PARAMS)
BLASTSIM_STATE_STORAGE(ChargeLedgers, BLASTSIM_CHARGE_LEDGER)
struct ChargeArrays {
  ChargeCellParamsArrays cells;  // per cell i + nx j
  ChargeLedgersArrays ledger;    // per cell
};
}  // namespace detail

namespace {
//! The cells i0..i1, j0..j1 (inclusive, clipped to the grid) whose centres may lie within r [m] of c.
struct CellBox {
  int i0, i1, j0, j1;
  index_t count() const { return static_cast<index_t>(i1 - i0 + 1) * (j1 - j0 + 1); }
};
CellBox cells_around(const cip::GasGrid& g, const std::array<double, 2>& c, double r) {
  return {std::max(0, static_cast<int>(std::floor((c[0] - r - g.x_min) / g.dx))),
          std::min(g.nx - 1, static_cast<int>(std::ceil((c[0] + r - g.x_min) / g.dx))),
          std::max(0, static_cast<int>(std::floor((c[1] - r - g.y_min) / g.dy))),
          std::min(g.ny - 1, static_cast<int>(std::ceil((c[1] + r - g.y_min) / g.dy)))};
}
ChargeCells charge_cells(const detail::ChargeArrays& a, const cip::GasGrid& g) { return {a.cells.view(), g.nx, g.ny}; }
}  // namespace

Charges::Charges(const cip::GasSolver& gas, const std::vector<Charge>& charges, const ChargeProducts& products)
    : charges_(charges), products_(products), burnt_until_(-std::numeric_limits<double>::infinity()),
      a_(std::make_unique<detail::ChargeArrays>()) {
  if (!gas.materials().two)
    throw InputError("charges: the gas has no detonation products (GasMaterials::two is off); give the explosive");
  if (!(products.density > 0) || !std::isfinite(products.specific_energy))
    throw InputError("charges: the products' state needs a positive density and a finite energy");
  const cip::GasGrid g = gas.grid();
  const index_t cells = static_cast<index_t>(g.nx) * g.ny;
  std::vector<int> owner(cells, -1);
  std::vector<double> burn(cells, 0.0);
  for (std::size_t k = 0; k < charges.size(); ++k) {
    const Charge& c = charges[k];
    const std::string name = "charge " + std::to_string(k);
    if (!(c.radius > 0) || !(c.radius <= c.hole_radius))
      throw InputError(name + ": radius " + std::to_string(c.radius) + " m must be > 0 and <= the hole radius " +
                       std::to_string(c.hole_radius) + " m");
    if (c.initiation == Initiation::point && !(c.detonation_velocity > 0))
      throw InputError(name + ": a point initiation needs a detonation velocity > 0");
    if (!(c.initiation_time >= 0)) throw InputError(name + ": initiation time must be >= 0 s");
    int count = 0;
    std::array<double, 2> window{std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()};
    const CellBox box = cells_around(g, c.center, c.radius);
    for (int j = box.j0; j <= box.j1; ++j)
      for (int i = box.i0; i <= box.i1; ++i) {
        const double x = g.x_min + (i + 0.5) * g.dx, y = g.y_min + (j + 0.5) * g.dy;
        if (std::hypot(x - c.center[0], y - c.center[1]) > c.radius) continue;
        const index_t cell = static_cast<index_t>(j) * g.nx + i;
        if (owner[cell] >= 0)
          throw InputError(name + " and charge " + std::to_string(owner[cell]) + " overlap (they share cell " +
                           std::to_string(i) + ", " + std::to_string(j) + ")");
        owner[cell] = static_cast<int>(k);
        burn[cell] = lighting_time(c, x, y);
        window[0] = std::min(window[0], burn[cell]), window[1] = std::max(window[1], burn[cell]);
        ++count;
      }
    if (count == 0)
      throw InputError(name + ": radius " + std::to_string(c.radius) + " m holds no cell centre of the gas grid (cells " +
                       std::to_string(g.dx) + " m): refine the grid");
    window_.push_back(window);
  }
  copy_from_host(a_->cells.charge, owner);
  copy_from_host(a_->cells.burn_time, burn);
  a_->ledger.burn.assign(cells, ChargeLedger{0, 0, 0, 0});
}

Charges::~Charges() = default;

void Charges::run(Stage stage, CouplingContext& ctx, const StageStep& /*step*/) {
  switch (stage) {
    case Stage::cover: return cover(ctx);
    case Stage::after_cells: return after_cells(ctx);
    default: stage_not_run(*this, stage);
  }
}

void Charges::report(const CouplingDiagnostics& d, CsvRecord& o) const {
  o.real("charge_detonation_energy_J_per_m", d.charges.detonation_energy);
}

void Charges::cover(CouplingContext& ctx) {
  const cip::GasGrid g = ctx.gas.grid();
  const ChargeCells cells = charge_cells(*a_, g);
  const double t = ctx.gas.time();
  for_each_cell("ibm.charge.cover.u", 0, g.nx + 1, 0, g.ny, ChargeCoverKernel{cells, 0, t, ctx.owners.u});
  for_each_cell("ibm.charge.cover.v", 0, g.nx, 0, g.ny + 1, ChargeCoverKernel{cells, 1, t, ctx.owners.v});
}

void Charges::after_cells(CouplingContext& ctx) {
  if (ctx.first) return;  // the run's initial state; the budget counts what burning adds
  const cip::GasGrid g = ctx.gas.grid();
  const double t = ctx.gas.time();
  for_each_cell("ibm.charge.burn", 0, g.nx, 0, g.ny,
                ChargeBurnKernel{charge_cells(*a_, g), ctx.gas.immersed_boundary().cell_active, a_->ledger.view(),
                                 burnt_until_, t, g.cell_area(), products_, ctx.gas.cells()});
  burnt_until_ = t;
}

bool Charges::due(double t) const {
  for (const std::array<double, 2>& w : window_)
    if (w[0] <= t && burnt_until_ < w[1] && burnt_until_ < t) return true;
  return false;
}

double Charges::next_event(double t) const {
  double next = std::numeric_limits<double>::infinity();
  for (const Charge& c : charges_)
    if (c.initiation_time > t) next = std::min(next, c.initiation_time);
  return next;
}

std::vector<double> Charges::pressures(const cip::GasSolver& gas, double ambient_pressure) const {
  const cip::GasGrid g = gas.grid();
  const cip::GasMaterials mat = gas.materials();
  const cip::MaterialReadView m = gas.material_fields();
  const cip::GasStateReadView s = gas.state();
  const Field2D<const std::uint8_t> active = gas.immersed_boundary().cell_active;
  std::vector<double> out;
  for (const Charge& c : charges_) {
    const CellBox box = cells_around(g, c.center, c.hole_radius);
    const int i0 = box.i0, j0 = box.j0, ni = box.i1 - box.i0 + 1;
    const double cx = c.center[0], cy = c.center[1], r = c.hole_radius;
    const Vec2Sum sum = reduce_sum("ibm.charge.pressure", box.count(), Vec2Sum{0, 0},
                                   HoleCellPressure{g, mat, m, s, active, i0, j0, ni, cx, cy, r});
    out.push_back(sum.y > 0 ? sum.x / sum.y : ambient_pressure);
  }
  return out;
}

std::vector<double> Charges::energies(const cip::GasSolver& gas) const {
  std::vector<double> out;
  const cip::GasGrid g = gas.grid();
  const int nx = g.nx;
  for (std::size_t k = 0; k < charges_.size(); ++k) {
    const CellBox box = cells_around(g, charges_[k].center, charges_[k].radius);  // its cells lie in there
    const int kk = static_cast<int>(k), i0 = box.i0, j0 = box.j0, ni = box.i1 - box.i0 + 1;
    out.push_back(reduce_sum("ibm.charge.energy", box.count(), 0.0,
                             ChargeCellEnergy{a_->cells.view(), a_->ledger.read(), nx, i0, j0, ni, kk}));
  }
  return out;
}

void Charges::add_diagnostics(const CouplingContext& /*ctx*/, CouplingDiagnostics& d) const {
  const ChargeLedger* led = a_->ledger.read().burn;
  const ChargeCellParams cells = a_->cells.view();
  const double until = burnt_until_;
  const index_t n = static_cast<index_t>(a_->ledger.burn.size());
  auto total = [&](double ChargeLedger::*field) {
    return reduce_sum("ibm.charge.ledger", n, 0.0, FieldOf<ChargeLedger>{led, field});
  };
  ChargeTotals& q = d.charges;
  q.products_mass = total(&ChargeLedger::products_mass);
  q.detonation_energy = total(&ChargeLedger::detonation_energy);
  q.replaced_mass = total(&ChargeLedger::replaced_mass);
  q.replaced_energy = total(&ChargeLedger::replaced_energy);
  q.burnt_cells = std::lround(reduce_sum("ibm.charge.burnt", n, 0.0, BurntChargeCell{cells, until}));
  d.energy_added += q.detonation_energy - q.replaced_energy;
}

void Charges::write_checkpoint(CheckpointWriter& w) const {
  write_array(w, "ibm.charge.ledger", a_->ledger.burn);
  w.value("ibm.charge.burnt_until", burnt_until_);
}

void Charges::read_checkpoint(CheckpointReader& r) {
  read_array(r, "ibm.charge.ledger", a_->ledger.burn, a_->ledger.burn.size());
  burnt_until_ = r.value<double>("ibm.charge.burnt_until");
  if (std::isnan(burnt_until_)) r.fail("ibm.charge.burnt_until", "not a number");
}

}  // namespace blastsim::ibm
