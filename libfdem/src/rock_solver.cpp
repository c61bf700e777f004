//! \file rock_solver.cpp
//! \brief RockSolver: set-up from the FDEM topology, the explicit step, contact broad phase, energies, snapshots.
#include "blastsim/fdem/rock_solver.hpp"

#include "blastsim/core/checkpoint.hpp"
#include "blastsim/core/csr.hpp"
#include "blastsim/core/device_groups.hpp"
#include "blastsim/core/error.hpp"
#include "blastsim/fdem/rock_step_kernels.hpp"
#include "rock_storage.hpp"


#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>

namespace blastsim::fdem {


namespace {

double length(const std::array<double, 2>& a, const std::array<double, 2>& b) {
  return std::hypot(b[0] - a[0], b[1] - a[1]);
}

}  // namespace

RockSolver::RockSolver(const FdemTopology& topo, const RockMaterial& material, const RockOptions& options,
                       const std::vector<JointProperties>& joint_properties)
    : material_(material), options_(options), a_(std::make_unique<detail::RockArrays>()) {
  material_.validate();
  options_.validate();
  triangles_ = topo.triangle_count();
  joints_ = static_cast<int>(topo.joints.size());
  boundary_edges_ = topo.boundary_edges;
  node_vertex_ = topo.node_vertex;
  const int nodes = 3 * triangles_;
  const double E = material_.youngs_modulus, rho = material_.density;
  const double cp = material_.p_wave_speed();
  const double p_joint_stiff = options_.joint_penalty_factor * E;
  const double p_contact_stiff = options_.contact ? options_.contact_penalty_factor * E : 0.0;

  std::vector<double> x(nodes), y(nodes), mass(nodes), area0(triangles_), eta(triangles_);
  std::vector<Mat2> inv_f0(triangles_);
  double omega_max = 0;
  for (int t = 0; t < triangles_; ++t) {
    const auto& p0 = topo.node_positions[3 * t];
    const auto& p1 = topo.node_positions[3 * t + 1];
    const auto& p2 = topo.node_positions[3 * t + 2];
    const Mat2 F0 = edge_matrix({p0[0], p0[1]}, {p1[0], p1[1]}, {p2[0], p2[1]});
    inv_f0[t] = F0.inverse();
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

  detail::RockArrays& a = *a_;
  copy_from_host(a.node_params.x0, x), copy_from_host(a.node_params.y0, y), copy_from_host(a.node_params.mass, mass);
  std::vector<int> vertex = topo.node_vertex;  // without mesh vertices (a hand-made topology) no two nodes share one
  if (vertex.size() != static_cast<size_t>(nodes)) {
    vertex.resize(nodes);
    for (int n = 0; n < nodes; ++n) vertex[n] = n;
  }
  copy_from_host(a.node_params.vertex, vertex);
  copy_from_host(a.triangle_params.inv_f0, inv_f0), copy_from_host(a.triangle_params.area0, area0);
  copy_from_host(a.triangle_params.eta, eta);
  a.node_loads.constraint.assign(nodes, 0), a.node_loads.v_prescribed.assign(nodes, Vec2{0.0, 0.0});
  a.node_loads.dashpot.assign(nodes, Mat2{0.0, 0.0, 0.0, 0.0});
  a.node_params.held.assign(nodes, Vec2{0.0, 0.0});
  copy_from_host(a.nodes.x, x), copy_from_host(a.nodes.y, y);
  a.nodes.vx.assign(nodes, 0.0), a.nodes.vy.assign(nodes, 0.0);
  for (DeviceVector<double>* f : {&a.forces.triangle_x, &a.forces.triangle_y, &a.forces.contact_x, &a.forces.contact_y,
                                  &a.forces.pressure_x, &a.forces.pressure_y})
    f->assign(nodes, 0.0);
  a.ledger.work.assign(nodes, NodeWork{0, 0, 0, 0, 0, 0}), a.ledger.support.assign(nodes, Vec2{0.0, 0.0});
  a.triangles.stress.assign(triangles_, TriangleStress{0, 0, 0});
  a.triangles.dissipation.assign(triangles_, TriangleDissipation{0, 0});

  std::vector<int> slot_neighbour(3 * triangles_, -1), slot_joint(3 * triangles_, -1);
  std::vector<std::uint8_t> exposed(3 * triangles_, 0);
  for (const BoundaryEdge& b : boundary_edges_) exposed[b.n0] = kEdgeBoundary;
  if (!joint_properties.empty() && joint_properties.size() != static_cast<std::size_t>(joints_))
    throw InputError("RockSolver: " + std::to_string(joint_properties.size()) + " joint properties for " +
                     std::to_string(joints_) + " joints");
  const JointProperties uniform = joint_properties_of(material_);
  std::vector<JointStrength> strength(joints_);
  std::vector<double> joint_length(joints_);
  const double p_joint = options_.joint_penalty_factor * E;
  for (int j = 0; j < joints_; ++j) {
    const Joint& J = topo.joints[j];
    slot_neighbour[J.a0] = J.triangle_b, slot_joint[J.a0] = j;
    slot_neighbour[J.b0] = J.triangle_a, slot_joint[J.b0] = j;
    joint_nodes_host_.push_back({J.a0, J.a1, J.b0, J.b1});
    const double h = length(topo.node_positions[J.a0], topo.node_positions[J.a1]);
    strength[j] = joint_properties.empty() ? joint_strength(uniform, h, p_joint)
                                           : joint_strength(joint_properties[j], h, p_joint, j);
    joint_length[j] = h;
  }
  copy_from_host(a.edge_params.neighbour, slot_neighbour), copy_from_host(a.edge_params.joint, slot_joint);
  a.edges.joint_force.assign(3 * triangles_, SlotForce{{0.0, 0.0}, {0.0, 0.0}});
  copy_from_host(a.edges.exposed, exposed);
  a.edge_loads.pressure.assign(3 * triangles_, 0.0);
  a.edge_loads.node_load.assign(3 * triangles_, Vec2{0.0, 0.0});
  copy_from_host(a.joint_params.nodes, joint_nodes_host_), copy_from_host(a.joint_params.strength, strength);
  copy_from_host(a.joint_params.length, joint_length);
  a.joint_params.preload.assign(joints_, JointPreload{0.0, 0.0});
  a.joints.damage.assign(joints_, JointPointDamage{{0, 0, 0}});
  a.joints.plastic.assign(joints_, JointPointPlastic{{0, 0, 0}, {0, 0, 0}});
  a.joints.separation.assign(joints_, JointPointValues{{0, 0, 0}, {0, 0, 0}});
  a.joints.traction.assign(joints_, JointPointValues{{0, 0, 0}, {0, 0, 0}});
  a.joints.broken.assign(joints_, 0);
  a.joint_work.tangent.assign(joints_, Vec2{0.0, 0.0});
  a.peaks.speed2.assign(3 * triangles_, 0.0);
  probes_ = std::make_unique<RockProbes>();
  contact_ = std::make_unique<ContactSearch>(triangles_, vertex, joint_nodes_host_, options_.contact_buffer,
                                             options_.contact);
  if (options_.contact) rebuild_contact_grid();
}

std::vector<JointStrength> RockSolver::joint_strengths() const { return to_host(a_->joint_params.strength); }

void RockSolver::set_joint_properties(const std::vector<int>& joints, const JointProperties& q) {
  if (steps_ > 0) throw std::logic_error("RockSolver::set_joint_properties: only before the first step");
  if (in_situ_set_) throw std::logic_error("RockSolver::set_joint_properties: before set_in_situ_stress()");
  std::vector<JointStrength> strength = to_host(a_->joint_params.strength);
  const std::vector<double> length = to_host(a_->joint_params.length);
  const double p_joint = options_.joint_penalty_factor * material_.youngs_modulus;
  for (int j : joints) {
    if (j < 0 || j >= joints_) throw InputError("joint " + std::to_string(j) + " does not exist");
    strength[j] = joint_strength(q, length[j], p_joint, j);
  }
  copy_from_host(a_->joint_params.strength, strength);
}


RockSolver::~RockSolver() = default;
RockSolver::RockSolver(RockSolver&&) noexcept = default;
RockSolver& RockSolver::operator=(RockSolver&&) noexcept = default;

ContactRock RockSolver::contact_rock() const {
  const detail::RockArrays& a = *a_;
  return {a.nodes.read(), a.node_params.view(), a.edge_params.view(), a.joints.read()};
}

void RockSolver::rebuild_contact_grid() { contact_->rebuild(contact_rock(), steps_); }

long RockSolver::contact_rebuilds() const { return contact_->rebuilds(); }

void RockSolver::step(double dt) {
  advance(dt, 1);
  finish_motion(reduce_max("fdem.vmax", node_count(), 0.0, peak_speed_kernel()));
}

NodeSpeedPeak RockSolver::peak_speed_kernel() const { return NodeSpeedPeak{a_->peaks.read()}; }

void RockSolver::advance(double dt, int substeps, const std::function<void(int)>& before_step) {
  if (substeps < 1) throw std::invalid_argument("RockSolver::advance: substeps must be at least 1");
  if (pending_time_ != 0) throw std::logic_error("RockSolver::advance: finish_motion() of the previous advance missing");
  if (!(dt > 0) || dt > stable_dt_) {
    std::ostringstream os;
    os << "rock time step dt = " << dt << " s: must be in (0, " << stable_dt_
       << "] s, the stable step of the explicit scheme (elastic wave and joint/contact penalty springs)";
    throw InputError(os.str());
  }
  // The travel is known up to the last read; the substeps after the first are covered by the last speed.
  const double ahead = last_speed_ * dt * (substeps - 1);
  if (contact_->rebuild_due(ahead)) rebuild_contact_grid();
  for (int k = 0; k < substeps; ++k) {
    if (before_step) before_step(k);
    triangle_forces(dt);
    joint_forces();
    contact_forces(dt);
    update_nodes(dt);
    time_ += dt;
    ++steps_;
    probes_->record(a_->nodes.read(), time_);
  }
  pending_time_ = dt * substeps;  // update_nodes() kept each node's largest speed (flagged if not finite)
}

void RockSolver::finish_motion(double v_max) {
  fill_device("fdem.speed2_peak.clear", a_->peaks.speed2, 0.0);
  const double advanced = pending_time_;
  pending_time_ = 0;
  if (!(v_max < 1e300)) {
    const std::vector<double> hx = to_host(a_->nodes.vx), hy = to_host(a_->nodes.vy);
    size_t bad = 0;
    while (bad < hx.size() && std::isfinite(hx[bad] * hx[bad] + hy[bad] * hy[bad])) ++bad;
    const std::vector<double> x0 = to_host(a_->node_params.x0), y0 = to_host(a_->node_params.y0);
    std::ostringstream where;
    if (bad < x0.size()) where << " (initially at " << x0[bad] << ", " << y0[bad] << " m)";
    const std::vector<double> x = to_host(a_->nodes.x), y = to_host(a_->nodes.y);
    for (size_t t = 0; 3 * t + 2 < x.size(); ++t) {  // a triangle turned inside out has no stress (triangle_stress)
      const size_t n = 3 * t;
      const double area2 = (x[n + 1] - x[n]) * (y[n + 2] - y[n]) - (x[n + 2] - x[n]) * (y[n + 1] - y[n]);
      if (!(area2 > 0)) {
        where << "; the first triangle inverted or without a finite area is " << t << " (signed area " << 0.5 * area2
              << " m2, initially at " << x0[n] << ", " << y0[n]
              << " m): the step is too long for the loads on it, or the rock too soft";
        break;
      }
    }
    std::ostringstream when;
    when << std::scientific << std::setprecision(6) << time_;
    throw InstabilityError("rock velocity not finite at step " + std::to_string(steps_) + " (t = " + when.str() +
                           " s), node " + std::to_string(bad) + " of triangle " + std::to_string(bad / 3) + where.str());
  }
  contact_->moved(v_max * advanced);
  last_speed_ = v_max;
}

// Munjiza 2004 ch. 2: constant-strain triangles.
void RockSolver::triangle_forces(double dt) {
  detail::RockArrays& a = *a_;
  for_each_index("fdem.triangles", triangles_,
                 TriangleForceKernel{a.nodes.read(), a.triangle_params.view(), a.edges.read(), a.edge_loads.read(), a.forces.view(),
                                     a.triangles.view(), material_.lame_lambda(), material_.shear_modulus(),
                                     pressure_scale_, dt, contact_->travel(), options_.contact, dt_prev_});
}

// Munjiza 2004 ch. 7: cohesive joints, in two passes (the geometry, then the joint law and the forces).
void RockSolver::joint_forces() {
  detail::RockArrays& a = *a_;
  if (joints_ == 0) return;
  for_each_index("fdem.joints.geometry", joints_,
                 JointGeometryKernel{a.nodes.read(), a.joint_params.view(), a.joints.view(), a.joint_work.view()});
  for_each_index("fdem.joints", joints_,
                 JointForceKernel{a.joint_params.view(), a.joints.view(), a.edges.view(), a.joint_work.read()});
}

// Munjiza 2004 ch. 2: distributed-potential contact, with Coulomb friction (ContactSearch).
void RockSolver::contact_forces(double dt) {
  detail::RockArrays& a = *a_;
  contact_->forces(contact_rock(), a.forces.view(), a.triangles.view(),
                   options_.contact_penalty_factor * material_.youngs_modulus, material_.contact_friction, dt);
}

// Symplectic Euler (docs/fdem-solver.md): gather the node's forces, integrate.
void RockSolver::update_nodes(double dt) {
  detail::RockArrays& a = *a_;
  for_each_index("fdem.nodes", node_count(),
                 NodeUpdateKernel{a.node_params.view(), a.node_loads.view(), a.forces.read(),
                                  a.edges.read(), a.nodes.view(), a.ledger.view(),
                                  options_.gravity[0], options_.gravity[1], dt, dt_prev_, a.peaks.view()});
  dt_prev_ = dt;
}

void RockSolver::prescribe_velocity(const std::vector<int>& nodes, bool along_x, bool along_y, double vx, double vy) {
  detail::RockArrays& a = *a_;
  std::vector<std::uint8_t> c = to_host(a.node_loads.constraint);
  std::vector<Vec2> vp = to_host(a.node_loads.v_prescribed);
  std::vector<double> hvx = to_host(a.nodes.vx), hvy = to_host(a.nodes.vy);
  for (int n : nodes) {
    if (n < 0 || n >= node_count()) throw InputError("prescribed node " + std::to_string(n) + " does not exist");
    if (along_x) c[n] |= kPrescribedX, vp[n].x = vx, hvx[n] = vx;
    if (along_y) c[n] |= kPrescribedY, vp[n].y = vy, hvy[n] = vy;
  }
  copy_from_host(a.node_loads.constraint, c);
  copy_from_host(a.node_loads.v_prescribed, vp);
  copy_from_host(a.nodes.vx, hvx);
  copy_from_host(a.nodes.vy, hvy);
  reset_contact_budgets();
}

void RockSolver::set_viscous_boundary(const std::vector<int>& slots) {
  std::vector<char> is_boundary(3 * static_cast<size_t>(triangles_), 0);
  for (const BoundaryEdge& b : boundary_edges_) is_boundary[b.n0] = 1;
  detail::RockArrays& a = *a_;
  std::vector<std::uint8_t> c = to_host(a.node_loads.constraint);
  std::vector<Mat2> C = to_host(a.node_loads.dashpot);
  const std::vector<double> x0 = to_host(a.node_params.x0), y0 = to_host(a.node_params.y0);
  const double rho = material_.density, cp = material_.p_wave_speed(), cs = material_.s_wave_speed();
  std::vector<char> done(is_boundary.size(), 0);
  for (int s : slots) {
    if (s < 0 || s >= 3 * triangles_ || !is_boundary[s])
      throw InputError("viscous boundary: edge slot " + std::to_string(s) + " is not an edge of the mesh boundary");
    if (done[s]) continue;  // an edge listed twice gets its dashpots once
    done[s] = 1;
    const int n0 = slot_first_node(s), n1 = slot_second_node(s);
    const Mat2 k = viscous_boundary_coefficients(rho, cp, cs, {x0[n0], y0[n0]}, {x0[n1], y0[n1]});
    for (int n : {n0, n1}) {
      C[n] = {C[n].a + k.a, C[n].b + k.b, C[n].c + k.c, C[n].d + k.d};
      c[n] |= kViscousBoundary;
    }
  }
  copy_from_host(a.node_loads.constraint, c);
  copy_from_host(a.node_loads.dashpot, C);
}

namespace {
//! Copies a host array of 2 values per node into the x and y arrays of the nodes; `what` names the caller.
void copy_node_pairs(const std::vector<double>& xy, int nodes, DeviceVector<double>& x, DeviceVector<double>& y,
                     const char* what) {
  if (xy.size() != 2 * static_cast<size_t>(nodes))
    throw InputError(std::string(what) + " needs 2 values per node (" + std::to_string(2 * nodes) + ")");
  std::vector<double> hx(nodes), hy(nodes);
  for (int n = 0; n < nodes; ++n) hx[n] = xy[2 * n], hy[n] = xy[2 * n + 1];
  copy_from_host(x, hx);
  copy_from_host(y, hy);
}
}  // namespace

void RockSolver::set_velocities(const std::vector<double>& vxy) {
  copy_node_pairs(vxy, node_count(), a_->nodes.vx, a_->nodes.vy, "set_velocities");
  reset_contact_budgets();
}

void RockSolver::reset_contact_budgets() { contact_->reset_budgets(); }

void RockSolver::set_positions(const std::vector<double>& xy) {
  copy_node_pairs(xy, node_count(), a_->nodes.x, a_->nodes.y, "set_positions");
  contact_->jumped();  // the contact broad phase is rebuilt before the next step
}

void RockSolver::set_edge_pressure(const std::vector<int>& slots, double pressure) {
  std::vector<double> p = to_host(a_->edge_loads.pressure);
  for (int s : slots) {
    if (s < 0 || s >= 3 * triangles_) throw InputError("edge slot " + std::to_string(s) + " does not exist");
    p[s] = pressure;
  }
  copy_from_host(a_->edge_loads.pressure, p);
}

std::vector<int> RockSolver::joints_on_segment(double xa, double ya, double xb, double yb, double tolerance) const {
  const std::vector<double> px = to_host(a_->node_params.x0), py = to_host(a_->node_params.y0);
  const double lx = xb - xa, ly = yb - ya, len2 = lx * lx + ly * ly;
  auto on_segment = [&](int n) {  // distance from the segment within tolerance
    const double s = len2 > 0 ? std::clamp(((px[n] - xa) * lx + (py[n] - ya) * ly) / len2, 0.0, 1.0) : 0.0;
    return std::hypot(px[n] - xa - s * lx, py[n] - ya - s * ly) <= tolerance;
  };
  std::vector<int> out;
  for (int j = 0; j < joints_; ++j) {
    const JointNodes& n = joint_nodes_host_[j];
    if (on_segment(n.a0) && on_segment(n.a1)) out.push_back(j);
  }
  return out;
}

void RockSolver::break_joints(const std::vector<int>& joints) {
  detail::RockArrays& a = *a_;
  std::vector<std::uint8_t> broken = to_host(a.joints.broken), exposed = to_host(a.edges.exposed);
  std::vector<JointPointDamage> damage = to_host(a.joints.damage);
  for (int j : joints) {
    if (j < 0 || j >= joints_) throw InputError("joint " + std::to_string(j) + " does not exist");
    broken[j] = 1;
    for (int q = 0; q < kJointPoints; ++q) damage[j].point[q] = 1.0;
    exposed[joint_nodes_host_[j].a0] = kEdgeCrackFace;  // face A's slot (its first node)
    exposed[joint_nodes_host_[j].b0] = kEdgeCrackFace;  // face B's slot
  }
  copy_from_host(a.joints.broken, broken);
  copy_from_host(a.edges.exposed, exposed);
  copy_from_host(a.joints.damage, damage);
}


void RockSolver::set_probes(const std::vector<std::array<double, 2>>& points, const std::vector<double>& until) {
  probes_->set(points, until, to_host(a_->node_params.x0), to_host(a_->node_params.y0));
}

std::vector<ProbeSample> RockSolver::probe_samples() const { return probes_->samples(a_->nodes.read()); }


RockView RockSolver::view() {
  return {std::as_const(*this).view(), a_->edge_loads.view()};
}

RockReadView RockSolver::view() const {
  const detail::RockArrays& a = *a_;
  return {a.nodes.read(), a.edge_params.view(), a.edges.read(), a.joint_params.view(), a.joints.read(),
          a.triangles.read(), triangles_, joints_};
}

std::vector<double> RockSolver::edge_pressures() const { return to_host(a_->edge_loads.pressure); }
std::vector<std::uint8_t> RockSolver::edge_exposure() const { return to_host(a_->edges.exposed); }
std::vector<Vec2> RockSolver::node_loads() const { return to_host(a_->edge_loads.node_load); }

double RockSolver::kinetic_energy() const {
  return reduce_sum("fdem.energy.kinetic", node_count(), 0.0, NodeKineticEnergy{a_->nodes.read(), a_->node_params.view()});
}

RockEnergies RockSolver::energies() const {
  const detail::RockArrays& a = *a_;
  const JointParams jp = a.joint_params.view();
  const JointState<Access::read> js = a.joints.read();
  RockEnergies e;
  e.kinetic = kinetic_energy();
  // the strain at the middle of the last step (x - v dt / 2), where the work ledger and the kinetic energy of
  // the half-step velocities stand (docs/fdem-solver.md, "Triangle internal force")
  e.strain = reduce_sum("fdem.energy.strain", triangles_, 0.0,
                        TriangleStrainEnergy{a.nodes.read(), a.triangle_params.view(), 0.5 * dt_prev_,
                                             material_.lame_lambda(), material_.shear_modulus()});
  auto work_sum = [&](double NodeWork::*kind) {
    return reduce_sum("fdem.energy.work", node_count(), 0.0, NodeWorkOf{a.ledger.read(), kind});
  };
  e.pressure_work = work_sum(&NodeWork::pressure);
  e.boundary_work = work_sum(&NodeWork::boundary);
  e.external_work = e.pressure_work + work_sum(&NodeWork::support) + work_sum(&NodeWork::gravity) + e.boundary_work;
  e.joint_work = work_sum(&NodeWork::joint);
  e.contact_work = work_sum(&NodeWork::contact);
  e.damping_dissipated = reduce_sum("fdem.energy.damping", triangles_, 0.0,
                                    TriangleDissipationOf{a.triangles.read(), &TriangleDissipation::damping});
  e.friction_dissipated = reduce_sum("fdem.energy.friction", triangles_, 0.0,
                                     TriangleDissipationOf{a.triangles.read(), &TriangleDissipation::friction});
  e.joint_stored = reduce_sum("fdem.energy.joints", joints_, 0.0, JointStoredEnergy{jp, js});
  e.fracture_dissipated = e.joint_work - (e.joint_stored - joint_stored_initial_);
  e.broken_joints = static_cast<int>(reduce_sum("fdem.broken", joints_, 0.0, BrokenJointLength{jp, js, false}));
  e.crack_length = reduce_sum("fdem.crack_length", joints_, 0.0, BrokenJointLength{jp, js, true});
  return e;
}

std::vector<std::array<double, 2>> RockSolver::support_reactions(const std::vector<std::vector<int>>& groups) const {
  const std::vector<Vec2> f = to_host(a_->ledger.support);
  std::vector<std::array<double, 2>> sums(groups.size(), {0.0, 0.0});
  for (size_t g = 0; g < groups.size(); ++g)
    for (int n : groups[g]) sums[g][0] += f[n].x, sums[g][1] += f[n].y;
  return sums;
}

double RockSolver::contact_force_norm() const {
  return reduce_sum("fdem.contact_norm", node_count(), 0.0, NodeContactForce{a_->forces.read()});
}

RockSnapshot RockSolver::snapshot() const {
  const detail::RockArrays& a = *a_;
  RockSnapshot s;
  s.x = to_host(a.nodes.x), s.y = to_host(a.nodes.y), s.vx = to_host(a.nodes.vx), s.vy = to_host(a.nodes.vy);
  s.x0 = to_host(a.node_params.x0), s.y0 = to_host(a.node_params.y0);
  const std::vector<TriangleStress> stress = to_host(a.triangles.stress);
  s.stress.resize(3 * stress.size());
  for (size_t t = 0; t < stress.size(); ++t)
    s.stress[3 * t] = stress[t].xx, s.stress[3 * t + 1] = stress[t].xy, s.stress[3 * t + 2] = stress[t].yy;
  const std::vector<JointPointDamage> d = to_host(a.joints.damage);
  s.joint_damage.resize(joints_);
  for (int j = 0; j < joints_; ++j) s.joint_damage[j] = std::max({d[j].point[0], d[j].point[1], d[j].point[2]});
  s.joint_broken = to_host(a.joints.broken);
  s.joint_nodes.resize(joints_);
  for (int j = 0; j < joints_; ++j) {
    const JointNodes& n = joint_nodes_host_[j];
    s.joint_nodes[j] = {n.a0, n.a1, n.b0, n.b1};
  }
  return s;
}

void RockSolver::write_checkpoint(CheckpointWriter& w) const {
  w.value("rock.counts", std::array<int, 2>{triangles_, joints_});
  detail::RockArrays::for_each_checkpoint_array(*a_, [&](const std::string& name, const auto& v, bool) { write_array(w, name, v); });
  w.value("rock.time", time_);
  w.value("rock.pressure_scale", pressure_scale_);
  w.value("rock.previous_dt", dt_prev_);
  w.value("rock.stable_dt", stable_dt_);
  w.value("rock.last_speed", last_speed_);
  if (joint_stored_initial_ != 0) w.value("rock.joint_stored_initial", joint_stored_initial_);
  w.value("rock.steps", steps_);
  contact_->write_checkpoint(w);
  probes_->write_checkpoint(w);
}

void RockSolver::read_checkpoint(CheckpointReader& r) {
  const std::array<int, 2> counts = r.value<std::array<int, 2>>("rock.counts");
  if (counts[0] != triangles_ || counts[1] != joints_)
    throw InputError("checkpoint " + r.path() + ": its rock has " + std::to_string(counts[0]) + " triangles and " +
                     std::to_string(counts[1]) + " joints, this case's mesh " + std::to_string(triangles_) + " and " +
                     std::to_string(joints_));
  detail::RockArrays::for_each_checkpoint_array(*a_, [&](const std::string& name, auto& v, bool fixed) {
    // Checkpoints of builds before the plastic shear slip lack it: their joints go on with zero plastic slip, so
    // all their slip counts as elastic (capped at the shear strength) and their damage as it was.
    if (name == "rock.joints.plastic" && !r.has(name)) return;
    read_array(r, name, v, fixed ? v.size() : 0);
  });
  time_ = r.non_negative("rock.time");
  pressure_scale_ = r.non_negative("rock.pressure_scale");
  dt_prev_ = r.non_negative("rock.previous_dt");
  if (r.non_negative("rock.stable_dt") != stable_dt_) r.fail("rock.stable_dt", "differs from this mesh's (another mesh?)");
  last_speed_ = r.non_negative("rock.last_speed");
  joint_stored_initial_ = r.has("rock.joint_stored_initial") ? r.non_negative("rock.joint_stored_initial") : 0.0;
  steps_ = r.value<long>("rock.steps");
  if (steps_ < 0 || steps_ > kMaxCheckpointSteps) r.fail("rock.steps", "negative or above 1e15");
  probes_->read_checkpoint(r);  // set_probes() came first, as when it was written
  // Every index and flag against what it addresses, before any kernel reads it.
  const detail::RockArrays& a = *a_;
  r.check_range("rock.node_loads.constraint", to_host(a.node_loads.constraint), 0,
              kPrescribedX | kPrescribedY | kViscousBoundary | kHeldLoad);
  r.check_range("rock.edges.exposed", to_host(a.edges.exposed), 0, 2);
  r.check_range("rock.joints.broken", to_host(a.joints.broken), 0, 1);
  std::vector<double> damage;
  for (const JointPointDamage& jd : to_host(a.joints.damage)) damage.insert(damage.end(), jd.point, jd.point + kJointPoints);
  r.check_range("rock.joints.damage", damage, 0, 1);
  std::vector<double> slip, path;
  for (const JointPointPlastic& jp : to_host(a.joints.plastic)) {
    slip.insert(slip.end(), jp.slip, jp.slip + kJointPoints);
    path.insert(path.end(), jp.path, jp.path + kJointPoints);
  }
  const double huge = std::numeric_limits<double>::max();
  r.check_range("rock.joints.plastic", slip, -huge, huge);
  r.check_range("rock.joints.plastic", path, 0, huge);
  contact_->read_checkpoint(r, contact_rock(), steps_);
}

}  // namespace blastsim::fdem
