//! \file rock_storage.hpp
//! \brief The rock solver's device arrays (internal): one owning group per field list of rock_fields.hpp,
//! the views the kernels take, and the checkpoint records, all generated from those lists.
#pragma once

#include "blastsim/core/device_groups.hpp"
#include "blastsim/fdem/rock_fields.hpp"

#include <string>

namespace blastsim::fdem::detail {

BLASTSIM_CONST_STORAGE(NodeParams, BLASTSIM_ROCK_NODE_PARAMS)
BLASTSIM_CONST_STORAGE(TriangleParams, BLASTSIM_ROCK_TRIANGLE_PARAMS)
BLASTSIM_CONST_STORAGE(EdgeParams, BLASTSIM_ROCK_EDGE_PARAMS)
BLASTSIM_CONST_STORAGE(JointParams, BLASTSIM_ROCK_JOINT_PARAMS)
BLASTSIM_CONST_STORAGE(NodeLoads, BLASTSIM_ROCK_NODE_LOADS)
BLASTSIM_STATE_STORAGE(NodeMotion, BLASTSIM_ROCK_NODE_MOTION)
BLASTSIM_STATE_STORAGE(NodeForces, BLASTSIM_ROCK_NODE_FORCES)
BLASTSIM_STATE_STORAGE(NodeLedger, BLASTSIM_ROCK_NODE_LEDGER)
BLASTSIM_STATE_STORAGE(TriangleState, BLASTSIM_ROCK_TRIANGLE_STATE)
BLASTSIM_STATE_STORAGE(EdgeState, BLASTSIM_ROCK_EDGE_STATE)
BLASTSIM_STATE_STORAGE(EdgeLoads, BLASTSIM_ROCK_EDGE_LOADS)
BLASTSIM_STATE_STORAGE(JointState, BLASTSIM_ROCK_JOINT_STATE)
BLASTSIM_STATE_STORAGE(JointWork, BLASTSIM_ROCK_JOINT_WORK)
BLASTSIM_STATE_STORAGE(NodePeaks, BLASTSIM_ROCK_NODE_PEAKS)

//! All arrays of one RockSolver.
struct RockArrays {
  // params
  NodeParamsArrays node_params;
  TriangleParamsArrays triangle_params;
  EdgeParamsArrays edge_params;
  JointParamsArrays joint_params;
  // loads
  NodeLoadsArrays node_loads;
  EdgeLoadsArrays edge_loads;
  // state
  NodeMotionArrays nodes;
  NodeForcesArrays forces;
  NodeLedgerArrays ledger;
  TriangleStateArrays triangles;
  EdgeStateArrays edges;
  JointStateArrays joints;
  // work arrays of a step (not checkpointed)
  JointWorkArrays joint_work;
  NodePeaksArrays peaks;

  //! Calls fn(record name, array, fixed size) for every array a checkpoint holds: the loads and the state, not the
  //! params (the restarted solver builds them from the same mesh and material); contact writes its own
  //! (ContactSearch). Every size is fixed by the mesh.
  //! Self is RockArrays or const RockArrays.
  template <class Self, class Fn>
  static void for_each_checkpoint_array(Self& a, Fn&& fn) {
    auto group = [&](auto& arrays, const std::string& prefix, bool fixed) {
      arrays.for_each([&](const char* name, auto& v) { fn(prefix + name, v, fixed); });
    };
    group(a.node_loads, "rock.node_loads.", true);
    group(a.edge_loads, "rock.edge_loads.", true);
    group(a.nodes, "rock.nodes.", true);
    group(a.forces, "rock.forces.", true);
    group(a.ledger, "rock.ledger.", true);
    group(a.triangles, "rock.triangles.", true);
    group(a.edges, "rock.edges.", true);
    group(a.joints, "rock.joints.", true);
  }
};

}  // namespace blastsim::fdem::detail
