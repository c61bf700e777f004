//! \file rock_solver.hpp
//! \brief The FDEM rock solver: explicit step of elastic triangles, cohesive joints, contact with friction.
//!
//! Device-array interface (what the gas coupling and other codes use, view(): a RockView of rock_fields.hpp):
//! node positions and velocities, one pressure per triangle edge (`loads.pressure`, applied only where
//! `edges.exposed` is set: the mesh boundary and both faces of every broken joint). Edge slot 3 t + k of triangle t runs from node 3 t + k to
//! node 3 t + (k + 1) % 3 (nodes counter-clockwise), so a slot index is also the index of its first node.
//! Force assembly is a gather (every node sums its own contributions), so results are bitwise repeatable.
//! The arrays live behind the class (rock_fields.hpp lists them), so this header needs no backend headers.
#pragma once

#include "blastsim/core/checkpoint_fwd.hpp"
#include "blastsim/fdem/contact_search.hpp"
#include "blastsim/fdem/heterogeneity.hpp"
#include "blastsim/fdem/in_situ_stress.hpp"
#include "blastsim/fdem/material.hpp"
#include "blastsim/fdem/mesh.hpp"
#include "blastsim/fdem/rock_fields.hpp"
#include "blastsim/fdem/rock_probes.hpp"
#include "blastsim/fdem/rock_step_kernels.hpp"
#include "blastsim/fdem/rock_types.hpp"

#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

namespace blastsim::fdem {

namespace detail {
struct RockArrays;
}

class RockSolver {
 public:
  //! `joints`, when not empty, gives each joint of the topology its own strength and fracture energies
  //! (heterogeneous rock: heterogeneous_joints()); empty: every joint has the material's. Throws InputError on
  //! a size other than the topology's joint count or a joint whose properties the joint law cannot take.
  RockSolver(const FdemTopology& topology, const RockMaterial& material, const RockOptions& options,
             const std::vector<JointProperties>& joints = {});
  ~RockSolver();
  RockSolver(RockSolver&&) noexcept;
  RockSolver& operator=(RockSolver&&) noexcept;

  //! Largest stable time step [s] of the explicit scheme: 2 / omega_max, omega_max^2 bounded per triangle
  //! by 4 c_p^2 / h^2 (h its smallest altitude) + 6 sqrt(2) p / (rho A) (joint penalty p) + 36 p_c / (rho h^2)
  //! (contact penalty p_c, when contact is on), reduced for damping by sqrt(1 + beta^2) - beta.
  double stable_dt() const { return stable_dt_; }
  //! Advances by dt [s]. Throws InputError if dt > stable_dt(), InstabilityError on a non-finite state.
  //! One step = triangle_forces(), joint_forces(), contact_forces(), update_nodes(), then the speed check:
  //! advance(dt, 1), then finish_motion() with the largest node speed (the host waits for it).
  void step(double dt);
  //! Advances by `substeps` steps of dt [s] without reading anything back (the host does not wait). The
  //! contact broad phase is rebuilt first where the nodes may travel half its buffer before the next read
  //! (the travel so far plus, over the substeps after the first, the last speed read). Each node update keeps
  //! every node's largest speed; the caller then reduces peak_speed_kernel() over node_count() nodes (alone,
  //! or fused with its own reduction) and passes the maximum to finish_motion() before the next advance().
  //! `before_step(k)`, when given, runs before substep k (a coupling that updates loads within the steps).
  void advance(double dt, int substeps, const std::function<void(int)>& before_step = {});
  //! Ends an advance(): InstabilityError if `v_max` [m/s] flags a non-finite speed, else the broad phase's
  //! travel grows by v_max times the time advanced; clears the speed peaks (a kernel, no wait).
  void finish_motion(double v_max);
  //! Device functor: node k's largest speed since the last finish_motion() (1e308 if not finite).
  NodeSpeedPeak peak_speed_kernel() const;

