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

//! GasLoading's arrays, as field lists (storage in gas_loading.cpp). The rock's nodes at the start of a coupled
//! step, for the work of the loads over it (GasLoading::keep_nodes()).
#define BLASTSIM_IBM_NODE_START(X)                           \
  X(double, x0, "each node's x at the step's start [m]")    \
  X(double, y0, "its y [m]")                                 \
  X(double, vx0, "its velocity along x [m/s]")              \
  X(double, vy0, "along y [m/s]")
//! Per edge slot (GasLoad::edge_pressures_paid): the cell that gave its pressure and that pressure, then the
//! work it did over the step, keyed by that cell and sorted by key.
#define BLASTSIM_IBM_EDGE_WORK(X)                                                              \
  X(int, source, "the cell j nx + i that gave the slot's pressure (-1: none)")                \
  X(double, loaded, "the pressure it gave [Pa]")                                              \
  X(int, key, "the paying cell, or 0x7fffffff (sorted after EdgeWorkKernel)")                 \
  X(int, record, "the slot at each sorted position")                                          \
  X(double, work, "the work the slot's pressure did on the rock over the step [J/m]")
BLASTSIM_VIEW_GROUP(NodeStart, BLASTSIM_IBM_NODE_START)
BLASTSIM_VIEW_GROUP(EdgeWork, BLASTSIM_IBM_EDGE_WORK)

//! The rock's nodes as the step starts (NodeStart).
struct NodeStartKernel {
  fdem::NodeMotion<Access::read> nodes;
  NodeStart<Access::read_write> start;
  BLAST_HD void operator()(index_t k) const {
    start.x0[k] = nodes.x[k], start.y0[k] = nodes.y[k], start.vx0[k] = nodes.vx[k], start.vy0[k] = nodes.vy[k];
  }
};

//! Pressure on each exposed rock edge (docs/coupling.md "Gas -> rock"): the cell the edge faces (the one
//! holding the point a hundredth of a cell off the midpoint along the outward normal) gives its pressure when
//! it is active. Otherwise a boundary edge takes the active cell nearest to its midpoint within 2 cells (the
//! paper's rule; ties go to the first in scan order) and a crack face the ambient pressure: a crack narrower
//! than the grid holds no gas, and loading its faces with the pressure of a cell beside it would do work
//! that no gas pays for (both faces of a closed crack get the same pressure, which cancels). With face forces
//! (GasLoad::face_forces) the grid gas loads the rock through FaceLoadKernel instead, and every edge pressure
//! is 0. The faces of a crack with its own gas are loaded afterwards by the crack gas (CrackFacePressureKernel).
//! With GasLoad::edge_pressures_paid (`paid`) each slot also records the cell whose pressure it took (j nx + i;
//! -1: none, the ambient pressure or not exposed) and that pressure, for EdgeWorkKernel.
struct EdgePressureKernel {
  fdem::RockView rock;
  cip::GasGrid g;
  cip::GasMaterials mat;
  cip::MaterialReadView materials;  // read in two-material runs
  Field2D<const std::uint8_t> active;
  Field2D<const double> rho, e;
  double ambient_pressure;
  bool face_forces;
  bool paid;                              //!< GasLoad::edge_pressures_paid: writes ew.source and ew.loaded
  EdgeWork<Access::read_write> ew;
  BLAST_HD void operator()(index_t si) const {
    const int s = static_cast<int>(si);
    const std::uint8_t kind = rock.edges.exposed[s];
    if (paid) ew.source[s] = -1;
    if (kind == fdem::kEdgeInside) return;
    if (face_forces) {
      rock.loads.pressure[s] = 0.0;
      return;
    }
    const int a = fdem::slot_first_node(s), b = fdem::slot_second_node(s);
    const double mx = 0.5 * (rock.nodes.x[a] + rock.nodes.x[b]), my = 0.5 * (rock.nodes.y[a] + rock.nodes.y[b]);
    int fi = 0, fj = 0;
    double p = ambient_pressure;
    int from = -1;  // the cell that gave p
    if (facing_cell(g, {rock.nodes.x[a], rock.nodes.y[a]}, {rock.nodes.x[b], rock.nodes.y[b]}, fi, fj) && active(fi, fj)) {
      p = cip::cell_pressure(mat, materials, rho(fi, fj), e(fi, fj), fi, fj);
      from = fj * g.nx + fi;
    } else if (kind == fdem::kEdgeBoundary) {
      const int ci = static_cast<int>(floor((mx - g.x_min) / g.dx)), cj = static_cast<int>(floor((my - g.y_min) / g.dy));
      double best = 1e300;
      for (int j = imax(0, cj - 2); j <= imin(g.ny - 1, cj + 2); ++j)
        for (int i = imax(0, ci - 2); i <= imin(g.nx - 1, ci + 2); ++i) {
          if (!active(i, j)) continue;
          const double dx = g.cell_x(i) - mx, dy = g.cell_y(j) - my, d = dx * dx + dy * dy;
          if (d < best) best = d, p = cip::cell_pressure(mat, materials, rho(i, j), e(i, j), i, j), from = j * g.nx + i;
        }
    }
    rock.loads.pressure[s] = p;
    if (paid) ew.source[s] = from, ew.loaded[s] = p;
  }
};

