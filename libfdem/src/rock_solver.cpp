//! \file rock_solver.cpp
//! \brief RockSolver: set-up from the FDEM topology, the explicit step, contact broad phase, energies, snapshots.
#include "blastsim/fdem/rock_solver.hpp"

#include "blastsim/core/checkpoint.hpp"
#include "blastsim/core/error.hpp"
#include "rock_kernels.hpp"

#include <thrust/binary_search.h>
#include <thrust/extrema.h>
#include <thrust/iterator/counting_iterator.h>
#include <thrust/reduce.h>
#include <thrust/scan.h>
#include <thrust/sequence.h>
#include <thrust/sort.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

namespace blastsim::fdem {

void RockOptions::validate() const {
  auto fail = [](const char* key, double value, const char* allowed) {
    std::ostringstream os;
    os << key << " = " << value << ": must be " << allowed;
    throw InputError(os.str());
  };
  if (!(joint_penalty_factor > 0)) fail("joint_penalty_factor", joint_penalty_factor, "> 0 (p / E, typically 10 to 100)");
  if (!(contact_penalty_factor > 0)) fail("contact_penalty_factor", contact_penalty_factor, "> 0 (p_c / E)");
  if (!(damping_ratio >= 0 && damping_ratio < 1)) fail("damping_ratio", damping_ratio, "in [0, 1)");
  if (!(contact_buffer > 0 && contact_buffer <= 2)) fail("contact_buffer", contact_buffer, "in (0, 2]");
  if (!std::isfinite(gravity[0]) || !std::isfinite(gravity[1])) fail("gravity", gravity[0], "finite");
}

namespace {

template <class T>
DeviceVector<T> upload(const std::vector<T>& host) {
  DeviceVector<T> d;
  copy_from_host(d, host);
  return d;
}

double length(const std::array<double, 2>& a, const std::array<double, 2>& b) {
  return std::hypot(b[0] - a[0], b[1] - a[1]);
}

}  // namespace

RockSolver::RockSolver(const FdemTopology& topo, const RockMaterial& material, const RockOptions& options)
    : material_(material), options_(options) {
  material_.validate();
  options_.validate();
  triangles_ = topo.triangle_count();
  joints_ = static_cast<int>(topo.joints.size());
  boundary_edges_ = topo.boundary_edges;
  const int nodes = 3 * triangles_;
  const double E = material_.youngs_modulus, rho = material_.density;
  const double cp = material_.p_wave_speed();
  const double p_joint_stiff = options_.joint_penalty_factor * E;
  const double p_contact_stiff = options_.contact ? options_.contact_penalty_factor * E : 0.0;

  std::vector<double> x(nodes), y(nodes), mass(nodes), inv_f0(4 * triangles_), area0(triangles_), eta(triangles_);
  double omega_max = 0;
  for (int t = 0; t < triangles_; ++t) {
    const auto& p0 = topo.node_positions[3 * t];
    const auto& p1 = topo.node_positions[3 * t + 1];
    const auto& p2 = topo.node_positions[3 * t + 2];
    const Mat2 F0 = edge_matrix({p0[0], p0[1]}, {p1[0], p1[1]}, {p2[0], p2[1]});
    const Mat2 inv = F0.inverse();
    inv_f0[4 * t] = inv.a, inv_f0[4 * t + 1] = inv.b, inv_f0[4 * t + 2] = inv.c, inv_f0[4 * t + 3] = inv.d;
    const double A = 0.5 * F0.det();
    area0[t] = A;
    const double l01 = length(p0, p1), l12 = length(p1, p2), l20 = length(p2, p0);
    const double h_min = 2 * A / std::max({l01, l12, l20});  // smallest altitude
    eta[t] = 2.0 * (l01 + l12 + l20) / 3.0 * options_.damping_ratio * std::sqrt(E * rho);
    for (int k = 0; k < 3; ++k) {
      x[3 * t + k] = topo.node_positions[3 * t + k][0];
      y[3 * t + k] = topo.node_positions[3 * t + k][1];
      mass[3 * t + k] = rho * A / 3.0;
    }
    // Bounds of omega^2 [1/s2], added: elastic 4 c_p^2 / h^2; joint springs p/3 and p/6 per node on two
    // edges (Gershgorin row sum 2 p over the node mass rho A / 3, times sqrt(2) for the rotated axes);
    // contact: a penetration d loads an edge with p_c L 3 d / h from each side, on reduced mass rho L h / 12.
    const double omega2 = 4 * cp * cp / (h_min * h_min) + 6 * std::sqrt(2.0) * p_joint_stiff / (rho * A) +
                          36 * p_contact_stiff / (rho * h_min * h_min);
    omega_max = std::max(omega_max, std::sqrt(omega2));
  }
  const double beta = options_.damping_ratio;
  stable_dt_ = 2.0 / omega_max * (std::sqrt(1 + beta * beta) - beta);

  x_ = upload(x), y_ = upload(y), x0_ = upload(x), y0_ = upload(y), mass_ = upload(mass);
  vx_.assign(nodes, 0.0), vy_.assign(nodes, 0.0);
  f_tri_x_.assign(nodes, 0.0), f_tri_y_.assign(nodes, 0.0), f_con_x_.assign(nodes, 0.0), f_con_y_.assign(nodes, 0.0);
  f_pres_x_.assign(nodes, 0.0), f_pres_y_.assign(nodes, 0.0);
  constraint_.assign(nodes, 0), v_prescribed_.assign(2 * nodes, 0.0), work_.assign(kWorkKinds * nodes, 0.0);
  support_.assign(2 * nodes, 0.0);
  inv_f0_ = upload(inv_f0), area0_ = upload(area0), eta_ = upload(eta);
  stress_.assign(3 * triangles_, 0.0), dissipation_.assign(2 * triangles_, 0.0);

  std::vector<int> slot_neighbour(3 * triangles_, -1), slot_joint(3 * triangles_, -1);
  std::vector<std::uint8_t> exposed(3 * triangles_, 0);
  for (const BoundaryEdge& b : boundary_edges_) exposed[b.n0] = kEdgeBoundary;
  std::vector<int> joint_nodes(4 * joints_);
  std::vector<double> strength(8 * joints_);
  const double p_joint = options_.joint_penalty_factor * E;
  for (int j = 0; j < joints_; ++j) {
    const Joint& J = topo.joints[j];
    slot_neighbour[J.a0] = J.triangle_b, slot_joint[J.a0] = j;
    slot_neighbour[J.b0] = J.triangle_a, slot_joint[J.b0] = j;
    joint_nodes[4 * j] = J.a0, joint_nodes[4 * j + 1] = J.a1, joint_nodes[4 * j + 2] = J.b0, joint_nodes[4 * j + 3] = J.b1;
    joint_nodes_host_.push_back({J.a0, J.a1, J.b0, J.b1});
    const double h = length(topo.node_positions[J.a0], topo.node_positions[J.a1]);
    double* s = &strength[8 * j];
    s[0] = material_.tensile_strength;
    s[1] = material_.cohesion;
    s[2] = std::tan(material_.friction_angle);
    s[3] = 2 * h * material_.tensile_strength / p_joint;  // o_p
    s[4] = 2 * h * material_.cohesion / p_joint;          // s_p
    s[5] = softening_length(material_.fracture_energy_mode1, material_.tensile_strength, s[3]);  // o_t
    s[6] = softening_length(material_.fracture_energy_mode2, material_.cohesion, s[4]);          // s_t
    s[7] = h;
  }
  slot_force_.assign(12 * triangles_, 0.0);
  slot_neighbour_ = upload(slot_neighbour), slot_joint_ = upload(slot_joint);
  edge_exposed_ = upload(exposed);
  edge_pressure_.assign(3 * triangles_, 0.0);
  joint_nodes_ = upload(joint_nodes), joint_strength_ = upload(strength);
  joint_damage_.assign(3 * joints_, 0.0), joint_state_.assign(6 * joints_, 0.0), joint_traction_.assign(6 * joints_, 0.0);
  joint_broken_.assign(joints_, 0);
  sorted_triangles_.assign(triangles_, 0), cell_key_.assign(triangles_, 0);
  cell_start_.assign(1, 0), cell_end_.assign(1, 0);
  neighbour_offset_.assign(triangles_ + 1, 0), neighbour_list_.assign(1, 0);
  if (options_.contact) rebuild_contact_grid();
}

detail::RockArrays RockSolver::arrays() {
  return {device_ptr(x_), device_ptr(y_), device_ptr(vx_), device_ptr(vy_), device_ptr(x0_), device_ptr(y0_),
          device_ptr(mass_), device_ptr(f_tri_x_), device_ptr(f_tri_y_), device_ptr(f_con_x_), device_ptr(f_con_y_),
          device_ptr(f_pres_x_), device_ptr(f_pres_y_),
          device_ptr(constraint_), device_ptr(v_prescribed_), device_ptr(work_), device_ptr(support_), device_ptr(inv_f0_),
          device_ptr(area0_), device_ptr(eta_), device_ptr(stress_), device_ptr(dissipation_),
          device_ptr(slot_force_), device_ptr(slot_neighbour_), device_ptr(slot_joint_), device_ptr(edge_exposed_),
          device_ptr(edge_pressure_), device_ptr(joint_nodes_), device_ptr(joint_strength_),
          device_ptr(joint_damage_), device_ptr(joint_state_), device_ptr(joint_traction_),
          device_ptr(joint_broken_), device_ptr(cell_key_), device_ptr(sorted_triangles_), device_ptr(cell_start_),
          device_ptr(cell_end_), device_ptr(neighbour_offset_), device_ptr(neighbour_list_)};
}

void RockSolver::rebuild_contact_grid() {
  const detail::RockArrays r = arrays();
  const index_t n = node_count();
  const double* xs = r.x;
  const double* ys = r.y;
  const double xmax = reduce_max("fdem.grid.xmax", n, -1e300, [=] BLAST_HD(index_t k) { return xs[k]; });
  const double ymax = reduce_max("fdem.grid.ymax", n, -1e300, [=] BLAST_HD(index_t k) { return ys[k]; });
  const double xmin = -reduce_max("fdem.grid.xmin", n, -1e300, [=] BLAST_HD(index_t k) { return -xs[k]; });
  const double ymin = -reduce_max("fdem.grid.ymin", n, -1e300, [=] BLAST_HD(index_t k) { return -ys[k]; });
  // Largest distance from a triangle's centroid to its vertices.
  const double r_max = reduce_max("fdem.grid.rmax", triangles_, 0.0, [=] BLAST_HD(index_t t) {
    const double cx = (xs[3 * t] + xs[3 * t + 1] + xs[3 * t + 2]) / 3.0;
    const double cy = (ys[3 * t] + ys[3 * t + 1] + ys[3 * t + 2]) / 3.0;
    double d = 0;
    for (int k = 0; k < 3; ++k) d = fmax(d, hypot(xs[3 * t + k] - cx, ys[3 * t + k] - cy));
    return d;
  });
  if (!std::isfinite(xmin + xmax + ymin + ymax + r_max))
    throw InstabilityError("rock node positions are not finite at step " + std::to_string(steps_));
  if (buffer_ == 0) buffer_ = options_.contact_buffer * 2 * r_max;
  // Two triangles that touch have centroids within 2 r_max; each may drift buffer/2 before the next build.
  cell_size_ = 2 * r_max + buffer_;
  const double cap = std::max(4.0 * triangles_, 1024.0);  // keep the cell array in proportion to the mesh
  while (((xmax - xmin) / cell_size_ + 3) * ((ymax - ymin) / cell_size_ + 3) > cap) cell_size_ *= 2;
  grid_x0_ = xmin - cell_size_;
  grid_y0_ = ymin - cell_size_;
  grid_nx_ = static_cast<int>((xmax - grid_x0_) / cell_size_) + 2;
  grid_ny_ = static_cast<int>((ymax - grid_y0_) / cell_size_) + 2;
  const double cs = cell_size_, gx0 = grid_x0_, gy0 = grid_y0_;
  const int gnx = grid_nx_, gny = grid_ny_;
  int* key = device_ptr(cell_key_);
  int* sorted = device_ptr(sorted_triangles_);
  for_each_index("fdem.grid.keys", triangles_, [=] BLAST_HD(index_t t) {
    const double cx = (xs[3 * t] + xs[3 * t + 1] + xs[3 * t + 2]) / 3.0;
    const double cy = (ys[3 * t] + ys[3 * t + 1] + ys[3 * t + 2]) / 3.0;
    int i = static_cast<int>(floor((cx - gx0) / cs)), j = static_cast<int>(floor((cy - gy0) / cs));
    i = i < 0 ? 0 : (i >= gnx ? gnx - 1 : i);
    j = j < 0 ? 0 : (j >= gny ? gny - 1 : j);
    key[t] = j * gnx + i;
    sorted[t] = static_cast<int>(t);
  });
  // Stable sort: triangles keep index order inside a cell, so the contact sums run in a fixed order.
  thrust::stable_sort_by_key(thrust::device, cell_key_.begin(), cell_key_.end(), sorted_triangles_.begin());
  const index_t cells = static_cast<index_t>(gnx) * gny;
  cell_start_.resize(cells);
  cell_end_.resize(cells);
  thrust::lower_bound(thrust::device, cell_key_.begin(), cell_key_.end(), thrust::counting_iterator<int>(0),
                      thrust::counting_iterator<int>(static_cast<int>(cells)), cell_start_.begin());
  thrust::upper_bound(thrust::device, cell_key_.begin(), cell_key_.end(), thrust::counting_iterator<int>(0),
                      thrust::counting_iterator<int>(static_cast<int>(cells)), cell_end_.begin());
  // Candidate lists (CSR): count, scan, fill; each triangle's list in a fixed order.
  detail::RockArrays r2 = arrays();
  neighbour_offset_.resize(triangles_ + 1);
  detail::NeighbourSearchKernel search{r2, buffer_, cs, gx0, gy0, gnx, gny, device_ptr(neighbour_offset_), nullptr};
  for_each_index("fdem.contact.count", triangles_, search);
  thrust::exclusive_scan(thrust::device, neighbour_offset_.begin(), neighbour_offset_.end(), neighbour_offset_.begin());
  const int total = neighbour_offset_.back();
  neighbour_list_.resize(std::max(total, 1));
  r2 = arrays();
  search.r = r2;
  search.list = device_ptr(neighbour_list_);
  for_each_index("fdem.contact.fill", triangles_, search);
  build_contact_pairs();
  travel_since_build_ = 0;
  ++rebuilds_;
}

void RockSolver::build_contact_pairs() {
  const int* offset = device_ptr(neighbour_offset_);
  const int* list = device_ptr(neighbour_list_);
  pair_offset_.resize(triangles_ + 1);
  pair_offset_[triangles_] = 0;
  for_each_index("fdem.grid.pair_count", triangles_, detail::PairCountKernel{offset, list, device_ptr(pair_offset_)});
  thrust::exclusive_scan(thrust::device, pair_offset_.begin(), pair_offset_.end(), pair_offset_.begin());
  const int pairs = pair_offset_.back();
  pairs_ = pairs;
  const index_t slots = neighbour_list_.size();
  slot_pair_.resize(slots);
  pair_ij_.resize(2 * static_cast<index_t>(std::max(pairs, 1)));
  pair_touch_.resize(std::max(pairs, 1));
  pair_load_.resize(13 * static_cast<index_t>(std::max(pairs, 1)));
  for_each_index("fdem.grid.pair_index", triangles_,
                 detail::PairIndexKernel{offset, list, device_ptr(pair_offset_), device_ptr(slot_pair_), device_ptr(pair_ij_)});
  const int used = neighbour_offset_.back();  // the list holds at least one entry even when empty
  const double unmatched = reduce_sum("fdem.grid.pair_check", used, 0.0, detail::UnmatchedSlot{device_ptr(slot_pair_)});
  if (unmatched > 0)
    throw std::logic_error("contact broad phase: " + std::to_string(static_cast<long>(unmatched)) +
                           " candidate slots have no partner slot (the candidate lists must be symmetric)");
}

void RockSolver::step(double dt) {
  if (!(dt > 0) || dt > stable_dt_) {
    std::ostringstream os;
    os << "rock time step dt = " << dt << " s: must be in (0, " << stable_dt_
       << "] s, the stable step of the explicit scheme (elastic wave and joint/contact penalty springs)";
    throw InputError(os.str());
  }
  if (options_.contact && 2 * travel_since_build_ > buffer_) rebuild_contact_grid();
  triangle_forces(dt);
  joint_forces();
  contact_forces(dt);
  update_nodes(dt);
  const detail::RockArrays r = arrays();
  time_ += dt;
  ++steps_;
  // Largest speed (infinite if any is not finite): drives the contact rebuild and catches instability.
  const double* vx = r.vx;
  const double* vy = r.vy;
  const double v_max = reduce_max("fdem.vmax", node_count(), 0.0, [=] BLAST_HD(index_t k) {
    const double s = vx[k] * vx[k] + vy[k] * vy[k];
    return s == s && s < 1e300 ? sqrt(s) : 1e308;
  });
  if (!(v_max < 1e300)) {
    const std::vector<double> hx = to_host(vx_), hy = to_host(vy_);
    size_t bad = 0;
    while (bad < hx.size() && std::isfinite(hx[bad] * hx[bad] + hy[bad] * hy[bad])) ++bad;
    throw InstabilityError("rock velocity not finite at step " + std::to_string(steps_) + " (t = " +
                           std::to_string(time_) + " s), node " + std::to_string(bad) + " of triangle " +
                           std::to_string(bad / 3));
  }
  travel_since_build_ += v_max * dt;
}

// Munjiza 2004 ch. 2: constant-strain triangles.
void RockSolver::triangle_forces(double dt) {
  for_each_index("fdem.triangles", triangles_,
                 detail::TriangleForceKernel{arrays(), material_.lame_lambda(), material_.shear_modulus(), pressure_scale_, dt});
}

// Munjiza 2004 ch. 7: cohesive joints.
void RockSolver::joint_forces() {
  if (joints_ > 0) for_each_index("fdem.joints", joints_, detail::JointForceKernel{arrays()});
}

// Munjiza 2004 ch. 2: distributed-potential contact, with Coulomb friction. Each pair once (one thread a
// pair), then each triangle gathers its side of its pairs.
void RockSolver::contact_forces(double dt) {
  if (!options_.contact) return;
  const double penalty = options_.contact_penalty_factor * material_.youngs_modulus;
  const detail::ContactPairKernel pair{arrays(), device_ptr(pair_ij_), device_ptr(pair_touch_), device_ptr(pair_load_),
                                       penalty, material_.contact_friction, dt};
#if defined(BLASTSIM_BACKEND_CUDA) || defined(__CUDACC__)
  for_each_index("fdem.contact.pairs", pairs_, pair);  // in pair order: neighbouring threads read neighbouring pairs
#else
  // CPU: the static OpenMP schedule gives each thread one contiguous run of pairs, and the pairs that touch
  // (numbered with their triangles: around the hole and the cracks) bunch up in a few runs. Visiting them in
  // interleaved blocks spreads them over the threads; a pair's result does not depend on when it runs.
  const detail::InterleavedPairs interleaved{pair, pairs_, detail::InterleavedPairs::block_length_for(pairs_)};
  for_each_index("fdem.contact.pairs", interleaved.launch_size(), interleaved);
#endif
  for_each_index("fdem.contact.gather", triangles_,
                 detail::ContactGatherKernel{arrays(), device_ptr(slot_pair_), device_ptr(pair_ij_),
                                             device_ptr(pair_touch_), device_ptr(pair_load_), dt});
}

// Symplectic Euler (fdem.md): gather the node's forces, integrate.
void RockSolver::update_nodes(double dt) {
  for_each_index("fdem.nodes", node_count(),
                 detail::NodeUpdateKernel{arrays(), options_.gravity[0], options_.gravity[1], dt, dt_prev_});
  dt_prev_ = dt;
}

void RockSolver::prescribe_velocity(const std::vector<int>& nodes, bool along_x, bool along_y, double vx, double vy) {
  std::vector<std::uint8_t> c = to_host(constraint_);
  std::vector<double> vp = to_host(v_prescribed_), hvx = to_host(vx_), hvy = to_host(vy_);
  for (int n : nodes) {
    if (n < 0 || n >= node_count()) throw InputError("prescribed node " + std::to_string(n) + " does not exist");
    if (along_x) c[n] |= 1, vp[2 * n] = vx, hvx[n] = vx;
    if (along_y) c[n] |= 2, vp[2 * n + 1] = vy, hvy[n] = vy;
  }
  copy_from_host(constraint_, c);
  copy_from_host(v_prescribed_, vp);
  copy_from_host(vx_, hvx);
  copy_from_host(vy_, hvy);
}

void RockSolver::set_velocities(const std::vector<double>& vxy) {
  if (vxy.size() != 2 * static_cast<size_t>(node_count()))
    throw InputError("set_velocities needs 2 values per node (" + std::to_string(2 * node_count()) + ")");
  std::vector<double> hx(node_count()), hy(node_count());
  for (int n = 0; n < node_count(); ++n) hx[n] = vxy[2 * n], hy[n] = vxy[2 * n + 1];
  copy_from_host(vx_, hx);
  copy_from_host(vy_, hy);
}

void RockSolver::set_edge_pressure(const std::vector<int>& slots, double pressure) {
  std::vector<double> p = to_host(edge_pressure_);
  for (int s : slots) {
    if (s < 0 || s >= 3 * triangles_) throw InputError("edge slot " + std::to_string(s) + " does not exist");
    p[s] = pressure;
  }
  copy_from_host(edge_pressure_, p);
}

std::vector<int> RockSolver::joints_on_segment(double xa, double ya, double xb, double yb, double tolerance) const {
  const std::vector<double> px = to_host(x0_), py = to_host(y0_);
  const double lx = xb - xa, ly = yb - ya, len2 = lx * lx + ly * ly;
  auto on_segment = [&](int n) {  // distance from the segment within tolerance
    const double s = len2 > 0 ? std::clamp(((px[n] - xa) * lx + (py[n] - ya) * ly) / len2, 0.0, 1.0) : 0.0;
    return std::hypot(px[n] - xa - s * lx, py[n] - ya - s * ly) <= tolerance;
  };
  std::vector<int> out;
  for (int j = 0; j < joints_; ++j) {
    const std::array<int, 4>& n = joint_nodes_host_[j];
    if (on_segment(n[0]) && on_segment(n[1])) out.push_back(j);
  }
  return out;
}

void RockSolver::break_joints(const std::vector<int>& joints) {
  std::vector<std::uint8_t> broken = to_host(joint_broken_), exposed = to_host(edge_exposed_);
  std::vector<double> damage = to_host(joint_damage_);
  for (int j : joints) {
    if (j < 0 || j >= joints_) throw InputError("joint " + std::to_string(j) + " does not exist");
    broken[j] = 1;
    for (int q = 0; q < 3; ++q) damage[3 * j + q] = 1.0;
    exposed[joint_nodes_host_[j][0]] = kEdgeCrackFace;  // face A's slot (its first node)
    exposed[joint_nodes_host_[j][2]] = kEdgeCrackFace;  // face B's slot
  }
  copy_from_host(joint_broken_, broken);
  copy_from_host(edge_exposed_, exposed);
  copy_from_host(joint_damage_, damage);
}

RockView RockSolver::view() {
  return {device_ptr(x_), device_ptr(y_), device_ptr(vx_), device_ptr(vy_), device_ptr(edge_exposed_),
          device_ptr(edge_pressure_), triangles_};
}

RockEnergies RockSolver::energies() {
  const detail::RockArrays r = arrays();
  RockEnergies e;
  e.kinetic = reduce_sum("fdem.energy.kinetic", node_count(), 0.0, [=] BLAST_HD(index_t n) {
    return 0.5 * r.mass[n] * (r.vx[n] * r.vx[n] + r.vy[n] * r.vy[n]);
  });
  const double lambda = material_.lame_lambda(), mu = material_.shear_modulus();
  e.strain = reduce_sum("fdem.energy.strain", triangles_, 0.0, [=] BLAST_HD(index_t t) {
    Vec2 p[3];
    detail::triangle_nodes(r, static_cast<int>(t), p);
    const Mat2 inv{r.inv_f0[4 * t], r.inv_f0[4 * t + 1], r.inv_f0[4 * t + 2], r.inv_f0[4 * t + 3]};
    return r.area0[t] * triangle_strain_energy_density(inv, edge_matrix(p[0], p[1], p[2]), lambda, mu);
  });
  auto work_sum = [&](int c) {
    return reduce_sum("fdem.energy.work", node_count(), 0.0, [=] BLAST_HD(index_t n) { return r.work[kWorkKinds * n + c]; });
  };
  e.pressure_work = work_sum(0);
  e.external_work = e.pressure_work + work_sum(3) + work_sum(4);
  e.joint_work = work_sum(1);
  e.contact_work = work_sum(2);
  e.damping_dissipated =
      reduce_sum("fdem.energy.damping", triangles_, 0.0, [=] BLAST_HD(index_t t) { return r.dissipation[2 * t]; });
  e.friction_dissipated =
      reduce_sum("fdem.energy.friction", triangles_, 0.0, [=] BLAST_HD(index_t t) { return r.dissipation[2 * t + 1]; });
  e.joint_stored = reduce_sum("fdem.energy.joints", joints_, 0.0, [=] BLAST_HD(index_t j) {
    if (r.joint_broken[j]) return 0.0;
    const double h = r.joint_strength[8 * j + 7];
    const double w[3] = {h / 6.0, 4.0 * h / 6.0, h / 6.0};
    double sum = 0;
    for (int q = 0; q < 3; ++q)  // secant estimate: half traction times separation
      sum += 0.5 * w[q] * (r.joint_traction[6 * j + 2 * q] * r.joint_state[6 * j + 2 * q] +
                           r.joint_traction[6 * j + 2 * q + 1] * r.joint_state[6 * j + 2 * q + 1]);
    return sum;
  });
  e.fracture_dissipated = e.joint_work - e.joint_stored;
  e.broken_joints = static_cast<int>(reduce_sum("fdem.broken", joints_, 0.0, [=] BLAST_HD(index_t j) {
    return r.joint_broken[j] ? 1.0 : 0.0;
  }));
  e.crack_length = reduce_sum("fdem.crack_length", joints_, 0.0, [=] BLAST_HD(index_t j) {
    return r.joint_broken[j] ? r.joint_strength[8 * j + 7] : 0.0;
  });
  return e;
}

std::array<double, 2> RockSolver::support_reaction(const std::vector<int>& nodes) const {
  return support_reactions({nodes})[0];
}

std::vector<std::array<double, 2>> RockSolver::support_reactions(const std::vector<std::vector<int>>& groups) const {
  const std::vector<double> f = to_host(support_);
  std::vector<std::array<double, 2>> sums(groups.size(), {0.0, 0.0});
  for (size_t g = 0; g < groups.size(); ++g)
    for (int n : groups[g]) sums[g][0] += f[2 * n], sums[g][1] += f[2 * n + 1];
  return sums;
}

double RockSolver::contact_force_norm() {
  const double* fx = device_ptr(f_con_x_);
  const double* fy = device_ptr(f_con_y_);
  return reduce_sum("fdem.contact_norm", node_count(), 0.0,
                    [=] BLAST_HD(index_t n) { return sqrt(fx[n] * fx[n] + fy[n] * fy[n]); });
}

RockSnapshot RockSolver::snapshot() const {
  RockSnapshot s;
  s.x = to_host(x_), s.y = to_host(y_), s.vx = to_host(vx_), s.vy = to_host(vy_);
  s.x0 = to_host(x0_), s.y0 = to_host(y0_);
  s.stress = to_host(stress_);
  const std::vector<double> d = to_host(joint_damage_);
  s.joint_damage.resize(joints_);
  for (int j = 0; j < joints_; ++j) s.joint_damage[j] = std::max({d[3 * j], d[3 * j + 1], d[3 * j + 2]});
  s.joint_broken = to_host(joint_broken_);
  s.joint_nodes = joint_nodes_host_;
  return s;
}

template <class Self, class Fn>
void RockSolver::for_each_checkpoint_array(Self& r, Fn&& fn) {
  fn("rock.x", r.x_), fn("rock.y", r.y_), fn("rock.vx", r.vx_), fn("rock.vy", r.vy_), fn("rock.x0", r.x0_), fn("rock.y0", r.y0_);
  fn("rock.mass", r.mass_), fn("rock.f_tri_x", r.f_tri_x_), fn("rock.f_tri_y", r.f_tri_y_), fn("rock.f_con_x", r.f_con_x_);
  fn("rock.f_con_y", r.f_con_y_), fn("rock.f_pres_x", r.f_pres_x_), fn("rock.f_pres_y", r.f_pres_y_);
  fn("rock.constraint", r.constraint_), fn("rock.v_prescribed", r.v_prescribed_), fn("rock.work", r.work_);
  fn("rock.support", r.support_), fn("rock.inv_f0", r.inv_f0_), fn("rock.area0", r.area0_), fn("rock.eta", r.eta_);
  fn("rock.stress", r.stress_), fn("rock.dissipation", r.dissipation_), fn("rock.slot_force", r.slot_force_);
  fn("rock.slot_neighbour", r.slot_neighbour_), fn("rock.slot_joint", r.slot_joint_), fn("rock.edge_exposed", r.edge_exposed_);
  fn("rock.edge_pressure", r.edge_pressure_), fn("rock.joint_nodes", r.joint_nodes_), fn("rock.joint_strength", r.joint_strength_);
  fn("rock.joint_damage", r.joint_damage_), fn("rock.joint_state", r.joint_state_), fn("rock.joint_traction", r.joint_traction_);
  fn("rock.joint_broken", r.joint_broken_), fn("rock.cell_key", r.cell_key_), fn("rock.sorted_triangles", r.sorted_triangles_);
  fn("rock.cell_start", r.cell_start_), fn("rock.cell_end", r.cell_end_), fn("rock.neighbour_offset", r.neighbour_offset_);
  fn("rock.neighbour_list", r.neighbour_list_);
}

void RockSolver::write_checkpoint(CheckpointWriter& w) const {
  w.value("rock.counts", std::array<int, 2>{triangles_, joints_});
  for_each_checkpoint_array(*this, [&](const std::string& name, const auto& v) { w.array(name, v); });
  w.value("rock.scalars", std::array<double, 9>{time_, pressure_scale_, dt_prev_, cell_size_, grid_x0_, grid_y0_, buffer_,
                                                travel_since_build_, stable_dt_});
  w.value("rock.integers", std::array<long, 4>{steps_, rebuilds_, grid_nx_, grid_ny_});
}

void RockSolver::read_checkpoint(CheckpointReader& r) {
  const std::array<int, 2> counts = r.value<std::array<int, 2>>("rock.counts");
  if (counts[0] != triangles_ || counts[1] != joints_)
    throw InputError("checkpoint " + r.path() + ": its rock has " + std::to_string(counts[0]) + " triangles and " +
                     std::to_string(counts[1]) + " joints, this case's mesh " + std::to_string(triangles_) + " and " +
                     std::to_string(joints_));
  for_each_checkpoint_array(*this, [&](const std::string& name, auto& v) { r.array(name, v); });
  const std::array<double, 9> d = r.value<std::array<double, 9>>("rock.scalars");
  time_ = d[0], pressure_scale_ = d[1], dt_prev_ = d[2], cell_size_ = d[3], grid_x0_ = d[4], grid_y0_ = d[5];
  buffer_ = d[6], travel_since_build_ = d[7], stable_dt_ = d[8];
  const std::array<long, 4> n = r.value<std::array<long, 4>>("rock.integers");
  steps_ = n[0], rebuilds_ = n[1], grid_nx_ = static_cast<int>(n[2]), grid_ny_ = static_cast<int>(n[3]);
  if (options_.contact) build_contact_pairs();
}

}  // namespace blastsim::fdem
