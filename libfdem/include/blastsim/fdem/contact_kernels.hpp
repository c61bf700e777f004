//! \file contact_kernels.hpp
//! \brief Munjiza's distributed-potential contact between two triangles (Munjiza 2004, ch. 2) with Coulomb friction.
//!
//! The potential of a triangle is phi(x) = min over its three sub-triangles (centroid + one edge) of
//! 3 A_i(x) / A: 1 at the centroid, 0 on the edges, linear in each sub-triangle. The contact force on a
//! contactor C from a target T is p_c times the boundary integral of n (phi_C - phi_T) over the overlap.
//! On C's own edges phi_C = 0, so each edge of C inside T carries the normal load -p_c n_C phi_T; the
//! remaining part (T's edges inside C) is the same term with the roles swapped. Evaluating every pair
//! both ways round therefore gives the whole force. One evaluation (an edge of C against T) is
//! edge_against_target(); it returns the loads on C's two edge nodes and the reaction on T's three nodes,
//! applied at the same points, so linear and angular momentum balance exactly.
//!
//! An offset s in [0, 1) replaces phi by (phi - s)^+ on both triangles of a pair: (1 - s) times the potential of
//! each triangle shrunk by 1 - s about its centroid, so the pair pushes only against overlap beyond depth s. A pair
//! whose corners met at a bonded mesh vertex enters contact with s equal to the depth it already had
//! (docs/fdem-solver.md, "Which pairs touch"); s = 0 is Munjiza's contact, evaluated by the same arithmetic.
#pragma once

#include "blastsim/fdem/triangle_kernels.hpp"

#include <cmath>

