//! \file immersed_boundary_kernels.hpp
//! \brief The kernels of the immersed boundary, rock -> gas (paper sec. 2.3; docs/coupling.md "Rock -> gas"):
//! the face points covered by triangles, their imposed velocities, the new mask, and the gas moved between cells
//! that change state. ImmersedBoundary (immersed_boundary.hpp) launches them; tests call them on a few cells.
//! Plain header: no backend dependency.
#pragma once

#include "blastsim/core/checkpoint_traits.hpp"
#include "blastsim/cip/gas_state.hpp"
#include "blastsim/cip/grid.hpp"
#include "blastsim/core/access.hpp"
#include "blastsim/core/atomic.hpp"
#include "blastsim/core/field2d.hpp"
#include "blastsim/fdem/rock_fields.hpp"
#include "blastsim/ibm/coupling_kernels.hpp"

#include <cmath>
#include <cstdint>

namespace blastsim::ibm {

//! Owner of a face point: none, a rock triangle (>= 0), or an unburnt charge (charge_kernels.hpp).
inline constexpr int kNoOwner = -1, kChargeOwner = -2;
//! No process claims the gas of a cell covered with nowhere to go (CellClaims::claim).
inline constexpr int kNoClaim = -1;

//! The immersed boundary's arrays on the gas grid's padded shape, as field lists X(element type, name,
//! comment) (core/access.hpp; storage in immersed_boundary.cpp): the face points' owners, rasterised every
//! rock_to_gas() and read by the other processes (CouplingContext); the cell update being built; and the
//! transition ledger, one record per cell i + nx j.
#define BLASTSIM_IBM_FACE_OWNERS(X)                                                               \
  X(int, u, "owner of each x-face point (i, j): a triangle (>= 0), kNoOwner or kChargeOwner")    \
  X(int, v, "owner of each y-face point")
#define BLASTSIM_IBM_CELL_UPDATE(X)                                                              \
  X(std::uint8_t, active, "the mask being built (1: active)")                                    \
  X(std::uint8_t, changed, "1 where the cell's gas moved in this update")                        \
  X(cip::CellContent, next, "what the cell holds after the move, per unit area")
#define BLASTSIM_IBM_CELL_CLAIMS(X)                                                                                \
  X(int, claim, "the crack segment whose gap holds a face point of the cell (kNoClaim: none), set each cover")    \
  X(cip::CellContent, taken, "the gas [per unit area] a covered cell with no stable cell beside it gave its claim")

//! Cumulative transitions of one cell [per unit thickness].
struct TransitionLedger {
  double covered;         //!< times it became inactive
  double uncovered;       //!< times it became active
  double mass_created;    //!< [kg/m] ambient gas given to it, less gas removed with nowhere to go
  double energy_created;  //!< [J/m] likewise
  double mass_lost;       //!< [kg/m] of that, the gas removed with nowhere to go (>= 0)
  double energy_lost;     //!< [J/m] likewise
};
}  // namespace blastsim::ibm
BLASTSIM_CHECKPOINT_REALS(blastsim::ibm::TransitionLedger)
namespace blastsim::ibm {
#define BLASTSIM_IBM_LEDGER(X) X(TransitionLedger, transitions, "per cell i + nx j, since the first update")

BLASTSIM_FIELD_GROUP(FaceOwners, BLASTSIM_IBM_FACE_OWNERS)
BLASTSIM_FIELD_GROUP(CellUpdate, BLASTSIM_IBM_CELL_UPDATE)
BLASTSIM_FIELD_GROUP(CellClaims, BLASTSIM_IBM_CELL_CLAIMS)
BLASTSIM_VIEW_GROUP(ImmersedLedger, BLASTSIM_IBM_LEDGER)

//! The face points of one kind (face 0: x-faces at (x_min + i dx, y_min + (j + 1/2) dy); 1: y-faces at
//! (x_min + (i + 1/2) dx, y_min + j dy)) inside the bounding box of the triangle with nodes (x, y): indices
//! i0..i1, j0..j1 (empty when i0 > i1 or j0 > j1) and the points' offsets in cells; `margin` [m] widens the box
//! on every side.
struct FaceBox {
  int i0, i1, j0, j1;
  double ox, oy;
};
BLAST_HD inline FaceBox triangle_face_box(const cip::GasGrid& g, const double* x, const double* y, int face,
                                          double margin = 0.0) {
  const double x0 = min_of(x[0], min_of(x[1], x[2])) - margin, x1 = max_of(x[0], max_of(x[1], x[2])) + margin;
  const double y0 = min_of(y[0], min_of(y[1], y[2])) - margin, y1 = max_of(y[0], max_of(y[1], y[2])) + margin;
  const double ox = face == 0 ? 0.0 : 0.5, oy = face == 0 ? 0.5 : 0.0;
  const int ni = face == 0 ? g.nx + 1 : g.nx, nj = face == 0 ? g.ny : g.ny + 1;
  return {imax(0, static_cast<int>(ceil((x0 - g.x_min) / g.dx - ox))),
          imin(ni - 1, static_cast<int>(floor((x1 - g.x_min) / g.dx - ox))),
          imax(0, static_cast<int>(ceil((y0 - g.y_min) / g.dy - oy))),
          imin(nj - 1, static_cast<int>(floor((y1 - g.y_min) / g.dy - oy))), ox, oy};
}

//! Marks the x-face (u) and y-face (v) points inside each triangle (docs/coupling.md "Rock -> gas": bounding-box
//! rasterisation), keeping the highest triangle index per point.
struct CoverKernel {
  fdem::RockView rock;
  cip::GasGrid g;
  FaceOwners<Access::read_write> owners;
  BLAST_HD void operator()(index_t ti) const {
    const int t = static_cast<int>(ti);
    double x[3], y[3];
    for (int k = 0; k < 3; ++k) x[k] = rock.nodes.x[3 * t + k], y[k] = rock.nodes.y[3 * t + k];
    for (int face = 0; face < 2; ++face) {
      const FaceBox b = triangle_face_box(g, x, y, face);
      for (int j = b.j0; j <= b.j1; ++j)
        for (int i = b.i0; i <= b.i1; ++i) {
          double w[3];
          if (barycentric(x, y, g.x_min + (i + b.ox) * g.dx, g.y_min + (j + b.oy) * g.dy, w) && inside(w))
            atomic_max(&(face == 0 ? owners.u : owners.v)(i, j), t);
        }
    }
  }
};

//! How a rock triangle meets the gas at one face point: the weights of its three nodes and, with the face-force
//! load (GasLoad::face_forces), the unit normal of the rock surface the point stands for.
struct FacePointCoupling {
  double w[3];
  double nx, ny;  // (0, 0): the point takes the whole velocity component (edge pressures; no exposed edge)
};

//! The face point (px, py) of an x-face (axis 0) or y-face (axis 1) covered by triangle t with nodes (x, y).
//! Edge pressures (the paper's rule, `surface` false): the linear shape functions at the point. Face forces
//! (`surface` true): the point stands for the rock surface between it and the cell beside it, so it moves onto
//! an exposed edge of t - the one the line through the point along the grid axis crosses nearest to it, or else
//! the exposed edge nearest to it - with that edge's linear weights there, and only the surface's normal motion
//! counts (a slip wall); a triangle with no exposed edge keeps its shape functions and the whole velocity
//! component (docs/coupling.md "Face forces").
BLAST_HD inline FacePointCoupling face_point_coupling(const fdem::RockView& rock, int t, const double* x, const double* y,
                                                      double px, double py, int axis, bool surface) {
  FacePointCoupling c{{1.0 / 3, 1.0 / 3, 1.0 / 3}, 0.0, 0.0};
  int edge = -1;
  double at = 0.0, edge_x = 0.0, edge_y = 0.0;  // position along the chosen edge (0 at its first node), its vector
  if (surface) {
    double along = 1e300, near = 1e300;  // the nearest crossing along the axis; the nearest edge
    int crossed = -1, nearest = -1;
    double s_crossed = 0.0, s_nearest = 0.0, cx = 0.0, cy = 0.0, nx = 0.0, ny = 0.0;
    for (int k = 0; k < 3; ++k) {  // unrolled: every index below is known at compile time
      if (rock.edges.exposed[3 * t + k] == fdem::kEdgeInside) continue;
      const int k1 = (k + 1) % 3;
      const double ex = x[k1] - x[k], ey = y[k1] - y[k];
      const double e_along = axis == 0 ? ex : ey, e_across = axis == 0 ? ey : ex;
      const double p_along = axis == 0 ? px - x[k] : py - y[k], p_across = axis == 0 ? py - y[k] : px - x[k];
      if (e_across != 0.0) {
        const double sc = p_across / e_across;  // the edge's point level with the face point across the axis
        const double d = fabs(sc * e_along - p_along);
        if (sc >= 0.0 && sc <= 1.0 && d < along) along = d, crossed = k, s_crossed = sc, cx = ex, cy = ey;
      }
      double sn = ((px - x[k]) * ex + (py - y[k]) * ey) / (ex * ex + ey * ey);
      sn = sn < 0.0 ? 0.0 : (sn > 1.0 ? 1.0 : sn);
      const double dx = px - (x[k] + sn * ex), dy = py - (y[k] + sn * ey), d2 = dx * dx + dy * dy;
      if (d2 < near) near = d2, nearest = k, s_nearest = sn, nx = ex, ny = ey;
    }
    edge = crossed >= 0 ? crossed : nearest;
    at = crossed >= 0 ? s_crossed : s_nearest;
    edge_x = crossed >= 0 ? cx : nx, edge_y = crossed >= 0 ? cy : ny;
  }
  if (edge < 0) {
    barycentric(x, y, px, py, c.w);
    return c;
  }
  for (int k = 0; k < 3; ++k) c.w[k] = k == edge ? 1.0 - at : (k == (edge + 1) % 3 ? at : 0.0);
  const double l = sqrt(edge_x * edge_x + edge_y * edge_y);
  c.nx = edge_y / l, c.ny = -edge_x / l;
  return c;
}

//! Imposed velocity of each face point from its covering triangle's nodes (face_point_coupling()); zero on the
//! wall of an unburnt charge.
struct ImposedVelocityKernel {
  fdem::RockView rock;
  cip::GasGrid g;
  int face;  // 0: x-faces (u), 1: y-faces (v)
  Field2D<const int> owner;
  Field2D<std::uint8_t> prescribed;
  Field2D<double> imposed;
  bool surface;  // face forces: surface points, normal motion (face_point_coupling())
  BLAST_HD void operator()(int i, int j) const {
    const int t = owner(i, j);
    prescribed(i, j) = t != kNoOwner;
    if (t == kChargeOwner) imposed(i, j) = 0.0;  // the wall of an unburnt charge, at rest
    if (t < 0) return;
    double x[3], y[3];
    for (int k = 0; k < 3; ++k) x[k] = rock.nodes.x[3 * t + k], y[k] = rock.nodes.y[3 * t + k];
    const double px = g.x_min + (i + (face == 0 ? 0.0 : 0.5)) * g.dx;
    const double py = g.y_min + (j + (face == 0 ? 0.5 : 0.0)) * g.dy;
    const FacePointCoupling c = face_point_coupling(rock, t, x, y, px, py, face, surface);
    double u = 0.0;
    for (int k = 0; k < 3; ++k) {
      const double vx = rock.nodes.vx[3 * t + k], vy = rock.nodes.vy[3 * t + k];
      if (c.nx == 0.0 && c.ny == 0.0) u += c.w[k] * (face == 0 ? vx : vy);
      else u += c.w[k] * (face == 0 ? c.nx : c.ny) * (c.nx * vx + c.ny * vy);  // the normal motion's component
    }
    imposed(i, j) = u;
  }
};

//! A cell is inactive when its four face points are in rock or an unburnt charge (docs/coupling.md "Rock -> gas"):
//! the new mask.
struct NewMaskKernel {
  FaceOwners<Access::read> owners;
  Field2D<std::uint8_t> new_active;
  BLAST_HD void operator()(int i, int j) const {
    const bool covered = owners.u(i, j) != kNoOwner && owners.u(i + 1, j) != kNoOwner && owners.v(i, j) != kNoOwner &&
                         owners.v(i, j + 1) != kNoOwner;
    new_active(i, j) = covered ? 0 : 1;
  }
};

//! Moves gas between cells that change state (docs/coupling.md "Cells that change state"). A covered cell
//! gives its mass and energy (internal, and the kinetic energy of its faces: handed_energy()) in equal shares
//! to its stable edge neighbours (active before and after), or, with none (two cut cells that shared their only
//! open face), to the stable cells of its 3 x 3 block; it then holds the ambient state. An uncovered cell starts
//! from the ambient state at rest: the gas of its neighbours flows in through the solver (splitting a
//! neighbour's gas instead made near-vacuum chains along opening cracks, and negative densities when the hole
//! gas arrived). Every cell computes its own new content from the old ones (a gather: no atomics,
//! order-independent), with the materials' share moving with the mass (cip::GasCells). The ledger counts the
//! transitions and the mass and energy they create: the ambient gas of uncovered cells, minus the gas of a
//! covered cell with no stable cell in its block, unless another model claims that cell (`claims.claim`: the
//! crack segment whose gap covers it, CrackGapCoverKernel): then its gas goes to `claims.taken` for the claimant
//! to collect in after_cells, and nothing is created or lost. `reset` (the first call): covered cells take the
//! ambient state, nothing moves and nothing is counted. A cell that changes state holds air.
struct TransitionKernel {
  Field2D<const std::uint8_t> old_active;
  CellUpdate<Access::read_write> update;  //!< reads the new mask `active`; writes `changed` and `next`
  cip::GasCellsRead cells;
  ImmersedLedger<Access::read_write> ledger;
  CellClaims<Access::read_write> claims;  //!< reads `claim`; writes `taken` of the claimed cells
  int nx, ny;
  double cell_area, rho_ambient, e_ambient;
  bool reset;

