//! \file coupling_step_kernels.hpp
//! \brief The kernels of the immersed-boundary coupling step (paper sec. 2.3; docs/coupling.md): rock -> gas
//! (face points covered by triangles, imposed velocities, the new mask, gas moved between cells that change
//! state) and gas -> rock (edge pressures, the gas force). GasRockCoupler calls them; tests call them on a
//! few cells. Plain header: no backend dependency.
#pragma once

#include "blastsim/cip/eos.hpp"
#include "blastsim/cip/gas_state.hpp"
#include "blastsim/cip/gas_step_kernels.hpp"
#include "blastsim/cip/gas_types.hpp"
#include "blastsim/cip/grid.hpp"
#include "blastsim/core/atomic.hpp"
#include "blastsim/core/field2d.hpp"
#include "blastsim/fdem/rock_fields.hpp"
#include "blastsim/fdem/rock_solver.hpp"
#include "blastsim/ibm/charge_kernels.hpp"
#include "blastsim/ibm/coupling_kernels.hpp"
#include "blastsim/ibm/crack_gas_kernels.hpp"

#include <cmath>
#include <cstdint>

namespace blastsim::ibm {


BLAST_HD inline int imax(int a, int b) { return a > b ? a : b; }
BLAST_HD inline int imin(int a, int b) { return a < b ? a : b; }

//! A pair of sums for device reductions (forces).
struct Vec2Sum {
  double x, y;
  BLAST_HD Vec2Sum operator+(const Vec2Sum& o) const { return {x + o.x, y + o.y}; }
};

//! Marks the x-face (u) and y-face (v) points inside each triangle (docs/coupling.md "Rock -> gas": bounding-box
//! rasterisation), keeping the highest triangle index per point.
struct CoverKernel {
  fdem::RockView rock;
  cip::GasGrid g;
  Field2D<int> u_owner, v_owner;
  BLAST_HD void operator()(index_t ti) const {
    const int t = static_cast<int>(ti);
    double x[3], y[3];
    for (int k = 0; k < 3; ++k) x[k] = rock.x[3 * t + k], y[k] = rock.y[3 * t + k];
    const double x0 = min_of(x[0], min_of(x[1], x[2])), x1 = max_of(x[0], max_of(x[1], x[2]));
    const double y0 = min_of(y[0], min_of(y[1], y[2])), y1 = max_of(y[0], max_of(y[1], y[2]));
    for (int face = 0; face < 2; ++face) {
      // x-faces sit at (x_min + i dx, y_min + (j + 1/2) dy), y-faces at (x_min + (i + 1/2) dx, y_min + j dy).
      const double ox = face == 0 ? 0.0 : 0.5, oy = face == 0 ? 0.5 : 0.0;
      const int ni = face == 0 ? g.nx + 1 : g.nx, nj = face == 0 ? g.ny : g.ny + 1;
      const int i0 = imax(0, static_cast<int>(ceil((x0 - g.x_min) / g.dx - ox)));
      const int i1 = imin(ni - 1, static_cast<int>(floor((x1 - g.x_min) / g.dx - ox)));
      const int j0 = imax(0, static_cast<int>(ceil((y0 - g.y_min) / g.dy - oy)));
      const int j1 = imin(nj - 1, static_cast<int>(floor((y1 - g.y_min) / g.dy - oy)));
      for (int j = j0; j <= j1; ++j)
        for (int i = i0; i <= i1; ++i) {
          double w[3];
          if (barycentric(x, y, g.x_min + (i + ox) * g.dx, g.y_min + (j + oy) * g.dy, w) && inside(w))
            atomic_max(&(face == 0 ? u_owner : v_owner)(i, j), t);
        }
    }
  }
};

//! Imposed velocity of each face point from its covering triangle's nodes (linear shape functions); zero on the
//! wall of an unburnt charge.
struct ImposedVelocityKernel {
  fdem::RockView rock;
  cip::GasGrid g;
  int face;  // 0: x-faces (u), 1: y-faces (v)
  Field2D<const int> owner;
  Field2D<std::uint8_t> prescribed;
  Field2D<double> imposed;
  BLAST_HD void operator()(int i, int j) const {
    const int t = owner(i, j);
    prescribed(i, j) = t != kNoOwner;
    if (t == kChargeOwner) imposed(i, j) = 0.0;  // the wall of an unburnt charge, at rest
    if (t < 0) return;
    double x[3], y[3], w[3] = {1.0 / 3, 1.0 / 3, 1.0 / 3};
    for (int k = 0; k < 3; ++k) x[k] = rock.x[3 * t + k], y[k] = rock.y[3 * t + k];
    const double px = g.x_min + (i + (face == 0 ? 0.0 : 0.5)) * g.dx;
    const double py = g.y_min + (j + (face == 0 ? 0.5 : 0.0)) * g.dy;
    barycentric(x, y, px, py, w);
    const double* vel = face == 0 ? rock.vx : rock.vy;
    imposed(i, j) = w[0] * vel[3 * t] + w[1] * vel[3 * t + 1] + w[2] * vel[3 * t + 2];
  }
};

//! A cell is inactive when its four face points are in rock or an unburnt charge (docs/coupling.md "Rock -> gas"):
//! the new mask.
struct NewMaskKernel {
  Field2D<const int> u_owner, v_owner;
  Field2D<std::uint8_t> new_active;
  BLAST_HD void operator()(int i, int j) const {
    const bool covered = u_owner(i, j) != kNoOwner && u_owner(i + 1, j) != kNoOwner && v_owner(i, j) != kNoOwner &&
                         v_owner(i, j + 1) != kNoOwner;
    new_active(i, j) = covered ? 0 : 1;
  }
};

//! Moves gas between cells that change state (docs/coupling.md "Cells that change state"). A covered cell
//! gives its mass and energy (internal, and the kinetic energy of its faces: handed_energy()) in equal shares
//! to its stable edge neighbours (active before and after), or, with none (two cut cells that shared their only open face), to the stable cells of its 3 x 3
//! block; it then holds the ambient state. An uncovered cell starts from the ambient state at rest: the gas
//! of its neighbours flows in through the solver (splitting a neighbour's gas instead made near-vacuum
//! chains along opening cracks, and negative densities when the hole gas arrived). Every cell computes its
//! own new value from the old ones (a gather: no atomics, order-independent). The ledger counts the
//! transitions and the mass and energy they create: the ambient gas of uncovered cells, minus the gas of a
//! covered cell with no stable cell in its block. `reset` (the first call): covered cells take the ambient
//! state, nothing moves and nothing is counted. In a two-material run the products' partial density moves
//! with the mass and the receiving cell's volume fraction becomes the mass-weighted mean of its own and the
//! given gas's; a cell that changes state holds air.
struct TransitionKernel {
  Field2D<const std::uint8_t> old_active, new_active;
  Field2D<const double> rho, e, u, v;
  Field2D<double> rho_next, e_next;
  bool two;
  cip::MaterialReadView materials;  // read when two
  cip::MaterialView next;           // products alpha and m1 after the move (written when two)
  Field2D<std::uint8_t> changed;
  double* ledger;  // 4 per cell (i + nx j)
  int nx, ny;
  double cell_area, rho_ambient, e_ambient;
  bool reset;

