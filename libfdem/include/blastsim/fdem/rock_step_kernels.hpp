//! \file rock_step_kernels.hpp
//! \brief The kernels of one FDEM step (triangles, joints, contact, node update; one thread per item) over the
//! views of rock_fields.hpp: each kernel's members say what it reads (params, read views) and what it writes.
#pragma once

#include "blastsim/fdem/contact_search_kernels.hpp"
#include "blastsim/fdem/joint_kernels.hpp"
#include "blastsim/fdem/rock_fields.hpp"
#include "blastsim/fdem/rock_types.hpp"
#include "blastsim/fdem/triangle_kernels.hpp"

#include <cstdint>

namespace blastsim::fdem {

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
  ContactTravel<Access::read_write> travel;  //!< per triangle [m]: the travel counter (kept with contact only)
  bool count_travel;                         //!< with contact
  double dt_moved;  //!< [s] the step of the last node update (0: none yet)
  BLAST_HD void operator()(index_t ti) const {
    const int t = static_cast<int>(ti);
    Vec2 p[3], v[3];
    for (int k = 0; k < 3; ++k) {
      p[k] = nodes.position(3 * t + k);
      v[k] = nodes.velocity(3 * t + k);
    }
    if (count_travel) {
      const double m0 = node_step_travel(v[0].x, v[0].y, p[0].x, p[0].y, dt_moved);
      const double m1 = node_step_travel(v[1].x, v[1].y, p[1].x, p[1].y, dt_moved);
      const double m2 = node_step_travel(v[2].x, v[2].y, p[2].x, p[2].y, dt_moved);
      travel.travel[t] = add_travel(travel.travel[t], max_of(max_of(m0, m1), m2));
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
  JointWork<Access::read_write> work;    //!< writes tangent: t of this substep
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
    work.tangent[j] = t;
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
  JointWork<Access::read> work;         //!< tangent: t of this substep (JointGeometryKernel)
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
    const Vec2 t = work.tangent[j];
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

// ---- the rock's sums (RockSolver::energies(); one term an index, added by reduce_sum) ----

//! Kinetic energy [J/m] of node n.
struct NodeKineticEnergy {
  NodeMotion<Access::read> nodes;
  NodeParams params;  //!< mass
  BLAST_HD double operator()(index_t n) const {
    return 0.5 * params.mass[n] * (nodes.vx[n] * nodes.vx[n] + nodes.vy[n] * nodes.vy[n]);
  }
};

//! Strain energy [J/m] of triangle t at the positions x - half_step v (the middle of the last step, where the work
//! ledger and the kinetic energy of the half-step velocities stand).
struct TriangleStrainEnergy {
  NodeMotion<Access::read> nodes;
  TriangleParams params;  //!< area0, inv_f0
  double half_step;       //!< [s] half the last step
  double lambda, mu;      //!< [Pa]
  BLAST_HD double operator()(index_t t) const {
    Vec2 p[3];
    for (int k = 0; k < 3; ++k) {
      const int n = 3 * static_cast<int>(t) + k;
      p[k] = {nodes.x[n] - half_step * nodes.vx[n], nodes.y[n] - half_step * nodes.vy[n]};
    }
    return params.area0[t] * triangle_strain_energy_density(params.inv_f0[t], edge_matrix(p[0], p[1], p[2]), lambda, mu);
  }
};

//! One kind of work [J/m] of node n (NodeWork's field `kind`).
struct NodeWorkOf {
  NodeLedger<Access::read> ledger;
  double NodeWork::*kind;
  BLAST_HD double operator()(index_t n) const { return ledger.work[n].*kind; }
};

//! One kind of dissipation [J/m] of triangle t (TriangleDissipation's field `kind`).
struct TriangleDissipationOf {
  TriangleState<Access::read> state;
  double TriangleDissipation::*kind;
  BLAST_HD double operator()(index_t t) const { return state.dissipation[t].*kind; }
};

//! Elastic energy [J/m] joint j stores (joint_stored_energy()).
struct JointStoredEnergy {
  JointParams params;
  JointState<Access::read> joints;
  BLAST_HD double operator()(index_t j) const { return joint_stored_energy(params, joints, static_cast<int>(j)); }
};

//! Of a broken joint j: its length [m] (`length` true) or 1 (a count); 0 for an intact one.
struct BrokenJointLength {
  JointParams params;
  JointState<Access::read> joints;
  bool length;
  BLAST_HD double operator()(index_t j) const { return joints.broken[j] ? (length ? params.length[j] : 1.0) : 0.0; }
};

//! Magnitude [N/m] of the contact force on node n.
struct NodeContactForce {
  NodeForces<Access::read> forces;
  BLAST_HD double operator()(index_t n) const {
    return sqrt(forces.contact_x[n] * forces.contact_x[n] + forces.contact_y[n] * forces.contact_y[n]);
  }
};

//! Multiplies every node's velocity by f (the in-situ relaxation's damping, one step of it; f = 0: at rest).
struct ScaleVelocitiesKernel {
  NodeMotion<Access::read_write> nodes;  //!< vx, vy
  double f;
  BLAST_HD void operator()(index_t n) const {
    nodes.vx[n] *= f;
    nodes.vy[n] *= f;
  }
};

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
  NodePeaks<Access::read> peaks;  //!< speed2
  BLAST_HD double operator()(index_t n) const { return speed_from_speed2(peaks.speed2[n]); }
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
  EdgeState<Access::read> edges;  //!< joint_force
  NodeMotion<Access::read_write> nodes;
  NodeLedger<Access::read_write> ledger;
  double gx, gy, dt, dt_prev;
  NodePeaks<Access::read_write> peaks;  //!< speed2 [m2/s2]
  BLAST_HD void operator()(index_t ni) const {
    const int n = static_cast<int>(ni);
    const SlotForce& starting = edges.joint_force[n];                // the slot that starts at n (n is its first node)
    const SlotForce& ending = edges.joint_force[slot_ending_at(n)];  // the slot that ends at n
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
    if (speed2 > peaks.speed2[n]) peaks.speed2[n] = speed2;
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
