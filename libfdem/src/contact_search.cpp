//! \file contact_search.cpp
//! \brief ContactSearch: the broad phase, the pairs and their work lists, the contact forces, the checkpoint.
#include "blastsim/fdem/contact_search.hpp"

#include "blastsim/core/checkpoint.hpp"
#include "blastsim/core/csr.hpp"
#include "blastsim/core/device_groups.hpp"
#include "blastsim/core/error.hpp"
#include "blastsim/fdem/contact_search_kernels.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

namespace blastsim::fdem {

namespace detail {
BLASTSIM_STATE_STORAGE(ContactGrid, BLASTSIM_ROCK_CONTACT_GRID)
BLASTSIM_STATE_STORAGE(ContactPairs, BLASTSIM_ROCK_CONTACT_PAIRS)
BLASTSIM_CONST_STORAGE(ContactVertexJoints, BLASTSIM_CONTACT_VERTEX_JOINTS)
BLASTSIM_STATE_STORAGE(ContactVertices, BLASTSIM_CONTACT_VERTICES)
BLASTSIM_STATE_STORAGE(ContactLists, BLASTSIM_CONTACT_LISTS)
BLASTSIM_STATE_STORAGE(ContactTravel, BLASTSIM_CONTACT_TRAVEL)
BLASTSIM_STATE_STORAGE(ContactSlots, BLASTSIM_CONTACT_SLOTS)

//! The arrays of one ContactSearch: the broad phase (checkpointed), the pairs (derived; only their offsets are
//! checkpointed, per slot), the joints at each mesh vertex (fixed) and the vertices' bonds, the work lists and the
//! triangles' travel counters (not checkpointed: a restart makes the pairs anew, every one tested at its first step).
struct ContactArrays {
  ContactGridArrays grid;
  ContactPairsArrays pairs;
  ContactVertexJointsArrays at_vertex;
  ContactVerticesArrays vertices;
  ContactListsArrays lists;
  ContactTravelArrays travel;
};
}  // namespace detail

namespace {
//! The contact offset of every candidate slot's pair (-1 for all when there are no pairs).
detail::ContactSlotsArrays slot_offsets(const detail::ContactArrays& a, int pairs) {
  const int used = read_element(a.grid.neighbour_offset, static_cast<index_t>(a.grid.neighbour_offset.size()) - 1);
  detail::ContactSlotsArrays out;
  out.offset.assign(std::max(used, 1), -1.0);
  if (pairs > 0) for_each_index("fdem.grid.slot_offsets", used, SlotOffsetKernel{a.pairs.read(), out.view()});
  return out;
}

//! Sets each pair's contact offset from the slot that held it in the candidate lists `old` (`slots` their
//! offsets), -1 where the pair was no candidate there.
void carry_offsets(detail::ContactArrays& a, int pairs, const detail::ContactGridArrays& old,
                   const detail::ContactSlotsArrays& slots) {
  if (pairs > 0)
    for_each_index("fdem.grid.carry_offsets", pairs, CarryOffsetKernel{a.pairs.view(), old.read(), slots.read()});
}

}  // namespace

ContactSearch::ContactSearch(int triangles, const std::vector<int>& node_vertex,
                             const std::vector<JointNodes>& joint_nodes, double buffer_fraction, bool enabled)
    : triangles_(triangles), joints_(static_cast<int>(joint_nodes.size())), buffer_fraction_(buffer_fraction),
      enabled_(enabled), a_(std::make_unique<detail::ContactArrays>()) {
  detail::ContactArrays& a = *a_;
  // Joints per mesh vertex (CSR): each joint touches the two vertices of its edge (its ends 2 j and 2 j + 1).
  vertices_ = node_vertex.empty() ? 0 : *std::max_element(node_vertex.begin(), node_vertex.end()) + 1;
  std::vector<int> end_vertex(2 * static_cast<std::size_t>(joints_));
  for (int j = 0; j < joints_; ++j)
    end_vertex[2 * j] = node_vertex[joint_nodes[j].a0], end_vertex[2 * j + 1] = node_vertex[joint_nodes[j].a1];
  HostCsr at_vertex = group_by_key(end_vertex, vertices_);
  for (int& e : at_vertex.entry) e /= 2;  // the end's joint
  const std::vector<int>& vertex_offset = at_vertex.offset;
  copy_from_host(a.at_vertex.offset, vertex_offset);
  copy_from_host(a.at_vertex.joints, at_vertex.entry.empty() ? std::vector<int>{0} : at_vertex.entry);
  // Bonded: at least one joint there, none broken yet (a vertex without joints bonds nothing).
  std::vector<std::uint8_t> bonded(std::max(vertices_, 1), 0);
  for (int v = 0; v < vertices_; ++v) bonded[v] = vertex_offset[v + 1] > vertex_offset[v] ? 1 : 0;
  copy_from_host(a.vertices.bonded, bonded);
  a.grid.sorted_triangles.assign(triangles_, 0), a.grid.cell_key.assign(triangles_, 0);
  a.grid.cell_start.assign(1, 0), a.grid.cell_end.assign(1, 0);
  a.grid.neighbour_offset.assign(triangles_ + 1, 0), a.grid.neighbour_list.assign(1, 0);
  a.travel.travel.assign(triangles_, 0.0);
}

ContactSearch::~ContactSearch() = default;
ContactSearch::ContactSearch(ContactSearch&&) noexcept = default;
ContactSearch& ContactSearch::operator=(ContactSearch&&) noexcept = default;

ContactTravel<Access::read_write> ContactSearch::travel() { return a_->travel.view(); }

void ContactSearch::reset_budgets() {
  if (pairs_ > 0) fill_device("fdem.contact.budgets", a_->pairs.reach, -1.0);
}

void ContactSearch::rebuild(const ContactRock& rock, long step) {
  detail::ContactArrays& a = *a_;
  // The pairs' contact offsets outlive the lists: kept per slot of the old lists, carried to the new pairs.
  const bool carry = pairs_ > 0;
  detail::ContactGridArrays old;
  detail::ContactSlotsArrays old_slots;
  if (carry) {
    old_slots = slot_offsets(a, pairs_);
    old.neighbour_offset = a.grid.neighbour_offset, old.neighbour_list = a.grid.neighbour_list;
  }
  const NodeMotion<Access::read> m = rock.nodes;
  const index_t n = 3 * static_cast<index_t>(triangles_);
  const double xmax = reduce_max("fdem.grid.xmax", n, -1e300, NodeCoordinate{m, 0, 1.0});
  const double ymax = reduce_max("fdem.grid.ymax", n, -1e300, NodeCoordinate{m, 1, 1.0});
  const double xmin = -reduce_max("fdem.grid.xmin", n, -1e300, NodeCoordinate{m, 0, -1.0});
  const double ymin = -reduce_max("fdem.grid.ymin", n, -1e300, NodeCoordinate{m, 1, -1.0});
  // Largest distance from a triangle's centroid to its vertices.
  const double r_max = reduce_max("fdem.grid.rmax", triangles_, 0.0, TriangleRadius{m});
  if (!std::isfinite(xmin + xmax + ymin + ymax + r_max))
    throw InstabilityError("rock node positions are not finite at step " + std::to_string(step));
  if (buffer_ == 0) buffer_ = buffer_fraction_ * 2 * r_max;
  // Two triangles that touch have centroids within 2 r_max; each may drift buffer/2 before the next build.
  cell_size_ = 2 * r_max + buffer_;
  const double cap = std::max(4.0 * triangles_, 1024.0);  // keep the cell array in proportion to the mesh
  while (((xmax - xmin) / cell_size_ + 3) * ((ymax - ymin) / cell_size_ + 3) > cap) cell_size_ *= 2;
  grid_x0_ = xmin - cell_size_;
  grid_y0_ = ymin - cell_size_;
  grid_nx_ = static_cast<int>((xmax - grid_x0_) / cell_size_) + 2;
  grid_ny_ = static_cast<int>((ymax - grid_y0_) / cell_size_) + 2;
  const ContactGridShape shape{cell_size_, grid_x0_, grid_y0_, grid_nx_, grid_ny_};
  detail::ContactGridArrays& g = a.grid;
  for_each_index("fdem.grid.keys", triangles_, CellKeyKernel{m, g.view(), shape});
  // Stable sort: triangles keep index order inside a cell, so the contact sums run in a fixed order.
  stable_sort_by_key("fdem.grid.sort", g.cell_key, g.sorted_triangles, triangles_);
  const index_t cells = static_cast<index_t>(shape.nx) * shape.ny;
  g.cell_start.resize(cells);
  g.cell_end.resize(cells);
  lower_bounds("fdem.grid.cell_start", g.cell_key, triangles_, g.cell_start, static_cast<int>(cells));
  upper_bounds("fdem.grid.cell_end", g.cell_key, triangles_, g.cell_end, static_cast<int>(cells));
  // Candidate lists (CSR): count, scan, fill; each triangle's list in a fixed order.
  g.neighbour_offset.resize(triangles_ + 1);
  for_each_index("fdem.contact.count", triangles_, NeighbourSearchKernel{m, g.view(), shape, buffer_, false});
  const int total = exclusive_scan_total("fdem.contact.scan", g.neighbour_offset);
  g.neighbour_list.resize(std::max(total, 1));
  for_each_index("fdem.contact.fill", triangles_, NeighbourSearchKernel{m, g.view(), shape, buffer_, true});
  build_pairs(rock);
  if (carry) carry_offsets(a, pairs_, old, old_slots);
  travel_since_build_ = 0;
  ++rebuilds_;
}

void ContactSearch::build_pairs(const ContactRock& rock) {
  detail::ContactArrays& a = *a_;
  detail::ContactPairsArrays& p = a.pairs;
  p.pair_offset.resize(triangles_ + 1);
  write_element(p.pair_offset, triangles_, 0);
  for_each_index("fdem.grid.pair_count", triangles_, PairCountKernel{a.grid.read(), p.view()});
  const int pairs = exclusive_scan_total("fdem.grid.pair_scan", p.pair_offset);
  pairs_ = pairs;
  const index_t slots = a.grid.neighbour_list.size();
  p.slot_pair.resize(slots);
  p.pair.resize(std::max(pairs, 1));
  p.touch.assign(std::max(pairs, 1), 0);  // a pair contact never evaluates (held together) never touches
  p.load.resize(std::max(pairs, 1));
  p.offset.assign(std::max(pairs, 1), -1.0);  // none yet; a rebuild carries the old ones over
  p.reach.assign(std::max(pairs, 1), -1.0);   // every pair is tested at its first step
  p.bond.resize(std::max(pairs, 1));
  for_each_index("fdem.grid.pair_index", triangles_, PairIndexKernel{a.grid.read(), p.view()});
  if (pairs > 0)
    for_each_index("fdem.grid.pair_bond", pairs, PairBondKernel{rock.node_params, rock.edge_params, p.view()});
  // the list holds at least one entry even when empty
  const int used = read_element(a.grid.neighbour_offset, triangles_);
  const double unmatched = reduce_sum("fdem.grid.pair_check", used, 0.0, UnmatchedSlot{p.read()});
  if (unmatched > 0)
    throw std::logic_error("contact broad phase: " + std::to_string(static_cast<long>(unmatched)) +
                           " candidate slots have no partner slot (the candidate lists must be symmetric)");
  list_free_pairs(rock);
}

// Most candidate pairs of an intact mesh are held together by a joint or at a bonded vertex (about five in six
// in the single-hole example) and never need a contact test. Contact evaluates the pairs free when the lists
// are made, and those a joint's break has released since (ReleasedPairsKernel); a pair released is never held
// again, so no list has to shrink between builds.
void ContactSearch::list_free_pairs(const ContactRock& rock) {
  detail::ContactArrays& a = *a_;
  update_vertex_bonds(rock.joints);  // the bonds as the joints now stand (a restart or a break may have changed them)
  detail::ContactListsArrays& l = a.lists;
  l.joint_broken_listed.resize(joints_);
  for_each_index("fdem.grid.joints_listed", joints_, ListJointsKernel{rock.joints, l.view()});
  l.vertex_bonded_listed = a.vertices.bonded;
  l.free_pairs.resize(std::max(pairs_, 1));
  free_pairs_ = static_cast<int>(select_indices("fdem.grid.free_pairs", pairs_, l.free_pairs,
                                                PairFree{a.pairs.read(), rock.joints, a.vertices.read()}));
  // Each joint's pair, and the pairs grouped by the vertex they meet at (stable: in pair order within a vertex).
  l.joint_pair.assign(std::max(joints_, 1), -1);
  l.vertex_key.resize(std::max(pairs_, 1));
  l.vertex_pairs.resize(std::max(pairs_, 1));
  for_each_index("fdem.grid.pair_groups", pairs_, PairGroupKernel{a.pairs.read(), vertices_, l.view()});
  stable_sort_by_key("fdem.grid.vertex_pairs", l.vertex_key, l.vertex_pairs, pairs_);
  l.vertex_pair_offset.resize(vertices_ + 1);
  lower_bounds("fdem.grid.vertex_pair_offset", l.vertex_key, pairs_, l.vertex_pair_offset, vertices_ + 1);
}

void ContactSearch::update_vertex_bonds(const JointState<Access::read>& joints) {
  if (joints_ > 0)
    for_each_index("fdem.vertex_bonds", vertices_, VertexBondKernel{a_->at_vertex.view(), joints, a_->vertices.view()});
}

// Munjiza 2004 ch. 2: distributed-potential contact, with Coulomb friction. Each pair once (one thread a
// pair), then each triangle gathers its side of its pairs.
void ContactSearch::forces(const ContactRock& rock, NodeForces<Access::read_write> forces,
                           TriangleState<Access::read_write> state, double penalty, double friction, double dt) {
  if (!enabled_) return;
  detail::ContactArrays& a = *a_;
  update_vertex_bonds(rock.joints);  // the joints of this step included
  const ContactPairKernel pair{rock.nodes,        rock.node_params, rock.joints, a.vertices.read(),
                               a.pairs.view(),    a.travel.read(),  penalty,     friction,
                               dt};
  // The free pairs (list_free_pairs), then those released since the lists were made, each in interleaved chunks:
  // the pairs that need work bunch up in index space (around the hole and the cracks; the other free pairs are
  // skipped on their travel budgets), and each host thread takes one contiguous run of launch indices.
  const auto listed = Interleaved<ListedPairs>::over(ListedPairs{pair, a.lists.read()}, free_pairs_);
  for_each_index("fdem.contact.pairs", listed.launch_size(), listed);
  if (joints_ > 0) {
    const ReleasedPairsKernel rk{pair, a.lists.read(), joints_};
    const index_t n = joints_ + static_cast<index_t>(vertices_);
    const auto released = Interleaved<ReleasedPairsKernel>::over(rk, n);
    for_each_index("fdem.contact.released", released.launch_size(), released);
  }
  for_each_index("fdem.contact.gather", triangles_, ContactGatherKernel{a.grid.read(), a.pairs.read(), forces, state, dt});
}

void ContactSearch::write_checkpoint(CheckpointWriter& w) const {
  a_->grid.for_each([&](const char* name, const auto& v) { write_array(w, std::string("rock.grid.") + name, v); });
  w.value("rock.contact.rebuilds", rebuilds_);
  w.value("rock.contact.cell_size", cell_size_);
  w.value("rock.contact.origin", std::array<double, 2>{grid_x0_, grid_y0_});
  w.value("rock.contact.cells", std::array<int, 2>{grid_nx_, grid_ny_});
  w.value("rock.contact.buffer", buffer_);
  w.value("rock.contact.travel", travel_since_build_);
  if (enabled_) write_array(w, "rock.contact.slot_offset", slot_offsets(*a_, pairs_).offset);
}

void ContactSearch::read_checkpoint(CheckpointReader& r, const ContactRock& rock, long steps) {
  detail::ContactArrays& a = *a_;
  a.grid.for_each([&](const char* name, auto& v) { read_array(r, std::string("rock.grid.") + name, v); });
  cell_size_ = r.non_negative("rock.contact.cell_size");
  buffer_ = r.non_negative("rock.contact.buffer");
  travel_since_build_ = r.non_negative("rock.contact.travel");
  const std::array<double, 2> origin = r.value<std::array<double, 2>>("rock.contact.origin");
  if (!std::isfinite(origin[0]) || !std::isfinite(origin[1])) r.fail("rock.contact.origin", "not finite");
  grid_x0_ = origin[0], grid_y0_ = origin[1];
  rebuilds_ = r.value<long>("rock.contact.rebuilds");
  if (rebuilds_ < 0 || rebuilds_ > steps + 1) r.fail("rock.contact.rebuilds", "negative or more than the rock's steps");
  const std::array<int, 2> cells = r.value<std::array<int, 2>>("rock.contact.cells");
  const int min_cells = enabled_ ? 1 : 0;  // without contact no grid is ever built
  for (const int n : cells)
    if (n < min_cells || n > (1 << 20)) r.fail("rock.contact.cells", "contact grid size out of range");
  grid_nx_ = cells[0], grid_ny_ = cells[1];
  if (!enabled_) return;
  // Every index against what it addresses, before any kernel reads it.
  const detail::ContactGridArrays& g = a.grid;
  const double T = triangles_;
  const double cell_count = static_cast<double>(grid_nx_) * grid_ny_;
  if (g.cell_key.size() != static_cast<size_t>(triangles_) || g.sorted_triangles.size() != static_cast<size_t>(triangles_))
    r.fail("rock.grid.cell_key", "its size is not the triangle count");
  if (static_cast<double>(g.cell_start.size()) != cell_count || static_cast<double>(g.cell_end.size()) != cell_count)
    r.fail("rock.grid.cell_start", "its size is not the contact grid's cell count");
  r.check_range("rock.grid.cell_key", to_host(g.cell_key), 0, cell_count - 1);
  r.check_range("rock.grid.sorted_triangles", to_host(g.sorted_triangles), 0, T - 1);
  const std::vector<int> start = to_host(g.cell_start), end = to_host(g.cell_end);
  r.check_range("rock.grid.cell_start", start, 0, T);
  r.check_range("rock.grid.cell_end", end, 0, T);
  for (size_t c = 0; c < start.size(); ++c)
    if (start[c] > end[c]) r.fail("rock.grid.cell_start", "cell " + std::to_string(c) + " starts after it ends");
  const std::vector<int> offset = to_host(g.neighbour_offset);
  if (offset.size() != static_cast<size_t>(triangles_) + 1 || offset[0] != 0)
    r.fail("rock.grid.neighbour_offset", "not an offset array of the triangles");
  for (size_t t = 1; t < offset.size(); ++t)
    if (offset[t] < offset[t - 1]) r.fail("rock.grid.neighbour_offset", "decreases at " + std::to_string(t));
  if (static_cast<size_t>(offset.back()) > g.neighbour_list.size())
    r.fail("rock.grid.neighbour_offset", "addresses past the candidate list");
  r.check_range("rock.grid.neighbour_list", to_host(g.neighbour_list), 0, T - 1);
  try {
    build_pairs(rock);
  } catch (const std::logic_error& e) {
    r.fail("rock.grid.neighbour_list", e.what());
  }
  detail::ContactSlotsArrays slots;
  read_array(r, "rock.contact.slot_offset", slots.offset, g.neighbour_list.size());
  r.check_range("rock.contact.slot_offset", to_host(slots.offset), -1, 1);
  carry_offsets(a, pairs_, g, slots);
}

}  // namespace blastsim::fdem
