//! \file rock_solver.hpp
//! \brief The FDEM rock solver: explicit step of elastic triangles, cohesive joints, contact with friction.
//!
//! Device-array interface (what the gas coupling and other codes use): node positions and velocities, one
//! pressure per triangle edge (`edge_pressure()`, applied only where `edge_exposed()` is set: the mesh
//! boundary and both faces of every broken joint). Edge slot 3 t + k of triangle t runs from node 3 t + k to
//! node 3 t + (k + 1) % 3 (nodes counter-clockwise), so a slot index is also the index of its first node.
//! Force assembly is a gather (every node sums its own contributions), so results are bitwise repeatable.
#pragma once

#include "blastsim/core/backend.hpp"
#include "blastsim/fdem/material.hpp"
#include "blastsim/fdem/mesh.hpp"
#include "blastsim/fdem/rock_types.hpp"

#include <array>
#include <cstdint>
#include <vector>

namespace blastsim {
class CheckpointWriter;
class CheckpointReader;
}  // namespace blastsim

namespace blastsim::fdem {

namespace detail {
struct RockArrays;
}

//! Non-owning device views of the rock state, for coupling kernels.
struct RockView {
  const double* x;
  const double* y;
  const double* vx;
  const double* vy;
  const std::uint8_t* edge_exposed;  //!< per edge slot: kEdgeInside, kEdgeBoundary or kEdgeCrackFace
  double* edge_pressure;             //!< per edge slot [Pa], read by the next step
  int triangles;
};

class RockSolver {
 public:
  RockSolver(const FdemTopology& topology, const RockMaterial& material, const RockOptions& options);

  //! Largest stable time step [s] of the explicit scheme: 2 / omega_max, omega_max^2 bounded per triangle
  //! by 4 c_p^2 / h^2 (h its smallest altitude) + 6 sqrt(2) p / (rho A) (joint penalty p) + 36 p_c / (rho h^2)
  //! (contact penalty p_c, when contact is on), reduced for damping by sqrt(1 + beta^2) - beta.
  double stable_dt() const { return stable_dt_; }

  //! Advances by dt [s]. Throws InputError if dt > stable_dt(), InstabilityError on a non-finite state.
  //! One step = triangle_forces(), joint_forces(), contact_forces(), update_nodes(), then the speed check.
  void step(double dt);

  // --- the phases of step(), public for benchmarks and profiling (call them in this order) ---
  void triangle_forces(double dt);  //!< internal forces, stresses, damping, edge pressures (one thread per triangle)
  void joint_forces();              //!< cohesive joints, damage, breakage (one thread per joint)
  void contact_forces(double dt);   //!< contact and friction (one thread per triangle); no-op without contact
  void update_nodes(double dt);     //!< gather and integrate (one thread per node)

  // --- loads and constraints (host calls between steps) ---
  //! Prescribes the velocity of `nodes` [m/s] along x and/or y (fixed nodes: zero velocity).
  void prescribe_velocity(const std::vector<int>& nodes, bool along_x, bool along_y, double vx, double vy);
  //! Sets every node's velocity [m/s] from a host array of 2 per node.
  void set_velocities(const std::vector<double>& vxy);
  //! Pressure [Pa] on the given edge slots (the rest keep theirs); pushes into the rock.
  void set_edge_pressure(const std::vector<int>& slots, double pressure);
  //! Joints (indices) whose two ends lie within `tolerance` [m] of the segment (xa, ya)-(xb, yb) in the
  //! initial mesh: the joints along a straight line of the mesh, e.g. a pre-cut crack.
  std::vector<int> joints_on_segment(double xa, double ya, double xb, double yb, double tolerance) const;
  //! Breaks the given joints now (a pre-cut crack): damage 1, no cohesion, both faces exposed to the gas.
  void break_joints(const std::vector<int>& joints);
  //! Multiplier of every edge pressure (a load ramp), 1 by default.
  void set_pressure_scale(double s) { pressure_scale_ = s; }

  // --- device-array interface ---
  RockView view();
  DeviceVector<double>& edge_pressure() { return edge_pressure_; }
  const DeviceVector<std::uint8_t>& edge_exposed() const { return edge_exposed_; }

  // --- checkpoint and restart ---
  //! Appends every array and counter of the solver to a checkpoint; read_checkpoint() restores them into a
  //! solver built from the same mesh and options, so the run continues bit for bit.
  void write_checkpoint(CheckpointWriter& w) const;
  void read_checkpoint(CheckpointReader& r);

