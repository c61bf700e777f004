//! \file test_rock_gmsh.cpp
//! \brief FDEM validation on Gmsh meshes: F2 (Lame cylinder), F6 (Brazilian disc), F8 (uniaxial compression).
#include "blastsim/fdem/fragments.hpp"
#include "blastsim/fdem/gmsh_mesh.hpp"
#include "blastsim/fdem/rock_model.hpp"
#include "blastsim/fdem/rock_solver.hpp"
#include "catch.hpp"
#include "rock_cases.hpp"

#include <cmath>
#include <cstdio>
#include <map>

using namespace blastsim::fdem;
using namespace blastsim::fdem::testing;

namespace {
//! Smooth load ramp 0 -> 1 over [0, T] (half cosine): quasi-static loading with little dynamic overshoot.
//! Options of the slow-loading strength tests: light damping, no contact (the peak precedes separation).
RockOptions strength_test_options() {
  RockOptions o;
  o.damping_ratio = 0.1;
  o.contact = false;
  return o;
}

double ramp(double t, double T) { return t >= T ? 1.0 : 0.5 * (1.0 - std::cos(M_PI * t / T)); }

//! Centroid and polar stresses (sigma_r, sigma_theta) of triangle t from a snapshot (current positions).
void polar_stress(const RockSnapshot& s, int t, double& r, double& sr, double& st) {
  const double cx = (s.x[3 * t] + s.x[3 * t + 1] + s.x[3 * t + 2]) / 3;
  const double cy = (s.y[3 * t] + s.y[3 * t + 1] + s.y[3 * t + 2]) / 3;
  r = std::hypot(cx, cy);
  const double c = cx / r, sn = cy / r;
  const double sxx = s.stress[3 * t], sxy = s.stress[3 * t + 1], syy = s.stress[3 * t + 2];
  sr = sxx * c * c + syy * sn * sn + 2 * sxy * sn * c;
  st = sxx * sn * sn + syy * c * c - 2 * sxy * sn * c;
}
}  // namespace

TEST_CASE("F2: Lame thick cylinder under inner pressure, quasi-static", "[long][fdem][F2][gmsh]") {
  const double a = 0.02, b = 0.1, h = 0.004, p = 2.0e6;  // below the tensile strength: no cracking
  const NamedMesh m = gmsh_disc_with_hole(0, 0, b, a, h);
  const FdemTopology topo = build_topology(m.mesh);
  RockOptions opt;
  opt.contact = false;
  opt.damping_ratio = 0.3;
  RockSolver s(topo, RockMaterial::paper_table2(), opt);
  s.set_edge_pressure(boundary_slots(topo, m.boundary_groups.at("hole"), "hole"), p);
  const double c = s.material().p_wave_speed();
  const double T = 20 * b / c;  // ramp over 20 transit times of the wall
  const double dt = 0.9 * s.stable_dt();
  run_to(s, T, dt, [&] { s.set_pressure_scale(ramp(s.time(), T)); });
  run_to(s, 1.5 * T, dt);
  const RockSnapshot snap = s.snapshot();
  // Radial bins between the two boundary rows of elements; each bin's mean over all angles.
  const int bins = 8;
  const double r0 = a + 2 * h, r1 = b - 2 * h;
  std::vector<double> sum_r(bins, 0), sum_t(bins, 0), sum_rad(bins, 0), sum_sq_t(bins, 0), count(bins, 0);
  for (int t = 0; t < s.triangle_count(); ++t) {
    double r, sr, st;
    polar_stress(snap, t, r, sr, st);
    if (r < r0 || r >= r1) continue;
    const int k = static_cast<int>((r - r0) / (r1 - r0) * bins);
    sum_r[k] += sr, sum_t[k] += st, sum_rad[k] += r, sum_sq_t[k] += st * st, count[k] += 1;
  }
  double worst = 0;
  for (int k = 0; k < bins; ++k) {
    const double r = sum_rad[k] / count[k];
    const double k2 = p * a * a / (b * b - a * a);
    const double exact_r = k2 * (1 - b * b / (r * r)), exact_t = k2 * (1 + b * b / (r * r));
    const double mr = sum_r[k] / count[k], mt = sum_t[k] / count[k];
    const double scatter = std::sqrt(std::fmax(0.0, sum_sq_t[k] / count[k] - mt * mt));
    std::printf("F2 r = %.4f m: sigma_r %.4f vs %.4f MPa, sigma_theta %.4f vs %.4f MPa (angular scatter %.3f MPa, "
                "%d triangles)\n",
                r, mr / 1e6, exact_r / 1e6, mt / 1e6, exact_t / 1e6, scatter / 1e6, static_cast<int>(count[k]));
    worst = std::fmax(worst, std::fmax(std::fabs(mr - exact_r), std::fabs(mt - exact_t)) / p);
  }
  std::printf("F2: largest bin-mean error %.2f %% of p\n", 100 * worst);
  CHECK(worst < 0.03);
  CHECK(s.energies().broken_joints == 0);
}