  BLAST_HD bool in_grid(int i, int j) const { return i >= 0 && i < nx && j >= 0 && j < ny; }
  BLAST_HD bool stable(int i, int j) const { return in_grid(i, j) && old_active(i, j) && new_active(i, j); }
  BLAST_HD bool dying(int i, int j) const { return in_grid(i, j) && old_active(i, j) && !new_active(i, j); }
  BLAST_HD int count_stable(int i, int j) const {
    return stable(i - 1, j) + stable(i + 1, j) + stable(i, j - 1) + stable(i, j + 1);
  }
  BLAST_HD int count_stable_block(int i, int j) const {
    return count_stable(i, j) + stable(i - 1, j - 1) + stable(i + 1, j - 1) + stable(i - 1, j + 1) + stable(i + 1, j + 1);
  }
  //! Gas energy per cell area [J/m3] that a covered cell (i, j) hands on: its internal energy, and the kinetic
  //! energy that leaves the totals (GasTotals) when its faces are stopped: its own quarter of each face's
  //! m u^2 and, across a face to a stable cell, that cell's quarter too.
  BLAST_HD double handed_energy(int i, int j) const {
    double k = 0;
    auto face = [&](double w, int oi, int oj) { k += (stable(oi, oj) ? 0.5 : 0.25) * 0.5 * (rho(i, j) + rho(oi, oj)) * w * w; };
    face(u(i, j), i - 1, j);
    face(u(i + 1, j), i + 1, j);
    face(v(i, j), i, j - 1);
    face(v(i, j + 1), i, j + 1);
    return rho(i, j) * e(i, j) + k;
  }