  // --- the phases of step(), public for benchmarks and profiling (call them in this order) ---
  void triangle_forces(double dt);  //!< internal forces, stresses, damping, edge pressures (one thread per triangle)
  void joint_forces();              //!< cohesive joints, damage, breakage (one thread per joint)
  void contact_forces(double dt);   //!< contact and friction (one thread a pair, then a gather); no-op without contact
  void update_nodes(double dt);     //!< gather and integrate (one thread per node)

  // --- loads and constraints (host calls between steps) ---
  //! Prescribes the velocity of `nodes` [m/s] along x and/or y (fixed nodes: zero velocity).
  void prescribe_velocity(const std::vector<int>& nodes, bool along_x, bool along_y, double vx, double vy);
  //! Makes the given boundary edge slots a viscous (non-reflecting) boundary, where the model cuts a rock mass
  //! that goes on beyond it: Lysmer and Kuhlemeyer's dashpots, rho c_p on the normal and rho c_s on the
  //! tangential velocity (rock_step_kernels.hpp), lumped on the edges' nodes from the initial geometry and
  //! taken implicitly (no limit on the step). Their work is RockEnergies::boundary_work. Throws InputError for a
  //! slot that is not a mesh-boundary edge.
  void set_viscous_boundary(const std::vector<int>& slots);
  //! Sets every node's velocity [m/s] from a host array of 2 per node.
  void set_velocities(const std::vector<double>& vxy);
  //! Sets every node's position [m] from a host array of 2 per node (the reference mesh stays): moving whole
  //! pieces rigidly, e.g. the two sides of a pre-cut crack apart, leaves their triangles unstrained. The contact
  //! search is rebuilt before the next step.
  void set_positions(const std::vector<double>& xy);
  //! Pressure [Pa] on the given edge slots (the rest keep theirs); pushes into the rock.
  void set_edge_pressure(const std::vector<int>& slots, double pressure);
  //! Joints (indices) whose two ends lie within `tolerance` [m] of the segment (xa, ya)-(xb, yb) in the
  //! initial mesh: the joints along a straight line of the mesh, e.g. a pre-cut crack.
  std::vector<int> joints_on_segment(double xa, double ya, double xb, double yb, double tolerance) const;
  //! Breaks the given joints now (a pre-cut crack): damage 1, no cohesion, both faces exposed to the gas.
  void break_joints(const std::vector<int>& joints);
  //! Multiplier of every edge pressure (a load ramp), 1 by default.
  void set_pressure_scale(double s) { pressure_scale_ = s; }
  double pressure_scale() const { return pressure_scale_; }

  // --- device-array interface ---
  RockView view();
  RockReadView view() const;  //!< the same without the loads, for queries
  //! Host copies of the edge pressures [Pa] and exposure flags, one per edge slot (for tests and output).
  std::vector<double> edge_pressures() const;
  std::vector<std::uint8_t> edge_exposure() const;
  //! Host copy of the coupler's node loads [N/m] (RockView::loads.node_load), one per node.
  std::vector<Vec2> node_loads() const;

  // --- checkpoint and restart ---
  //! Appends every array and counter of the solver to a checkpoint; read_checkpoint() restores them into a
  //! solver built from the same mesh and options, so the run continues bit for bit.
  void write_checkpoint(CheckpointWriter& w) const;
  void read_checkpoint(CheckpointReader& r);

