//! \file rock_fields.hpp
//! \brief Every array of the rock solver, declared once: params (fixed after construction), loads (set by the
//! host between steps), state (what evolves) and the contact broad phase, as X-macro lists that generate the
//! kernels' views here and the solver's storage and checkpoint records in rock_storage.hpp.
//!
//! A list entry is X(element type, name, comment). A group's view holds one pointer per entry; params views
//! are read-only, the others come as View<Access::read> (const pointers) or View<Access::read_write>, so
//! a kernel's members show what it reads and what it writes. Indexing: node n = 3 t + k of triangle t (each
//! triangle owns its three nodes); edge slot 3 t + k runs from node 3 t + k to node 3 t + (k + 1) % 3;
//! joint j joins two edge slots. Plain header: no backend dependency.
#pragma once

#include "blastsim/core/checkpoint_traits.hpp"
#include "blastsim/core/access.hpp"
#include "blastsim/fdem/in_situ_stress.hpp"
#include "blastsim/fdem/joint_kernels.hpp"
#include "blastsim/fdem/rock_types.hpp"
#include "blastsim/fdem/triangle_kernels.hpp"

#include <cstdint>

namespace blastsim::fdem {

//! Cumulative work [J/m] of each kind of force on one node (trapezoid rule, NodeUpdateKernel).
struct NodeWork {
  double pressure;  //!< edge pressures (in a coupled run: the gas)
  double joint;     //!< done on the cohesive joints (the negative of their forces' work)
  double contact;   //!< done on the contacts
  double support;   //!< prescribed-velocity supports
  double gravity;   //!< dead loads: gravity and the in-situ tractions of held boundaries
  double boundary;  //!< viscous-boundary dashpots (<= 0: the energy the waves carried out of the model)
};
}  // namespace blastsim::fdem
BLASTSIM_CHECKPOINT_REALS(blastsim::fdem::NodeWork)
namespace blastsim::fdem {

//! Bits of NodeLoads::constraint: velocity prescribed along x, along y; node on a viscous boundary; node on a
//! boundary held by the in-situ stress (a dead load).
inline constexpr std::uint8_t kPrescribedX = 1, kPrescribedY = 2, kViscousBoundary = 4, kHeldLoad = 8;

//! Cauchy stress of a constant-strain triangle [Pa].
struct TriangleStress {
  double xx, xy, yy;
};

//! Cumulative dissipation [J/m] booked on one triangle.
struct TriangleDissipation {
  double damping;   //!< its viscous damping eta D
  double friction;  //!< Coulomb friction of the contact pairs it leads
};

//! Joint forces [N/m] on the two nodes of one edge slot (its first node, then its second).
struct SlotForce {
  Vec2 first, second;
};

//! The four nodes of a joint: face A runs a0 -> a1; face B runs b0 -> b1, b0 opposite a1, b1 opposite a0.
//! a0 (b0) is also the edge slot of face A (B).
struct JointNodes {
  int a0, a1, b0, b1;
};

//! Values at a joint's three integration points (its two ends and its middle, weights 1/6, 2/3, 1/6).
inline constexpr int kJointPoints = 3;
struct JointPointValues {
  double normal[kJointPoints];  //!< opening [m] or normal traction [Pa], tension positive
  double shear[kJointPoints];   //!< slip [m] or shear traction [Pa]
};
struct JointPointDamage {
  double point[kJointPoints];  //!< damage D in [0, 1]
};
//! The shear history of a joint's three points (joint_traction(), JointHistory).
struct JointPointPlastic {
  double slip[kJointPoints];  //!< plastic slip s_pl [m], signed
  double path[kJointPoints];  //!< accumulated plastic slip kappa [m]
};

//! The two triangles of a contact pair, i < j.
struct TrianglePair {
  int i, j;
};

//! What a touching contact pair puts on its triangles' nodes [N/m] and its friction power [W/m].
struct PairLoad {
  Vec2 on_i[3], on_j[3];
  double friction_power;
};

// ---- params: fixed after construction -------------------------------------------------------------------
#define BLASTSIM_ROCK_NODE_PARAMS(X)                             \
  X(double, x0, "initial x [m]")                                 \
  X(double, y0, "initial y [m]")                                 \
  X(double, mass, "lumped mass, a third of its triangle's [kg/m]")  \
  X(int, vertex, "the mesh vertex it is a copy of")              \
  X(Vec2, held, "in-situ traction of a held boundary on the node [N/m] (a dead load; set before the first step), read where constraint bit 3 is set")
#define BLASTSIM_ROCK_TRIANGLE_PARAMS(X)                                   \
  X(Mat2, inv_f0, "inverse of the initial edge matrix [1/m]")             \
  X(double, area0, "initial area [m2]")                                   \
  X(double, eta, "viscous damping coefficient [Pa s]")
#define BLASTSIM_ROCK_EDGE_PARAMS(X)                         \
  X(int, neighbour, "triangle across the edge slot, or -1")  \
  X(int, joint, "joint across the edge slot, or -1")
#define BLASTSIM_ROCK_JOINT_PARAMS(X)                           \
  X(JointNodes, nodes, "its four nodes")                        \
  X(JointStrength, strength, "peak stresses and lengths of the joint law") \
  X(double, length, "initial length [m]")                       \
  X(JointPreload, preload, "opening and slip added so the in-situ stress is carried at rest [m] (0: none)")

// ---- loads: set by the host between steps, read by the kernels -------------------------------------------
#define BLASTSIM_ROCK_NODE_LOADS(X)                                                            \
  X(std::uint8_t, constraint, "bit 0: x velocity prescribed; bit 1: y; bit 2: viscous boundary")   \
  X(Vec2, v_prescribed, "prescribed velocity [m/s]")                                               \
  X(Mat2, dashpot, "viscous-boundary coefficients C [N s/m2] (force -C v), read where bit 2 is set")

#define BLASTSIM_ROCK_EDGE_LOADS(X)                                                                \
  X(double, pressure, "pressure on the edge when exposed [Pa] (set_edge_pressure(), or a coupler each step)") \
  X(Vec2, node_load, "load on the slot's first node (node 3 t + k) [N/m], written by a coupler each step")

// ---- state: what evolves ----------------------------------------------------------------------------------
#define BLASTSIM_ROCK_NODE_MOTION(X)    \
  X(double, x, "position x [m]")        \
  X(double, y, "position y [m]")        \
  X(double, vx, "velocity x [m/s]")     \
  X(double, vy, "velocity y [m/s]")
#define BLASTSIM_ROCK_NODE_FORCES(X)                                   \
  X(double, triangle_x, "force of its triangle, x [N/m]")              \
  X(double, triangle_y, "force of its triangle, y [N/m]")              \
  X(double, contact_x, "contact force, x [N/m]")                       \
  X(double, contact_y, "contact force, y [N/m]")                       \
  X(double, pressure_x, "load of its triangle's exposed-edge pressures, x [N/m]") \
  X(double, pressure_y, "load of its triangle's exposed-edge pressures, y [N/m]")
#define BLASTSIM_ROCK_NODE_LEDGER(X)                             \
  X(NodeWork, work, "cumulative work of each kind of force")     \
  X(Vec2, support, "force of the prescribed-velocity support in the last step [N/m]")
#define BLASTSIM_ROCK_TRIANGLE_STATE(X)                          \
  X(TriangleStress, stress, "Cauchy stress of the last step")    \
  X(TriangleDissipation, dissipation, "cumulative dissipation")
#define BLASTSIM_ROCK_EDGE_STATE(X)                                                        \
  X(SlotForce, joint_force, "force of the joint across the slot on the slot's two nodes") \
  X(std::uint8_t, exposed, "kEdgeInside, kEdgeBoundary or kEdgeCrackFace")
#define BLASTSIM_ROCK_JOINT_STATE(X)                                       \
  X(JointPointDamage, damage, "irreversible damage at the three points")   \
  X(JointPointPlastic, plastic, "plastic slip and its accumulated path at the three points [m]") \
  X(JointPointValues, separation, "opening and slip at the three points [m]") \
  X(JointPointValues, traction, "normal and shear traction at the three points [Pa]") \
  X(std::uint8_t, broken, "1 once two of its three points reached damage 1")

//! Read-only views of the params.
BLASTSIM_CONST_GROUP(NodeParams, BLASTSIM_ROCK_NODE_PARAMS)
BLASTSIM_CONST_GROUP(TriangleParams, BLASTSIM_ROCK_TRIANGLE_PARAMS)
BLASTSIM_CONST_GROUP(EdgeParams, BLASTSIM_ROCK_EDGE_PARAMS)
BLASTSIM_CONST_GROUP(JointParams, BLASTSIM_ROCK_JOINT_PARAMS)
BLASTSIM_CONST_GROUP(NodeLoads, BLASTSIM_ROCK_NODE_LOADS)

BLASTSIM_VIEW_GROUP(EdgeLoads, BLASTSIM_ROCK_EDGE_LOADS)

//! Views of the state, with the access the kernel needs.
template <Access A>
struct NodeMotion {
  BLASTSIM_ROCK_NODE_MOTION(BLASTSIM_VIEW_MEMBER)
  BLASTSIM_READ_CONVERSION(NodeMotion, BLASTSIM_ROCK_NODE_MOTION(BLASTSIM_MEMBER_NAME))
  BLAST_HD Vec2 position(int n) const { return {x[n], y[n]}; }
  BLAST_HD Vec2 velocity(int n) const { return {vx[n], vy[n]}; }
  //! Positions of triangle t's nodes.
  BLAST_HD void triangle(int t, Vec2 p[3]) const {
    for (int k = 0; k < 3; ++k) p[k] = position(3 * t + k);
  }
};
BLASTSIM_VIEW_GROUP(NodeForces, BLASTSIM_ROCK_NODE_FORCES)
BLASTSIM_VIEW_GROUP(NodeLedger, BLASTSIM_ROCK_NODE_LEDGER)
BLASTSIM_VIEW_GROUP(TriangleState, BLASTSIM_ROCK_TRIANGLE_STATE)
BLASTSIM_VIEW_GROUP(EdgeState, BLASTSIM_ROCK_EDGE_STATE)
BLASTSIM_VIEW_GROUP(JointState, BLASTSIM_ROCK_JOINT_STATE)

// ---- work arrays of a step (not checkpointed) ----
#define BLASTSIM_ROCK_JOINT_WORK(X) \
  X(Vec2, tangent, "per joint: the unit tangent of its faces in this substep (JointGeometryKernel, read by JointForceKernel)")
#define BLASTSIM_ROCK_NODE_PEAKS(X) \
  X(double, speed2, "per node: the square of its largest speed since the last finish_motion() [m2/s2]; zero between steps")
BLASTSIM_VIEW_GROUP(JointWork, BLASTSIM_ROCK_JOINT_WORK)
BLASTSIM_VIEW_GROUP(NodePeaks, BLASTSIM_ROCK_NODE_PEAKS)

//! What a coupler reads of the rock (docs/coupling.md), built from the groups above: the nodes' motion, the
//! edge slots' exposure and the joints, read-only (RockSolver::view() const).
struct RockReadView {
  NodeMotion<Access::read> nodes;
  EdgeParams edge;                //!< per slot: the triangle and the joint across it
  EdgeState<Access::read> edges;  //!< per slot: exposure (kEdgeInside, kEdgeBoundary, kEdgeCrackFace)
  JointParams joint;              //!< per joint: its four nodes
  JointState<Access::read> joints;  //!< per joint: broken flag, damage, opening
  TriangleState<Access::read> triangles;  //!< per triangle: Cauchy stress of its last step
  int triangle_count, joint_count;
};
//! What a coupler sees of the rock in a step (RockSolver::view()): the read view, and the edge loads it writes
//! (pressures and node loads, which the rock's next step applies).
struct RockView : RockReadView {
  EdgeLoads<Access::read_write> loads;  //!< per slot: pressure [Pa]; node load [N/m] on its first node
};

//! The edge-slot rule (one place for it): slot 3 t + k of triangle t runs from node 3 t + k to the next
//! node of the triangle, counter-clockwise.
BLAST_HD inline int slot_first_node(int slot) { return slot; }
BLAST_HD inline int slot_second_node(int slot) { return 3 * (slot / 3) + (slot % 3 + 1) % 3; }
//! The slot that ends at node n (n is its second node).
BLAST_HD inline int slot_ending_at(int n) { return 3 * (n / 3) + (n % 3 + 2) % 3; }
//! Outward normal of the edge from p0 to p1 of a counter-clockwise triangle, scaled by the edge length.
BLAST_HD inline Vec2 edge_outward_normal(const Vec2& p0, const Vec2& p1) { return {p1.y - p0.y, -(p1.x - p0.x)}; }

}  // namespace blastsim::fdem