  BLAST_HD void operator()(int i, int j) const {
    double m = rho(i, j), E = rho(i, j) * e(i, j);  // per cell area
    double m1 = two ? materials.m1(i, j) : 0.0, am = two ? materials.alpha(i, j) * m : 0.0;  // products; alpha x mass
    bool moved = old_active(i, j) != new_active(i, j);
    double* led = ledger + 4 * (static_cast<index_t>(j) * nx + i);
    if (moved) {  // covered or uncovered: the ambient state
      if (!reset) {
        if (new_active(i, j)) {
          led[1] += 1.0, led[2] += rho_ambient * cell_area, led[3] += rho_ambient * e_ambient * cell_area;
        } else {
          led[0] += 1.0;
          if (count_stable_block(i, j) == 0) led[2] -= m * cell_area, led[3] -= handed_energy(i, j) * cell_area;
        }
      }
      m = rho_ambient, E = rho_ambient * e_ambient;
      m1 = 0.0, am = 0.0;
    } else if (stable(i, j) && !reset) {
      for (int nj = j - 1; nj <= j + 1; ++nj)
        for (int ni = i - 1; ni <= i + 1; ++ni) {
          if (!dying(ni, nj)) continue;
          const int a = count_stable(ni, nj);       // >= 1 when this cell is its edge neighbour
          if (a > 0 && ni != i && nj != j) continue;  // a diagonal giver only when it has no stable edge neighbour
          const double share = 1.0 / (a > 0 ? a : count_stable_block(ni, nj));
          m += share * rho(ni, nj);
          E += share * handed_energy(ni, nj);
          if (two) {
            m1 += share * materials.m1(ni, nj);
            am += share * materials.alpha(ni, nj) * rho(ni, nj);
          }
          moved = true;
        }
    }
    changed(i, j) = moved;
    rho_next(i, j) = m;
    e_next(i, j) = moved ? E / m : e(i, j);
    if (two) {
      next.m1(i, j) = m1;
      next.alpha(i, j) = moved ? am / m : materials.alpha(i, j);
    }
  }
};

//! Writes the moved gas back (derivatives of a changed cell set to zero), stops the faces of covered cells
//! (their imposed velocity; their kinetic energy went with the cell's gas) and installs the new mask. Two
//! covered neighbours write their common face with the same value.
struct ApplyTransitionKernel {
  Field2D<const std::uint8_t> new_active, changed;
  Field2D<const double> rho_next, e_next, u_imposed, v_imposed;
  Field2D<std::uint8_t> active;
  cip::GasStateView s;
  bool two;
  cip::MaterialReadView next;
  cip::MaterialView materials;
  BLAST_HD void operator()(int i, int j) const {
    if (active(i, j) && !new_active(i, j)) {
      s.u.f(i, j) = u_imposed(i, j), s.u.f(i + 1, j) = u_imposed(i + 1, j);
      s.v.f(i, j) = v_imposed(i, j), s.v.f(i, j + 1) = v_imposed(i, j + 1);
    }
    active(i, j) = new_active(i, j);
    if (!changed(i, j)) return;
    s.rho.f(i, j) = rho_next(i, j), s.rho.gx(i, j) = 0.0, s.rho.gy(i, j) = 0.0;
    s.e.f(i, j) = e_next(i, j), s.e.gx(i, j) = 0.0, s.e.gy(i, j) = 0.0;
    if (two) materials.alpha(i, j) = next.alpha(i, j), materials.m1(i, j) = next.m1(i, j);
  }
};

//! Cell (i, j) holding point (x, y), or false outside the grid.
BLAST_HD inline bool cell_of(const cip::GasGrid& g, double x, double y, int& i, int& j) {
  i = static_cast<int>(floor((x - g.x_min) / g.dx));
  j = static_cast<int>(floor((y - g.y_min) / g.dy));
  return i >= 0 && i < g.nx && j >= 0 && j < g.ny;
}

//! The cell an exposed edge from p0 to p1 faces: the one holding the point a hundredth of a cell off its
//! midpoint along its outward normal (rule 1 of docs/coupling.md "Gas -> rock"); false outside the grid.
BLAST_HD inline bool facing_cell(const cip::GasGrid& g, const fdem::Vec2& p0, const fdem::Vec2& p1, int& i, int& j) {
  const fdem::Vec2 n = fdem::edge_outward_normal(p0, p1);
  const double off = 0.01 * fmin(g.dx, g.dy) / sqrt(n.x * n.x + n.y * n.y);
  return cell_of(g, 0.5 * (p0.x + p1.x) + off * n.x, 0.5 * (p0.y + p1.y) + off * n.y, i, j);
}

//! Pressure on each exposed rock edge (docs/coupling.md "Gas -> rock"). A face of a crack that holds its own
//! gas (crack gas on, docs/coupling.md "Gas in the cracks") takes that gas's pressure. Otherwise the cell the edge faces (the one
//! holding the point a hundredth of a cell off the midpoint along the outward normal) gives its pressure when
//! it is active. Otherwise a boundary edge takes the active cell nearest to its midpoint within 2 cells (the
//! paper's rule; ties go to the first in scan order) and a crack face the ambient pressure: a crack narrower
//! than the grid holds no gas, and loading its faces with the pressure of a cell beside it would do work
//! that no gas pays for (both faces of a closed crack get the same pressure, which cancels).
struct EdgePressureKernel {
  fdem::RockView rock;
  cip::GasGrid g;
  cip::GasMaterials mat;
  cip::MaterialReadView materials;  // read in two-material runs
  Field2D<const std::uint8_t> active;
  Field2D<const double> rho, e;
  double ambient_pressure;
  const std::uint8_t* crack_kind;        // per joint, or null without crack gas
  const ChannelPrimitive* crack_state;   // per joint
  const double* crack_load_factor;       // per joint: crack_width()'s dw_dopening
  BLAST_HD void operator()(index_t si) const {
    const int s = static_cast<int>(si);
    const std::uint8_t kind = rock.edge_exposed[s];
    if (kind == fdem::kEdgeInside) return;
    if (kind == fdem::kEdgeCrackFace && crack_kind) {  // a crack with its own gas: that gas's pressure (crack_width())
      const int j = rock.edge_joint[s];
      if (j >= 0 && crack_kind[j] == kSegmentGas) {
        rock.edge_pressure[s] = crack_state[j].p * crack_load_factor[j];
        return;
      }
    }
    const int a = fdem::slot_first_node(s), b = fdem::slot_second_node(s);
    const double mx = 0.5 * (rock.x[a] + rock.x[b]), my = 0.5 * (rock.y[a] + rock.y[b]);
    int fi = 0, fj = 0;
    double p = ambient_pressure;
    if (facing_cell(g, {rock.x[a], rock.y[a]}, {rock.x[b], rock.y[b]}, fi, fj) && active(fi, fj)) {
      p = cip::cell_pressure(mat, materials, rho(fi, fj), e(fi, fj), fi, fj);
    } else if (kind == fdem::kEdgeBoundary) {
      const int ci = static_cast<int>(floor((mx - g.x_min) / g.dx)), cj = static_cast<int>(floor((my - g.y_min) / g.dy));
      double best = 1e300;
      for (int j = imax(0, cj - 2); j <= imin(g.ny - 1, cj + 2); ++j)
        for (int i = imax(0, ci - 2); i <= imin(g.nx - 1, ci + 2); ++i) {
          if (!active(i, j)) continue;
          const double dx = g.cell_x(i) - mx, dy = g.cell_y(j) - my, d = dx * dx + dy * dy;
          if (d < best) best = d, p = cip::cell_pressure(mat, materials, rho(i, j), e(i, j), i, j);
        }
    }
    rock.edge_pressure[s] = p;
  }
};

//! Force of the edge pressures on the rock [N/m]: p L along the inward normal of every exposed edge.
struct EdgeForceOf {
  fdem::RockView rock;
  BLAST_HD Vec2Sum operator()(index_t si) const {
    const int s = static_cast<int>(si);
    if (!rock.edge_exposed[s]) return {0, 0};
    const int a = fdem::slot_first_node(s), b = fdem::slot_second_node(s);
    const double p = rock.edge_pressure[s];  // along the inward normal
    const fdem::Vec2 n = fdem::edge_outward_normal({rock.x[a], rock.y[a]}, {rock.x[b], rock.y[b]});
    return {-p * n.x, -p * n.y};
  }
};

// ---- the gas in the cracks (docs/coupling.md "Gas in the cracks") -----------------------------------------

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
  CrackNetworkView n;
  double* length;
  double* aperture;
  ChannelConserved* handover;
  int* handover_cell;
  double* load_factor;
  double residual_aperture;
  BLAST_HD void operator()(index_t ji) const {
    const int s = static_cast<int>(ji);
    handover_cell[s] = -1;
    if (!rock.joint_broken[s]) {
      n.kind[s] = kSegmentNone;
      return;
    }
    const fdem::JointNodes jn = rock.joint_nodes[s];
    const fdem::Vec2 a0{rock.x[jn.a0], rock.y[jn.a0]}, a1{rock.x[jn.a1], rock.y[jn.a1]};
    const fdem::Vec2 b0{rock.x[jn.b0], rock.y[jn.b0]}, b1{rock.x[jn.b1], rock.y[jn.b1]};
    const double la = sqrt((a1.x - a0.x) * (a1.x - a0.x) + (a1.y - a0.y) * (a1.y - a0.y));
    const double lb = sqrt((b1.x - b0.x) * (b1.x - b0.x) + (b1.y - b0.y) * (b1.y - b0.y));
    const fdem::Vec2 nrm = fdem::edge_outward_normal(a0, a1);  // from face A towards face B, length la
    const double open0 = ((b1.x - a0.x) * nrm.x + (b1.y - a0.y) * nrm.y) / la;
    const double open1 = ((b0.x - a1.x) * nrm.x + (b0.y - a1.y) * nrm.y) / la;
    const CrackWidth cw = crack_width(0.5 * (open0 + open1), residual_aperture);
    const double L = 0.5 * (la + lb), w = cw.w, V = L * w;
    length[s] = L, aperture[s] = w, load_factor[s] = cw.dw_dopening;
    int ci = -1, cj = -1, fi = 0, fj = 0;
    if (facing_cell(g, a0, a1, fi, fj) && active(fi, fj)) ci = fi, cj = fj;
    else if (facing_cell(g, b0, b1, fi, fj) && active(fi, fj)) ci = fi, cj = fj;
    const bool meets_grid = ci >= 0;
    const std::uint8_t kind = n.kind[s];
    if (kind == kSegmentNone || (kind == kSegmentGrid && !meets_grid)) {
      n.kind[s] = meets_grid ? kSegmentGrid : kSegmentGas, n.cons[s] = {0, 0, 0, 0, 0}, n.volume[s] = V;
      return;
    }
    if (kind != kSegmentGas) return;
    ChannelConserved c = n.cons[s];
    const double V_old = n.volume[s];
    const ChannelPrimitive P = segment_state(mat, c, V_old);
    if (!is_vacuum(P)) c.E -= P.p * (V - V_old);
    n.volume[s] = V;
    if (meets_grid) {
      handover[s] = c, handover_cell[s] = cj * g.nx + ci;
      n.kind[s] = kSegmentGrid, c = {0, 0, 0, 0, 0};
    }
    n.cons[s] = c;
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
  Field2D<const double> rho, e;
  cip::MaterialReadView materials;
  CrackGraphView graph;
  CrackNetworkView n;
  const std::uint8_t* outline;  // per junction
  std::uint8_t* mouth;
  ChannelPrimitive* reservoir;
  int* junction_cell;
  BLAST_HD void operator()(index_t ji) const {
    const int J = static_cast<int>(ji);
    mouth[J] = 0, junction_cell[J] = -1;
    int end = -1;
    for (int k = graph.junction_offset[J]; k < graph.junction_offset[J + 1] && end < 0; ++k)
      if (n.kind[graph.junction_entry[k] / 2] == kSegmentGas) end = graph.junction_entry[k];
    if (end < 0) return;
    const fdem::JointNodes jn = rock.joint_nodes[end / 2];
    const int na = end % 2 == 0 ? jn.a0 : jn.a1, nb = end % 2 == 0 ? jn.b1 : jn.b0;
    const double x = 0.5 * (rock.x[na] + rock.x[nb]), y = 0.5 * (rock.y[na] + rock.y[nb]);
    int ci = 0, cj = 0;
    const bool inside = cell_of(g, x, y, ci, cj);
    int fi = -1, fj = -1;
    if (inside && active(ci, cj)) {
      fi = ci, fj = cj;
    } else if (outline[J]) {
      double best = 1e300;
      for (int j = imax(0, cj - 1); j <= imin(g.ny - 1, cj + 1); ++j)
        for (int i = imax(0, ci - 1); i <= imin(g.nx - 1, ci + 1); ++i) {
          if (!active(i, j)) continue;
          const double dx = g.cell_x(i) - x, dy = g.cell_y(j) - y, d = dx * dx + dy * dy;
          if (d < best) best = d, fi = i, fj = j;
        }
    }
    if (fi < 0) return;
    const double r = rho(fi, fj);
    const double alpha = mat.two ? materials.alpha(fi, fj) : 0.0, Y = mat.two ? materials.m1(fi, fj) / r : 0.0;
    mouth[J] = 1, junction_cell[J] = fj * g.nx + fi;
    reservoir[J] = channel_state(mat, r, 0.0, e(fi, fj), Y, alpha);
  }
};

//! The cell key of every deposit record (0 .. junctions - 1: the mouths, then the segments' hand-overs; a
//! record without a cell sorts last).
struct CrackDepositKeyKernel {
  const int* junction_cell;
  const int* handover_cell;
  int* key;
  int junctions;
  BLAST_HD void operator()(index_t k) const {
    const int c = k < junctions ? junction_cell[k] : handover_cell[k - junctions];
    key[k] = c < 0 ? 0x7fffffff : c;
  }
};

//! Adds the cracks' deposits to their cells (one thread per run of equal cell keys in the sorted records: the
//! first of the run sums them in sorted order, so the bytes do not depend on the thread schedule). Records
//! 0 .. junctions - 1 are the mouths' deposits, the rest the segments' hand-overs. The deposited energy is
//! internal energy of the cell (the cell's faces keep their velocities).
struct CrackDepositKernel {
  const int* key;    // sorted cell keys (INT_MAX: none)
  const int* order;  // record of each sorted position
  const ChannelConserved* deposit;
  const ChannelConserved* handover;
  int junctions, records, nx;
  double cell_area;
  cip::GasStateView s;
  bool two;
  cip::MaterialView materials;
  BLAST_HD void operator()(index_t ki) const {
    const int k = static_cast<int>(ki);
    const int c = key[k];
    if (c == 0x7fffffff || (k > 0 && key[k - 1] == c)) return;
    ChannelConserved sum{0, 0, 0, 0, 0};
    for (int r = k; r < records && key[r] == c; ++r) {
      const int rec = order[r];
      const ChannelConserved d = rec < junctions ? deposit[rec] : handover[rec - junctions];
      sum.m += d.m, sum.E += d.E, sum.m1 += d.m1, sum.am += d.am;
    }
    const int i = c % nx, j = c / nx;
    const double m_old = s.rho.f(i, j) * cell_area, m_new = m_old + sum.m;
    const double E_new = s.e.f(i, j) * m_old + sum.E;
    s.rho.f(i, j) = m_new / cell_area;
    s.e.f(i, j) = E_new / m_new;
    if (two) {
      materials.alpha(i, j) = (materials.alpha(i, j) * m_old + sum.am) / m_new;
      materials.m1(i, j) += sum.m1 / cell_area;
    }
  }
};

//! The two values the host reads after a coupled step (GasRockCoupler::step()): the gas's largest signal rate
//! [1/s] (the next dt) and the rock's largest node speed over the step's substeps [m/s] (contact rebuild,
//! instability check), in one reduction, so the host waits once a step.
struct StepScalars {
  double signal_rate, rock_speed;
};
struct StepScalarsOf {
  cip::SignalRate gas;
  fdem::NodeSpeedPeak rock;
  index_t cells;
  BLAST_HD StepScalars operator()(index_t k) const {
    return k < cells ? StepScalars{gas(k), 0.0} : StepScalars{0.0, rock(k - cells)};
  }
};
//! Componentwise maximum (order-independent: the same bits on any reduction tree; the flags for a non-finite
//! state, +infinity and 1e308, win as they do in each solver's own reduction).
struct MaxOfStepScalars {
  BLAST_HD StepScalars operator()(const StepScalars& a, const StepScalars& b) const {
    return {a.signal_rate > b.signal_rate ? a.signal_rate : b.signal_rate,
            a.rock_speed > b.rock_speed ? a.rock_speed : b.rock_speed};
  }
};

}  // namespace blastsim::ibm