// F6 and F8 report their figures (docs/validation.md: looser, mesh-dependent bounds). In this model a crack runs
// along element edges. F6 is run twice: on a disc whose mesh has a row of joints along the loaded diameter
// (the crack path the analytic solution assumes; asserted against the 15 % bound) and on a free mesh
// (reported: near the centre every joint is inclined, and the compression across the diameter, three times
// the tension, adds to its normal stress; a joint 15 degrees off needs 1.37 times the load). F8 is reported
// with bounds on what the model does (docs/fdem-solver.md). Contact is off: the peak precedes separation.

namespace {
struct BrazilianResult {
  double strength;          //!< 2 F / (pi D t) at the peak load [Pa]
  double t_peak;            //!< [s]
  int broken;
  double near_axis_fraction;  //!< of the crack length within 0.2 R of the loaded diameter
};

//! Brazilian test on a disc of radius R: two loading arcs (boundary nodes within 0.12 R of the poles,
//! x free) move towards the centre at v each, slowly enough (25 mm/s: the peak comes after some 75 wave
//! transits) that the peak is quasi-static to a few per cent.
BrazilianResult brazilian(double R, double h, bool joints_along_diameter) {
  const double v = 0.025;
  std::vector<Segment> chord;
  if (joints_along_diameter) chord.push_back({{0.0, -R}, {0.0, R}});
  const NamedMesh m = gmsh_disc(0, 0, R, h, chord);
  const FdemTopology topo = build_topology(m.mesh);
  RockSolver s(topo, RockMaterial::paper_table2(), strength_test_options());
  auto on_arc = [&](double x, double y, double sign) {
    return sign * y > 0.9 * R && std::fabs(x) < 0.12 * R && std::hypot(x, y) > R - 1e-9;
  };
  const auto top = nodes_where(topo, [&](double x, double y) { return on_arc(x, y, 1.0); });
  const auto bottom = nodes_where(topo, [&](double x, double y) { return on_arc(x, y, -1.0); });
  REQUIRE(top.size() >= 2);
  s.prescribe_velocity(top, false, true, 0, -v);
  s.prescribe_velocity(bottom, false, true, 0, v);
  s.prescribe_velocity({top[0]}, true, false, 0, 0);  // no rigid drift along x
  double peak = 0, t_peak = 0;
  run_to(s, 2.2e-3, 0.9 * s.stable_dt(), [&] {
    const double f = 0.5 * (s.support_reactions({bottom})[0][1] - s.support_reactions({top})[0][1]);  // compressive load [N/m]
    if (f > peak) peak = f, t_peak = s.time();
  });
  const RockSnapshot snap = s.snapshot();
  double near_axis = 0, total = 0;
  for (size_t j = 0; j < snap.joint_broken.size(); ++j) {
    if (!snap.joint_broken[j]) continue;
    const auto& n = snap.joint_nodes[j];
    const double mx = 0.5 * (snap.x0[n[0]] + snap.x0[n[1]]);
    const double len = std::hypot(snap.x0[n[1]] - snap.x0[n[0]], snap.y0[n[1]] - snap.y0[n[0]]);
    total += len;
    if (std::fabs(mx) < 0.2 * R) near_axis += len;
  }
  return {2 * peak / (M_PI * 2 * R), t_peak, s.energies().broken_joints, total > 0 ? near_axis / total : 0.0};
}
}  // namespace

