//! \file rock_kernels.hpp
//! \brief Device kernels of one FDEM step (internal): triangles, joints, contact, node update; one thread per item.
#pragma once

#include "blastsim/fdem/contact_kernels.hpp"
#include "blastsim/fdem/joint_kernels.hpp"
#include "blastsim/fdem/triangle_kernels.hpp"

#include <cstdint>

namespace blastsim::fdem::detail {

//! Raw device pointers of the solver's arrays, copied by value into every kernel.
struct RockArrays {
  double *x, *y, *vx, *vy;
  const double *x0, *y0, *mass;
  double *f_tri_x, *f_tri_y, *f_con_x, *f_con_y, *f_pres_x, *f_pres_y;
  const std::uint8_t* constraint;
  const double* v_prescribed;
  double* work;     // kWorkKinds per node: pressure, joint, contact, support, gravity [J/m]
  double* support;  // 2 per node: force of the prescribed-velocity support in the last step [N/m]
  const double *inv_f0, *area0, *eta;
  double *stress, *dissipation;
  double* slot_force;
  const int *slot_neighbour, *slot_joint;
  std::uint8_t* edge_exposed;
  const double* edge_pressure;
  const int* joint_nodes;
  const double* joint_strength;
  double *joint_damage, *joint_state, *joint_traction;
  std::uint8_t* joint_broken;
  const int *cell_key, *sorted_triangles, *cell_start, *cell_end;
  const int *neighbour_offset, *neighbour_list;  // contact candidates per triangle (CSR), from the last build
};

//! Bounding box of triangle t's current nodes.
struct Box {
  double lo_x, lo_y, hi_x, hi_y;
};
BLAST_HD inline Box triangle_box(const RockArrays& r, int t) {
  Box b{1e300, 1e300, -1e300, -1e300};
  for (int k = 0; k < 3; ++k) {
    const double x = r.x[3 * t + k], y = r.y[3 * t + k];
    // min_of / max_of, not fmin / fmax (positions are finite: step() checks the speeds).
    b.lo_x = min_of(x, b.lo_x), b.lo_y = min_of(y, b.lo_y), b.hi_x = max_of(b.hi_x, x), b.hi_y = max_of(b.hi_y, y);
  }
  return b;
}
BLAST_HD inline bool boxes_apart(const Box& a, const Box& b, double margin) {
  return a.lo_x > b.hi_x + margin || b.lo_x > a.hi_x + margin || a.lo_y > b.hi_y + margin || b.lo_y > a.hi_y + margin;
}

//! Broad phase (Munjiza's uniform grid, sort-by-cell form): for triangle t, the triangles in the 3 x 3 cells
//! around its centroid's cell whose boxes come within `margin` (the buffer). With `list` null it only counts
//! them (first pass); the second pass writes them from `offset` on, in a fixed order.
struct NeighbourSearchKernel {
  RockArrays r;
  double margin, cell_size, grid_x0, grid_y0;
  int grid_nx, grid_ny;
  int* count;
  int* list;
  BLAST_HD void operator()(index_t ti) const {
    const int i = static_cast<int>(ti);
    const Box bi = triangle_box(r, i);
    const double cx = (r.x[3 * i] + r.x[3 * i + 1] + r.x[3 * i + 2]) / 3.0;
    const double cy = (r.y[3 * i] + r.y[3 * i + 1] + r.y[3 * i + 2]) / 3.0;
    int ci = static_cast<int>(floor((cx - grid_x0) / cell_size));
    int cj = static_cast<int>(floor((cy - grid_y0) / cell_size));
    ci = ci < 0 ? 0 : (ci >= grid_nx ? grid_nx - 1 : ci);
    cj = cj < 0 ? 0 : (cj >= grid_ny ? grid_ny - 1 : cj);
    int m = list ? r.neighbour_offset[i] : 0;
    for (int dj = -1; dj <= 1; ++dj)
      for (int di = -1; di <= 1; ++di) {
        const int ii = ci + di, jj = cj + dj;
        if (ii < 0 || jj < 0 || ii >= grid_nx || jj >= grid_ny) continue;
        const int cell = jj * grid_nx + ii;
        for (int s = r.cell_start[cell]; s < r.cell_end[cell]; ++s) {
          const int j = r.sorted_triangles[s];
          if (j == i || boxes_apart(bi, triangle_box(r, j), margin)) continue;
          if (list) list[m] = j;
          ++m;
        }
      }
    if (!list) count[i] = m;
  }
};

BLAST_HD inline Vec2 node_position(const RockArrays& r, int n) { return {r.x[n], r.y[n]}; }
BLAST_HD inline Vec2 node_velocity(const RockArrays& r, int n) { return {r.vx[n], r.vy[n]}; }

//! Positions of triangle t's nodes.
BLAST_HD inline void triangle_nodes(const RockArrays& r, int t, Vec2 p[3]) {
  for (int k = 0; k < 3; ++k) p[k] = node_position(r, 3 * t + k);
}

//! Internal forces of each triangle on its own three nodes (Munjiza ch. 2; fdem.md "Triangle internal
//! force"), its Cauchy stress for output, the work of its viscous damping eta D (dissipation), and the
//! pressure loads of its exposed edges on its nodes (uniform on each edge, one-point rule, half to each node,
//! along the inward normal; docs/ibm.md). Everything from the positions at the start of the step: the
//! node update that moves the nodes runs after.
struct TriangleForceKernel {
  RockArrays r;
  double lambda, mu, pressure_scale, dt;
  BLAST_HD void operator()(index_t ti) const {
    const int t = static_cast<int>(ti);
    Vec2 p[3], v[3];
    for (int k = 0; k < 3; ++k) {
      p[k] = node_position(r, 3 * t + k);
      v[k] = node_velocity(r, 3 * t + k);
    }
    const Mat2 inv_F0{r.inv_f0[4 * t], r.inv_f0[4 * t + 1], r.inv_f0[4 * t + 2], r.inv_f0[4 * t + 3]};
    const Mat2 FX = edge_matrix(p[0], p[1], p[2]);
    const Mat2 LX = edge_matrix(v[0], v[1], v[2]);
    const double eta = r.eta[t];
    const Mat2 T = triangle_stress(inv_F0, FX, LX, lambda, mu, eta);
    Vec2 f[3];
    triangle_nodal_forces(T, p[0], p[1], p[2], f);
    for (int k = 0; k < 3; ++k) {
      r.f_tri_x[3 * t + k] = f[k].x;
      r.f_tri_y[3 * t + k] = f[k].y;
    }
    r.stress[3 * t] = T.a;
    r.stress[3 * t + 1] = T.b;
    r.stress[3 * t + 2] = T.d;
    Vec2 fp[3] = {{0, 0}, {0, 0}, {0, 0}};
    for (int e = 0; e < 3; ++e) {  // edge slot 3t+e runs from node e to node e+1
      const int s = 3 * t + e;
      const double pe = r.edge_exposed[s] ? pressure_scale * r.edge_pressure[s] : 0.0;
      if (pe == 0.0) continue;
      const int e1 = (e + 1) % 3;
      const Vec2 half{-0.5 * pe * (p[e1].y - p[e].y), 0.5 * pe * (p[e1].x - p[e].x)};
      fp[e] = {fp[e].x + half.x, fp[e].y + half.y};
      fp[e1] = {fp[e1].x + half.x, fp[e1].y + half.y};
    }
    for (int k = 0; k < 3; ++k) {
      r.f_pres_x[3 * t + k] = fp[k].x;
      r.f_pres_y[3 * t + k] = fp[k].y;
    }
    if (eta > 0) {  // dissipation rate A eta D:D
      const Mat2 L = LX * FX.inverse();
      const double dxy = 0.5 * (L.b + L.c);
      const double area = 0.5 * FX.det();
      r.dissipation[2 * t] += area * eta * (L.a * L.a + L.d * L.d + 2.0 * dxy * dxy) * dt;
    }
  }
};

//! Cohesive joints (Munjiza ch. 7; fdem.md "Cohesive joint"): opening and slip at the edge's two ends and
//! middle (weights 1/6, 2/3, 1/6 of the initial length), the joint law with irreversible damage, and the
//! forces on the four nodes, written into the two edge slots the joint joins. A joint is broken once two
//! of its three points reach damage 1; its faces then become exposed edges and carry no cohesion.
struct JointForceKernel {
  RockArrays r;
  BLAST_HD void operator()(index_t ji) const {
    const int j = static_cast<int>(ji);
    const int a0 = r.joint_nodes[4 * j], a1 = r.joint_nodes[4 * j + 1];
    const int b0 = r.joint_nodes[4 * j + 2], b1 = r.joint_nodes[4 * j + 3];
    double* fa = r.slot_force + 4 * a0;  // slot of face A: its first node is a0, its second a1
    double* fb = r.slot_force + 4 * b0;  // slot of face B: b0, then b1
    if (r.joint_broken[j]) {
      for (int c = 0; c < 4; ++c) fa[c] = fb[c] = 0.0;
      return;
    }
    const double* sp = r.joint_strength + 8 * j;
    const JointStrength strength{sp[0], sp[1], sp[2], sp[3], sp[4], sp[5], sp[6]};
    const double length0 = sp[7];
    const Vec2 pa0 = node_position(r, a0), pa1 = node_position(r, a1);
    const Vec2 pb0 = node_position(r, b0), pb1 = node_position(r, b1);
    // Mean direction of the two faces (both run a0 -> a1), and the normal pointing out of face A.
    Vec2 t{pa1.x - pa0.x + pb0.x - pb1.x, pa1.y - pa0.y + pb0.y - pb1.y};
    const double tl = sqrt(t.x * t.x + t.y * t.y);
    t = {t.x / tl, t.y / tl};
    const Vec2 n{t.y, -t.x};
    const double xi[3] = {0.0, 0.5, 1.0};
    const double w[3] = {length0 / 6.0, 4.0 * length0 / 6.0, length0 / 6.0};
    Vec2 f_a0{0, 0}, f_a1{0, 0};  // loads on face A's nodes; face B gets the opposite at b1, b0
    int broken_points = 0;
    for (int q = 0; q < 3; ++q) {
      const Vec2 xa{pa0.x + xi[q] * (pa1.x - pa0.x), pa0.y + xi[q] * (pa1.y - pa0.y)};
      const Vec2 xb{pb1.x + xi[q] * (pb0.x - pb1.x), pb1.y + xi[q] * (pb0.y - pb1.y)};
      const Vec2 d{xb.x - xa.x, xb.y - xa.y};
      const double o = d.x * n.x + d.y * n.y, s = d.x * t.x + d.y * t.y;
      const JointTraction tr = joint_traction(o, s, strength, r.joint_damage[3 * j + q]);
      r.joint_damage[3 * j + q] = tr.damage;
      r.joint_state[6 * j + 2 * q] = o;
      r.joint_state[6 * j + 2 * q + 1] = s;
      r.joint_traction[6 * j + 2 * q] = tr.normal;
      r.joint_traction[6 * j + 2 * q + 1] = tr.shear;
      if (tr.damage >= 1.0) ++broken_points;
      // Face A is pulled towards B by tension and dragged along the slip by shear.
      const Vec2 load{(tr.normal * n.x + tr.shear * t.x) * w[q], (tr.normal * n.y + tr.shear * t.y) * w[q]};
      f_a0 = {f_a0.x + (1.0 - xi[q]) * load.x, f_a0.y + (1.0 - xi[q]) * load.y};
      f_a1 = {f_a1.x + xi[q] * load.x, f_a1.y + xi[q] * load.y};
    }
    if (broken_points >= 2) {
      r.joint_broken[j] = 1;
      r.edge_exposed[a0] = kEdgeCrackFace;
      r.edge_exposed[b0] = kEdgeCrackFace;
      for (int c = 0; c < 4; ++c) fa[c] = fb[c] = 0.0;
      return;
    }
    fa[0] = f_a0.x;
    fa[1] = f_a0.y;
    fa[2] = f_a1.x;
    fa[3] = f_a1.y;
    // b0 sits opposite a1 and b1 opposite a0.
    fb[0] = -f_a1.x;
    fb[1] = -f_a1.y;
    fb[2] = -f_a0.x;
    fb[3] = -f_a0.y;
  }
};

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

//! Second pass: the pair of every candidate slot (slot_pair), and each pair's triangles (pair_ij, 2 per pair).
//! A slot whose partner's list lacks it (which symmetric lists never do) gets -1; the caller checks.
struct PairIndexKernel {
  const int *offset, *list, *pair_offset;
  int *slot_pair, *pair_ij;
  BLAST_HD void operator()(index_t ti) const {
    const int i = static_cast<int>(ti);
    int k = 0;
    for (int s = offset[i]; s < offset[i + 1]; ++s) {
      const int j = list[s];
      if (j > i) {
        const int p = pair_offset[i] + k++;
        slot_pair[s] = p;
        pair_ij[2 * p] = i;
        pair_ij[2 * p + 1] = j;
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

//! 1 for a candidate slot that PairIndexKernel found no pair for (summed to check the lists' symmetry).
struct UnmatchedSlot {
  const int* slot_pair;
  BLAST_HD double operator()(index_t s) const { return slot_pair[s] < 0 ? 1.0 : 0.0; }
};

//! Contact of one pair (i, j), i < j (Munjiza's distributed potential, contact_kernels.hpp): the loads on
//! both triangles' nodes from all six edge-against-target evaluations, each evaluated once. Pairs joined by
//! an intact joint or apart (bounding boxes, then separating axes) are skipped. Pairs that only share a
//! vertex are tested like any other (Munjiza): their corners overlap by the joints' give, and the small
//! contact force that makes is part of the model (docs/fdem-solver.md). Writes the pair's touch flag and,
//! when it touches, its 13 values: loads on i's three nodes (x, y), on j's three, and the friction power [W/m].
struct ContactPairKernel {
  RockArrays r;
  const int* pair_ij;
  std::uint8_t* touch;
  double* load;
  double penalty, friction, dt;
  BLAST_HD bool joined(int i, int j) const {
    for (int e = 0; e < 3; ++e)
      if (r.slot_neighbour[3 * i + e] == j) {
        const int joint = r.slot_joint[3 * i + e];
        return joint >= 0 && !r.joint_broken[joint];
      }
    return false;
  }
  BLAST_HD void operator()(index_t p) const {
    const int i = pair_ij[2 * p], j = pair_ij[2 * p + 1];
    touch[p] = 0;
    if (joined(i, j) || boxes_apart(triangle_box(r, i), triangle_box(r, j), 0.0)) return;
    Vec2 x[2][3];
    triangle_nodes(r, i, x[0]);
    triangle_nodes(r, j, x[1]);
    if (!triangles_overlap(x[0], x[1])) return;
    Vec2 v[2][3];
    double m[2][3], mt[2] = {0, 0};
    BLAST_UNROLL
    for (int side = 0; side < 2; ++side)
      BLAST_UNROLL
      for (int k = 0; k < 3; ++k) {
        const int n = 3 * (side == 0 ? i : j) + k;
        v[side][k] = node_velocity(r, n);
        m[side][k] = r.mass[n];
        mt[side] += m[side][k];
      }
    Vec2 f[2][3] = {{{0, 0}, {0, 0}, {0, 0}}, {{0, 0}, {0, 0}, {0, 0}}};
    double friction_power = 0;
    bool touching = false;
    BLAST_UNROLL
    for (int c = 0; c < 2; ++c) {  // contactor c's edges against target 1 - c
      const int t = 1 - c;
      BLAST_UNROLL
      for (int e = 0; e < 3; ++e) {
        const int e1 = (e + 1) % 3;
        const EdgeContactLoad l = edge_against_target(x[c][e], x[c][e1], x[t], v[c][e], v[c][e1], v[t],
                                                      m[c][e] + m[c][e1], mt[t], penalty, friction, dt);
        if (!l.touching) continue;
        touching = true;
        f[c][e] = {f[c][e].x + l.edge[0].x, f[c][e].y + l.edge[0].y};
        f[c][e1] = {f[c][e1].x + l.edge[1].x, f[c][e1].y + l.edge[1].y};
        BLAST_UNROLL
        for (int k = 0; k < 3; ++k) f[t][k] = {f[t][k].x + l.target[k].x, f[t][k].y + l.target[k].y};
        friction_power += l.friction_power;
      }
    }
    if (!touching) return;
    touch[p] = 1;
    double* out = load + 13 * p;
    BLAST_UNROLL
    for (int side = 0; side < 2; ++side)
      BLAST_UNROLL
      for (int k = 0; k < 3; ++k) out[6 * side + 2 * k] = f[side][k].x, out[6 * side + 2 * k + 1] = f[side][k].y;
    out[12] = friction_power;
  }
};

//! ContactPairKernel over the pairs in 64 interleaved blocks (CPU load balance: see RockSolver::contact_forces):
//! launch index q visits pair (q mod 64) x block_length + q / 64; indices past the last pair do nothing.
struct InterleavedPairs {
  static constexpr index_t blocks = 64;
  ContactPairKernel pair;
  index_t pairs;
  index_t block_length;  //!< block_length_for(pairs)
  static index_t block_length_for(index_t n) { return (n + blocks - 1) / blocks; }
  index_t launch_size() const { return blocks * block_length; }
  BLAST_HD void operator()(index_t q) const {
    const index_t p = (q % blocks) * block_length + q / blocks;
    if (p < pairs) pair(p);
  }
};

//! Contact force on each triangle's own nodes: the sum, in the fixed order of its candidate list, of its
//! side of every touching pair (a gather: no two threads write the same node, the same bytes every run).
//! The friction dissipation of a pair is booked on its first triangle.
struct ContactGatherKernel {
  RockArrays r;
  const int *slot_pair, *pair_ij;
  const std::uint8_t* touch;
  const double* load;
  double dt;
  BLAST_HD void operator()(index_t ti) const {
    const int i = static_cast<int>(ti);
    Vec2 f[3] = {{0, 0}, {0, 0}, {0, 0}};
    double friction_power = 0;
    for (int s = r.neighbour_offset[i]; s < r.neighbour_offset[i + 1]; ++s) {
      const int p = slot_pair[s];
      if (!touch[p]) continue;
      const int side = pair_ij[2 * p] == i ? 0 : 1;
      const double* in = load + 13 * static_cast<index_t>(p) + 6 * side;
      for (int k = 0; k < 3; ++k) f[k] = {f[k].x + in[2 * k], f[k].y + in[2 * k + 1]};
      if (side == 0) friction_power += load[13 * static_cast<index_t>(p) + 12];
    }
    for (int k = 0; k < 3; ++k) {
      r.f_con_x[3 * i + k] = f[k].x;
      r.f_con_y[3 * i + k] = f[k].y;
    }
    r.dissipation[2 * i + 1] += friction_power * dt;
  }
};

//! Node update (symplectic Euler, fdem.md): gathers the node's forces (its triangle, the joints on its two
//! edges, contact, pressure on its triangle's exposed edges, gravity), applies prescribed velocities, moves the node,
//! and accumulates the work of each kind of force by the trapezoid rule: the force at x_n works over half of
//! the previous displacement and half of the next one, so linear springs' work equals their energy change
//! (f . v_new dt alone would add f^2 dt^2 / 2m every step).
struct NodeUpdateKernel {
  RockArrays r;
  double gx, gy, dt, dt_prev;
  BLAST_HD void operator()(index_t ni) const {
    const int n = static_cast<int>(ni);
    const int t = n / 3, k = n % 3;
    const int slot_first = n;                        // edge n -> next node: n is its first node
    const int slot_second = 3 * t + (k + 2) % 3;     // edge previous node -> n: n is its second node
    const double m = r.mass[n];
    const Vec2 f_joint{r.slot_force[4 * slot_first] + r.slot_force[4 * slot_second + 2],
                       r.slot_force[4 * slot_first + 1] + r.slot_force[4 * slot_second + 3]};
    const Vec2 f_grav{m * gx, m * gy}, f_pres{r.f_pres_x[n], r.f_pres_y[n]};
    const Vec2 f_ext{f_grav.x + f_pres.x, f_grav.y + f_pres.y};
    const Vec2 f_con{r.f_con_x[n], r.f_con_y[n]};
    const Vec2 f{r.f_tri_x[n] + f_joint.x + f_con.x + f_ext.x, r.f_tri_y[n] + f_joint.y + f_con.y + f_ext.y};
    Vec2 v{r.vx[n] + f.x / m * dt, r.vy[n] + f.y / m * dt};
    Vec2 support{0, 0};
    const std::uint8_t cons = r.constraint[n];
    if (cons & 1) {
      support.x = m * (r.v_prescribed[2 * n] - r.vx[n]) / dt - f.x;
      v.x = r.v_prescribed[2 * n];
    }
    if (cons & 2) {
      support.y = m * (r.v_prescribed[2 * n + 1] - r.vy[n]) / dt - f.y;
      v.y = r.v_prescribed[2 * n + 1];
    }
    const Vec2 d{0.5 * (r.vx[n] * dt_prev + v.x * dt), 0.5 * (r.vy[n] * dt_prev + v.y * dt)};
    r.support[2 * n] = support.x;
    r.support[2 * n + 1] = support.y;
    r.vx[n] = v.x;
    r.vy[n] = v.y;
    r.x[n] += v.x * dt;
    r.y[n] += v.y * dt;
    double* w = r.work + kWorkKinds * n;
    w[0] += f_pres.x * d.x + f_pres.y * d.y;
    w[1] -= f_joint.x * d.x + f_joint.y * d.y;
    w[2] -= f_con.x * d.x + f_con.y * d.y;
    w[3] += support.x * d.x + support.y * d.y;
    w[4] += f_grav.x * d.x + f_grav.y * d.y;
  }
};

}  // namespace blastsim::fdem::detail
