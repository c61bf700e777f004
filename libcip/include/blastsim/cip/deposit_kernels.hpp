//! \file deposit_kernels.hpp
//! \brief The kernels that add what a coupling gives a sparse set of cells (mass, momentum, energy, materials)
//! to the staggered gas so that mass, momentum and total energy change by exactly what was given, as GasTotals
//! measures them (CellDeposits, cell_deposits.hpp, launches them; docs/coupling.md "Deposits into the grid").
//! Plain header: no backend dependency.
#pragma once

#include "blastsim/cip/gas_state.hpp"
#include "blastsim/cip/grid.hpp"
#include "blastsim/core/access.hpp"
#include "blastsim/core/field2d.hpp"

#include <cstdint>

namespace blastsim::cip {

//! What a coupling gives one cell over a step, per unit thickness: `given` mass [kg/m] moving with the momentum
//! (px, py) [kg/s]; `drawn` mass [kg/m] (<= 0) taken out of the cell at the velocities of its faces; `energy`
//! [J/m], the total energy of the given gas less that of the drawn gas; products mass and alpha x mass [kg/m]
//! (net). `cell` = i + nx j, or -1 for an entry that gives nothing. At most one entry per cell.
struct CellDeposit {
  int cell;
  double given, drawn, px, py, energy, products_mass, alpha_mass;
};

//! A cell's neighbourhood before its deposit: its own and its four edge neighbours' densities [kg/m3] (cell,
//! left, right, bottom, top), its four faces' velocities [m/s] (left and right x-faces, bottom and top y-faces),
//! each face's weight in GasTotals (1/2 per active cell beside it) and whether it is free (an interior face
//! whose velocity is not imposed: the deposit may change it).
struct DepositNeighbourhood {
  double rho[5];
  double u[4];
  double weight[4];
  std::uint8_t free[4];
};

//! Per entry: its neighbourhood before the deposit, and the momentum [kg/s] along x and y it could not give
//! because the cell has no free face in that direction (a cell between solid faces: the momentum meets the wall).
#define BLASTSIM_CELL_DEPOSIT_SCRATCH(X)                                                     \
  X(DepositNeighbourhood, before, "the cell's neighbourhood before the deposit")            \
  X(double, refused_x, "momentum [kg/s] along x no free x-face of the cell could take")     \
  X(double, refused_y, "momentum [kg/s] along y no free y-face of the cell could take")
BLASTSIM_VIEW_GROUP(CellDepositScratch, BLASTSIM_CELL_DEPOSIT_SCRATCH)

//! The entries (CellDeposits::entries()), and per cell where its entry is.
#define BLASTSIM_CELL_DEPOSIT_LIST(X) X(CellDeposit, entry, "what each entry gives its cell")
#define BLASTSIM_CELL_DEPOSIT_SLOTS(X) \
  X(int, slot, "per cell: its entry's index, or -1 (set by DepositGatherKernel, reset by DepositClearKernel)")
BLASTSIM_VIEW_GROUP(CellDepositList, BLASTSIM_CELL_DEPOSIT_LIST)
BLASTSIM_FIELD_GROUP(CellDepositSlots, BLASTSIM_CELL_DEPOSIT_SLOTS)

//! Face f of cell (i, j) (0 left, 1 right: x-faces; 2 bottom, 3 top: y-faces): its neighbour across it.
BLAST_HD inline void deposit_neighbour(int f, int i, int j, int& ni, int& nj) {
  ni = i + (f == 0 ? -1 : f == 1 ? 1 : 0), nj = j + (f == 2 ? -1 : f == 3 ? 1 : 0);
}

//! The momentum [kg/s] an entry puts on its free faces along direction d (0: x, 1: y), and how many free faces
//! share it: the given momentum less what the given mass already carries on its imposed faces (there the velocity
//! stays, and the face's mass grows by half the given mass, GasTotals' measure), so the total is the given
//! momentum exactly. A cell with no free face in that direction places nothing (its refused momentum).
struct DepositShare {
  double momentum;
  int faces;
};
BLAST_HD inline DepositShare deposit_share(const CellDeposit& d, const DepositNeighbourhood& b, int dir) {
  double p = dir == 0 ? d.px : d.py;
  int faces = 0;
  for (int f = 2 * dir; f < 2 * dir + 2; ++f) {
    if (b.free[f]) ++faces;
    else p -= b.weight[f] * 0.5 * d.given * b.u[f];
  }
  return {p, faces};
}

//! Pass 1 (one thread per entry): marks the entry's cell in `slot` and keeps its neighbourhood.
struct DepositGatherKernel {
  GasGrid g;
  CellDepositList<Access::read> list;
  CellDepositSlots<Access::read_write> slots;
  GasStateReadView s;
  ImmersedBoundaryReadView ib;
  CellDepositScratch<Access::read_write> scratch;
  BLAST_HD void operator()(index_t k) const {
    const int c = list.entry[k].cell;
    scratch.refused_x[k] = 0.0, scratch.refused_y[k] = 0.0;
    if (c < 0) return;
    const int i = c % g.nx, j = c / g.nx;
    slots.slot(i, j) = static_cast<int>(k);
    DepositNeighbourhood b;
    b.rho[0] = s.rho.f(i, j);
    for (int f = 0; f < 4; ++f) {
      int ni, nj;
      deposit_neighbour(f, i, j, ni, nj);
      b.rho[f + 1] = s.rho.f(ni, nj);
      const bool xface = f < 2;
      const int fi = f == 1 ? i + 1 : i, fj = f == 3 ? j + 1 : j;  // the face's own index
      b.u[f] = xface ? s.u.f(fi, fj) : s.v.f(fi, fj);
      const bool inside = ni >= 0 && ni < g.nx && nj >= 0 && nj < g.ny;
      const bool imposed = xface ? ib.u_prescribed(fi, fj) != 0 : ib.v_prescribed(fi, fj) != 0;
      b.free[f] = inside && !imposed && ib.cell_active(ni, nj) ? 1 : 0;
      b.weight[f] = 0.5 * ((ib.cell_active(i, j) ? 1.0 : 0.0) + (inside && ib.cell_active(ni, nj) ? 1.0 : 0.0));
    }
    scratch.before[k] = b;
  }
};

//! The entry of the neighbour across face f of the cell of entry k, or -1.
BLAST_HD inline int neighbour_entry(const GasGrid& g, const CellDepositList<Access::read>& list,
                                    const CellDepositSlots<Access::read>& slots, int k, int f) {
  const int c = list.entry[k].cell, i = c % g.nx, j = c / g.nx;
  int ni, nj;
  deposit_neighbour(f, i, j, ni, nj);
  if (ni < 0 || ni >= g.nx || nj < 0 || nj >= g.ny) return -1;
  return slots.slot(ni, nj);
}

//! Face f of the cell (i, j) of entry d (nk: the entry across it, or -1): the face's own index, its dual mass
//! [kg/m] before the deposits (half of each side's mass, from the densities kept in b) and after both sides'.
struct DepositFace {
  int fi, fj;
  double M, M_new;
};
BLAST_HD inline DepositFace deposit_face(const GasGrid& g, const CellDepositList<Access::read>& list, const CellDeposit& d,
                                         const DepositNeighbourhood& b, int nk, int i, int j, int f) {
  const double dm = d.given + d.drawn + (nk >= 0 ? list.entry[nk].given + list.entry[nk].drawn : 0.0);
  const double M = 0.5 * (b.rho[0] + b.rho[f + 1]) * g.cell_area();
  return {f == 1 ? i + 1 : i, f == 3 ? j + 1 : j, M, M + 0.5 * dm};
}

//! Pass 2 (one thread per entry): the new velocity of each free face of its cell that it owns (its left and
//! bottom faces, and its right and top faces when the cell beyond holds no entry; so no face is written twice).
//! The face keeps its momentum (the mass of its dual cell, half of each side's, times its velocity) and gains
//! each side's share of its momentum to place (deposit_share()) and each side's drawn mass at its own velocity:
//! u' = (M u + sum of the sides' shares + (drawn_L + drawn_R) u / 2) / M', M' = M + (dm_L + dm_R) / 2.
struct DepositMomentumKernel {
  GasGrid g;
  CellDepositList<Access::read> list;
  CellDepositSlots<Access::read> slots;
  CellDepositScratch<Access::read_write> scratch;  //!< reads before; writes refused_x, refused_y
  GasStateView s;                                  //!< writes the free faces' u and v
  BLAST_HD void operator()(index_t ki) const {
    const int k = static_cast<int>(ki);
    const CellDeposit& d = list.entry[k];
    if (d.cell < 0) return;
    const int i = d.cell % g.nx, j = d.cell / g.nx;
    const DepositNeighbourhood& b = scratch.before[k];
    for (int dir = 0; dir < 2; ++dir) {
      const DepositShare own = deposit_share(d, b, dir);
      if (own.faces == 0) (dir == 0 ? scratch.refused_x[k] : scratch.refused_y[k]) = own.momentum;
    }
    for (int f = 0; f < 4; ++f) {
      if (!b.free[f]) continue;
      const int nk = neighbour_entry(g, list, slots, k, f);
      if ((f == 1 || f == 3) && nk >= 0) continue;  // the neighbour's entry owns this face
      const int dir = f < 2 ? 0 : 1;
      const DepositShare own = deposit_share(d, b, dir);
      const double u = b.u[f];
      double gain = own.momentum / own.faces + 0.5 * d.drawn * u;
      if (nk >= 0) {
        const CellDeposit& n = list.entry[nk];
        const DepositShare other = deposit_share(n, scratch.before[nk], dir);
        gain += (other.faces > 0 ? other.momentum / other.faces : 0.0) + 0.5 * n.drawn * u;
      }
      const DepositFace face = deposit_face(g, list, d, b, nk, i, j, f);
      (f < 2 ? s.u.f(face.fi, face.fj) : s.v.f(face.fi, face.fj)) = (face.M * u + gain) / face.M_new;
    }
  }
};

//! Pass 3 (one thread per entry): the cell's new density, internal energy and materials. Every face of the cell
//! changed its kinetic energy (GasTotals' measure: weight x (M' u'^2 - M u^2) / 2; its mass, its velocity or both
//! changed); the cell pays that change from its internal energy, all of it or half when the cell beyond also
//! holds an entry (which pays the other half), so the gas's total energy grows by exactly the entry's energy.
//! Where the change would take more than half of the cell's internal energy, half is taken and the rest counted
//! in the positivity ledger, a source of the energy budget.
struct DepositCellKernel {
  GasGrid g;
  CellDepositList<Access::read> list;
  CellDepositSlots<Access::read> slots;
  CellDepositScratch<Access::read> scratch;
  GasCells cells;
  BLAST_HD void operator()(index_t ki) const {
    const int k = static_cast<int>(ki);
    const CellDeposit& d = list.entry[k];
    if (d.cell < 0) return;
    const int i = d.cell % g.nx, j = d.cell / g.nx;
    const DepositNeighbourhood& b = scratch.before[k];
    const double area = g.cell_area();
    double kinetic = 0.0;
    for (int f = 0; f < 4; ++f) {
      const int nk = neighbour_entry(g, list, slots, k, f);
      const DepositFace face = deposit_face(g, list, d, b, nk, i, j, f);
      const double u = b.u[f], u_new = f < 2 ? cells.s.u.f(face.fi, face.fj) : cells.s.v.f(face.fi, face.fj);
      const double change = b.weight[f] * 0.5 * (face.M_new * u_new * u_new - face.M * u * u);
      kinetic += nk >= 0 ? 0.5 * change : change;
    }
    const double m_old = b.rho[0] * area, m_new = m_old + d.given + d.drawn;
    const double internal = cells.s.e.f(i, j) * m_old + d.energy;
    const double taken = kinetic > 0.5 * internal && internal > 0.0 ? 0.5 * internal : kinetic;
    cells.positivity_heat(i, j) += (kinetic - taken) / area;
    cells.s.rho.f(i, j) = m_new / area;
    cells.s.e.f(i, j) = (internal - taken) / m_new;
    if (cells.two) cells.m.alpha(i, j) = (cells.m.alpha(i, j) * m_old + d.alpha_mass) / m_new;
    if (cells.traced) cells.m.m1(i, j) += d.products_mass / area;
  }
};

//! Pass 4 (one thread per entry): clears its cell's slot.
struct DepositClearKernel {
  GasGrid g;
  CellDepositList<Access::read> list;
  CellDepositSlots<Access::read_write> slots;
  BLAST_HD void operator()(index_t k) const {
    const int c = list.entry[k].cell;
    if (c >= 0) slots.slot(c % g.nx, c / g.nx) = -1;
  }
};

}  // namespace blastsim::cip
