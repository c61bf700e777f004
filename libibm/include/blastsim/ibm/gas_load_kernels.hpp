//! \file gas_load_kernels.hpp
//! \brief The kernels of the gas's load on the rock (docs/coupling.md "Gas -> rock" and "Face forces"): edge
//! pressures, the face forces of the prescribed faces, and the resulting force for the diagnostics.
//! GasLoading (gas_loading.hpp) launches them. Plain header: no backend dependency.
#pragma once

#include "blastsim/cip/eos.hpp"
#include "blastsim/cip/gas_state.hpp"
#include "blastsim/cip/grid.hpp"
#include "blastsim/core/field2d.hpp"
#include "blastsim/fdem/rock_fields.hpp"
#include "blastsim/ibm/coupling_kernels.hpp"
#include "blastsim/ibm/immersed_boundary_kernels.hpp"

#include <cmath>
#include <cstdint>

namespace blastsim::ibm {

//! Pressure on each exposed rock edge (docs/coupling.md "Gas -> rock"): the cell the edge faces (the one
//! holding the point a hundredth of a cell off the midpoint along the outward normal) gives its pressure when
//! it is active. Otherwise a boundary edge takes the active cell nearest to its midpoint within 2 cells (the
//! paper's rule; ties go to the first in scan order) and a crack face the ambient pressure: a crack narrower
//! than the grid holds no gas, and loading its faces with the pressure of a cell beside it would do work
//! that no gas pays for (both faces of a closed crack get the same pressure, which cancels). With face forces
//! (GasLoad::face_forces) the grid gas loads the rock through FaceLoadKernel instead, and every edge pressure
//! is 0. The faces of a crack with its own gas are loaded afterwards by the crack gas (CrackFacePressureKernel).
struct EdgePressureKernel {
  fdem::RockView rock;
  cip::GasGrid g;
  cip::GasMaterials mat;
  cip::MaterialReadView materials;  // read in two-material runs
  Field2D<const std::uint8_t> active;
  Field2D<const double> rho, e;
  double ambient_pressure;
  bool face_forces;
  BLAST_HD void operator()(index_t si) const {
    const int s = static_cast<int>(si);
    const std::uint8_t kind = rock.edges.exposed[s];
    if (kind == fdem::kEdgeInside) return;
    if (face_forces) {
      rock.loads.pressure[s] = 0.0;
      return;
    }
    const int a = fdem::slot_first_node(s), b = fdem::slot_second_node(s);
    const double mx = 0.5 * (rock.nodes.x[a] + rock.nodes.x[b]), my = 0.5 * (rock.nodes.y[a] + rock.nodes.y[b]);
    int fi = 0, fj = 0;
    double p = ambient_pressure;
    if (facing_cell(g, {rock.nodes.x[a], rock.nodes.y[a]}, {rock.nodes.x[b], rock.nodes.y[b]}, fi, fj) && active(fi, fj)) {
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
    rock.loads.pressure[s] = p;
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
  FaceOwners<Access::read> owners;
  Field2D<const double> P;  // p + q of the last step [Pa]
  bool use_step_pressure;
  double owner_margin;  // [m] how far outside a triangle with a crack face its face points may lie (crack gaps)
  BLAST_HD double pressure(int i, int j) const {
    return use_step_pressure ? P(i, j) : cip::cell_pressure(mat, materials, rho(i, j), e(i, j), i, j);
  }
  BLAST_HD void operator()(index_t ti) const {
    const int t = static_cast<int>(ti);
    double x[3], y[3];
    for (int k = 0; k < 3; ++k) x[k] = rock.nodes.x[3 * t + k], y[k] = rock.nodes.y[3 * t + k];
    double fx[3] = {0.0, 0.0, 0.0}, fy[3] = {0.0, 0.0, 0.0};
    bool crack_face = false;  // the gap beside a crack face may hold face points this triangle owns
    for (int k = 0; k < 3; ++k) crack_face = crack_face || rock.edges.exposed[3 * t + k] == fdem::kEdgeCrackFace;
    for (int face = 0; face < 2; ++face) {
      const FaceBox b = triangle_face_box(g, x, y, face, crack_face ? owner_margin : 0.0);
      const double ox = b.ox, oy = b.oy;
      const Field2D<const int> owner = face == 0 ? owners.u : owners.v;  // by value: no run-time-chosen reference
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
    for (int k = 0; k < 3; ++k) rock.loads.node_load[3 * t + k] = {fx[k], fy[k]};
  }
};

//! Force of the gas on the rock [N/m] per slot: p L along the inward normal of an exposed edge, plus the face
//! force on the slot's node (GasLoad::face_forces).
struct EdgeForceOf {
  fdem::RockView rock;
  BLAST_HD Vec2Sum operator()(index_t si) const {
    const int s = static_cast<int>(si);
    const fdem::Vec2 load = rock.loads.node_load[s];
    if (!rock.edges.exposed[s]) return {load.x, load.y};
    const int a = fdem::slot_first_node(s), b = fdem::slot_second_node(s);
    const double p = rock.loads.pressure[s];  // along the inward normal
    const fdem::Vec2 n = fdem::edge_outward_normal({rock.nodes.x[a], rock.nodes.y[a]}, {rock.nodes.x[b], rock.nodes.y[b]});
    return {load.x - p * n.x, load.y - p * n.y};
  }
};

}  // namespace blastsim::ibm