  BLAST_HD bool in_grid(int i, int j) const { return i >= 0 && i < nx && j >= 0 && j < ny; }
  BLAST_HD bool stable(int i, int j) const { return in_grid(i, j) && old_active(i, j) && update.active(i, j); }
  BLAST_HD bool dying(int i, int j) const { return in_grid(i, j) && old_active(i, j) && !update.active(i, j); }
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
    const auto& rho = cells.s.rho.f;
    double k = 0;
    auto face = [&](double w, int oi, int oj) { k += (stable(oi, oj) ? 0.5 : 0.25) * 0.5 * (rho(i, j) + rho(oi, oj)) * w * w; };
    face(cells.s.u.f(i, j), i - 1, j);
    face(cells.s.u.f(i + 1, j), i + 1, j);
    face(cells.s.v.f(i, j), i, j - 1);
    face(cells.s.v.f(i, j + 1), i, j + 1);
    return rho(i, j) * cells.s.e.f(i, j) + k;
  }

  //! Whether a cell of its 3 x 3 block (itself included) is covered in this update.
  BLAST_HD bool dying_in_block(int i, int j) const {
    for (int nj = j - 1; nj <= j + 1; ++nj)
      for (int ni = i - 1; ni <= i + 1; ++ni)
        if (dying(ni, nj)) return true;
    return false;
  }