TEST_CASE("F6: Brazilian disc: tensile strength from the peak load, crack along the loaded diameter",
          "[long][fdem][F6][gmsh]") {
  const double ft = RockMaterial::paper_table2().tensile_strength;
  const BrazilianResult aligned = brazilian(0.05, 0.004, true);
  const BrazilianResult free_mesh = brazilian(0.05, 0.004, false);
  for (const auto& [name, r] : {std::pair<const char*, BrazilianResult>{"joints along the diameter", aligned},
                                {"free mesh", free_mesh}})
    std::printf("F6 (%s): peak at %.3f ms, 2F/(pi D) = %.3f MPa vs f_t %.2f MPa (%+.1f %%); %d joints broken, "
                "%.0f %% of the crack length within 0.2 R of the loaded diameter\n",
                name, 1e3 * r.t_peak, r.strength / 1e6, ft / 1e6, 100 * (r.strength / ft - 1), r.broken,
                100 * r.near_axis_fraction);
  CHECK(std::fabs(aligned.strength / ft - 1) < 0.15);
  CHECK(aligned.near_axis_fraction > 0.5);
  // Free mesh (reported): fails, in the right place, above f_t and within 1.6 f_t.
  CHECK(free_mesh.strength > ft);
  CHECK(free_mesh.strength < 1.6 * ft);
  CHECK(free_mesh.near_axis_fraction > 0.5);
}

namespace {
struct UniaxialResult {
  double strength;      //!< peak axial stress F / W [Pa]
  double t_peak;        //!< [s]
  int broken;           //!< joints broken at the end
  double plane_broken;  //!< fraction of the joints on the embedded plane broken at the end (no plane: 0)
};

//! Uniaxial compression of a W x H specimen (elements of size h) between frictionless platens, the top one
//! moving down at v = 0.1 m/s (the peak comes after some 65 wave transits of the height). `plane_at_mc_angle`:
//! the mesh has a row of joints through the centre at 45 - phi/2 from the load axis, the plane on which
//! Mohr-Coulomb failure happens at the lowest load (the failure surface the analytic strength assumes).
UniaxialResult uniaxial(double W, double H, double h, bool plane_at_mc_angle) {
  const double v = 0.1;
  const RockMaterial rock = RockMaterial::paper_table2();
  const double rise = 0.5 * W / std::tan(0.25 * M_PI - 0.5 * rock.friction_angle);  // [m] over half the width
  REQUIRE(rise < 0.5 * H);
  std::vector<Segment> plane;
  if (plane_at_mc_angle) plane.push_back({{0.0, 0.5 * H - rise}, {W, 0.5 * H + rise}});
  const NamedMesh m = gmsh_rectangle(0, 0, W, H, h, plane);
  const FdemTopology topo = build_topology(m.mesh);
  RockSolver s(topo, rock, strength_test_options());
  const auto top = nodes_where(topo, [&](double, double y) { return y > H - 1e-9; });
  const auto bottom = nodes_where(topo, [&](double, double y) { return y < 1e-9; });
  s.prescribe_velocity(top, false, true, 0, -v);  // frictionless platens
  s.prescribe_velocity(bottom, false, true, 0, 0);
  s.prescribe_velocity({bottom[0]}, true, false, 0, 0);
  double peak = 0, t_peak = 0;
  run_to(s, 2.2e-3, 0.9 * s.stable_dt(), [&] {
    const double f = s.support_reactions({bottom})[0][1] / W;
    if (f > peak) peak = f, t_peak = s.time();
  });
  const RockSnapshot snap = s.snapshot();
  int on_plane = 0, on_plane_broken = 0;
  for (size_t j = 0; plane_at_mc_angle && j < snap.joint_broken.size(); ++j) {
    const auto& n = snap.joint_nodes[j];
    const double mx = 0.5 * (snap.x0[n[0]] + snap.x0[n[1]]), my = 0.5 * (snap.y0[n[0]] + snap.y0[n[1]]);
    const double off = std::fabs((my - 0.5 * H) * 0.5 * W - (mx - 0.5 * W) * rise) / std::hypot(0.5 * W, rise);
    if (off > 1e-6 * W) continue;
    ++on_plane;
    on_plane_broken += snap.joint_broken[j] ? 1 : 0;
  }
  return {peak, t_peak, s.energies().broken_joints, on_plane > 0 ? double(on_plane_broken) / on_plane : 0.0};
}
}  // namespace