//! GasLoad::edge_pressures_paid, one thread per edge slot after the rock's substeps (docs/coupling.md "Edge
//! pressures that the gas pays for"): the work W [J/m] that the slot's pressure did on the rock over the coupled
//! step, keyed by the cell that gave the pressure (EdgePressureKernel's `source`; 0x7fffffff: none). The rock's
//! ledger (fdem::NodeUpdateKernel) counts f . d on each node per substep, f the pressure's half share -p L n / 2
//! on the geometry at the substep's start and d its trapezoid displacement, which runs from x - v dt_prev / 2 to
//! x + v_new dt / 2; over the substeps the d of a node add up to the path from x_0 - v_0 dt_prev / 2 to
//! x_end - v_end dt_sub / 2, and the edge's force is taken on the geometry half way along it (midpoint rule: the
//! difference from the ledger is of second order in the step's motion). A slot
//! whose pressure is no longer the one the grid gas gave (a crack face that its own gas loads, CrackGasCoupling,
//! whose work that gas pays) is not keyed.
struct EdgeWorkKernel {
  fdem::RockView rock;  // after the substeps
  NodeStart<Access::read> start;      // each node at the start of the step [m], [m/s]
  double dt_sub, dt_prev;             // the rock's substep, its step before this coupled step [s]
  double pressure_scale;              // the rock's factor on the edge pressures (fdem::RockSolver::pressure_scale())
  EdgeWork<Access::read_write> ew;    // reads source, loaded; writes key, record, work [J/m]
  BLAST_HD void operator()(index_t si) const {
    const int s = static_cast<int>(si);
    ew.record[s] = s;
    ew.work[s] = 0.0;
    ew.key[s] = 0x7fffffff;
    if (ew.source[s] < 0 || !rock.edges.exposed[s] || rock.loads.pressure[s] != ew.loaded[s]) return;
    const int ends[2] = {fdem::slot_first_node(s), fdem::slot_second_node(s)};
    fdem::Vec2 mid[2];          // each node half way along the ledger's path
    double dx = 0.0, dy = 0.0;  // the two nodes' ledger displacements, added
    for (int q = 0; q < 2; ++q) {
      const int k = ends[q];
      // The ledger's path runs from x_0 - v_0 dt_prev / 2 to x_end - v_end dt_sub / 2.
      const double xa = start.x0[k] - 0.5 * start.vx0[k] * dt_prev, xb = rock.nodes.x[k] - 0.5 * rock.nodes.vx[k] * dt_sub;
      const double ya = start.y0[k] - 0.5 * start.vy0[k] * dt_prev, yb = rock.nodes.y[k] - 0.5 * rock.nodes.vy[k] * dt_sub;
      mid[q] = {0.5 * (xa + xb), 0.5 * (ya + yb)};
      dx += xb - xa, dy += yb - ya;
    }
    const fdem::Vec2 n = fdem::edge_outward_normal(mid[0], mid[1]);
    ew.work[s] = -0.5 * pressure_scale * ew.loaded[s] * (n.x * dx + n.y * dy);
    ew.key[s] = ew.source[s];
  }
};

