//! \file charge_kernels.hpp
//! \brief Kernels of the explosive charges (docs/coupling.md "Charges"): an unburnt charge as a solid in the
//! immersed-boundary masks, the burn of its cells at their lighting times, and the burn times themselves.
#pragma once

#include "blastsim/cip/gas_state.hpp"
#include "blastsim/core/field2d.hpp"
#include "blastsim/core/macros.hpp"
#include "blastsim/ibm/charges.hpp"

#include <cmath>
#include <cstdint>

namespace blastsim::ibm {

//! Owner of a face point in the coupler's cover arrays: none, a rock triangle (>= 0), or an unburnt charge.
inline constexpr int kNoOwner = -1, kChargeOwner = -2;

//! Lighting time [s] of a point (x, y) [m] of a charge: its initiation time, plus, for a point initiation, the
//! time the detonation front needs to come from the initiation point at the detonation velocity (Wilkins'
//! programmed burn: the front is a circle |x - x0| = D (t - t0)). Host code (GasRockCoupler::set_charges tabulates
//! it per cell).
inline double lighting_time(const Charge& c, double x, double y) {
  if (c.initiation != Initiation::point) return c.initiation_time;
  const double dx = x - c.point[0], dy = y - c.point[1];
  return c.initiation_time + std::sqrt(dx * dx + dy * dy) / c.detonation_velocity;
}

//! The charge cells of the grid (params, one per cell i + nx j, built by GasRockCoupler::set_charges).
struct ChargeCells {
  const int* charge;        //!< the charge whose circle holds the cell centre, or -1
  const double* burn_time;  //!< [s] the lighting time of the cell centre
  int nx, ny;
  //! Cell (i, j) belongs to a charge that has not burnt there by time t [s] (false outside the grid).
  BLAST_HD bool unburnt(int i, int j, double t) const {
    if (i < 0 || j < 0 || i >= nx || j >= ny) return false;
    const index_t c = static_cast<index_t>(j) * nx + i;
    return charge[c] >= 0 && t < burn_time[c];
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
//! empty. The cell's own ledger entry (4 per cell: products mass, detonation energy, and the mass
//! and internal energy of the gas it held, all per unit thickness) records what changed; no other cell is
//! written, so the result does not depend on the order.
struct ChargeBurnKernel {
  ChargeCells cells;
  Field2D<const std::uint8_t> active;  //!< the new mask
  double* ledger;
  double burnt_until;  //!< [s] the time of the previous burn: the cells lit by then have burnt
  double t, cell_area;
  ChargeProducts products;
  cip::GasStateView s;
  cip::MaterialView m;
  BLAST_HD void operator()(int i, int j) const {
    const index_t c = static_cast<index_t>(j) * cells.nx + i;
    if (cells.charge[c] < 0 || cells.burn_time[c] <= burnt_until || t < cells.burn_time[c]) return;
    if (!active(i, j)) return;  // under rock (the mesh's polygon cuts into the hole's circle): no explosive there
    double* led = ledger + 4 * c;
    const double rho = s.rho.f(i, j), e = s.e.f(i, j);
    led[0] += products.density * cell_area;
    led[1] += products.density * products.specific_energy * cell_area;
    led[2] += rho * cell_area;
    led[3] += rho * e * cell_area;
    s.rho.f(i, j) = products.density, s.rho.gx(i, j) = 0.0, s.rho.gy(i, j) = 0.0;
    s.e.f(i, j) = products.specific_energy, s.e.gx(i, j) = 0.0, s.e.gy(i, j) = 0.0;
    m.alpha(i, j) = 1.0;
    m.m1(i, j) = products.density;
  }
};

}  // namespace blastsim::ibm
