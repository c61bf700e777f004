//! \file rock_storage.hpp
//! \brief The rock solver's device arrays (internal): one owning group per field list of rock_fields.hpp,
//! the views the kernels take, and the checkpoint records, all generated from those lists.
#pragma once

#include "blastsim/core/backend.hpp"
#include "blastsim/fdem/fragment_kernels.hpp"
#include "blastsim/fdem/rock_fields.hpp"

#include <string>

namespace blastsim::fdem::detail {

#define BLASTSIM_STORAGE_MEMBER(type, name, comment) DeviceVector<type> name;
#define BLASTSIM_VIEW_POINTER(type, name, comment) device_ptr(name),

//! A group of owning arrays with read-only views (params, loads).
#define BLASTSIM_CONST_GROUP(Group, LIST)                         \
  struct Group##Arrays {                                          \
    LIST(BLASTSIM_STORAGE_MEMBER)                                 \
    Group view() const { return Group{LIST(BLASTSIM_VIEW_POINTER)}; } \
  };
//! A group of owning arrays with views of either access.
#define BLASTSIM_STATE_GROUP(Group, LIST)                                       \
  struct Group##Arrays {                                                        \
    LIST(BLASTSIM_STORAGE_MEMBER)                                               \
    template <Access A = Access::read_write>                                    \
    Group<A> view() {                                                           \
      return Group<A>{LIST(BLASTSIM_VIEW_POINTER)};                             \
    }                                                                           \
    Group<Access::read> read() const { return Group<Access::read>{LIST(BLASTSIM_VIEW_POINTER)}; } \
  };

BLASTSIM_CONST_GROUP(NodeParams, BLASTSIM_ROCK_NODE_PARAMS)
BLASTSIM_CONST_GROUP(TriangleParams, BLASTSIM_ROCK_TRIANGLE_PARAMS)
BLASTSIM_CONST_GROUP(EdgeParams, BLASTSIM_ROCK_EDGE_PARAMS)
BLASTSIM_CONST_GROUP(JointParams, BLASTSIM_ROCK_JOINT_PARAMS)
BLASTSIM_CONST_GROUP(NodeLoads, BLASTSIM_ROCK_NODE_LOADS)
BLASTSIM_STATE_GROUP(NodeMotion, BLASTSIM_ROCK_NODE_MOTION)
BLASTSIM_STATE_GROUP(NodeForces, BLASTSIM_ROCK_NODE_FORCES)
BLASTSIM_STATE_GROUP(NodeLedger, BLASTSIM_ROCK_NODE_LEDGER)
BLASTSIM_STATE_GROUP(TriangleState, BLASTSIM_ROCK_TRIANGLE_STATE)
BLASTSIM_STATE_GROUP(EdgeState, BLASTSIM_ROCK_EDGE_STATE)
BLASTSIM_STATE_GROUP(JointState, BLASTSIM_ROCK_JOINT_STATE)
BLASTSIM_STATE_GROUP(ContactGrid, BLASTSIM_ROCK_CONTACT_GRID)
BLASTSIM_STATE_GROUP(ContactPairs, BLASTSIM_ROCK_CONTACT_PAIRS)

//! All arrays of one RockSolver.
struct RockArrays {
  // params
  NodeParamsArrays node_params;
  TriangleParamsArrays triangle_params;
  EdgeParamsArrays edge_params;
  JointParamsArrays joint_params;
  // loads
  NodeLoadsArrays node_loads;
  // state
  NodeMotionArrays nodes;
  NodeForcesArrays forces;
  NodeLedgerArrays ledger;
  TriangleStateArrays triangles;
  EdgeStateArrays edges;
  JointStateArrays joints;
  // contact broad phase (checkpointed) and its pairs (derived)
  ContactGridArrays grid;
  ContactPairsArrays pairs;
  // velocity probes (set_probes): their stations (fixed) and peaks (checkpointed as rock.probes.peak)
  DeviceVector<ProbeStation> probe_station;
  DeviceVector<ProbePeak> probe_peak;
  DeviceVector<Vec2> probe_velocity;  // work array of probe_samples()
  // largest speed of each node since the last finish_motion() [m/s]; zero between steps, not checkpointed
  DeviceVector<double> speed_peak;
  // work arrays of fragment_labels() (two label buffers), sized on first use
  DeviceVector<int> label_a, label_b;

  //! Calls fn(record name, array, fixed size) for every array a checkpoint holds: the loads and the state,
  //! not the params (the restarted solver builds them from the same mesh and material) nor the derived contact
  //! pairs; `fixed size` is false for the contact grid's arrays, whose sizes change with each rebuild.
  //! Self is RockArrays or const RockArrays.
  template <class Self, class Fn>
  static void for_each_checkpoint_array(Self& a, Fn&& fn) {
#define BLASTSIM_VISIT_ARRAY(type, name, comment) fn(prefix + #name, group.name, fixed);
#define BLASTSIM_VISIT_GROUP(member, LIST, FIXED)            \
  {                                                          \
    auto& group = a.member;                                  \
    const std::string prefix = "rock." #member ".";          \
    const bool fixed = FIXED;                                \
    LIST(BLASTSIM_VISIT_ARRAY)                               \
  }
    BLASTSIM_VISIT_GROUP(node_loads, BLASTSIM_ROCK_NODE_LOADS, true)
    BLASTSIM_VISIT_GROUP(nodes, BLASTSIM_ROCK_NODE_MOTION, true)
    BLASTSIM_VISIT_GROUP(forces, BLASTSIM_ROCK_NODE_FORCES, true)
    BLASTSIM_VISIT_GROUP(ledger, BLASTSIM_ROCK_NODE_LEDGER, true)
    BLASTSIM_VISIT_GROUP(triangles, BLASTSIM_ROCK_TRIANGLE_STATE, true)
    BLASTSIM_VISIT_GROUP(edges, BLASTSIM_ROCK_EDGE_STATE, true)
    BLASTSIM_VISIT_GROUP(joints, BLASTSIM_ROCK_JOINT_STATE, true)
    BLASTSIM_VISIT_GROUP(grid, BLASTSIM_ROCK_CONTACT_GRID, false)
#undef BLASTSIM_VISIT_GROUP
#undef BLASTSIM_VISIT_ARRAY
  }
};

#undef BLASTSIM_CONST_GROUP
#undef BLASTSIM_STATE_GROUP
#undef BLASTSIM_VIEW_POINTER
#undef BLASTSIM_STORAGE_MEMBER

}  // namespace blastsim::fdem::detail