  BLAST_HD void operator()(int i, int j) const {
    bool moved = old_active(i, j) != update.active(i, j);
    // Most cells keep their state and have no covered cell beside them: nothing moves, and `next` is not read
    // (ApplyTransitionKernel), so it is left as it is.
    if (!moved && (reset || !old_active(i, j) || !dying_in_block(i, j))) {
      update.changed(i, j) = 0;
      return;
    }
    cip::CellContent c = cells.own(i, j, cells.s.rho.f(i, j) * cells.s.e.f(i, j));
    TransitionLedger& led = ledger.transitions[static_cast<index_t>(j) * nx + i];
    if (moved) {  // covered or uncovered: the ambient state
      if (!reset) {
        if (update.active(i, j)) {
          led.uncovered += 1.0, led.mass_created += rho_ambient * cell_area;
          led.energy_created += rho_ambient * e_ambient * cell_area;
        } else {
          led.covered += 1.0;
          if (count_stable_block(i, j) == 0) {
            const double e = handed_energy(i, j);
            if (claims.claim(i, j) != kNoClaim) {
              claims.taken(i, j) = {c.mass, e, c.products_mass, c.alpha_mass};
            } else {
              led.mass_created -= c.mass * cell_area, led.energy_created -= e * cell_area;
              led.mass_lost += c.mass * cell_area, led.energy_lost += e * cell_area;
            }
          }
        }
      }
      c = {rho_ambient, rho_ambient * e_ambient, 0.0, 0.0};
    } else if (stable(i, j) && !reset) {
      for (int nj = j - 1; nj <= j + 1; ++nj)
        for (int ni = i - 1; ni <= i + 1; ++ni) {
          if (!dying(ni, nj)) continue;
          const int a = count_stable(ni, nj);       // >= 1 when this cell is its edge neighbour
          if (a > 0 && ni != i && nj != j) continue;  // a diagonal giver only when it has no stable edge neighbour
          const double share = 1.0 / (a > 0 ? a : count_stable_block(ni, nj));
          cells.add_share(c, share, ni, nj, handed_energy(ni, nj));
          moved = true;
        }
    }
    update.changed(i, j) = moved;
    update.next(i, j) = c;
  }
};

//! Writes the moved gas back (cip::GasCells::replace(): derivatives of a changed cell set to zero), stops the
//! faces of covered cells (their imposed velocity; their kinetic energy went with the cell's gas) and installs
//! the new mask. Two covered neighbours write their common face with the same value.
struct ApplyTransitionKernel {
  CellUpdate<Access::read> update;
  Field2D<const double> u_imposed, v_imposed;
  Field2D<std::uint8_t> active;
  cip::GasCells cells;
  BLAST_HD void operator()(int i, int j) const {
    if (active(i, j) && !update.active(i, j)) {
      cells.s.u.f(i, j) = u_imposed(i, j), cells.s.u.f(i + 1, j) = u_imposed(i + 1, j);
      cells.s.v.f(i, j) = v_imposed(i, j), cells.s.v.f(i, j + 1) = v_imposed(i, j + 1);
    }
    active(i, j) = update.active(i, j);
    if (update.changed(i, j)) cells.replace(i, j, update.next(i, j));
  }
};

}  // namespace blastsim::ibm