//! GasLoad::edge_pressures_paid: each cell pays the work of the edges it loaded (EdgeWorkKernel), one thread per
//! position of the slots sorted by cell (stable: slot order within a cell), the first of a cell's run summing it
//! in that order (deterministic, no atomics). The work leaves the cell's internal energy; where it would take
//! more than half of it, half is taken and the rest counted in the positivity ledger (as cip::DepositCellKernel
//! does), a source of the energy budget.
struct EdgeWorkChargeKernel {
  EdgeWork<Access::read> ew;  // key (sorted), record (the slot at each sorted position), work
  int slots, nx;
  double cell_area;  // [m2]
  cip::GasCells cells;
  BLAST_HD void operator()(index_t ki) const {
    const int k = static_cast<int>(ki);
    const int c = ew.key[k];
    if (c == 0x7fffffff || (k > 0 && ew.key[k - 1] == c)) return;
    double W = 0.0;
    for (int r = k; r < slots && ew.key[r] == c; ++r) W += ew.work[ew.record[r]];
    const int i = c % nx, j = c / nx;
    const double mass = cells.s.rho.f(i, j) * cell_area, internal = cells.s.e.f(i, j) * mass;
    const double taken = W > 0.5 * internal && internal > 0.0 ? 0.5 * internal : W;
    cells.positivity_heat(i, j) += (W - taken) / cell_area;
    cells.s.e.f(i, j) = (internal - taken) / mass;
  }
};

//! How far a prescribed face moved over the gas step as the gas's energy equation counted it [m] (paper eq. 3
//! with the face's time-centred velocity, cip::CellNonAdvectionKernel): (u_old + u_imposed) / 2 dt, u_old its
//! velocity at the step's start (the imposed velocity of the step before).
struct FaceStepMotion {
  Field2D<const double> u_old, v_old, u_imposed, v_imposed;
  double dt;  // the gas step [s]
  BLAST_HD double paid(int axis, int i, int j) const {
    return 0.5 * ((axis == 0 ? u_old : v_old)(i, j) + (axis == 0 ? u_imposed : v_imposed)(i, j)) * dt;
  }
};

//! Pressure work on an active cell whose volume changed by dV [m2 per unit thickness] at its pressure P = p + q of
//! the step: its internal energy changes by P dV.
struct CellPressureWork {
  cip::GasGrid g;
  Field2D<const double> P;  // p + q of the step [Pa]
  Field2D<const std::uint8_t> active;
  Field2D<const double> rho;
  Field2D<double> e;  // [J/kg]
  BLAST_HD void add(int i, int j, double dV) const {
    if (dV != 0.0) e(i, j) += P(i, j) * dV / (g.dx * g.dy * rho(i, j));
  }
};

//! GasLoad::edge_pressures_paid, per cell after the rock's substeps: an active cell takes back the work its energy
//! equation did at its prescribed faces in the gas step (FaceStepMotion), P A at each: the gas then loses to the
//! rock what EdgeWorkChargeKernel charges, the rock's own count of the edges' work (docs/coupling.md for what
//! is not paid: ambient-loaded edges, slots whose crack changes kind within a step, outflow boundary faces).
struct PrescribedFaceRefundKernel {
  Field2D<const std::uint8_t> u_prescribed, v_prescribed;
  FaceStepMotion motion;
  CellPressureWork cell;
  BLAST_HD double paid(int axis, int i, int j) const {
    return (axis == 0 ? u_prescribed : v_prescribed)(i, j) ? motion.paid(axis, i, j) : 0.0;
  }
  BLAST_HD void operator()(int i, int j) const {
    if (!cell.active(i, j)) return;
    cell.add(i, j, (paid(0, i + 1, j) - paid(0, i, j)) * cell.g.dy + (paid(1, i, j + 1) - paid(1, i, j)) * cell.g.dx);
  }
};

//! The coupling a face point's force was put on the rock with (FaceLoadKernel), marked with the load it belongs
//! to, so that a face not loaded by the step's load is told apart without clearing the records.
struct FaceLoadRecord {
  FacePointCoupling c;
  double stamp;
};