  // --- diagnostics and output (host copies; each costs a device sync) ---
  RockEnergies energies() const;
  RockSnapshot snapshot() const;
  //! Total force [N/m] that the prescribed-velocity supports exerted on each group of nodes in the last step (one
  //! copy of the support forces).
  std::vector<std::array<double, 2>> support_reactions(const std::vector<std::vector<int>>& groups) const;
  //! Sum over nodes of the contact force magnitude [N/m] of the last step (0: nothing touches).
  double contact_force_norm() const;
  double time() const { return time_; }
  //! [s] the last step's dt (0 before the first). The work ledgers pair a step's forces with half of the last
  //! step's displacement and half of their own (leapfrog), so the positions x - v last_step() / 2 are the ones
  //! whose changes the ledgers' works are paid along.
  double last_step() const { return dt_prev_; }
  long steps() const { return steps_; }
  int triangle_count() const { return triangles_; }
  int node_count() const { return 3 * triangles_; }
  int joint_count() const { return joints_; }
  const std::vector<BoundaryEdge>& boundary_edges() const { return boundary_edges_; }
  const RockMaterial& material() const { return material_; }
  //! Mesh vertex of each node (3 per triangle), from the topology the solver was built from.
  const std::vector<int>& node_vertex() const { return node_vertex_; }
  //! The four nodes of each joint (host copy of the params).
  const std::vector<JointNodes>& joint_nodes() const { return joint_nodes_host_; }
  // --- analysis on the device (rock_analysis.hpp and fragments.hpp use the results) ---
  //! Gives `joints` the strength and fracture energies `q` (natural joints of a set), before the first step.
  //! Throws InputError for a joint that does not exist or properties the joint law cannot take,
  //! std::logic_error after a step.
  void set_joint_properties(const std::vector<int>& joints, const JointProperties& q);
  //! Kinetic energy [J/m] of the nodes (one reduction).
  double kinetic_energy() const;
  //! Each joint's strength parameters as the joint law uses them (host copy; heterogeneous rock shows its draw).
  std::vector<JointStrength> joint_strengths() const;
  //! Sets velocity probes at points [m] of the initial mesh (replacing any earlier set; their peaks start at
  //! zero). Each follows the material point (the triangle holding it, by barycentric weights); every step()
  //! then updates its peak particle velocity on the device, up to the time `until` [s] of the probe (empty:
  //! no end; e.g. the first arrival of a wave, before reflections and the throw of the piece). Throws
  //! InputError naming a point that lies in no triangle.
  void set_probes(const std::vector<std::array<double, 2>>& points, const std::vector<double>& until = {});
  //! Per probe: its current velocity and the peak so far (host copy).
  std::vector<ProbeSample> probe_samples() const;

  //! Number of contact-grid rebuilds so far (broad phase).
  long contact_rebuilds() const;
  //! Rebuilds the contact broad phase (uniform grid, triangles sorted by cell). step() calls it whenever the
  //! nodes may have travelled half the buffer since the last build; public for benchmarks.
  void rebuild_contact_grid();

 private:
  // The in-situ set-up and relaxation (rock_model.hpp, in_situ_setup.cpp) set the rock's state before its first step.
  friend void set_in_situ_stress(RockSolver& rock, const InSituStress& s, const std::vector<int>& held);
  friend EquilibriumReport equilibrate(RockSolver& rock, const EquilibriumOptions& options);
  ContactRock contact_rock() const;  //!< what contact reads of the rock
  //! Contact tests every free pair at the next step (its travel budgets, docs/fdem-solver.md, start again):
  //! called wherever the velocities change outside the node update, since the triangles' travel counters
  //! read the velocities to know how far the last update moved the nodes.
  void reset_contact_budgets();

  RockMaterial material_;
  RockOptions options_;
  int triangles_ = 0, joints_ = 0;
  std::vector<BoundaryEdge> boundary_edges_;
  std::vector<JointNodes> joint_nodes_host_;
  std::vector<int> node_vertex_;
  double stable_dt_ = 0, time_ = 0, pressure_scale_ = 1.0, dt_prev_ = 0;
  double joint_stored_initial_ = 0;  // [J/m] the joints' elastic energy at the start (in-situ preload)
  bool in_situ_set_ = false;
  long steps_ = 0;
  std::unique_ptr<detail::RockArrays> a_;  // every device array but contact's (rock_storage.hpp)
  std::unique_ptr<ContactSearch> contact_;  // contact between the triangles: its arrays and broad phase
  std::unique_ptr<RockProbes> probes_;      // velocity probes
  double last_speed_ = 0;    // largest node speed of the last finish_motion() [m/s]
  double pending_time_ = 0;  // time advanced since the last finish_motion() [s]
};

}  // namespace blastsim::fdem
