//! \file coupling_step_kernels.hpp
//! \brief The kernels of the immersed-boundary coupling step (paper sec. 2.3; docs/coupling.md): rock -> gas
//! (face points covered by triangles, imposed velocities, the new mask, gas moved between cells that change
//! state) and gas -> rock (edge pressures, the gas force). GasRockCoupler calls them; tests call them on a
//! few cells. Plain header: no backend dependency.
#pragma once

#include "blastsim/cip/eos.hpp"
#include "blastsim/cip/gas_state.hpp"
#include "blastsim/cip/gas_types.hpp"
#include "blastsim/cip/grid.hpp"
#include "blastsim/core/atomic.hpp"
#include "blastsim/core/field2d.hpp"
#include "blastsim/fdem/rock_fields.hpp"
#include "blastsim/fdem/rock_solver.hpp"
#include "blastsim/ibm/coupling_kernels.hpp"

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

//! Imposed velocity of each face point from its covering triangle's nodes (linear shape functions).
struct ImposedVelocityKernel {
  fdem::RockView rock;
  cip::GasGrid g;
  int face;  // 0: x-faces (u), 1: y-faces (v)
  Field2D<const int> owner;
  Field2D<std::uint8_t> prescribed;
  Field2D<double> imposed;
  BLAST_HD void operator()(int i, int j) const {
    const int t = owner(i, j);
    prescribed(i, j) = t >= 0;
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

//! A cell is inactive when its four face points are in rock (docs/coupling.md "Rock -> gas"): the new mask.
struct NewMaskKernel {
  Field2D<const int> u_owner, v_owner;
  Field2D<std::uint8_t> new_active;
  BLAST_HD void operator()(int i, int j) const {
    const bool covered = u_owner(i, j) >= 0 && u_owner(i + 1, j) >= 0 && v_owner(i, j) >= 0 && v_owner(i, j + 1) >= 0;
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

//! Pressure on each exposed rock edge (docs/coupling.md "Gas -> rock"). The cell the edge faces (the one
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
  BLAST_HD void operator()(index_t si) const {
    const int s = static_cast<int>(si);
    const std::uint8_t kind = rock.edge_exposed[s];
    if (kind == fdem::kEdgeInside) return;
    const int a = fdem::slot_first_node(s), b = fdem::slot_second_node(s);
    const double mx = 0.5 * (rock.x[a] + rock.x[b]), my = 0.5 * (rock.y[a] + rock.y[b]);
    const fdem::Vec2 n = fdem::edge_outward_normal({rock.x[a], rock.y[a]}, {rock.x[b], rock.y[b]});
    const double off = 0.01 * fmin(g.dx, g.dy) / sqrt(n.x * n.x + n.y * n.y);
    const int fi = static_cast<int>(floor((mx + off * n.x - g.x_min) / g.dx));
    const int fj = static_cast<int>(floor((my + off * n.y - g.y_min) / g.dy));
    double p = ambient_pressure;
    if (fi >= 0 && fi < g.nx && fj >= 0 && fj < g.ny && active(fi, fj)) {
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
}  // namespace blastsim::ibm