//! Per face point (padded shape): the face velocities a gas step starts from, and the coupling each face force
//! was put on the rock with (GasLoad::face_forces).
#define BLASTSIM_IBM_FACE_WORK(X)                                                  \
  X(double, u_old, "x-face velocity at the gas step's start [m/s]")               \
  X(double, v_old, "y-face velocity at its start [m/s]")                          \
  X(FaceLoadRecord, record_u, "x-face point: the coupling its force used")        \
  X(FaceLoadRecord, record_v, "y-face point: the same")
BLASTSIM_FIELD_GROUP(FaceWork, BLASTSIM_IBM_FACE_WORK)

//! The face velocities a gas step starts from (FaceWork's u_old, v_old), entry k of the padded shape.
struct FaceStartKernel {
  Field2D<const double> u, v;              //!< the state's face velocities
  FaceWork<Access::read_write> face_work;  //!< writes u_old, v_old
  BLAST_HD void operator()(index_t k) const {
    face_work.u_old.data[k] = u.data[k];
    face_work.v_old.data[k] = v.data[k];
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
  Field2D<FaceLoadRecord> record_u, record_v;  // per face point it loads: the coupling used (FaceWorkLagKernel)
  double stamp;  // this load's mark in the records (the gas's step count)
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
          (face == 0 ? record_u : record_v)(i, j) = FaceLoadRecord{c, stamp};
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

//! The face forces' work over a coupled step (docs/coupling.md "Face forces", "Work over a step"). At a
//! prescribed face the gas's energy equation pays A P (u_old + u_imposed) / 2 dt on each side (u_old: the face's
//! velocity at the step's start, the imposed velocity of the step before), while the rock receives the face's
//! force A (P_low - P_high) times the motion of the surface point over its substeps as its ledger counts it (the
//! trapezoid rule: for every node 0.5 v_0 dt_prev + (x_end - x_0) - 0.5 v_end dt_sub). Where the rock accelerates
//! (the first microseconds of a charge) the two differ at first order in dt. Each active cell pays its share of
//! the difference: P A lag, lost at a face on its high side, gained at one on its low side, so that the gas gives
//! exactly the work the rock received. A gather per cell (each face's lag computed by both its cells alike).
struct FaceWorkLagKernel {
  fdem::RockView rock;  // after the substeps
  NodeStart<Access::read> start;  // each node at the start of the step [m], [m/s]
  double dt_sub, dt_prev;  // the rock's substep, its step before this coupled step [s]
  Field2D<const int> owner_u, owner_v;
  Field2D<const FaceLoadRecord> record_u, record_v;
  double stamp;  // the step's load
  FaceStepMotion motion;
  CellPressureWork cell;
  //! How far face (i, j) of `axis` moved along +axis over the step as the rock counts it, beyond what the gas
  //! paid for [m]; 0 where the rock took no force from it.
  BLAST_HD double lag(int axis, int i, int j) const {
    const int t = (axis == 0 ? owner_u : owner_v)(i, j);
    if (t < 0) return 0.0;
    const FaceLoadRecord r = (axis == 0 ? record_u : record_v)(i, j);
    if (r.stamp != stamp) return 0.0;  // not loaded in this step (no active cell beside it pushed)
    const FacePointCoupling& c = r.c;
    double d = 0.0;
    for (int k = 0; k < 3; ++k) {
      const int n = 3 * t + k;
      const double mx = rock.nodes.x[n] - start.x0[n] + 0.5 * (start.vx0[n] * dt_prev - rock.nodes.vx[n] * dt_sub);
      const double my = rock.nodes.y[n] - start.y0[n] + 0.5 * (start.vy0[n] * dt_prev - rock.nodes.vy[n] * dt_sub);
      if (c.nx == 0.0 && c.ny == 0.0) d += c.w[k] * (axis == 0 ? mx : my);
      else d += c.w[k] * (axis == 0 ? c.nx : c.ny) * (c.nx * mx + c.ny * my);
    }
    return d - motion.paid(axis, i, j);
  }
  BLAST_HD void operator()(int i, int j) const {
    if (!cell.active(i, j)) return;
    cell.add(i, j, (lag(0, i, j) - lag(0, i + 1, j)) * cell.g.dy + (lag(1, i, j) - lag(1, i, j + 1)) * cell.g.dx);
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
