//! \file rock_step_kernels.hpp
//! \brief The kernels of one FDEM step (triangles, joints, contact, node update; one thread per item) over the
//! views of rock_fields.hpp: each kernel's members say what it reads (params, read views) and what it writes.
#pragma once

#include "blastsim/fdem/contact_kernels.hpp"
#include "blastsim/fdem/joint_kernels.hpp"
#include "blastsim/fdem/rock_fields.hpp"
#include "blastsim/fdem/rock_types.hpp"
#include "blastsim/fdem/triangle_kernels.hpp"

#include <cstdint>

namespace blastsim::fdem {

//! Bounding box of triangle t's current nodes.
struct Box {
  double lo_x, lo_y, hi_x, hi_y;
};
BLAST_HD inline Box triangle_box(const NodeMotion<Access::read>& m, int t) {
  Box b{1e300, 1e300, -1e300, -1e300};
  for (int k = 0; k < 3; ++k) {
    const double x = m.x[3 * t + k], y = m.y[3 * t + k];
    // min_of / max_of, not fmin / fmax (positions are finite: step() checks the speeds).
    b.lo_x = min_of(x, b.lo_x), b.lo_y = min_of(y, b.lo_y), b.hi_x = max_of(b.hi_x, x), b.hi_y = max_of(b.hi_y, y);
  }
  return b;
}
BLAST_HD inline bool boxes_apart(const Box& a, const Box& b, double margin) {
  return a.lo_x > b.hi_x + margin || b.lo_x > a.hi_x + margin || a.lo_y > b.hi_y + margin || b.lo_y > a.hi_y + margin;
}
//! Gap between two boxes [m]: the largest of the four separations along x and y, > 0 exactly when
//! boxes_apart(a, b, 0) holds (the sign of a difference of finite doubles is exact).
BLAST_HD inline double box_gap(const Box& a, const Box& b) {
  return max_of(max_of(a.lo_x - b.hi_x, b.lo_x - a.hi_x), max_of(a.lo_y - b.hi_y, b.lo_y - a.hi_y));
}

//! Upper bound [m] on how far a node moved along either axis in one update x += vx dt, y += vy dt of symplectic
//! Euler (x, y the new position): |vx| dt + |vy| dt, plus the rounding of the products, the sums and this bound
//! (each at most 2^-53 of its result; 1e-15 of the step and the coordinates covers them).
BLAST_HD inline double node_step_travel(double vx, double vy, double x, double y, double dt) {
  const double step = (fabs(vx) + fabs(vy)) * dt;
  return step + 1e-15 * (step + fabs(x) + fabs(y));
}
//! A travel counter after one more update: (counter + step) rounded, then raised by two units in the last
//! place, so that it grows by at least `step` whatever the rounding. The growth from any step to a later one then
//! bounds how far the nodes moved in between.
BLAST_HD inline double add_travel(double counter, double step) {
  return (counter + step) * (1.0 + 4.440892098500626e-16);
}

//! The travel budget of a pair just tested [m]: with boxes a gap g > 0 apart, the pair cannot touch before its
//! triangles' travel sum (`moved` now) grows by g, so it is skipped while the sum stays below moved + g / 2. The
//! other half covers the rounding of the sums (at most about 1e-15 of `moved`), so a gap below 1e-12 of `moved`,
//! or boxes that meet, get -1: the pair is tested every step.
BLAST_HD inline double pair_reach(double gap, double moved) {
  return gap > 0 && gap > 1e-12 * moved ? moved + 0.5 * gap : -1.0;
}

//! Uniform grid of the contact broad phase: cell size and origin, cells along x and y.
struct ContactGridShape {
  double cell_size, x0, y0;
  int nx, ny;
  //! The cell holding (x, y), clamped to the grid.
  BLAST_HD void cell_of(double x, double y, int& i, int& j) const {
    i = static_cast<int>(floor((x - x0) / cell_size));
    j = static_cast<int>(floor((y - y0) / cell_size));
    i = i < 0 ? 0 : (i >= nx ? nx - 1 : i);
    j = j < 0 ? 0 : (j >= ny ? ny - 1 : j);
  }
};

//! Centroid of triangle t.
BLAST_HD inline Vec2 triangle_centroid(const NodeMotion<Access::read>& m, int t) {
  return {(m.x[3 * t] + m.x[3 * t + 1] + m.x[3 * t + 2]) / 3.0, (m.y[3 * t] + m.y[3 * t + 1] + m.y[3 * t + 2]) / 3.0};
}

//! Broad phase (Munjiza's uniform grid, sort-by-cell form): for triangle t, the triangles in the 3 x 3 cells
//! around its centroid's cell whose boxes come within `margin` (the buffer). With `list` null it only counts
//! them into `count` (first pass); the second pass writes them from offset[t] on, in a fixed order.
struct NeighbourSearchKernel {
  NodeMotion<Access::read> nodes;
  const int *sorted_triangles, *cell_start, *cell_end;
  const int* offset;  //!< read in the second pass only
  ContactGridShape grid;
  double margin;
  int* count;
  int* list;
  BLAST_HD void operator()(index_t ti) const {
    const int i = static_cast<int>(ti);
    const Box bi = triangle_box(nodes, i);
    const Vec2 c = triangle_centroid(nodes, i);
    int ci, cj;
    grid.cell_of(c.x, c.y, ci, cj);
    int m = list ? offset[i] : 0;
    for (int dj = -1; dj <= 1; ++dj)
      for (int di = -1; di <= 1; ++di) {
        const int ii = ci + di, jj = cj + dj;
        if (ii < 0 || jj < 0 || ii >= grid.nx || jj >= grid.ny) continue;
        const int cell = jj * grid.nx + ii;
        for (int s = cell_start[cell]; s < cell_end[cell]; ++s) {
          const int j = sorted_triangles[s];
          if (j == i || boxes_apart(bi, triangle_box(nodes, j), margin)) continue;
          if (list) list[m] = j;
          ++m;
        }
      }
    if (!list) count[i] = m;
  }
};

//! Internal forces of each triangle on its own three nodes (Munjiza 2004, ch. 2; docs/fdem-solver.md), its
//! Cauchy stress for output, the work of its viscous damping eta D (dissipation), and the pressure loads of
//! its exposed edges on its nodes (uniform on each edge, one-point rule, half to each node, along the inward
//! normal; docs/coupling.md). Everything from the positions at the start of the step: the node update that
//! moves the nodes runs after. It also adds to the triangle's travel counter the largest node_step_travel() of
//! its nodes in the node update before (their velocities now are the ones that moved them: RockSolver starts
//! contact's budgets again where it changes velocities between steps), for contact's travel budgets.
struct TriangleForceKernel {
  NodeMotion<Access::read> nodes;
  TriangleParams params;
  EdgeState<Access::read> edges;  //!< exposed
  EdgeLoads<Access::read> loads;  //!< pressure, node_load
  NodeForces<Access::read_write> forces;  //!< writes triangle_* and pressure_*
  TriangleState<Access::read_write> state;
  double lambda, mu, pressure_scale, dt;
  double* travel;   //!< per triangle [m]: the travel counter (null without contact: not kept)
  double dt_moved;  //!< [s] the step of the last node update (0: none yet)
  BLAST_HD void operator()(index_t ti) const {
    const int t = static_cast<int>(ti);
    Vec2 p[3], v[3];
    for (int k = 0; k < 3; ++k) {
      p[k] = nodes.position(3 * t + k);
      v[k] = nodes.velocity(3 * t + k);
    }
    if (travel) {
      const double m0 = node_step_travel(v[0].x, v[0].y, p[0].x, p[0].y, dt_moved);
      const double m1 = node_step_travel(v[1].x, v[1].y, p[1].x, p[1].y, dt_moved);
      const double m2 = node_step_travel(v[2].x, v[2].y, p[2].x, p[2].y, dt_moved);
      travel[t] = add_travel(travel[t], max_of(max_of(m0, m1), m2));
    }
    const Mat2 inv_F0 = params.inv_f0[t];
    const Mat2 FX = edge_matrix(p[0], p[1], p[2]);
    const Mat2 LX = edge_matrix(v[0], v[1], v[2]);
    const double eta = params.eta[t];
    const Mat2 T = triangle_stress(inv_F0, FX, LX, lambda, mu, eta);
    Vec2 f[3];
    triangle_nodal_forces(T, p[0], p[1], p[2], f);
    for (int k = 0; k < 3; ++k) {
      forces.triangle_x[3 * t + k] = f[k].x;
      forces.triangle_y[3 * t + k] = f[k].y;
    }
    state.stress[t] = {T.a, T.b, T.d};
    Vec2 fp[3] = {{0, 0}, {0, 0}, {0, 0}};
    for (int e = 0; e < 3; ++e) {
      const int s = 3 * t + e;
      const double pe = edges.exposed[s] ? pressure_scale * loads.pressure[s] : 0.0;
      if (pe == 0.0) continue;
      const int e1 = (e + 1) % 3;
      const Vec2 n = edge_outward_normal(p[e], p[e1]);
      const Vec2 half{-0.5 * pe * n.x, -0.5 * pe * n.y};
      fp[e] = {fp[e].x + half.x, fp[e].y + half.y};
      fp[e1] = {fp[e1].x + half.x, fp[e1].y + half.y};
    }
    for (int k = 0; k < 3; ++k) {
      const Vec2 load = loads.node_load[3 * t + k];
      forces.pressure_x[3 * t + k] = fp[k].x + load.x;
      forces.pressure_y[3 * t + k] = fp[k].y + load.y;
    }
    if (eta > 0) {  // dissipation rate A eta D:D
      const Mat2 L = LX * FX.inverse();
      const double dxy = 0.5 * (L.b + L.c);
      const double area = 0.5 * FX.det();
      state.dissipation[t].damping += area * eta * (L.a * L.a + L.d * L.d + 2.0 * dxy * dxy) * dt;
    }
  }
};

//! Geometry of an intact cohesive joint (Munjiza 2004, ch. 7; docs/fdem-solver.md): the unit tangent t of its
//! two faces' mean direction, and the opening and slip at the edge's two ends and middle, into
//! JointState::separation. The first of the two passes of the joint forces: it holds the joint's latency chain
//! (the node gathers, a root and a division), which JointForceKernel then reads, so that a host thread overlaps
//! the chains of successive joints instead of waiting on each.
struct JointGeometryKernel {
  NodeMotion<Access::read> nodes;
  JointParams params;
  JointState<Access::read_write> state;  //!< writes separation
  Vec2* tangent;                         //!< per joint: t of this substep
  BLAST_HD void operator()(index_t ji) const {
    const int j = static_cast<int>(ji);
    if (state.broken[j]) return;
    const JointNodes jn = params.nodes[j];
    // In-situ stress: the joint starts at the opening and slip whose tractions carry it (joint_preload()). No
    // addition without one, so a joint without in-situ stress keeps the same bits (signed zeros included).
    const JointPreload pre = params.preload[j];
    const bool preloaded = pre.opening != 0.0 || pre.slip != 0.0;
    const Vec2 pa0 = nodes.position(jn.a0), pa1 = nodes.position(jn.a1);
    const Vec2 pb0 = nodes.position(jn.b0), pb1 = nodes.position(jn.b1);
    // Mean direction of the two faces (both run a0 -> a1), and the normal pointing out of face A.
    Vec2 t{pa1.x - pa0.x + pb0.x - pb1.x, pa1.y - pa0.y + pb0.y - pb1.y};
    const double tl = sqrt(t.x * t.x + t.y * t.y);
    t = {t.x / tl, t.y / tl};
    const Vec2 n{t.y, -t.x};
    tangent[j] = t;
    const double xi[kJointPoints] = {0.0, 0.5, 1.0};
    JointPointValues& separation = state.separation[j];
    BLAST_UNROLL
    for (int q = 0; q < kJointPoints; ++q) {
      const Vec2 xa{pa0.x + xi[q] * (pa1.x - pa0.x), pa0.y + xi[q] * (pa1.y - pa0.y)};
      const Vec2 xb{pb1.x + xi[q] * (pb0.x - pb1.x), pb1.y + xi[q] * (pb0.y - pb1.y)};
      const Vec2 d{xb.x - xa.x, xb.y - xa.y};
      double o = d.x * n.x + d.y * n.y, s = d.x * t.x + d.y * t.y;
      if (preloaded) o += pre.opening, s += pre.slip;
      separation.normal[q] = o;
      separation.shear[q] = s;
    }
  }
};

//! Cohesive joints (Munjiza 2004, ch. 7; docs/fdem-solver.md), after JointGeometryKernel: the joint law with
//! irreversible damage at the edge's two ends and middle (weights 1/6, 2/3, 1/6 of the initial length), and the
//! forces on the four nodes, written into the two edge slots the joint joins. A joint is broken once two of
//! its three points reach damage 1; its faces then become exposed edges and carry no cohesion.
struct JointForceKernel {
  JointParams params;
  JointState<Access::read_write> state;
  EdgeState<Access::read_write> edges;  //!< writes joint_force, and exposed when the joint breaks
  const Vec2* tangent;                  //!< per joint: t of this substep (JointGeometryKernel)
  BLAST_HD void operator()(index_t ji) const {
    const int j = static_cast<int>(ji);
    const JointNodes jn = params.nodes[j];
    const int a0 = jn.a0, b0 = jn.b0;
    SlotForce& fa = edges.joint_force[a0];  // slot of face A: its first node is a0, its second a1
    SlotForce& fb = edges.joint_force[b0];  // slot of face B: b0, then b1
    if (state.broken[j]) {
      fa = fb = SlotForce{{0.0, 0.0}, {0.0, 0.0}};
      return;
    }
    const JointStrength strength = params.strength[j];
    const double length0 = params.length[j];
    const Vec2 t = tangent[j];
    const Vec2 n{t.y, -t.x};
    const double xi[kJointPoints] = {0.0, 0.5, 1.0};
    const double w[kJointPoints] = {length0 / 6.0, 4.0 * length0 / 6.0, length0 / 6.0};
    Vec2 f_a0{0, 0}, f_a1{0, 0};  // loads on face A's nodes; face B gets the opposite at b1, b0
    int broken_points = 0;
    JointPointDamage& damage = state.damage[j];
    JointPointPlastic& plastic = state.plastic[j];
    const JointPointValues& separation = state.separation[j];
    JointPointValues& traction = state.traction[j];
    BLAST_UNROLL
    for (int q = 0; q < kJointPoints; ++q) {
      const double o = separation.normal[q], s = separation.shear[q];
      const JointTraction tr =
          joint_traction(o, s, strength, JointHistory{damage.point[q], plastic.slip[q], plastic.path[q]});
      damage.point[q] = tr.damage;
      plastic.slip[q] = tr.plastic_slip;
      plastic.path[q] = tr.slip_path;
      traction.normal[q] = tr.normal;
      traction.shear[q] = tr.shear;
      if (tr.damage >= 1.0) ++broken_points;
      // Face A is pulled towards B by tension and dragged along the slip by shear.
      const Vec2 load{(tr.normal * n.x + tr.shear * t.x) * w[q], (tr.normal * n.y + tr.shear * t.y) * w[q]};
      f_a0 = {f_a0.x + (1.0 - xi[q]) * load.x, f_a0.y + (1.0 - xi[q]) * load.y};
      f_a1 = {f_a1.x + xi[q] * load.x, f_a1.y + xi[q] * load.y};
    }
    if (broken_points >= 2) {
      state.broken[j] = 1;
      edges.exposed[a0] = kEdgeCrackFace;
      edges.exposed[b0] = kEdgeCrackFace;
      fa = fb = SlotForce{{0.0, 0.0}, {0.0, 0.0}};
      return;
    }
    fa = SlotForce{f_a0, f_a1};
    // b0 sits opposite a1 and b1 opposite a0.
    fb = SlotForce{{-f_a1.x, -f_a1.y}, {-f_a0.x, -f_a0.y}};
  }
};

//! Estimate of the elastic energy [J/m] an intact joint still holds, summed over its three points with their
//! weights (0 for a broken joint): half the normal traction times the opening (a secant estimate) plus half the
//! shear traction times the elastic slip s - s_pl (exact: the shear branch is linear).
BLAST_HD inline double joint_stored_energy(const JointParams& params, const JointState<Access::read>& state, int j) {
  if (state.broken[j]) return 0.0;
  const double h = params.length[j];
  const double w[kJointPoints] = {h / 6.0, 4.0 * h / 6.0, h / 6.0};
  const JointPointValues& tr = state.traction[j];
  const JointPointValues& sep = state.separation[j];
  const JointPointPlastic& pl = state.plastic[j];
  double sum = 0;
  for (int q = 0; q < kJointPoints; ++q)
    sum += 0.5 * w[q] * (tr.normal[q] * sep.normal[q] + tr.shear[q] * (sep.shear[q] - pl.slip[q]));
  return sum;
}

//! Contact pairs from the broad phase's candidate lists, which are symmetric (j is in i's list exactly when i
//! is in j's: same cells, same box test). Each unordered pair {i, j} is numbered once, as (i, j) with i < j,
//! triangle by triangle: pair_offset[i] + the rank of j among i's candidates above i. First pass: how many
//! pairs each triangle leads.
struct PairCountKernel {
  const int *offset, *list;
  int* count;
  BLAST_HD void operator()(index_t ti) const {
    const int i = static_cast<int>(ti);
    int c = 0;
    for (int s = offset[i]; s < offset[i + 1]; ++s) c += list[s] > i ? 1 : 0;
    count[i] = c;
  }
};

//! Second pass: the pair of every candidate slot (slot_pair), and each pair's triangles (pair).
//! A slot whose partner's list lacks it (which symmetric lists never do) gets -1; the caller checks.
struct PairIndexKernel {
  const int *offset, *list, *pair_offset;
  int* slot_pair;
  TrianglePair* pair;
  BLAST_HD void operator()(index_t ti) const {
    const int i = static_cast<int>(ti);
    int k = 0;
    for (int s = offset[i]; s < offset[i + 1]; ++s) {
      const int j = list[s];
      if (j > i) {
        const int p = pair_offset[i] + k++;
        slot_pair[s] = p;
        pair[p] = {i, j};
        continue;
      }
      int rank = 0, found = -1;
      for (int t = offset[j]; t < offset[j + 1] && found < 0; ++t) {
        if (list[t] == i) found = pair_offset[j] + rank;
        rank += list[t] > j ? 1 : 0;
      }
      slot_pair[s] = found;
    }
  }
};

//! What holds pair (i, j) together while intact, found once per build of the pairs: the joint across their
//! common edge, or their one common mesh vertex (encoded -2 - v), or nothing (-1).
struct PairBondKernel {
  NodeParams node_params;  //!< vertex
  EdgeParams edge_params;  //!< neighbour, joint
  const TrianglePair* pair;
  int* bond;
  BLAST_HD void operator()(index_t p) const {
    const int i = pair[p].i, j = pair[p].j;
    for (int e = 0; e < 3; ++e)
      if (edge_params.neighbour[3 * i + e] == j) {
        bond[p] = edge_params.joint[3 * i + e] >= 0 ? edge_params.joint[3 * i + e] : -1;
        return;
      }
    int shared = -1, count = 0;
    for (int a = 0; a < 3; ++a) {
      const int v = node_params.vertex[3 * i + a];
      for (int c = 0; c < 3; ++c)
        if (node_params.vertex[3 * j + c] == v) shared = v, ++count;
    }
    bond[p] = count == 1 ? -2 - shared : -1;
  }
};

//! The contact offset of each candidate slot's pair (kept across rebuilds of the lists and in checkpoints).
struct SlotOffsetKernel {
  const int* slot_pair;
  const double* pair_offset;
  double* slot_offset;
  BLAST_HD void operator()(index_t s) const { slot_offset[s] = pair_offset[slot_pair[s]]; }
};

//! After a rebuild: each new pair (i, j) takes the offset its slot had in i's previous candidate list, or -1
//! (none yet) where j was not a candidate of i before.
struct CarryOffsetKernel {
  const TrianglePair* pair;
  const int *old_offset, *old_list;
  const double* old_slot_offset;
  double* offset;
  BLAST_HD void operator()(index_t p) const {
    const int i = pair[p].i, j = pair[p].j;
    double o = -1;
    for (int s = old_offset[i]; s < old_offset[i + 1]; ++s)
      if (old_list[s] == j) {
        o = old_slot_offset[s];
        break;
      }
    offset[p] = o;
  }
};

//! 1 for a candidate slot that PairIndexKernel found no pair for (summed to check the lists' symmetry).
struct UnmatchedSlot {
  const int* slot_pair;
  BLAST_HD double operator()(index_t s) const { return slot_pair[s] < 0 ? 1.0 : 0.0; }
};

//! The six edge-against-target evaluations of one pair of triangles x[0], x[1] (counter-clockwise), with
//! their node velocities and masses: the loads on both triangles' nodes, the friction power, and the pair's
//! depth (the larger of the two triangles' deepest potential on the other's edges; docs/fdem-solver.md).
struct PairContact {
  Vec2 f[2][3];
  double friction_power;
  double depth;
  bool touching;
};
BLAST_HD inline PairContact pair_contact(const Vec2 x[2][3], const Vec2 v[2][3], const double m[2][3], double penalty,
                                         double friction, double dt, double offset) {
  PairContact out{{{{0, 0}, {0, 0}, {0, 0}}, {{0, 0}, {0, 0}, {0, 0}}}, 0.0, 0.0, false};
  double mt[2] = {0, 0};
  BLAST_UNROLL
  for (int side = 0; side < 2; ++side)
    BLAST_UNROLL
    for (int k = 0; k < 3; ++k) mt[side] += m[side][k];
  BLAST_UNROLL
  for (int c = 0; c < 2; ++c) {  // contactor c's edges against target 1 - c
    const int t = 1 - c;
    BLAST_UNROLL
    for (int e = 0; e < 3; ++e) {
      const int e1 = (e + 1) % 3;
      const EdgeContactLoad l = edge_against_target(x[c][e], x[c][e1], x[t], v[c][e], v[c][e1], v[t],
                                                    m[c][e] + m[c][e1], mt[t], penalty, friction, dt, offset);
      out.depth = max_of(out.depth, l.depth);
      if (!l.touching) continue;
      out.touching = true;
      out.f[c][e] = {out.f[c][e].x + l.edge[0].x, out.f[c][e].y + l.edge[0].y};
      out.f[c][e1] = {out.f[c][e1].x + l.edge[1].x, out.f[c][e1].y + l.edge[1].y};
      BLAST_UNROLL
      for (int k = 0; k < 3; ++k) out.f[t][k] = {out.f[t][k].x + l.target[k].x, out.f[t][k].y + l.target[k].y};
      out.friction_power += l.friction_power;
    }
  }
  return out;
}

//! The contact offset of a pair that meets at one mesh vertex, after a step in which its depth was `depth`
//! (docs/fdem-solver.md, "Which pairs touch"): on entry (offset < 0: its vertex was bonded until now) the
//! depth its corners already overlap by, so it enters without a load; afterwards lowered to the depth
//! whenever the pair is no deeper than its offset. Lowering it then stores or frees no energy: the pair
//! carries no load before or after.
BLAST_HD inline double next_contact_offset(double offset, double depth) {
  return offset < 0 || depth < offset ? depth : offset;
}

//! Clears vertex_bonded[v] once a joint touching mesh vertex v has broken (a gather over v's joints; the flag
//! never comes back, and it depends only on joints.broken, so a restart rebuilds it exactly).
struct VertexBondKernel {
  const int *vertex_joint_offset, *vertex_joints;
  const std::uint8_t* joint_broken;
  std::uint8_t* vertex_bonded;
  BLAST_HD void operator()(index_t vi) const {
    const int v = static_cast<int>(vi);
    if (!vertex_bonded[v]) return;
    for (int k = vertex_joint_offset[v]; k < vertex_joint_offset[v + 1]; ++k)
      if (joint_broken[vertex_joints[k]]) {
        vertex_bonded[v] = 0;
        return;
      }
  }
};

//! Whether a candidate pair is held together (PairBondKernel's `bond`): by its joint while intact (bond >= 0), or
//! at its one common mesh vertex while all that vertex's joints are intact (bond <= -2). Once released, never
//! held again (joints do not heal).
BLAST_HD inline bool pair_held(int bond, const std::uint8_t* joint_broken, const std::uint8_t* vertex_bonded) {
  return bond >= 0 ? !joint_broken[bond] : bond <= -2 && vertex_bonded[-2 - bond];
}

//! Contact of one pair (i, j), i < j (Munjiza's distributed potential, contact_kernels.hpp): the loads on
//! both triangles' nodes from all six edge-against-target evaluations, each evaluated once. Skipped: pairs
//! joined by an intact joint, pairs that meet at one mesh vertex whose joints are all intact (their corners
//! are copies of one vertex held together by the joints, and overlap by the joints' give), and pairs apart
//! (bounding boxes, then separating axes). A pair that meets at one vertex enters when the vertex's first
//! joint breaks, with the offset of next_contact_offset(): it pushes only against overlap gained since
//! (docs/fdem-solver.md). Writes the pair's touch flag, its offset, and, when it touches, its loads on i's and
//! j's nodes and its friction power.
struct ContactPairKernel {
  NodeMotion<Access::read> nodes;
  NodeParams node_params;  //!< mass
  const std::uint8_t* joint_broken;
  const std::uint8_t* vertex_bonded;
  const TrianglePair* pair;
  const int* bond;  //!< PairBondKernel
  std::uint8_t* touch;
  PairLoad* load;
  double* offset;
  double* reach;          //!< per pair: pair_reach() of its last test
  const double* travel;   //!< per triangle: its travel counter (TriangleForceKernel); a side of its box moves
                          //!< at most as far as the counter grows
  double penalty, friction, dt;
  BLAST_HD void operator()(index_t p) const {
    const int b = bond[p];
    if (pair_held(b, joint_broken, vertex_bonded)) {  // held together (offset stays -1)
      touch[p] = 0;
      return;
    }
    const int vertex = b <= -2 ? -2 - b : -1;
    const int i = pair[p].i, j = pair[p].j;
    // Still apart since its last test: that test left touch 0 and the offset at next_contact_offset(s, 0) = 0,
    // which testing again would repeat (the same bytes, less work: most free pairs are neighbours a cell apart).
    const double moved = travel[i] + travel[j];
    if (moved < reach[p]) return;
    touch[p] = 0;
    const double s = vertex >= 0 ? offset[p] : 0.0;  // Munjiza's contact for all but pairs that meet at one vertex
    Vec2 x[2][3];
    nodes.triangle(i, x[0]);
    nodes.triangle(j, x[1]);
    const double gap = box_gap(triangle_box(nodes, i), triangle_box(nodes, j));
    reach[p] = pair_reach(gap, moved);
    if (gap > 0 || !triangles_overlap(x[0], x[1])) {
      if (vertex >= 0) offset[p] = next_contact_offset(s, 0.0);
      return;
    }
    Vec2 v[2][3];
    double m[2][3];
    BLAST_UNROLL
    for (int side = 0; side < 2; ++side)
      BLAST_UNROLL
      for (int k = 0; k < 3; ++k) {
        const int n = 3 * (side == 0 ? i : j) + k;
        v[side][k] = nodes.velocity(n);
        m[side][k] = node_params.mass[n];
      }
    // On entry (s < 0) an offset of 1 (the potentials' peak) gives no load and still measures the depth.
    const PairContact c = pair_contact(x, v, m, penalty, friction, dt, s < 0 ? 1.0 : s);
    if (vertex >= 0) offset[p] = next_contact_offset(s, c.depth);
    if (!c.touching) return;
    touch[p] = 1;
    PairLoad& out = load[p];
    BLAST_UNROLL
    for (int k = 0; k < 3; ++k) out.on_i[k] = c.f[0][k], out.on_j[k] = c.f[1][k];
    out.friction_power = c.friction_power;
  }
};

//! f(e) for e in [0, n), visited in chunks of consecutive indices taken from 64 interleaved lanes (CPU load
//! balance: the static OpenMP schedule gives each host thread one contiguous run of launch indices, and the
//! work of the contact kernels bunches up in index space: around the hole and the cracks). Launch index q lies
//! in visit k = q / chunk, which is chunk (k mod 64) x chunks_per_lane + k / 64, at offset q mod chunk; indices
//! past n do nothing. A thread's run thus takes chunks from all over [0, n), each read in order (on a GPU,
//! neighbouring threads still read neighbouring entries). over() picks the chunk (256 down to 16 entries) so that
//! each lane holds at least four chunks. f's results must not depend on when or by which thread it runs.
template <class F>
struct Interleaved {
  static constexpr index_t lanes = 64;
  F f;
  index_t n;
  int chunk_bits;  //!< chunk = 2^chunk_bits entries
  index_t chunks_per_lane;
  static Interleaved over(const F& f, index_t n) {
    int bits = 8;
    while (bits > 4 && n < (lanes * 4) << bits) --bits;
    const index_t chunk = index_t(1) << bits;
    return {f, n, bits, ((n + chunk - 1) / chunk + lanes - 1) / lanes};
  }
  index_t launch_size() const { return (lanes * chunks_per_lane) << chunk_bits; }
  BLAST_HD void operator()(index_t q) const {
    const index_t k = q >> chunk_bits;
    const index_t e = (((k % lanes) * chunks_per_lane + k / lanes) << chunk_bits) + (q & ((index_t(1) << chunk_bits) - 1));
    if (e < n) f(e);
  }
};

//! ContactPairKernel on entry e of a list of pairs.
struct ListedPairs {
  ContactPairKernel pair;
  const int* list;
  BLAST_HD void operator()(index_t e) const { pair(list[e]); }
};

//! Predicate of the free-pair list: candidate pair q is not held together (pair_held()).
struct PairFree {
  const int* bond;
  const std::uint8_t *joint_broken, *vertex_bonded;
  BLAST_HD bool operator()(int q) const { return !pair_held(bond[q], joint_broken, vertex_bonded); }
};

//! The keys that group the pairs by the mesh vertex they meet at (`vertices` for the pairs that meet at none),
//! and each joint's pair (-1 where the joint has none; joint_pair cleared before).
struct PairGroupKernel {
  const int* bond;
  int vertices;
  int *vertex_key, *vertex_pairs, *joint_pair;
  BLAST_HD void operator()(index_t q) const {
    const int b = bond[q];
    vertex_key[q] = b <= -2 ? -2 - b : vertices;
    vertex_pairs[q] = static_cast<int>(q);
    if (b >= 0) joint_pair[b] = static_cast<int>(q);  // a joint holds one pair: no two threads write one entry
  }
};

//! ContactPairKernel on the pairs released since the work lists were made (RockSolver::list_free_pairs): launch
//! index k < joints is joint k, whose pair it evaluates once the joint has broken since; k = joints + v is mesh
//! vertex v, whose pairs it evaluates once v has lost its bond since (VertexBondKernel of this step). Every such
//! pair is evaluated by exactly one thread, and none of them is in the free list.
struct ReleasedPairsKernel {
  ContactPairKernel pair;
  const std::uint8_t *joint_broken_listed, *vertex_bonded_listed;
  const int *joint_pair, *vertex_pair_offset, *vertex_pairs;
  index_t joints;
  BLAST_HD void operator()(index_t k) const {
    if (k < joints) {
      if (pair.joint_broken[k] && !joint_broken_listed[k] && joint_pair[k] >= 0) pair(joint_pair[k]);
      return;
    }
    const index_t v = k - joints;
    if (pair.vertex_bonded[v] || !vertex_bonded_listed[v]) return;
    for (int s = vertex_pair_offset[v]; s < vertex_pair_offset[v + 1]; ++s) pair(vertex_pairs[s]);
  }
};

//! Contact force on each triangle's own nodes: the sum, in the fixed order of its candidate list, of its
//! side of every touching pair (a gather: no two threads write the same node, the same bytes every run).
//! The friction dissipation of a pair is booked on its first triangle.
struct ContactGatherKernel {
  const int* neighbour_offset;
  ContactPairs<Access::read> pairs;  //!< slot_pair, pair, touch, load
  NodeForces<Access::read_write> forces;  //!< writes contact_*
  TriangleState<Access::read_write> state;  //!< adds to dissipation.friction
  double dt;
  BLAST_HD void operator()(index_t ti) const {
    const int i = static_cast<int>(ti);
    Vec2 f[3] = {{0, 0}, {0, 0}, {0, 0}};
    double friction_power = 0;
    for (int s = neighbour_offset[i]; s < neighbour_offset[i + 1]; ++s) {
      const int p = pairs.slot_pair[s];
      if (!pairs.touch[p]) continue;
      const bool first = pairs.pair[p].i == i;
      const PairLoad& in = pairs.load[p];
      for (int k = 0; k < 3; ++k) {
        const Vec2 l = first ? in.on_i[k] : in.on_j[k];
        f[k] = {f[k].x + l.x, f[k].y + l.y};
      }
      if (first) friction_power += in.friction_power;
    }
    for (int k = 0; k < 3; ++k) {
      forces.contact_x[3 * i + k] = f[k].x;
      forces.contact_y[3 * i + k] = f[k].y;
    }
    state.dissipation[i].friction += friction_power * dt;
  }
};

//! Viscous boundary of Lysmer and Kuhlemeyer (1969, J. Eng. Mech. Div. ASCE 95(EM4), 859-877): dashpots with
//! normal traction -rho c_p v_n and shear traction -rho c_s v_t absorb plane P and S waves that arrive at normal
//! incidence (the boundary has the impedance of the rock beyond it). Lumped on the nodes of a boundary edge from
//! p0 to p1: each end node gets force -C v with C = (L / 2) rho (c_p n n^T + c_s t t^T), L the edge length, n and
//! t its unit normal and tangent.
BLAST_HD inline Mat2 viscous_boundary_coefficients(double rho, double cp, double cs, const Vec2& p0, const Vec2& p1) {
  const double dx = p1.x - p0.x, dy = p1.y - p0.y;
  const double length = sqrt(dx * dx + dy * dy);
  const double tx = dx / length, ty = dy / length;  // unit tangent; the unit normal is (ty, -tx)
  const double k = 0.5 * rho * length;
  const double cxy = k * (cs - cp) * tx * ty;
  return {k * (cp * ty * ty + cs * tx * tx), cxy, cxy, k * (cp * tx * tx + cs * ty * ty)};
}

//! A node's new velocity with its dashpots taken implicitly (stable at any step): solves (m I + dt C) v = m v_free,
//! v_free being the velocity the node's other forces alone give it over the step.
BLAST_HD inline Vec2 viscous_boundary_velocity(double m, double dt, const Mat2& C, const Vec2& v_free) {
  const Mat2 inv = Mat2{m + dt * C.a, dt * C.b, dt * C.c, m + dt * C.d}.inverse();
  return {m * (inv.a * v_free.x + inv.b * v_free.y), m * (inv.c * v_free.x + inv.d * v_free.y)};
}

//! The square of a node's speed [m2/s2], or kSpeedFlag where it is not finite or above 1e300 (so that a maximum
//! over nodes flags instability).
inline constexpr double kSpeedFlag = 1e308;
BLAST_HD inline double node_speed2_or_flag(double vx, double vy) {
  const double s = vx * vx + vy * vy;
  return s == s && s < 1e300 ? s : kSpeedFlag;
}

//! A speed [m/s] from node_speed2_or_flag(): its root, or the flag itself.
BLAST_HD inline double speed_from_speed2(double s2) { return s2 < kSpeedFlag ? sqrt(s2) : kSpeedFlag; }

//! Node n's largest speed since the last read (NodeUpdateKernel keeps the largest square), for a maximum over
//! the nodes (RockSolver::peak_speed_kernel()). The root of the largest square is the largest of the roots, bit
//! for bit (a correctly rounded square root never decreases), so one root a node and read serves all substeps.
struct NodeSpeedPeak {
  const double* peak2;
  BLAST_HD double operator()(index_t n) const { return speed_from_speed2(peak2[n]); }
};

//! Node update (symplectic Euler, docs/fdem-solver.md): gathers the node's forces (its triangle, the joints
//! on its two edges, contact, pressure on its triangle's exposed edges, gravity and held in-situ tractions), takes its viscous-boundary
//! dashpots implicitly, applies prescribed velocities, moves the node, and accumulates the work of each kind of
//! force by the trapezoid rule: the force at x_n works over half of the previous displacement and half of the
//! next one, so linear springs' work equals their energy change (f . v_new dt alone would add f^2 dt^2 / 2m
//! every step). It also keeps the square of the node's largest speed since the last read (`speed2_peak`,
//! node_speed2_or_flag()), so the host reads one maximum after several substeps instead of one after each
//! (RockSolver::advance()).
struct NodeUpdateKernel {
  NodeParams params;  //!< mass, held load
  NodeLoads loads;
  NodeForces<Access::read> forces;
  const SlotForce* joint_force;
  NodeMotion<Access::read_write> nodes;
  NodeLedger<Access::read_write> ledger;
  double gx, gy, dt, dt_prev;
  double* speed2_peak;  //!< per node [m2/s2]
  BLAST_HD void operator()(index_t ni) const {
    const int n = static_cast<int>(ni);
    const SlotForce& starting = joint_force[n];                // the slot that starts at n (n is its first node)
    const SlotForce& ending = joint_force[slot_ending_at(n)];  // the slot that ends at n
    const double m = params.mass[n];
    const Vec2 f_joint{starting.first.x + ending.second.x, starting.first.y + ending.second.y};
    const std::uint8_t cons = loads.constraint[n];
    Vec2 f_dead{m * gx, m * gy};  // gravity, and the in-situ traction where the node's boundary is held
    if (cons & kHeldLoad) f_dead = {f_dead.x + params.held[n].x, f_dead.y + params.held[n].y};
    const Vec2 f_pres{forces.pressure_x[n], forces.pressure_y[n]};
    const Vec2 f_ext{f_dead.x + f_pres.x, f_dead.y + f_pres.y};
    const Vec2 f_con{forces.contact_x[n], forces.contact_y[n]};
    const Vec2 f{forces.triangle_x[n] + f_joint.x + f_con.x + f_ext.x, forces.triangle_y[n] + f_joint.y + f_con.y + f_ext.y};
    const double vx = nodes.vx[n], vy = nodes.vy[n];
    Vec2 v{vx + f.x / m * dt, vy + f.y / m * dt};
    Vec2 f_bnd{0, 0};  // viscous boundary
    Mat2 C{0, 0, 0, 0};
    if (cons & kViscousBoundary) {
      C = loads.dashpot[n];
      v = viscous_boundary_velocity(m, dt, C, v);
    }
    const Vec2 vp = loads.v_prescribed[n];
    if (cons & kPrescribedX) v.x = vp.x;
    if (cons & kPrescribedY) v.y = vp.y;
    if (cons & kViscousBoundary) f_bnd = {-(C.a * v.x + C.b * v.y), -(C.c * v.x + C.d * v.y)};
    Vec2 support{0, 0};
    if (cons & kPrescribedX) support.x = m * (vp.x - vx) / dt - f.x - f_bnd.x;
    if (cons & kPrescribedY) support.y = m * (vp.y - vy) / dt - f.y - f_bnd.y;
    const Vec2 d{0.5 * (vx * dt_prev + v.x * dt), 0.5 * (vy * dt_prev + v.y * dt)};
    ledger.support[n] = support;
    nodes.vx[n] = v.x;
    nodes.vy[n] = v.y;
    const double speed2 = node_speed2_or_flag(v.x, v.y);
    if (speed2 > speed2_peak[n]) speed2_peak[n] = speed2;
    nodes.x[n] += v.x * dt;
    nodes.y[n] += v.y * dt;
    NodeWork& w = ledger.work[n];
    w.pressure += f_pres.x * d.x + f_pres.y * d.y;
    w.joint -= f_joint.x * d.x + f_joint.y * d.y;
    w.contact -= f_con.x * d.x + f_con.y * d.y;
    w.support += support.x * d.x + support.y * d.y;
    w.gravity += f_dead.x * d.x + f_dead.y * d.y;
    w.boundary += (f_bnd.x * v.x + f_bnd.y * v.y) * dt;  // the dashpot's power at the velocity it acted on
  }
};

}  // namespace blastsim::fdem
