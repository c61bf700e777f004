//! \file in_situ_setup.cpp
//! \brief The rock's state before its first step under an in-situ stress (rock_model.hpp): the prestretch, the
//! joints' preload and the held loads (set_in_situ_stress()), and the viscous dynamic relaxation (equilibrate()).
#include "blastsim/core/device_groups.hpp"
#include "blastsim/core/error.hpp"
#include "blastsim/fdem/rock_model.hpp"
#include "blastsim/fdem/rock_step_kernels.hpp"
#include "rock_storage.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace blastsim::fdem {

void set_in_situ_stress(RockSolver& rock, const InSituStress& s, const std::vector<int>& held) {
  if (rock.steps_ > 0) throw std::logic_error("set_in_situ_stress: only before the first step");
  detail::RockArrays& a = *rock.a_;
  const std::vector<double> x0 = to_host(a.node_params.x0), y0 = to_host(a.node_params.y0);
  auto at = [&](int n) { return Vec2{x0[n], y0[n]}; };
  const double lambda = rock.material_.lame_lambda(), mu = rock.material_.shear_modulus();
  // Triangles: F = FX inv_f0 must be the prestretch F_s in the mesh's shape FX = F0, so inv_f0 = F0^-1 F_s.
  std::vector<Mat2> inv_f0(rock.triangles_);
  for (int t = 0; t < rock.triangles_; ++t) {
    const Vec2 p0 = at(3 * t), p1 = at(3 * t + 1), p2 = at(3 * t + 2);
    inv_f0[t] = edge_matrix(p0, p1, p2).inverse() * prestretch(s.at((p0.y + p1.y + p2.y) / 3.0), lambda, mu);
  }
  // Joints: the traction sigma n on face A (n out of A, t along a0 -> a1) is what the joint must put on it.
  const std::vector<JointStrength> strength = to_host(a.joint_params.strength);
  const std::vector<std::uint8_t> broken = to_host(a.joints.broken);
  std::vector<JointPreload> preload(rock.joints_, JointPreload{0.0, 0.0});
  for (int j = 0; j < rock.joints_; ++j) {
    if (broken[j]) continue;  // a pre-cut crack or open joint carries it through contact once it closes
    const Vec2 pa0 = at(rock.joint_nodes_host_[j].a0), pa1 = at(rock.joint_nodes_host_[j].a1);
    const double h = std::hypot(pa1.x - pa0.x, pa1.y - pa0.y);
    const Vec2 t{(pa1.x - pa0.x) / h, (pa1.y - pa0.y) / h}, n{t.y, -t.x};
    const Mat2 sig = s.at(0.5 * (pa0.y + pa1.y));
    const Vec2 sn{sig.a * n.x + sig.b * n.y, sig.c * n.x + sig.d * n.y};
    try {
      preload[j] = joint_preload(sn.x * n.x + sn.y * n.y, sn.x * t.x + sn.y * t.y, strength[j]);
    } catch (const InputError& e) {
      std::ostringstream os;
      os << "joint " << j << " at (" << 0.5 * (pa0.x + pa1.x) << ", " << 0.5 * (pa0.y + pa1.y) << ") m: " << e.what();
      throw InputError(os.str());
    }
  }
  // Held boundary edges: traction sigma N (N the outward normal scaled by the edge's length), half per node.
  std::vector<char> is_boundary(3 * static_cast<size_t>(rock.triangles_), 0), done(is_boundary.size(), 0);
  for (const BoundaryEdge& b : rock.boundary_edges_) is_boundary[b.n0] = 1;
  std::vector<std::uint8_t> c = to_host(a.node_loads.constraint);
  std::vector<Vec2> load(rock.node_count(), Vec2{0.0, 0.0});
  // Half of an edge's traction resultant sigma(midpoint) N, which each of its two nodes takes.
  auto half_traction = [&](int slot) {
    const int n0 = slot_first_node(slot), n1 = slot_second_node(slot);
    const Vec2 N = edge_outward_normal(at(n0), at(n1));
    const Mat2 sig = s.at(0.5 * (y0[n0] + y0[n1]));
    return Vec2{0.5 * (sig.a * N.x + sig.b * N.y), 0.5 * (sig.c * N.x + sig.d * N.y)};
  };
  for (int slot : held) {
    if (slot < 0 || slot >= 3 * rock.triangles_ || !is_boundary[slot])
      throw InputError("in-situ stress: edge slot " + std::to_string(slot) + " is not an edge of the mesh boundary");
    if (done[slot]) continue;
    done[slot] = 1;
    const Vec2 half = half_traction(slot);
    for (int n : {slot_first_node(slot), slot_second_node(slot)}) {
      load[n] = {load[n].x + half.x, load[n].y + half.y};
      c[n] |= kHeldLoad;
    }
  }
  if (s.gradient[0] != 0 || s.gradient[1] != 0 || s.gradient[2] != 0)
    carry_cut_weight(s, rock.boundary_edges_, rock.node_vertex_, x0, y0, done, load);
  copy_from_host(a.triangle_params.inv_f0, inv_f0);
  copy_from_host(a.joint_params.preload, preload);
  copy_from_host(a.node_params.held, load);
  copy_from_host(a.node_loads.constraint, c);
  rock.in_situ_set_ = true;
  // The joints' state at rest (their tractions now carry the stress) and the elastic energy they hold.
  rock.joint_forces();
  rock.joint_stored_initial_ = rock.energies().joint_stored;
}

