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

//! The face points of one kind (face 0: x-faces at (x_min + i dx, y_min + (j + 1/2) dy); 1: y-faces at
//! (x_min + (i + 1/2) dx, y_min + j dy)) inside the bounding box of the triangle with nodes (x, y): indices
//! i0..i1, j0..j1 (empty when i0 > i1 or j0 > j1) and the points' offsets in cells.
struct FaceBox {
  int i0, i1, j0, j1;
  double ox, oy;
};
BLAST_HD inline FaceBox triangle_face_box(const cip::GasGrid& g, const double* x, const double* y, int face) {
  const double x0 = min_of(x[0], min_of(x[1], x[2])), x1 = max_of(x[0], max_of(x[1], x[2]));
  const double y0 = min_of(y[0], min_of(y[1], y[2])), y1 = max_of(y[0], max_of(y[1], y[2]));
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
  Field2D<int> u_owner, v_owner;
  BLAST_HD void operator()(index_t ti) const {
    const int t = static_cast<int>(ti);
    double x[3], y[3];
    for (int k = 0; k < 3; ++k) x[k] = rock.x[3 * t + k], y[k] = rock.y[3 * t + k];
    for (int face = 0; face < 2; ++face) {
      const FaceBox b = triangle_face_box(g, x, y, face);
      for (int j = b.j0; j <= b.j1; ++j)
        for (int i = b.i0; i <= b.i1; ++i) {
          double w[3];
          if (barycentric(x, y, g.x_min + (i + b.ox) * g.dx, g.y_min + (j + b.oy) * g.dy, w) && inside(w))
            atomic_max(&(face == 0 ? u_owner : v_owner)(i, j), t);
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
      if (rock.edge_exposed[3 * t + k] == fdem::kEdgeInside) continue;
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
    for (int k = 0; k < 3; ++k) x[k] = rock.x[3 * t + k], y[k] = rock.y[3 * t + k];
    const double px = g.x_min + (i + (face == 0 ? 0.0 : 0.5)) * g.dx;
    const double py = g.y_min + (j + (face == 0 ? 0.5 : 0.0)) * g.dy;
    const FacePointCoupling c = face_point_coupling(rock, t, x, y, px, py, face, surface);
    double u = 0.0;
    for (int k = 0; k < 3; ++k) {
      const double vx = rock.vx[3 * t + k], vy = rock.vy[3 * t + k];
      if (c.nx == 0.0 && c.ny == 0.0) u += c.w[k] * (face == 0 ? vx : vy);
      else u += c.w[k] * (face == 0 ? c.nx : c.ny) * (c.nx * vx + c.ny * vy);  // the normal motion's component
    }
    imposed(i, j) = u;
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
  bool face_forces;  // GasLoad::face_forces: the grid gas loads the rock through FaceLoadKernel instead
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
    if (face_forces) {
      rock.edge_pressure[s] = 0.0;
      return;
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

//! GasLoad::face_forces (docs/coupling.md "Face forces"): the force the grid gas puts on the rock is the one its
//! own momentum equation applied at the prescribed faces. Per triangle t, every face point of its bounding box
//! that t covers (owner == t) carries A (P_low - P_high) along its axis, P = p + q of the gas's last step in the
//! active cells on either side (A the face's length), put on t's nodes with the weights and along the surface
//! normal that gave the face its imposed velocity (face_point_coupling()). So the rock's power under these loads
//! is the gas's power on the prescribed faces, term by term. Each triangle writes its own three node slots: no
//! atomics. Before the gas's first step (`use_step_pressure` false) P is the cells' pressure p.
struct FaceLoadKernel {
  fdem::RockView rock;
  cip::GasGrid g;
  cip::GasMaterials mat;
  cip::MaterialReadView materials;
  Field2D<const std::uint8_t> active;
  Field2D<const double> rho, e;
  Field2D<const int> u_owner, v_owner;
  Field2D<const double> P;  // p + q of the last step [Pa]
  bool use_step_pressure;
  BLAST_HD double pressure(int i, int j) const {
    return use_step_pressure ? P(i, j) : cip::cell_pressure(mat, materials, rho(i, j), e(i, j), i, j);
  }
  BLAST_HD void operator()(index_t ti) const {
    const int t = static_cast<int>(ti);
    double x[3], y[3];
    for (int k = 0; k < 3; ++k) x[k] = rock.x[3 * t + k], y[k] = rock.y[3 * t + k];
    double fx[3] = {0.0, 0.0, 0.0}, fy[3] = {0.0, 0.0, 0.0};
    for (int face = 0; face < 2; ++face) {
      const FaceBox b = triangle_face_box(g, x, y, face);
      const double ox = b.ox, oy = b.oy;
      const Field2D<const int> owner = face == 0 ? u_owner : v_owner;  // by value: no run-time-chosen reference
      for (int j = b.j0; j <= b.j1; ++j)
        for (int i = b.i0; i <= b.i1; ++i) {
          if (owner(i, j) != t) continue;
          const int il = face == 0 ? i - 1 : i, jl = face == 0 ? j : j - 1;  // the low-side cell; (i, j) the high
          double F = 0.0;  // [N/m] along +axis
          if (il >= 0 && jl >= 0 && active(il, jl)) F += pressure(il, jl);
          if (i < g.nx && j < g.ny && active(i, j)) F -= pressure(i, j);
          if (F == 0.0) continue;
          F *= face == 0 ? g.dy : g.dx;
          const FacePointCoupling c =
              face_point_coupling(rock, t, x, y, g.x_min + (i + ox) * g.dx, g.y_min + (j + oy) * g.dy, face, true);
          if (c.nx != 0.0 || c.ny != 0.0) {  // along the surface normal
            const double Fn = F * (face == 0 ? c.nx : c.ny);
            for (int k = 0; k < 3; ++k) fx[k] += c.w[k] * Fn * c.nx, fy[k] += c.w[k] * Fn * c.ny;
          } else if (face == 0) {  // no surface: along the axis
            for (int k = 0; k < 3; ++k) fx[k] += c.w[k] * F;
          } else {
            for (int k = 0; k < 3; ++k) fy[k] += c.w[k] * F;
          }
        }
    }
    for (int k = 0; k < 3; ++k) rock.node_load[3 * t + k] = {fx[k], fy[k]};
  }
};

//! Force of the gas on the rock [N/m] per slot: p L along the inward normal of an exposed edge, plus the face
//! force on the slot's node (GasLoad::face_forces).
struct EdgeForceOf {
  fdem::RockView rock;
  BLAST_HD Vec2Sum operator()(index_t si) const {
    const int s = static_cast<int>(si);
    const fdem::Vec2 load = rock.node_load[s];
    if (!rock.edge_exposed[s]) return {load.x, load.y};
    const int a = fdem::slot_first_node(s), b = fdem::slot_second_node(s);
    const double p = rock.edge_pressure[s];  // along the inward normal
    const fdem::Vec2 n = fdem::edge_outward_normal({rock.x[a], rock.y[a]}, {rock.x[b], rock.y[b]});
    return {load.x - p * n.x, load.y - p * n.y};
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
    if (!is_vacuum(P)) c.E -= expansion_work(c, P.p, V_old, V);
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