TEST_CASE("F8: uniaxial compression strength near 2 c cos(phi) / (1 - sin(phi))", "[long][fdem][F8][gmsh]") {
  const RockMaterial rock = RockMaterial::paper_table2();
  const double expected = 2 * rock.cohesion * std::cos(rock.friction_angle) / (1 - std::sin(rock.friction_angle));
  const double W = 0.05, H = 0.1;
  const UniaxialResult coarse = uniaxial(W, H, 0.005, true);
  const UniaxialResult fine = uniaxial(W, H, 0.0025, true);
  const UniaxialResult free_mesh = uniaxial(W, H, 0.005, false);
  for (const auto& [name, r] : {std::pair<const char*, UniaxialResult>{"plane at 45 - phi/2, h 5 mm", coarse},
                                {"plane at 45 - phi/2, h 2.5 mm", fine},
                                {"free mesh, h 5 mm", free_mesh}})
    std::printf("F8 (%s): peak axial stress %.2f MPa at %.3f ms vs 2c cos(phi)/(1 - sin(phi)) = %.2f MPa "
                "(%+.1f %%; bound 20 %%); %d joints broken, %.0f %% of the plane's\n",
                name, r.strength / 1e6, 1e3 * r.t_peak, expected / 1e6, 100 * (r.strength / expected - 1), r.broken,
                100 * r.plane_broken);
  for (const UniaxialResult& r : {coarse, fine}) {
    CHECK(std::fabs(r.strength / expected - 1) < 0.20);
    CHECK(r.plane_broken > 0.99);  // it failed along the plane
  }
  CHECK(std::fabs(fine.strength / coarse.strength - 1) < 0.05);  // the element size does not set the strength
  // Free mesh (reported): no row of joints at the Mohr-Coulomb angle; it fails above the analytic strength
  // and within 1.6 times it (docs/fdem-solver.md).
  CHECK(free_mesh.strength > expected);
  CHECK(free_mesh.strength < 1.6 * expected);
  CHECK(free_mesh.broken > 0);
}

