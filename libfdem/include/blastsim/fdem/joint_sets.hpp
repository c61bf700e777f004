//! \file joint_sets.hpp
//! \brief Natural joint sets of a rock mass: parallel traces of given orientation, spacing, trace length and
//! persistence, clipped to the rock, which the built mesh follows and whose joints take the set's properties.
#pragma once

#include "blastsim/fdem/gmsh_mesh.hpp"
#include "blastsim/fdem/heterogeneity.hpp"

#include <string>
#include <vector>

namespace blastsim::fdem {

struct MeshSpec;

//! One joint set. Its traces lie on the lines n . (x - c) = offset + k spacing (k integer; c the centre of the
//! rock's outline, n the normal of the traces' direction d = (cos angle, sin angle)); along each line they repeat
//! with period trace_length / persistence, the pattern shifted along the line by a uniform fraction of the
//! period drawn per line from `seed`. Traces are clipped to the rock (outline less holes); pieces shorter than
//! the mesh's half element are dropped.
struct JointSetSpec {
  std::string label = "joint_set";  //!< names the set in messages (e.g. rock.joint_set.0)
  double angle = 0;             //!< [rad] direction of the traces from +x, counter-clockwise
  double spacing = 0;           //!< [m] normal distance between neighbouring lines, > 0
  double trace_length = 0;      //!< [m] length of a trace; 0: every line crosses the whole rock (persistence 1)
  double persistence = 1;       //!< (0, 1]: trace length over the period along a line
  double offset = 0;            //!< [m] normal distance of one line from the outline's centre
  long long seed = 1;           //!< of the shifts along the lines
  bool open = false;            //!< broken from the start (no strength; contact and friction only)
  double initial_aperture = 0;  //!< [m] of open joints: crack gas room (coupled runs)
  JointProperties properties;   //!< strength of closed joints
  //! Explicit joints (a [[rock.joint]]): when not empty these segments [m] are the set's traces as given (the
  //! pattern fields above are not used); a built shape follows them, a mesh file needs edges along them.
  std::vector<Segment> segments;
};

//! The traces of `set` clipped to the rock of `shape` (a built shape: rectangle, disc, and those with holes),
//! in line order, then along each line. Pieces shorter than `min_length` [m] (half an element) are dropped.
//! So that the mesh needs no slivers, with a clearance of 2 min_length (an element): a line that runs that
//! close to the outline along its length gets no traces, a hole that a line meets at a shallow angle or misses
//! by less is cut out with that much to spare, and a trace end that close to the outline or a cut moves onto
//! it (ends near another set's traces: snap_trace_ends()). A set of explicit segments returns them. Throws InputError
//! naming set.label for a bad spacing, persistence or trace length, or a mesh file (no outline to clip to).
std::vector<Segment> joint_set_traces(const JointSetSpec& set, const MeshSpec& shape, double min_length);

//! Moves each trace end that lies within `clearance` [m] of a trace of another set, along its own line, onto
//! that trace (extending or shortening it: no sliver of rock between them), then drops traces shorter than
//! `min_length` [m].
void snap_trace_ends(std::vector<std::vector<Segment>>& sets, double clearance, double min_length);

//! The traces of every set of a rock (joint_set_traces() with half of shape.element_size as the shortest
//! piece), their ends snapped across sets with an element of clearance (snap_trace_ends()).
std::vector<std::vector<Segment>> joint_sets_traces(const std::vector<JointSetSpec>& sets, const MeshSpec& shape);

}  // namespace blastsim::fdem
