//! \file contact_search_kernels.hpp
//! \brief Contact between the rock's triangles (fdem::ContactSearch): its field lists, the broad phase on a uniform
//! grid (Munjiza 2004, ch. 5: sort by cell, candidate lists), the pairs and their work lists, the travel budgets,
//! and the pair and gather kernels of the contact forces (one thread a pair, then one a triangle).
#pragma once

#include "blastsim/fdem/contact_kernels.hpp"
#include "blastsim/fdem/rock_fields.hpp"
#include "blastsim/fdem/rock_types.hpp"
#include "blastsim/fdem/triangle_kernels.hpp"

#include <cstdint>

namespace blastsim::fdem {

// ---- contact broad phase (rebuilt from the positions; checkpointed so a restart keeps the same lists) ----
#define BLASTSIM_ROCK_CONTACT_GRID(X)                                              \
  X(int, cell_key, "grid cell of each triangle's centroid")                        \
  X(int, sorted_triangles, "triangles sorted by cell (stable: index order inside a cell)") \
  X(int, cell_start, "first entry of each cell in sorted_triangles")               \
  X(int, cell_end, "one past its last entry")                                      \
  X(int, neighbour_offset, "per triangle (+1): start of its candidate list (CSR)") \
  X(int, neighbour_list, "contact candidates within the buffer")
// ---- contact pairs: each candidate pair once, derived from the lists (only `offset` is checkpointed) ------
#define BLASTSIM_ROCK_CONTACT_PAIRS(X)                                    \
  X(int, pair_offset, "per triangle (+1): first pair it leads")           \
  X(int, slot_pair, "per candidate slot: its pair")                       \
  X(TrianglePair, pair, "the pair's triangles, i < j")                    \
  X(int, bond, "what holds the pair while intact: its joint (>= 0), -2 - v for one common mesh vertex v, or -1") \
  X(std::uint8_t, touch, "1 when the pair touched in this step")          \
  X(PairLoad, load, "the pair's loads, valid when touching")             \
  X(double, offset, "pairs meeting at one mesh vertex: contact offset s (-1: bonded, or none yet; checkpointed per slot)") \
  X(double, reach, "travel budget [m]: the pair stays apart while its triangles' travel sum is below it (-1: test it)")

// ---- what contact keeps beside the pairs (remade with them; not checkpointed: a restart remakes them) --------
//! Per mesh vertex: the joints that touch it (CSR, fixed).
#define BLASTSIM_CONTACT_VERTEX_JOINTS(X)                                \
  X(int, offset, "per mesh vertex (+1): start of its joints")            \
  X(int, joints, "the joints that touch each vertex")
//! Per mesh vertex: whether all its joints are intact (derived from the joints' broken flags each step).
#define BLASTSIM_CONTACT_VERTICES(X) X(std::uint8_t, bonded, "1 while every joint at the vertex is intact")
//! The work lists of the contact forces: the pairs that no intact joint or bonded vertex held when the lists were
//! made, the joints' and vertices' state then, each joint's pair, and the pairs that meet at each mesh vertex (CSR).
#define BLASTSIM_CONTACT_LISTS(X)                                                          \
  X(int, free_pairs, "the pairs free when the lists were made")                            \
  X(int, joint_pair, "per joint: its pair (-1: none)")                                     \
  X(int, vertex_pair_offset, "per mesh vertex (+1): start of the pairs that meet there")   \
  X(int, vertex_pairs, "the pairs grouped by the vertex they meet at")                     \
  X(std::uint8_t, joint_broken_listed, "per joint: broken when the lists were made")       \
  X(std::uint8_t, vertex_bonded_listed, "per mesh vertex: bonded when the lists were made")  \
  X(int, vertex_key, "per pair: the mesh vertex it meets at (the vertices' count for none): the sort key")
//! Per triangle: a bound on how far its nodes moved since the solver was made or restarted [m]
//! (TriangleForceKernel; the pairs' travel budgets, ContactPairs::reach).
#define BLASTSIM_CONTACT_TRAVEL(X) X(double, travel, "per triangle: its travel counter [m]")
//! Per candidate slot: its pair's contact offset, which outlives a rebuild of the lists (carried to the new pairs
//! and written to checkpoints as rock.contact.slot_offset).
#define BLASTSIM_CONTACT_SLOTS(X) X(double, offset, "per candidate slot: its pair's contact offset (-1: none)")

BLASTSIM_VIEW_GROUP(ContactGrid, BLASTSIM_ROCK_CONTACT_GRID)
BLASTSIM_VIEW_GROUP(ContactPairs, BLASTSIM_ROCK_CONTACT_PAIRS)
BLASTSIM_CONST_GROUP(ContactVertexJoints, BLASTSIM_CONTACT_VERTEX_JOINTS)
BLASTSIM_VIEW_GROUP(ContactVertices, BLASTSIM_CONTACT_VERTICES)
BLASTSIM_VIEW_GROUP(ContactLists, BLASTSIM_CONTACT_LISTS)
BLASTSIM_VIEW_GROUP(ContactTravel, BLASTSIM_CONTACT_TRAVEL)
BLASTSIM_VIEW_GROUP(ContactSlots, BLASTSIM_CONTACT_SLOTS)

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
//! around its centroid's cell whose boxes come within `margin` (the buffer). The first pass (`fill` false) only
//! counts them into neighbour_offset[t]; the second writes them into neighbour_list from the scanned
//! neighbour_offset[t] on, in a fixed order.
struct NeighbourSearchKernel {
  NodeMotion<Access::read> nodes;
  ContactGrid<Access::read_write> grid;  //!< reads sorted_triangles, cell_start, cell_end; writes as above
  ContactGridShape shape;
  double margin;
  bool fill;
  BLAST_HD void operator()(index_t ti) const {
    const int i = static_cast<int>(ti);
    const Box bi = triangle_box(nodes, i);
    const Vec2 c = triangle_centroid(nodes, i);
    int ci, cj;
    shape.cell_of(c.x, c.y, ci, cj);
    int m = fill ? grid.neighbour_offset[i] : 0;
    for (int dj = -1; dj <= 1; ++dj)
      for (int di = -1; di <= 1; ++di) {
        const int ii = ci + di, jj = cj + dj;
        if (ii < 0 || jj < 0 || ii >= shape.nx || jj >= shape.ny) continue;
        const int cell = jj * shape.nx + ii;
        for (int s = grid.cell_start[cell]; s < grid.cell_end[cell]; ++s) {
          const int j = grid.sorted_triangles[s];
          if (j == i || boxes_apart(bi, triangle_box(nodes, j), margin)) continue;
          if (fill) grid.neighbour_list[m] = j;
          ++m;
        }
      }
    if (!fill) grid.neighbour_offset[i] = m;
  }
};

//! The grid cell of each triangle's centroid (the sort key of the broad phase) and the identity order of the
//! triangles that the sort by cell then permutes.
struct CellKeyKernel {
  NodeMotion<Access::read> nodes;
  ContactGrid<Access::read_write> grid;  //!< writes cell_key, sorted_triangles
  ContactGridShape shape;
  BLAST_HD void operator()(index_t t) const {
    const Vec2 c = triangle_centroid(nodes, static_cast<int>(t));
    int i, j;
    shape.cell_of(c.x, c.y, i, j);
    grid.cell_key[t] = j * shape.nx + i;
    grid.sorted_triangles[t] = static_cast<int>(t);
  }
};

//! A node's coordinate along x (axis 0) or y (axis 1), or its negative (sign -1), for the extremes of the nodes.
struct NodeCoordinate {
  NodeMotion<Access::read> nodes;
  int axis;
  double sign;
  BLAST_HD double operator()(index_t k) const { return sign * (axis == 0 ? nodes.x[k] : nodes.y[k]); }
};

//! The largest distance from a triangle's centroid to its vertices [m].
struct TriangleRadius {
  NodeMotion<Access::read> nodes;
  BLAST_HD double operator()(index_t t) const {
    const Vec2 c = triangle_centroid(nodes, static_cast<int>(t));
    double d = 0;
    for (int k = 0; k < 3; ++k) d = fmax(d, hypot(nodes.x[3 * t + k] - c.x, nodes.y[3 * t + k] - c.y));
    return d;
  }
};

//! Contact pairs from the broad phase's candidate lists, which are symmetric (j is in i's list exactly when i
//! is in j's: same cells, same box test). Each unordered pair {i, j} is numbered once, as (i, j) with i < j,
//! triangle by triangle: pair_offset[i] + the rank of j among i's candidates above i. First pass: how many
//! pairs each triangle leads.
struct PairCountKernel {
  ContactGrid<Access::read> grid;          //!< neighbour_offset, neighbour_list
  ContactPairs<Access::read_write> pairs;  //!< writes pair_offset
  BLAST_HD void operator()(index_t ti) const {
    const int i = static_cast<int>(ti);
    int c = 0;
    for (int s = grid.neighbour_offset[i]; s < grid.neighbour_offset[i + 1]; ++s) c += grid.neighbour_list[s] > i ? 1 : 0;
    pairs.pair_offset[i] = c;
  }
};

//! Second pass: the pair of every candidate slot (slot_pair), and each pair's triangles (pair).
//! A slot whose partner's list lacks it (which symmetric lists never do) gets -1; the caller checks.
struct PairIndexKernel {
  ContactGrid<Access::read> grid;          //!< neighbour_offset, neighbour_list
  ContactPairs<Access::read_write> pairs;  //!< reads pair_offset; writes slot_pair, pair
  BLAST_HD void operator()(index_t ti) const {
    const int i = static_cast<int>(ti);
    const int* offset = grid.neighbour_offset;
    const int* list = grid.neighbour_list;
    int k = 0;
    for (int s = offset[i]; s < offset[i + 1]; ++s) {
      const int j = list[s];
      if (j > i) {
        const int p = pairs.pair_offset[i] + k++;
        pairs.slot_pair[s] = p;
        pairs.pair[p] = {i, j};
        continue;
      }
      int rank = 0, found = -1;
      for (int t = offset[j]; t < offset[j + 1] && found < 0; ++t) {
        if (list[t] == i) found = pairs.pair_offset[j] + rank;
        rank += list[t] > j ? 1 : 0;
      }
      pairs.slot_pair[s] = found;
    }
  }
};

//! What holds pair (i, j) together while intact, found once per build of the pairs: the joint across their
//! common edge, or their one common mesh vertex (encoded -2 - v), or nothing (-1).
struct PairBondKernel {
  NodeParams node_params;  //!< vertex
  EdgeParams edge_params;  //!< neighbour, joint
  ContactPairs<Access::read_write> pairs;  //!< reads pair; writes bond
  BLAST_HD void operator()(index_t p) const {
    const int i = pairs.pair[p].i, j = pairs.pair[p].j;
    for (int e = 0; e < 3; ++e)
      if (edge_params.neighbour[3 * i + e] == j) {
        pairs.bond[p] = edge_params.joint[3 * i + e] >= 0 ? edge_params.joint[3 * i + e] : -1;
        return;
      }
    int shared = -1, count = 0;
    for (int a = 0; a < 3; ++a) {
      const int v = node_params.vertex[3 * i + a];
      for (int c = 0; c < 3; ++c)
        if (node_params.vertex[3 * j + c] == v) shared = v, ++count;
    }
    pairs.bond[p] = count == 1 ? -2 - shared : -1;
  }
};

//! The contact offset of each candidate slot's pair (kept across rebuilds of the lists and in checkpoints).
struct SlotOffsetKernel {
  ContactPairs<Access::read> pairs;           //!< slot_pair, offset
  ContactSlots<Access::read_write> slots;  //!< writes offset
  BLAST_HD void operator()(index_t s) const { slots.offset[s] = pairs.offset[pairs.slot_pair[s]]; }
};

//! After a rebuild: each new pair (i, j) takes the offset its slot had in i's previous candidate list, or -1
//! (none yet) where j was not a candidate of i before.
struct CarryOffsetKernel {
  ContactPairs<Access::read_write> pairs;  //!< reads pair; writes offset
  ContactGrid<Access::read> old;           //!< the previous lists: neighbour_offset, neighbour_list
  ContactSlots<Access::read> old_slots;    //!< the offset of each of their slots
  BLAST_HD void operator()(index_t p) const {
    const int i = pairs.pair[p].i, j = pairs.pair[p].j;
    double o = -1;
    for (int s = old.neighbour_offset[i]; s < old.neighbour_offset[i + 1]; ++s)
      if (old.neighbour_list[s] == j) {
        o = old_slots.offset[s];
        break;
      }
    pairs.offset[p] = o;
  }
};

//! 1 for a candidate slot that PairIndexKernel found no pair for (summed to check the lists' symmetry).
struct UnmatchedSlot {
  ContactPairs<Access::read> pairs;  //!< slot_pair
  BLAST_HD double operator()(index_t s) const { return pairs.slot_pair[s] < 0 ? 1.0 : 0.0; }
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
  ContactVertexJoints at;                       //!< offset, joints
  JointState<Access::read> joints;              //!< broken
  ContactVertices<Access::read_write> vertices;  //!< bonded
  BLAST_HD void operator()(index_t vi) const {
    const int v = static_cast<int>(vi);
    if (!vertices.bonded[v]) return;
    for (int k = at.offset[v]; k < at.offset[v + 1]; ++k)
      if (joints.broken[at.joints[k]]) {
        vertices.bonded[v] = 0;
        return;
      }
  }
};

//! Whether a candidate pair is held together (PairBondKernel's `bond`): by its joint while intact (bond >= 0), or
//! at its one common mesh vertex while all that vertex's joints are intact (bond <= -2). Once released, never
//! held again (joints do not heal).
BLAST_HD inline bool pair_held(int bond, const JointState<Access::read>& joints,
                               const ContactVertices<Access::read>& vertices) {
  return bond >= 0 ? !joints.broken[bond] : bond <= -2 && vertices.bonded[-2 - bond];
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
  NodeParams node_params;               //!< mass
  JointState<Access::read> joints;      //!< broken
  ContactVertices<Access::read> vertices;  //!< bonded
  //! reads pair and bond (PairBondKernel); writes touch, load, offset and reach (pair_reach() of its last test)
  ContactPairs<Access::read_write> pairs;
  //! per triangle: its travel counter (TriangleForceKernel); a side of its box moves at most as far as it grows
  ContactTravel<Access::read> travel;
  double penalty, friction, dt;
  BLAST_HD void operator()(index_t p) const {
    const int b = pairs.bond[p];
    if (pair_held(b, joints, vertices)) {  // held together (offset stays -1)
      pairs.touch[p] = 0;
      return;
    }
    const int vertex = b <= -2 ? -2 - b : -1;
    const int i = pairs.pair[p].i, j = pairs.pair[p].j;
    // Still apart since its last test: that test left touch 0 and the offset at next_contact_offset(s, 0) = 0,
    // which testing again would repeat (the same bytes, less work: most free pairs are neighbours a cell apart).
    const double moved = travel.travel[i] + travel.travel[j];
    if (moved < pairs.reach[p]) return;
    pairs.touch[p] = 0;
    const double s = vertex >= 0 ? pairs.offset[p] : 0.0;  // Munjiza's contact for all but pairs that meet at one vertex
    Vec2 x[2][3];
    nodes.triangle(i, x[0]);
    nodes.triangle(j, x[1]);
    const double gap = box_gap(triangle_box(nodes, i), triangle_box(nodes, j));
    pairs.reach[p] = pair_reach(gap, moved);
    if (gap > 0 || !triangles_overlap(x[0], x[1])) {
      if (vertex >= 0) pairs.offset[p] = next_contact_offset(s, 0.0);
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
    if (vertex >= 0) pairs.offset[p] = next_contact_offset(s, c.depth);
    if (!c.touching) return;
    pairs.touch[p] = 1;
    PairLoad& out = pairs.load[p];
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
  ContactLists<Access::read> lists;  //!< free_pairs
  BLAST_HD void operator()(index_t e) const { pair(lists.free_pairs[e]); }
};

//! Predicate of the free-pair list: candidate pair q is not held together (pair_held()).
struct PairFree {
  ContactPairs<Access::read> pairs;  //!< bond
  JointState<Access::read> joints;
  ContactVertices<Access::read> vertices;
  BLAST_HD bool operator()(int q) const { return !pair_held(pairs.bond[q], joints, vertices); }
};

//! The joints' broken flags as the work lists are made (joint_broken_listed).
struct ListJointsKernel {
  JointState<Access::read> joints;         //!< broken
  ContactLists<Access::read_write> lists;  //!< writes joint_broken_listed
  BLAST_HD void operator()(index_t j) const { lists.joint_broken_listed[j] = joints.broken[j]; }
};

//! The keys that group the pairs by the mesh vertex they meet at (`vertices` for the pairs that meet at none),
//! and each joint's pair (-1 where the joint has none; joint_pair cleared before).
struct PairGroupKernel {
  ContactPairs<Access::read> pairs;        //!< bond
  int vertices;
  ContactLists<Access::read_write> lists;  //!< writes vertex_key, vertex_pairs, joint_pair
  BLAST_HD void operator()(index_t q) const {
    const int b = pairs.bond[q];
    lists.vertex_key[q] = b <= -2 ? -2 - b : vertices;
    lists.vertex_pairs[q] = static_cast<int>(q);
    if (b >= 0) lists.joint_pair[b] = static_cast<int>(q);  // a joint holds one pair: no two threads write one entry
  }
};

//! ContactPairKernel on the pairs released since the work lists were made (RockSolver::list_free_pairs): launch
//! index k < joints is joint k, whose pair it evaluates once the joint has broken since; k = joints + v is mesh
//! vertex v, whose pairs it evaluates once v has lost its bond since (VertexBondKernel of this step). Every such
//! pair is evaluated by exactly one thread, and none of them is in the free list.
struct ReleasedPairsKernel {
  ContactPairKernel pair;
  ContactLists<Access::read> lists;  //!< joint_broken_listed, vertex_bonded_listed, joint_pair, vertex_pair_*
  index_t joints;
  BLAST_HD void operator()(index_t k) const {
    if (k < joints) {
      if (pair.joints.broken[k] && !lists.joint_broken_listed[k] && lists.joint_pair[k] >= 0) pair(lists.joint_pair[k]);
      return;
    }
    const index_t v = k - joints;
    if (pair.vertices.bonded[v] || !lists.vertex_bonded_listed[v]) return;
    for (int s = lists.vertex_pair_offset[v]; s < lists.vertex_pair_offset[v + 1]; ++s) pair(lists.vertex_pairs[s]);
  }
};

//! Contact force on each triangle's own nodes: the sum, in the fixed order of its candidate list, of its
//! side of every touching pair (a gather: no two threads write the same node, the same bytes every run).
//! The friction dissipation of a pair is booked on its first triangle.
struct ContactGatherKernel {
  ContactGrid<Access::read> grid;    //!< neighbour_offset
  ContactPairs<Access::read> pairs;  //!< slot_pair, pair, touch, load
  NodeForces<Access::read_write> forces;  //!< writes contact_*
  TriangleState<Access::read_write> state;  //!< adds to dissipation.friction
  double dt;
  BLAST_HD void operator()(index_t ti) const {
    const int i = static_cast<int>(ti);
    Vec2 f[3] = {{0, 0}, {0, 0}, {0, 0}};
    double friction_power = 0;
    for (int s = grid.neighbour_offset[i]; s < grid.neighbour_offset[i + 1]; ++s) {
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

}  // namespace blastsim::fdem