  // --- diagnostics and output (host copies; each costs a device sync) ---
  RockEnergies energies();
  RockSnapshot snapshot() const;
  //! Total force [N/m] that the prescribed-velocity supports exerted on `nodes` in the last step.
  std::array<double, 2> support_reaction(const std::vector<int>& nodes) const;
  //! support_reaction() of each group of nodes, from one copy of the support forces.
  std::vector<std::array<double, 2>> support_reactions(const std::vector<std::vector<int>>& groups) const;
  //! Sum over nodes of the contact force magnitude [N/m] of the last step (0: nothing touches).
  double contact_force_norm();
  double time() const { return time_; }
  long steps() const { return steps_; }
  int triangle_count() const { return triangles_; }
  int node_count() const { return 3 * triangles_; }
  int joint_count() const { return joints_; }
  const std::vector<BoundaryEdge>& boundary_edges() const { return boundary_edges_; }
  const RockMaterial& material() const { return material_; }
  //! Number of contact-grid rebuilds so far (broad phase).
  long contact_rebuilds() const { return rebuilds_; }
  //! Rebuilds the contact broad phase (uniform grid, triangles sorted by cell). step() calls it whenever the
  //! nodes may have travelled half the buffer since the last build; public for benchmarks.
  void rebuild_contact_grid();

 private:
  void build_contact_pairs();  //!< pair numbering from the candidate lists (rebuild, checkpoint read)
  detail::RockArrays arrays();
  template <class Self, class Fn>
  static void for_each_checkpoint_array(Self& self, Fn&& fn);

  RockMaterial material_;
  RockOptions options_;
  int triangles_ = 0, joints_ = 0;
  std::vector<BoundaryEdge> boundary_edges_;
  std::vector<std::array<int, 4>> joint_nodes_host_;
  double stable_dt_ = 0, time_ = 0, pressure_scale_ = 1.0, dt_prev_ = 0;
  long steps_ = 0, rebuilds_ = 0;

  // nodes (3 per triangle)
  DeviceVector<double> x_, y_, vx_, vy_, x0_, y0_, mass_;
  DeviceVector<double> f_tri_x_, f_tri_y_, f_con_x_, f_con_y_;  // triangle and contact forces per node
  DeviceVector<double> f_pres_x_, f_pres_y_;                    // pressure loads per node (triangle phase)
  DeviceVector<std::uint8_t> constraint_;                      // bit 0: x prescribed, bit 1: y prescribed
  DeviceVector<double> v_prescribed_;                           // 2 per node
  DeviceVector<double> work_;  // kWorkKinds per node: pressure, joint, contact, support, gravity
  DeviceVector<double> support_;                                // 2 per node: support force of the last step
  // triangles
  DeviceVector<double> inv_f0_;      // 4 per triangle
  DeviceVector<double> area0_, eta_;  // [m2], damping coefficient [Pa s]
  DeviceVector<double> stress_;      // 3 per triangle
  DeviceVector<double> dissipation_;  // 2 per triangle: cumulative damping, friction [J/m]
  // edge slots (3 per triangle)
  DeviceVector<double> slot_force_;  // 4 per slot: joint force on the slot's first and second node
  DeviceVector<int> slot_neighbour_;  // triangle across the edge, or -1
  DeviceVector<int> slot_joint_;      // joint across the edge, or -1
  DeviceVector<std::uint8_t> edge_exposed_;
  DeviceVector<double> edge_pressure_;
  // joints
  DeviceVector<int> joint_nodes_;     // 4 per joint: a0, a1, b0, b1
  DeviceVector<double> joint_strength_;  // 8 per joint: JointStrength, then the initial length [m]
  DeviceVector<double> joint_damage_;    // 3 per joint
  DeviceVector<double> joint_state_;     // 6 per joint: opening and slip at the three points [m]
  DeviceVector<double> joint_traction_;  // 6 per joint: sigma and tau at the three points [Pa]
  DeviceVector<std::uint8_t> joint_broken_;
  // contact broad phase: uniform grid, triangles sorted by cell
  DeviceVector<int> cell_key_, sorted_triangles_, cell_start_, cell_end_;
  DeviceVector<int> neighbour_offset_, neighbour_list_;  // candidates within the buffer, per triangle (CSR)
  // contact pairs: each candidate pair once (i < j), rebuilt with the lists (not checkpointed: derived)
  int pairs_ = 0;
  DeviceVector<int> pair_offset_;  // per triangle (+1): first pair it leads
  DeviceVector<int> slot_pair_;    // per candidate slot: its pair
  DeviceVector<int> pair_ij_;      // 2 per pair: i < j
  DeviceVector<std::uint8_t> pair_touch_;  // per pair, this step: 1 when touching
  DeviceVector<double> pair_load_;  // 13 per pair, valid when touching: loads on i's and j's nodes, friction power
  double cell_size_ = 0, grid_x0_ = 0, grid_y0_ = 0;
  int grid_nx_ = 0, grid_ny_ = 0;
  double buffer_ = 0, travel_since_build_ = 0;
};

}  // namespace blastsim::fdem
