//! \file crack_coupling_kernels.hpp
//! \brief The kernels that join the crack gas to the rock and the grid (docs/coupling.md "Gas in the cracks"):
//! the channels' geometry from the rock, the hand-over of wide cracks to the grid, the mouths into the grid
//! gas, the deposits of what the cracks gave the cells, and the crack gas's pressure on the crack faces.
//! CrackGasCoupling (crack_gas_coupling.hpp) launches them. Plain header: no backend dependency.
#pragma once

#include "blastsim/cip/eos.hpp"
#include "blastsim/cip/gas_state.hpp"
#include "blastsim/cip/grid.hpp"
#include "blastsim/core/access.hpp"
#include "blastsim/core/field2d.hpp"
#include "blastsim/fdem/rock_fields.hpp"
#include "blastsim/ibm/coupling_kernels.hpp"
#include "blastsim/ibm/crack_gas_kernels.hpp"

#include <cmath>
#include <cstdint>

namespace blastsim::ibm {

//! The coupling's own arrays beside the network's, as field lists X(element type, name, comment) (storage in
//! crack_gas_coupling.cpp): per junction its place on the mesh outline (fixed) and its mouth's cell; per
//! segment what it hands to the grid in this step; per deposit record (the mouths, then the segments) the sort
//! by cell that makes the deposits' sums independent of the thread order.
#define BLASTSIM_CRACK_JUNCTION_PLACES(X) X(std::uint8_t, outline, "1: the junction's vertex lies on the mesh outline")
#define BLASTSIM_CRACK_MOUTH_CELLS(X) X(int, cell, "the cell i + nx j a junction's mouth opens into, or -1")
#define BLASTSIM_CRACK_HANDOVERS(X)                                                                  \
  X(int, cell, "the cell i + nx j a segment hands its gas to in this step, or -1")                  \
  X(ChannelConserved, gas, "the gas it hands over")                                                  \
  X(double, load_factor, "crack_width()'s dw_dopening: scales the gas's pressure on the faces")
#define BLASTSIM_CRACK_DEPOSIT_ORDER(X)                            \
  X(int, key, "cell key of each record (INT_MAX: none), sorted")   \
  X(int, record, "the record at each sorted position")

BLASTSIM_CONST_GROUP(CrackJunctionPlaces, BLASTSIM_CRACK_JUNCTION_PLACES)
BLASTSIM_VIEW_GROUP(CrackMouthCells, BLASTSIM_CRACK_MOUTH_CELLS)
BLASTSIM_VIEW_GROUP(CrackHandovers, BLASTSIM_CRACK_HANDOVERS)
BLASTSIM_VIEW_GROUP(CrackDepositOrder, BLASTSIM_CRACK_DEPOSIT_ORDER)

//! Aperture of a crack from the mean normal opening o of its faces [m] and the residual aperture w_r [m]:
//! w = w_r + o when open; closed (o < 0: the faces pressed together), w = w_r exp(o / w_r), which joins
//! smoothly (same value and slope at o = 0) and stays positive. dw_dopening scales the gas's pressure on the
//! faces, so that their work p L dw_dopening do is the gas's p dV exactly: a closed crack's gas loads its
//! faces less the more they are pressed together.
struct CrackWidth {
  double w, dw_dopening;
};
BLAST_HD inline CrackWidth crack_width(double opening, double residual) {
  if (opening >= 0) return {residual + opening, 1.0};
  const double f = exp(opening / residual);
  return {residual * f, f};
}

//! Work [J/m] a segment's gas (conserved c, pressure p [Pa]) does on its walls when its volume goes from V0 to V1
//! [m2 per m]: p (V1 - V0), unless that would take more than half of its internal energy U (a fast opening of a
//! nearly empty crack), where the explicit product overshoots and would leave a negative internal energy; then
//! the isentropic expansion at the gas's effective Gruneisen coefficient G = p V0 / U, U (1 - (V0 / V1)^G),
//! which keeps U positive (exact for an ideal gas).
BLAST_HD inline double expansion_work(const ChannelConserved& c, double p, double V0, double V1) {
  const double W = p * (V1 - V0), U = c.E - 0.5 * c.q * c.q / c.m;
  if (!(W > 0.5 * U) || !(U > 0.0)) return W;
  return U * (1.0 - pow(V0 / V1, p * V0 / U));
}

//! Every joint's channel from the rock (one thread per joint = segment): length L (mean of its two faces),
//! aperture w from the mean normal opening of its two ends (crack_width()), volume L w. A joint that just broke
//! becomes a gas segment holding nothing (a vacuum: its gas can only come from its neighbours, so the total is
//! kept exactly); a gas segment whose volume changes does the work p dV on its walls (E -= p dV: the rock's
//! edge pressures do the same work on the rock). Hand-over: when a face of the crack meets the grid gas (the
//! cell it faces is active, so the grid's gas loads it and is pushed by it), the segment gives its gas to that
//! cell (handover[], applied with the mouths' deposits) and the grid carries it from then on; once neither
//! face meets an active cell, the segment takes its own gas again, starting empty. So the two gases never
//! share a face, and every face's work is paid by the gas that loads it.
struct CrackGeometryKernel {
  fdem::RockView rock;
  cip::GasMaterials mat;
  cip::GasGrid g;
  Field2D<const std::uint8_t> active;
  CrackGeometry<Access::read_write> geo;
  CrackSegments<Access::read_write> seg;
  CrackHandovers<Access::read_write> handovers;
  double residual_aperture;
  BLAST_HD void operator()(index_t ji) const {
    const int s = static_cast<int>(ji);
    handovers.cell[s] = -1;
    if (!rock.joints.broken[s]) {
      seg.kind[s] = kSegmentNone;
      return;
    }
    const fdem::JointNodes jn = rock.joint.nodes[s];
    const fdem::NodeMotion<Access::read>& x = rock.nodes;
    const fdem::Vec2 a0 = x.position(jn.a0), a1 = x.position(jn.a1), b0 = x.position(jn.b0), b1 = x.position(jn.b1);
    const double la = sqrt((a1.x - a0.x) * (a1.x - a0.x) + (a1.y - a0.y) * (a1.y - a0.y));
    const double lb = sqrt((b1.x - b0.x) * (b1.x - b0.x) + (b1.y - b0.y) * (b1.y - b0.y));
    const fdem::Vec2 nrm = fdem::edge_outward_normal(a0, a1);  // from face A towards face B, length la
    const double open0 = ((b1.x - a0.x) * nrm.x + (b1.y - a0.y) * nrm.y) / la;
    const double open1 = ((b0.x - a1.x) * nrm.x + (b0.y - a1.y) * nrm.y) / la;
    const CrackWidth cw = crack_width(0.5 * (open0 + open1), residual_aperture);
    const double L = 0.5 * (la + lb), w = cw.w, V = L * w;
    geo.length[s] = L, geo.aperture[s] = w, handovers.load_factor[s] = cw.dw_dopening;
    int ci = -1, cj = -1, fi = 0, fj = 0;
    if (facing_cell(g, a0, a1, fi, fj) && active(fi, fj)) ci = fi, cj = fj;
    else if (facing_cell(g, b0, b1, fi, fj) && active(fi, fj)) ci = fi, cj = fj;
    const bool meets_grid = ci >= 0;
    const std::uint8_t kind = seg.kind[s];
    if (kind == kSegmentNone || (kind == kSegmentGrid && !meets_grid)) {
      seg.kind[s] = meets_grid ? kSegmentGrid : kSegmentGas, seg.cons[s] = {0, 0, 0, 0, 0}, seg.volume[s] = V;
      return;
    }
    if (kind != kSegmentGas) return;
    ChannelConserved c = seg.cons[s];
    const double V_old = seg.volume[s];
    const ChannelPrimitive P = segment_state(mat, c, V_old);
    if (!is_vacuum(P)) c.E -= expansion_work(c, P.p, V_old, V);
    seg.volume[s] = V;
    if (meets_grid) {
      handovers.gas[s] = c, handovers.cell[s] = cj * g.nx + ci;
      seg.kind[s] = kSegmentGrid, c = {0, 0, 0, 0, 0};
    }
    seg.cons[s] = c;
  }
};

//! Which junctions open into the grid gas, and its state there (one thread per junction). A junction is a
//! mouth when the cell holding it (the midpoint of its two faces' nodes at the first gas segment's end) is
//! active, or, for a vertex on the mesh outline (the blasthole wall, the free face), when an active cell's
//! centre lies in the 3 x 3 block around it (the nearest). The mouth's reservoir is that cell's gas at rest.
struct CrackMouthKernel {
  fdem::RockView rock;
  cip::GasMaterials mat;
  cip::GasGrid g;
  Field2D<const std::uint8_t> active;
  cip::GasCellsRead cells;
  CrackGraph graph;
  CrackSegments<Access::read> seg;
  CrackJunctionPlaces places;
  CrackMouths<Access::read_write> mouths;
  CrackMouthCells<Access::read_write> mouth_cells;
  BLAST_HD void operator()(index_t ji) const {
    const int J = static_cast<int>(ji);
    mouths.open[J] = 0, mouth_cells.cell[J] = -1;
    int end = -1;
    for (int k = graph.junction_offset[J]; k < graph.junction_offset[J + 1] && end < 0; ++k)
      if (seg.kind[graph.junction_entry[k] / 2] == kSegmentGas) end = graph.junction_entry[k];
    if (end < 0) return;
    const fdem::JointNodes jn = rock.joint.nodes[end / 2];
    const int na = end % 2 == 0 ? jn.a0 : jn.a1, nb = end % 2 == 0 ? jn.b1 : jn.b0;
    const double x = 0.5 * (rock.nodes.x[na] + rock.nodes.x[nb]), y = 0.5 * (rock.nodes.y[na] + rock.nodes.y[nb]);
    int ci = 0, cj = 0;
    const bool inside = cell_of(g, x, y, ci, cj);
    int fi = -1, fj = -1;
    if (inside && active(ci, cj)) {
      fi = ci, fj = cj;
    } else if (places.outline[J]) {
      double best = 1e300;
      for (int j = imax(0, cj - 1); j <= imin(g.ny - 1, cj + 1); ++j)
        for (int i = imax(0, ci - 1); i <= imin(g.nx - 1, ci + 1); ++i) {
          if (!active(i, j)) continue;
          const double dx = g.cell_x(i) - x, dy = g.cell_y(j) - y, d = dx * dx + dy * dy;
          if (d < best) best = d, fi = i, fj = j;
        }
    }
    if (fi < 0) return;
    const cip::GasCellsRead::Fractions f = cells.fractions(fi, fj);
    mouths.open[J] = 1, mouth_cells.cell[J] = fj * g.nx + fi;
    mouths.reservoir[J] = channel_state(mat, cells.s.rho.f(fi, fj), 0.0, cells.s.e.f(fi, fj), f.Y, f.alpha);
  }
};

//! The cell key of every deposit record (0 .. junctions - 1: the mouths, then the segments' hand-overs; a
//! record without a cell sorts last).
struct CrackDepositKeyKernel {
  CrackMouthCells<Access::read> mouth_cells;
  CrackHandovers<Access::read> handovers;
  CrackDepositOrder<Access::read_write> order;  //!< writes key
  int junctions;
  BLAST_HD void operator()(index_t k) const {
    const int c = k < junctions ? mouth_cells.cell[k] : handovers.cell[k - junctions];
    order.key[k] = c < 0 ? 0x7fffffff : c;
  }
};

//! Adds the cracks' deposits to their cells (one thread per run of equal cell keys in the sorted records: the
//! first of the run sums them in sorted order, so the bytes do not depend on the thread schedule). Records
//! 0 .. junctions - 1 are the mouths' deposits, the rest the segments' hand-overs. The deposited energy is
//! internal energy of the cell (the cell's faces keep their velocities).
struct CrackDepositKernel {
  CrackDepositOrder<Access::read> order;  //!< sorted cell keys (INT_MAX: none), the record of each sorted position
  CrackDeposits<Access::read> deposits;
  CrackHandovers<Access::read> handovers;
  int junctions, records, nx;
  double cell_area;
  cip::GasCells cells;
  BLAST_HD void operator()(index_t ki) const {
    const int k = static_cast<int>(ki);
    const int c = order.key[k];
    if (c == 0x7fffffff || (k > 0 && order.key[k - 1] == c)) return;
    ChannelConserved sum{0, 0, 0, 0, 0};
    for (int r = k; r < records && order.key[r] == c; ++r) {
      const int rec = order.record[r];
      const ChannelConserved d = rec < junctions ? deposits.deposit[rec] : handovers.gas[rec - junctions];
      sum.m += d.m, sum.E += d.E, sum.m1 += d.m1, sum.am += d.am;
    }
    cells.deposit(c % nx, c / nx, cip::CellContent{sum.m, sum.E, sum.m1, sum.am}, cell_area);
  }
};

//! The pressure of a crack's own gas on its two faces (docs/coupling.md "Gas in the cracks"), over what the
//! grid gas put there (one thread per joint): p times crack_width()'s dw_dopening, so that the faces' work is
//! the gas's p dV. Face A of joint s is edge slot a0, face B slot b0.
struct CrackFacePressureKernel {
  fdem::RockView rock;
  CrackSegments<Access::read> seg;
  CrackHandovers<Access::read> handovers;  //!< reads load_factor
  BLAST_HD void operator()(index_t si) const {
    const int s = static_cast<int>(si);
    if (seg.kind[s] != kSegmentGas) return;
    const fdem::JointNodes jn = rock.joint.nodes[s];
    const double p = seg.prim[s].p * handovers.load_factor[s];
    rock.loads.pressure[jn.a0] = p;
    rock.loads.pressure[jn.b0] = p;
  }
};

}  // namespace blastsim::ibm
