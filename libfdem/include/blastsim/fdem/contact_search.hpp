//! \file contact_search.hpp
//! \brief fdem::ContactSearch: contact between the rock's triangles, its own room of the rock solver: the broad
//! phase on a uniform grid, the candidate pairs and their work lists, the travel budgets, and the contact forces
//! with Coulomb friction (Munjiza 2004, ch. 2 and 5; docs/fdem-solver.md "Contact"). Host-safe: the arrays sit
//! behind a pointer (contact_search_kernels.hpp declares them).
#pragma once

#include "blastsim/core/checkpoint_fwd.hpp"
#include "blastsim/fdem/rock_fields.hpp"

#include <memory>
#include <vector>

namespace blastsim::fdem {

namespace detail {
struct ContactArrays;
}

//! What contact reads of the rock: the nodes' motion and params, the triangles' edges, the joints' state.
struct ContactRock {
  NodeMotion<Access::read> nodes;
  NodeParams node_params;           //!< vertex, mass
  EdgeParams edge_params;           //!< neighbour, joint
  JointState<Access::read> joints;  //!< broken
};

template <Access A>
struct ContactTravel;

//! The contact of one RockSolver. Every triangle pair that the broad phase finds within the buffer is a candidate,
//! numbered once; a pair joined by an intact joint, or meeting at a mesh vertex all of whose joints are intact, is
//! held together and never tested; the others are tested on their travel budgets (a pair apart by a gap is skipped
//! until its triangles have travelled half that gap). The lists are remade when the nodes may have travelled half
//! the buffer since the last build (RockSolver::advance()).
class ContactSearch {
 public:
  //! `triangles` and `joints` of the rock; `node_vertex`, the mesh vertex of each node (3 per triangle);
  //! `joint_nodes`, each joint's nodes (its ends a0, a1 name the vertices it touches); `buffer_fraction`, the
  //! buffer as a fraction of twice the largest triangle's radius (RockOptions::contact_buffer). Without contact
  //! (`enabled` false) nothing is ever built; the travel counters and the checkpoint records are kept alike.
  ContactSearch(int triangles, const std::vector<int>& node_vertex, const std::vector<JointNodes>& joint_nodes,
                double buffer_fraction, bool enabled);
  ~ContactSearch();
  ContactSearch(ContactSearch&&) noexcept;
  ContactSearch& operator=(ContactSearch&&) noexcept;

  bool enabled() const { return enabled_; }
  //! Whether the nodes may have travelled half the buffer, `ahead` [m] more included, since the last build.
  bool rebuild_due(double ahead) const { return enabled_ && 2 * (travel_since_build_ + ahead) > buffer_; }
  //! Builds the grid, the candidate lists, the pairs and their work lists from the rock's positions; the pairs'
  //! contact offsets are carried over from the lists before. InstabilityError (naming `step`) for positions that
  //! are not finite.
  void rebuild(const ContactRock& rock, long step);
  //! The nodes moved by at most `distance` [m] since the last call (RockSolver::finish_motion()).
  void moved(double distance) { travel_since_build_ += distance; }
  //! The nodes jumped (RockSolver::set_positions()): the lists are remade before the next step.
  void jumped() { travel_since_build_ = buffer_; }
  //! Every free pair is tested at the next step (its travel budget starts again): called wherever the velocities
  //! change outside the node update, since the triangles' travel counters read them.
  void reset_budgets();
  //! The triangles' travel counters, which TriangleForceKernel raises.
  ContactTravel<Access::read_write> travel();
  //! Contact forces of one step into forces.contact_* (overwritten) and the friction dissipation into `state`:
  //! the vertex bonds as the joints now stand, the free pairs and those released since the lists were made,
  //! then each triangle's gather. `penalty` [Pa], `friction` [-], dt [s].
  void forces(const ContactRock& rock, NodeForces<Access::read_write> forces, TriangleState<Access::read_write> state,
              double penalty, double friction, double dt);
  long rebuilds() const { return rebuilds_; }
  int pairs() const { return pairs_; }

  //! The grid, the candidate lists, the pairs' offsets per slot and the broad phase's scalars, under the records
  //! rock.grid.* and rock.contact.*.
  void write_checkpoint(CheckpointWriter& w) const;
  //! Reads them back, checks every index against what it addresses (naming the record), and remakes the pairs and
  //! their work lists from the lists read. `steps`, the rock's steps (bounds the rebuilds).
  void read_checkpoint(CheckpointReader& r, const ContactRock& rock, long steps);

 private:
  void build_pairs(const ContactRock& rock);       //!< pair numbering from the candidate lists
  void list_free_pairs(const ContactRock& rock);   //!< the work lists from the pairs and the joints' state
  void update_vertex_bonds(const JointState<Access::read>& joints);  //!< VertexBondKernel

  int triangles_ = 0, joints_ = 0, vertices_ = 0;
  double buffer_fraction_ = 0;
  bool enabled_ = false;
  std::unique_ptr<detail::ContactArrays> a_;
  // the grid (cell size, origin, cells), the buffer, the travel since the last build, the pairs
  double cell_size_ = 0, grid_x0_ = 0, grid_y0_ = 0;
  int grid_nx_ = 0, grid_ny_ = 0;
  double buffer_ = 0, travel_since_build_ = 0;
  long rebuilds_ = 0;
  int pairs_ = 0, free_pairs_ = 0;  // candidate pairs; those not held when the work lists were made
};

}  // namespace blastsim::fdem
