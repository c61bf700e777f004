//! \file charge_kernels.hpp
//! \brief Kernels of the explosive charges (docs/coupling.md "Charges"): an unburnt charge as a solid in the
//! immersed-boundary masks, the burn of its cells at their lighting times, and the burn times themselves.
//! Charges (charges.hpp) launches them. Plain header: no backend dependency.
#pragma once

#include "blastsim/core/checkpoint_traits.hpp"
#include "blastsim/cip/gas_state.hpp"
#include "blastsim/core/access.hpp"
#include "blastsim/core/field2d.hpp"
#include "blastsim/core/macros.hpp"
#include "blastsim/ibm/charge_types.hpp"
#include "blastsim/ibm/coupling_kernels.hpp"
#include "blastsim/ibm/immersed_boundary_kernels.hpp"

#include <cmath>
#include <cstdint>

namespace blastsim::ibm {

//! Lighting time [s] of a point (x, y) [m] of a charge: its initiation time, plus, for a point initiation, the
//! time the detonation front needs to come from the initiation point at the detonation velocity (Wilkins'
//! programmed burn: the front is a circle |x - x0| = D (t - t0)). Host code (Charges tabulates it per cell).
inline double lighting_time(const Charge& c, double x, double y) {
  if (c.initiation != Initiation::point) return c.initiation_time;
  const double dx = x - c.point[0], dy = y - c.point[1];
  return c.initiation_time + std::sqrt(dx * dx + dy * dy) / c.detonation_velocity;
}

//! The charges' arrays, one entry per grid cell i + nx j, as field lists X(element type, name, comment)
//! (storage in charges.cpp): which charge holds the cell and when it lights (params), and what its burn put in.
#define BLASTSIM_CHARGE_CELL_PARAMS(X)                                       \
  X(int, charge, "the charge whose circle holds the cell centre, or -1")    \
  X(double, burn_time, "[s] the lighting time of the cell centre")
//! What the burn of one cell changed [per unit thickness].
struct ChargeLedger {
  double products_mass;      //!< [kg/m] the products it was given
  double detonation_energy;  //!< [J/m] their energy rho0 e0 A
  double replaced_mass;      //!< [kg/m] the gas it held before
  double replaced_energy;    //!< [J/m] that gas's internal energy
};
}  // namespace blastsim::ibm
BLASTSIM_CHECKPOINT_REALS(blastsim::ibm::ChargeLedger)
namespace blastsim::ibm {
#define BLASTSIM_CHARGE_LEDGER(X) X(ChargeLedger, burn, "per cell i + nx j")

BLASTSIM_CONST_GROUP(ChargeCellParams, BLASTSIM_CHARGE_CELL_PARAMS)
BLASTSIM_VIEW_GROUP(ChargeLedgers, BLASTSIM_CHARGE_LEDGER)

//! The charge cells of the grid.
struct ChargeCells {
  ChargeCellParams cell;
  int nx, ny;
  //! Cell (i, j) belongs to a charge that has not burnt there by time t [s] (false outside the grid).
  BLAST_HD bool unburnt(int i, int j, double t) const {
    if (i < 0 || j < 0 || i >= nx || j >= ny) return false;
    const index_t c = static_cast<index_t>(j) * nx + i;
    return cell.charge[c] >= 0 && t < cell.burn_time[c];
  }
};

//! An unburnt charge keeps its volume: every face point of its cells not covered by rock becomes a wall at
//! rest (owner kChargeOwner), so its cells are inactive and the gas beside it (the air gap of a decoupled charge)
//! sees a rigid wall. `face` 0: the x-face (i, j) between cells (i - 1, j) and (i, j); 1: the y-face between
//! (i, j - 1) and (i, j).
struct ChargeCoverKernel {
  ChargeCells cells;
  int face;
  double t;
  Field2D<int> owner;
  BLAST_HD void operator()(int i, int j) const {
    if (owner(i, j) != kNoOwner) return;
    const bool before = face == 0 ? cells.unburnt(i - 1, j, t) : cells.unburnt(i, j - 1, t);
    if (before || cells.unburnt(i, j, t)) owner(i, j) = kChargeOwner;
  }
};

//! Burns the charge cells lit since the previous burn, in (burnt_until, t] (constant-volume explosion of each cell: the
//! products at the explosive's density rho0 and detonation energy e0, at rest; their faces were walls at
//! rest until now). A charge cell that the rock covers (the mesh's hole is a polygon inside the circle) burns
//! empty. The cell's own ledger record says what changed; no other cell is written, so the result does not
//! depend on the order.
struct ChargeBurnKernel {
  ChargeCells cells;
  Field2D<const std::uint8_t> active;  //!< the new mask
  ChargeLedgers<Access::read_write> ledger;
  double burnt_until;  //!< [s] the time of the previous burn: the cells lit by then have burnt
  double t, cell_area;
  ChargeProducts products;
  cip::GasCells gas;
  BLAST_HD void operator()(int i, int j) const {
    const index_t c = static_cast<index_t>(j) * cells.nx + i;
    if (cells.cell.charge[c] < 0 || cells.cell.burn_time[c] <= burnt_until || t < cells.cell.burn_time[c]) return;
    if (!active(i, j)) return;  // under rock (the mesh's polygon cuts into the hole's circle): no explosive there
    ChargeLedger& led = ledger.burn[c];
    const double rho = gas.s.rho.f(i, j), e = gas.s.e.f(i, j);
    led.products_mass += products.density * cell_area;
    led.detonation_energy += products.density * products.specific_energy * cell_area;
    led.replaced_mass += rho * cell_area;
    led.replaced_energy += rho * e * cell_area;
    gas.fill(i, j, cip::GasPhase::products, products.density, products.specific_energy);
  }
};

// ---- what the charges report (Charges::pressures(), energies(), add_diagnostics()) ----

//! Cell k of the box of cells from (i0, j0), ni wide: its pressure [Pa] and a count of 1 when it is active and its
//! centre lies within r of (cx, cy), else nothing (a sum gives the mean over a hole's open cells).
struct HoleCellPressure {
  cip::GasGrid g;
  cip::GasMaterials mat;
  cip::MaterialReadView m;
  cip::GasStateReadView s;
  Field2D<const std::uint8_t> active;
  int i0, j0, ni;
  double cx, cy, r;  //!< [m] the hole's centre and radius
  BLAST_HD Vec2Sum operator()(index_t k) const {
    const int i = i0 + static_cast<int>(k % ni), j = j0 + static_cast<int>(k / ni);
    const double x = g.x_min + (i + 0.5) * g.dx - cx, y = g.y_min + (j + 0.5) * g.dy - cy;
    if (!active(i, j) || x * x + y * y > r * r) return Vec2Sum{0, 0};
    return Vec2Sum{cip::cell_pressure(mat, m, s.rho.f(i, j), s.e.f(i, j), i, j), 1.0};
  }
};

//! Cell b of the box of cells from (i0, j0), ni wide, on a grid nx wide: the detonation energy [J/m] its burn
//! released when charge `charge` holds it.
struct ChargeCellEnergy {
  ChargeCellParams cells;
  ChargeLedgers<Access::read> ledger;
  int nx, i0, j0, ni, charge;
  BLAST_HD double operator()(index_t b) const {
    const index_t c = static_cast<index_t>(j0 + b / ni) * nx + i0 + b % ni;
    return cells.charge[c] == charge ? ledger.burn[c].detonation_energy : 0.0;
  }
};

//! 1 for a cell that a charge holds and that has burnt by `until` [s].
struct BurntChargeCell {
  ChargeCellParams cells;
  double until;
  BLAST_HD double operator()(index_t k) const { return cells.charge[k] >= 0 && cells.burn_time[k] <= until ? 1.0 : 0.0; }
};

}  // namespace blastsim::ibm
