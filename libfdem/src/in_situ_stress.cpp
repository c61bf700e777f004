//! \file in_situ_stress.cpp
//! \brief The in-situ stress field, the triangles' prestretch (Newton on the neo-Hookean stress) and the joints'
//! preload (the joint law inverted before its peak).
#include "blastsim/fdem/in_situ_stress.hpp"

#include "blastsim/core/error.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <utility>

namespace blastsim::fdem {

Mat2 InSituStress::at(double y) const {
  const double dy = y - reference_y;
  const double xx = at_reference[0] + dy * gradient[0], yy = at_reference[1] + dy * gradient[1];
  const double xy = at_reference[2] + dy * gradient[2];
  return {xx, xy, xy, yy};
}

Mat2 prestretch(const Mat2& sigma, double lambda, double mu) {
  // Plane-strain compliance: eps_xx = ((lambda + 2 mu) s_xx - lambda s_yy) / (4 mu (lambda + mu)), eps_xy = s_xy / 2 mu.
  const double k = 1.0 / (4.0 * mu * (lambda + mu));
  auto compliance = [&](double sxx, double syy, double sxy) {
    return Mat2{((lambda + 2 * mu) * sxx - lambda * syy) * k, 0.5 * sxy / mu, 0.5 * sxy / mu,
                ((lambda + 2 * mu) * syy - lambda * sxx) * k};
  };
  const Mat2 identity{1, 0, 0, 1}, no_motion{0, 0, 0, 0};
  const double scale = std::fabs(sigma.a) + std::fabs(sigma.d) + std::fabs(sigma.b);
  Mat2 F = identity;
  for (int it = 0; it < 60; ++it) {
    const Mat2 T = triangle_stress(identity, F, no_motion, lambda, mu, 0.0);
    const double rxx = sigma.a - T.a, ryy = sigma.d - T.d, rxy = sigma.b - T.b;
    if (!std::isfinite(rxx + ryy + rxy)) break;
    // Converged to round-off: that of B - I is about 1e-16 mu.
    if (std::fabs(rxx) + std::fabs(ryy) + std::fabs(rxy) <= 1e-13 * scale + 1e-14 * mu) return F;
    const Mat2 dF = compliance(rxx, ryy, rxy);
    F = {F.a + dF.a, F.b + dF.b, F.c + dF.c, F.d + dF.d};
  }
  std::ostringstream os;
  os << "in-situ stress [" << sigma.a << ", " << sigma.d << ", " << sigma.b
     << "] Pa (xx, yy, xy): no stretch of the rock carries it (the stress must be small against the elastic moduli, "
        "mu = " << mu << " Pa)";
  throw InputError(os.str());
}

JointPreload joint_preload(double normal, double shear, const JointStrength& j) {
  auto refuse = [&](const char* what, double limit) {
    std::ostringstream os;
    os << "in-situ traction sigma = " << normal << " Pa, tau = " << shear << " Pa: " << what << " (" << limit
       << " Pa); the joint would break before the blast";
    throw InputError(os.str());
  };
  JointPreload p{0.0, 0.0};
  // Normal: penalty 2 f_t o / o_p in compression, (2 r - r^2) f_t with r = o / o_p in tension before the peak.
  if (normal <= 0.0)
    p.opening = normal * j.peak_opening / (2.0 * j.tensile_strength);
  else if (normal < j.tensile_strength)
    p.opening = j.peak_opening * (1.0 - std::sqrt(1.0 - normal / j.tensile_strength));
  else
    refuse("not below the joint's tensile strength", j.tensile_strength);
  // Shear: elastic, tau = c s / s_p, below the Coulomb cap f_s = c - sigma tan(phi) under compression.
  const double fs = normal < 0.0 ? j.cohesion - normal * j.tan_friction : j.cohesion;
  if (!(std::fabs(shear) < fs)) refuse("|tau| not below the joint's shear strength", fs);
  p.slip = shear * j.peak_slip / j.cohesion;
  return p;
}

void carry_cut_weight(const InSituStress& s, const std::vector<BoundaryEdge>& boundary_edges,
                      const std::vector<int>& node_vertex, const std::vector<double>& x0, const std::vector<double>& y0,
                      const std::vector<char>& held_slot, std::vector<Vec2>& load) {
  // The boundary's closed loops: its edges joined where they share a mesh vertex (union-find on the vertices).
  std::vector<int> root(node_vertex.empty() ? 0 : *std::max_element(node_vertex.begin(), node_vertex.end()) + 1);
  for (std::size_t v = 0; v < root.size(); ++v) root[v] = static_cast<int>(v);
  auto find = [&](int v) {
    while (root[v] != v) v = root[v] = root[root[v]];
    return v;
  };
  for (const BoundaryEdge& b : boundary_edges) root[find(node_vertex[b.n0])] = find(node_vertex[b.n1]);
  std::vector<char> loop_held(root.size(), 0);
  for (const BoundaryEdge& b : boundary_edges)
    if (held_slot[b.n0]) loop_held[find(node_vertex[b.n0])] = 1;
  // What the field's tractions on the loops that hold nothing (the holes cut from the rock mass) add up to, as
  // nodal forces: with the held loads and the rock's weight they close the balance of the uncut rock mass.
  Vec2 force{0.0, 0.0};
  std::vector<std::pair<Vec2, Vec2>> point_forces;  // (position, force) of the holes' nodal tractions
  for (const BoundaryEdge& b : boundary_edges) {
    if (loop_held[find(node_vertex[b.n0])]) continue;
    const int n0 = b.n0, n1 = b.n1;
    const Vec2 N = edge_outward_normal({x0[n0], y0[n0]}, {x0[n1], y0[n1]});
    const Mat2 sig = s.at(0.5 * (y0[n0] + y0[n1]));
    const Vec2 half{0.5 * (sig.a * N.x + sig.b * N.y), 0.5 * (sig.c * N.x + sig.d * N.y)};
    for (int n : {n0, n1}) point_forces.push_back({Vec2{x0[n], y0[n]}, half});
    force = {force.x + 2 * half.x, force.y + 2 * half.y};
  }
  if (point_forces.empty()) return;
  // The held nodes' shares w_n (half the length of each held edge at the node) and their centroid r_c.
  std::vector<double> w(load.size(), 0.0);
  double total = 0;
  Vec2 rc{0.0, 0.0};
  for (const BoundaryEdge& b : boundary_edges) {
    if (!held_slot[b.n0]) continue;
    const double half_length = 0.5 * std::hypot(x0[b.n1] - x0[b.n0], y0[b.n1] - y0[b.n0]);
    for (int n : {b.n0, b.n1}) {
      w[n] += half_length, total += half_length;
      rc = {rc.x + half_length * x0[n], rc.y + half_length * y0[n]};
    }
  }
  rc = {rc.x / total, rc.y / total};
  double moment = 0, inertia = 0;  // about r_c: of the holes' forces, and sum w_n |r_n - r_c|^2
  for (const auto& [r, f] : point_forces) moment += (r.x - rc.x) * f.y - (r.y - rc.y) * f.x;
  for (std::size_t n = 0; n < w.size(); ++n)
    if (w[n] > 0) inertia += w[n] * ((x0[n] - rc.x) * (x0[n] - rc.x) + (y0[n] - rc.y) * (y0[n] - rc.y));
  // The held nodes take that resultant, force and moment, spread in proportion to their shares: f_n = w_n (A + B
  // z x (r_n - r_c)) with sum f_n = force and the moment about r_c equal: A = force / sum w, B = moment / inertia.
  const Vec2 A{force.x / total, force.y / total};
  const double B = inertia > 0 ? moment / inertia : 0.0;
  for (std::size_t n = 0; n < w.size(); ++n)
    if (w[n] > 0)
      load[n] = {load[n].x + w[n] * (A.x - B * (y0[n] - rc.y)), load[n].y + w[n] * (A.y + B * (x0[n] - rc.x))};
}

}  // namespace blastsim::fdem