namespace blastsim::fdem {

//! Loads of one edge-against-target evaluation [N/m]: on the contactor edge's nodes (start, end) and on the
//! target's nodes; `friction_power` [W/m] is the rate of work dissipated by its friction (>= 0).
struct EdgeContactLoad {
  Vec2 edge[2];
  Vec2 target[3];
  double friction_power;
  double depth;  //!< deepest phi_T on the edge's part inside the target (the unshrunk potential, in [0, 1])
  bool touching;
};

//! Twice the signed area of (a, b, c).
BLAST_HD inline double cross3(const Vec2& a, const Vec2& b, const Vec2& c) {
  return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
}

//! Separating-axis test of two counter-clockwise triangles: false when some edge of one has the whole other
//! triangle on or beyond its outer side (triangles that only touch count as apart).
BLAST_HD inline bool triangles_overlap(const Vec2 a[3], const Vec2 b[3]) {
  for (int pass = 0; pass < 2; ++pass) {
    const Vec2* p = pass == 0 ? a : b;
    const Vec2* q = pass == 0 ? b : a;
    for (int e = 0; e < 3; ++e) {
      const Vec2& u = p[e];
      const Vec2& v = p[(e + 1) % 3];
      if (cross3(u, v, q[0]) <= 0 && cross3(u, v, q[1]) <= 0 && cross3(u, v, q[2]) <= 0) return false;
    }
  }
  return true;
}

//! Clips the segment p + s (q - p), s in [s0, s1], to the half-plane left of the directed line a -> b
//! (the inside of a counter-clockwise triangle). Returns false if nothing is left.
BLAST_HD inline bool clip_to_left(const Vec2& p, const Vec2& q, const Vec2& a, const Vec2& b, double& s0, double& s1) {
  const double dp = cross3(a, b, p), dq = cross3(a, b, q);  // > 0: inside
  if (dp >= 0 && dq >= 0) return s1 > s0;
  if (dp < 0 && dq < 0) return false;
  const double s = dp / (dp - dq);  // crossing parameter
  if (dp < 0) {
    s0 = s0 > s ? s0 : s;
  } else {
    s1 = s1 < s ? s1 : s;
  }
  return s1 > s0;
}

//! Contact of the contactor edge p -> q (an edge of a counter-clockwise triangle, so its outward normal is
//! (dy, -dx)/|q - p|) against the target triangle t[0..2] (counter-clockwise), with penalty p_c [Pa].
//! Velocities vp, vq of the edge nodes and vt[] of the target nodes, with masses m_edge (the two edge nodes
//! together) and m_target, give the friction: a tangential load opposing the relative sliding velocity,
//! min(mu |F_n|, 0.5 m_eff |v_t| / dt) (Coulomb, capped so that one step at most halves the sliding speed;
//! m_eff the reduced mass), applied with the same distribution as the normal load. With `offset` s > 0 the
//! load is that of the shrunk potential (phi_T - s)^+ (file comment); `depth` is reported either way.
BLAST_HD inline EdgeContactLoad edge_against_target(const Vec2& p, const Vec2& q, const Vec2 t[3], const Vec2& vp,
                                                    const Vec2& vq, const Vec2 vt[3], double m_edge, double m_target,
                                                    double penalty, double friction, double dt, double offset = 0.0) {
  EdgeContactLoad out{};
  for (int k = 0; k < 3; ++k) {  // quick exit: the edge lies wholly outside one side of the target
    if (cross3(t[k], t[(k + 1) % 3], p) < 0 && cross3(t[k], t[(k + 1) % 3], q) < 0) return out;
  }
  const double len = sqrt((q.x - p.x) * (q.x - p.x) + (q.y - p.y) * (q.y - p.y));
  const Vec2 n{(q.y - p.y) / len, -(q.x - p.x) / len};  // outward normal of the contactor's edge
  const Vec2 g{(t[0].x + t[1].x + t[2].x) / 3.0, (t[0].y + t[1].y + t[2].y) / 3.0};
  const double inv_area2 = 1.0 / cross3(t[0], t[1], t[2]);  // 1 / (2 A) of the target
  double load = 0;              // integral of phi_T along the edge [m]
  double w_edge[2] = {0, 0};    // integrals of phi_T times the edge's shape functions
  double w_target[3] = {0, 0, 0};  // integrals of phi_T times the target's barycentric coordinates
  double depth = 0;
  for (int k = 0; k < 3; ++k) {
    const Vec2& a = t[k];
    const Vec2& b = t[(k + 1) % 3];
    // Sub-triangle (g, a, b) is counter-clockwise; phi = cross3(x, a, b) / cross3(g, a, b) = 3 A_k(x) / A.
    double s0 = 0, s1 = 1;
    if (!clip_to_left(p, q, a, b, s0, s1) || !clip_to_left(p, q, b, g, s0, s1) || !clip_to_left(p, q, g, a, s0, s1))
      continue;
    const double inv_sub2 = 1.0 / cross3(g, a, b);
    if (offset > 0) {  // phi is linear along the clipped part: its ends give the depth, then keep phi >= offset
      const double f0 = cross3({p.x + s0 * (q.x - p.x), p.y + s0 * (q.y - p.y)}, a, b) * inv_sub2;
      const double f1 = cross3({p.x + s1 * (q.x - p.x), p.y + s1 * (q.y - p.y)}, a, b) * inv_sub2;
      depth = max_of(depth, max_of(f0, f1));
      if (!(f0 > offset || f1 > offset)) continue;
      const double cut = s0 + (s1 - s0) * (offset - f0) / (f1 - f0);  // where phi = offset, when it is crossed
      if (f0 < offset) s0 = cut;
      if (f1 < offset) s1 = cut;
      if (!(s1 > s0)) continue;
    }
    const double seg = (s1 - s0) * len;
    // Simpson on [s0, s1]: exact for phi (linear) times a linear shape function.
    const double ss[3] = {s0, 0.5 * (s0 + s1), s1};
    const double ws[3] = {seg / 6.0, 4.0 * seg / 6.0, seg / 6.0};
    for (int m = 0; m < 3; ++m) {
      const Vec2 x{p.x + ss[m] * (q.x - p.x), p.y + ss[m] * (q.y - p.y)};
      const double phi_full = cross3(x, a, b) * inv_sub2;
      if (m != 1) depth = max_of(depth, phi_full);  // the ends of the clipped part (offset 0)
      const double phi = phi_full - offset;
      const double wp = ws[m] * phi;
      load += wp;
      w_edge[0] += wp * (1.0 - ss[m]);
      w_edge[1] += wp * ss[m];
      for (int c = 0; c < 3; ++c)  // barycentric coordinate of x for target node c
        w_target[c] += wp * cross3(x, t[(c + 1) % 3], t[(c + 2) % 3]) * inv_area2;
    }
  }
  out.depth = depth;
  if (!(load > 0)) return out;
  out.touching = true;
  const double fn = penalty * load;  // normal load magnitude [N/m], pushes the edge back along -n
  // Friction: relative velocity of the edge against the target at the load's centroid.
  Vec2 vc{(w_edge[0] * vp.x + w_edge[1] * vq.x) / load, (w_edge[0] * vp.y + w_edge[1] * vq.y) / load};
  Vec2 vtg{0, 0};
  for (int c = 0; c < 3; ++c) {
    vtg.x += w_target[c] * vt[c].x / load;
    vtg.y += w_target[c] * vt[c].y / load;
  }
  const Vec2 tan{-n.y, n.x};
  const double slide = (vc.x - vtg.x) * tan.x + (vc.y - vtg.y) * tan.y;  // [m/s]
  const double m_eff = m_edge * m_target / (m_edge + m_target);
  const double cap = 0.5 * m_eff * fabs(slide) / dt;
  const double ft_mag = friction * fn < cap ? friction * fn : cap;
  const double ft = slide > 0 ? -ft_mag : ft_mag;  // tangential load on the edge along `tan`
  out.friction_power = ft_mag * fabs(slide);
  const Vec2 f{-fn * n.x + ft * tan.x, -fn * n.y + ft * tan.y};  // total load on the contactor edge
  for (int e = 0; e < 2; ++e) out.edge[e] = {f.x * w_edge[e] / load, f.y * w_edge[e] / load};
  for (int c = 0; c < 3; ++c) out.target[c] = {-f.x * w_target[c] / load, -f.y * w_target[c] / load};
  return out;
}

}  // namespace blastsim::fdem