EquilibriumReport equilibrate(RockSolver& rock, const EquilibriumOptions& o) {
  if (rock.steps_ > 0) throw std::logic_error("equilibrate: only before the first step");
  if (!(o.tolerance > 0) || o.max_steps < 1)
    throw InputError("equilibration: the tolerance must be > 0 and max_steps >= 1");
  detail::RockArrays& a = *rock.a_;
  const double dt = rock.stable_dt_;
  // Size of the model (its bounding box's diagonal), its slowest mode about a quarter shear wave over it.
  const std::vector<double> x0 = to_host(a.node_params.x0), y0 = to_host(a.node_params.y0);
  const auto [xlo, xhi] = std::minmax_element(x0.begin(), x0.end());
  const auto [ylo, yhi] = std::minmax_element(y0.begin(), y0.end());
  const double size = x0.empty() ? 1.0 : std::hypot(*xhi - *xlo, *yhi - *ylo);
  const double omega = M_PI * rock.material_.s_wave_speed() / (2 * size);
  // Mass-proportional damping 2 omega: every mode's amplitude decays as exp(-omega t) (critical for the slowest).
  const double keep = std::exp(-2 * omega * dt);
  // The undamped check lasts two P-wave crossings.
  const long window = std::max(10L, static_cast<long>(std::ceil(2.0 * size / (rock.material_.p_wave_speed() * dt))));
  auto elastic = [&] {
    const RockEnergies e = rock.energies();
    return e.strain + e.joint_stored;
  };
  auto scale_velocities = [&](double f) {
    for_each_index("fdem.equilibrate.damp", rock.node_count(),
                   ScaleVelocitiesKernel{a.nodes.view(), f});
    rock.reset_contact_budgets();  // the velocities no longer tell how far the last update moved the nodes
  };
  // The relaxation finds the state before t = 0: the in-situ stress, gravity and the held boundaries only. The
  // run's own loads start at t = 0: the edge pressures (from the ramp's start), the platens' motion and the
  // initial velocities, so pressures are off, platens held still and every node starts at rest meanwhile.
  const double run_pressure_scale = rock.pressure_scale_;
  const std::vector<Vec2> run_prescribed = to_host(a.node_loads.v_prescribed);
  const std::vector<double> run_vx = to_host(a.nodes.vx), run_vy = to_host(a.nodes.vy);
  rock.pressure_scale_ = 0;
  fill_device("fdem.equilibrate.platens", a.node_loads.v_prescribed, Vec2{0.0, 0.0});
  EquilibriumReport r;
  scale_velocities(0.0);
  double reference = std::max(elastic(), 1e-300), window_peak = 0;
  long checking = 0;  // steps into the undamped check (0: damping)
  long quiet = 0;     // damped steps in a row below the tolerance (a check starts after half a window of them)
  while (r.steps < o.max_steps) {
    rock.step(dt);
    ++r.steps;
    const double ratio = rock.kinetic_energy() / reference;
    if (o.progress && o.progress_interval > 0 && r.steps % o.progress_interval == 0) o.progress(r.steps, ratio);
    if (checking > 0) {  // undamped: the rock must stay at rest for the whole window
      window_peak = std::max(window_peak, ratio);
      if (!(ratio <= o.tolerance)) {
        checking = 0;  // not at rest yet: back to damping
        continue;
      }
      if (++checking > window) {
        r.converged = true;
        break;
      }
      continue;
    }
    scale_velocities(keep);
    if (r.steps % 64 == 0) reference = std::max(reference, elastic());
    quiet = ratio <= o.tolerance ? quiet + 1 : 0;
    if (2 * quiet >= window) checking = 1, quiet = 0, window_peak = ratio, ++r.checks;
  }
  r.kinetic_ratio = window_peak;
  // The state reached starts the run: clock and ledgers at zero, the run's loads back, every node with the
  // velocity the run gave it before the relaxation (at rest unless rock.initial_velocity or a platen moves it).
  rock.pressure_scale_ = run_pressure_scale;
  copy_from_host(a.node_loads.v_prescribed, run_prescribed);
  copy_from_host(a.nodes.vx, run_vx);
  copy_from_host(a.nodes.vy, run_vy);
  rock.reset_contact_budgets();
  rock.time_ = 0, rock.dt_prev_ = 0, rock.steps_ = 0, rock.last_speed_ = 0;
  a.ledger.work.assign(rock.node_count(), NodeWork{0, 0, 0, 0, 0, 0});
  a.ledger.support.assign(rock.node_count(), Vec2{0.0, 0.0});
  a.triangles.dissipation.assign(rock.triangles_, TriangleDissipation{0, 0});
  rock.probes_->clear_peaks();
  const RockEnergies e = rock.energies();
  rock.joint_stored_initial_ = e.joint_stored;
  r.elastic_energy = e.strain + e.joint_stored;
  r.broken_joints = e.broken_joints;
  return r;
}

}  // namespace blastsim::fdem