namespace {
struct JointSetPull {
  int broken = 0;            //!< joints broken at the end
  int broken_off_set = 0;    //!< of which not on the set
  int set_joints = 0;        //!< joints on the set
  int broken_lines = 0;      //!< set lines with every joint broken
  int fragments = 0;
};

//! A 0.1 m square block (5 mm elements, the paper's rock, damping 0.1) whose top edge is pulled up at 0.02 m/s
//! for 0.1 ms with the bottom held: a load whose stress (a wave of rho c_p v = 0.28 MPa, then about 1 MPa of
//! static stretch) leaves the intact rock (f_t 6.3 MPa) whole. `set`: a horizontal set of four lines at
//! y = 12.5, 37.5, 62.5, 87.5 mm (open, or closed with the given strength).
JointSetPull pull_jointed_block(const JointSetSpec* set) {
  RockModelSpec spec;
  spec.material = RockMaterial::paper_table2();
  spec.options.damping_ratio = 0.1;
  spec.mesh.shape = MeshShape::rectangle;
  spec.mesh.min = {0.0, 0.0}, spec.mesh.max = {0.1, 0.1};
  spec.mesh.element_size = 0.005;
  spec.velocities.push_back({"top", {-1.0, 0.1 - 1e-9}, {1.0, 1.0}, {0.0, 0.02}, true, true});
  spec.velocities.push_back({"bottom", {-1.0, -1.0}, {1.0, 1e-9}, {0.0, 0.0}, true, true});
  if (set) spec.joint_sets.push_back(*set);
  RockModel m = build_rock_model(spec);
  RockSolver& s = *m.solver;
  run_to(s, 1e-4, 0.9 * s.stable_dt());
  const RockSnapshot snap = s.snapshot();
  JointSetPull r;
  r.fragments = 0;
  const std::vector<int> labels = fragment_labels(s.view());
  for (std::size_t t = 0; t < labels.size(); ++t) r.fragments += labels[t] == static_cast<int>(t) ? 1 : 0;
  std::vector<int> on_set(snap.joint_broken.size(), 0);
  if (set) {
    r.set_joints = static_cast<int>(m.set_joints[0].size());
    for (int j : m.set_joints[0]) on_set[j] = 1;
  }
  std::map<long, std::pair<int, int>> lines;  // line (y in 0.1 mm) -> (joints, broken)
  for (std::size_t j = 0; j < snap.joint_broken.size(); ++j) {
    if (!snap.joint_broken[j]) continue;
    ++r.broken;
    r.broken_off_set += on_set[j] ? 0 : 1;
  }
  for (std::size_t j = 0; set && j < on_set.size(); ++j) {
    if (!on_set[j]) continue;
    const auto& n = snap.joint_nodes[j];
    auto& line = lines[std::lround(1e4 * snap.y0[n[0]])];
    ++line.first;
    line.second += snap.joint_broken[j] ? 1 : 0;
  }
  for (const auto& [y, c] : lines) r.broken_lines += c.first == c.second ? 1 : 0;
  return r;
}
}  // namespace

TEST_CASE("J3 joint set: a block cut by a set breaks only along it under a pull that leaves intact rock whole",
          "[fdem][jointset][J3][gmsh][heavy]") {
  const JointSetPull intact = pull_jointed_block(nullptr);
  JointSetSpec set;
  set.label = "rock.joint_set.0";
  set.angle = 0;
  set.spacing = 0.025;
  set.offset = 0.0125;  // lines at y = 0.05 + 0.0125 + k 0.025
  set.open = true;
  const JointSetPull open = pull_jointed_block(&set);
  set.open = false;
  set.properties = joint_properties_of(RockMaterial::paper_table2());
  set.properties.tensile_strength = 0.1e6, set.properties.cohesion = 0.3e6;  // weak closed joints
  // Fracture energies small enough for the pull's 2 um to break the joints (softening over 2.59 G / f_t = 1.3 um).
  set.properties.fracture_energy_mode1 = 0.05, set.properties.fracture_energy_mode2 = 0.25;
  const JointSetPull weak = pull_jointed_block(&set);
  std::printf("J3: intact block: %d joints broken, %d piece(s); open set (%d joints on 4 lines): %d broken, %d off "
              "the set, %d pieces; weak set (f_t 0.1 MPa): %d broken, %d off the set, %d whole lines, %d pieces\n",
              intact.broken, intact.fragments, open.set_joints, open.broken, open.broken_off_set, open.fragments,
              weak.broken, weak.broken_off_set, weak.broken_lines, weak.fragments);
  CHECK(intact.broken == 0);
  CHECK(intact.fragments == 1);
  CHECK(open.set_joints >= 4 * 20);  // four lines of at least 0.1 m / 5 mm joints
  CHECK(open.broken == open.set_joints);
  CHECK(open.broken_off_set == 0);
  CHECK(open.fragments == 5);
  CHECK(weak.broken > 0);
  CHECK(weak.broken_off_set == 0);
  CHECK(weak.broken_lines >= 1);
}
