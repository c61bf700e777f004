//! \file triangle_kernels.hpp
//! \brief Large-deformation constant-strain triangle of FDEM (Munjiza 2004, ch. 2): stress and nodal forces.
#pragma once

#include "blastsim/core/macros.hpp"

#include <cmath>

namespace blastsim::fdem {

struct Vec2 {
  double x, y;
};

//! 2 x 2 matrix, row major: [[a, b], [c, d]].
struct Mat2 {
  double a, b, c, d;
  BLAST_HD double det() const { return a * d - b * c; }
  BLAST_HD Mat2 inverse() const {
    const double k = 1.0 / det();
    return {d * k, -b * k, -c * k, a * k};
  }
  BLAST_HD Mat2 operator*(const Mat2& o) const {
    return {a * o.a + b * o.c, a * o.b + b * o.d, c * o.a + d * o.c, c * o.b + d * o.d};
  }
  BLAST_HD Mat2 transposed() const { return {a, c, b, d}; }
};

//! Squared distance [m2] from (px, py) to the segment p0 - p1.
BLAST_HD inline double segment_distance2(const Vec2& p0, const Vec2& p1, double px, double py) {
  const double ex = p1.x - p0.x, ey = p1.y - p0.y, len2 = ex * ex + ey * ey;
  double t = len2 > 0.0 ? ((px - p0.x) * ex + (py - p0.y) * ey) / len2 : 0.0;
  t = t < 0.0 ? 0.0 : (t > 1.0 ? 1.0 : t);
  const double dx = px - p0.x - t * ex, dy = py - p0.y - t * ey;
  return dx * dx + dy * dy;
}

//! Distance [m] from p to the triangle a, b, c (either orientation): 0 inside it or on its edges.
BLAST_HD inline double distance_to_triangle(const Vec2& p, const Vec2& a, const Vec2& b, const Vec2& c) {
  const double s0 = (b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x);
  const double s1 = (c.x - b.x) * (p.y - b.y) - (c.y - b.y) * (p.x - b.x);
  const double s2 = (a.x - c.x) * (p.y - c.y) - (a.y - c.y) * (p.x - c.x);
  if ((s0 >= 0 && s1 >= 0 && s2 >= 0) || (s0 <= 0 && s1 <= 0 && s2 <= 0)) return 0.0;
  return sqrt(fmin(fmin(segment_distance2(a, b, p.x, p.y), segment_distance2(b, c, p.x, p.y)),
                   segment_distance2(c, a, p.x, p.y)));
}

//! Edge matrix [x1 - x0, x2 - x0] (columns) of a triangle.
BLAST_HD inline Mat2 edge_matrix(const Vec2& p0, const Vec2& p1, const Vec2& p2) {
  return {p1.x - p0.x, p2.x - p0.x, p1.y - p0.y, p2.y - p0.y};
}

//! Cauchy stress [Pa] of a constant-strain triangle in plane strain (Munjiza 2004, ch. 2; docs/fdem-solver.md, "Triangle internal force"):
//! F = FX F0^-1, B = F F^T, J = det F, T = mu (B - I)/J + lambda/2 (J - 1/J) I + eta D with
//! D = sym(L), L = LX FX^-1. For small strain it reduces to Hooke's law 2 mu eps + lambda tr(eps) I.
//! inv_F0: inverse of the initial edge matrix; FX, LX: current edge matrices of positions and velocities;
//! eta [Pa s]: viscous damping coefficient. NaN when J <= 0 (the triangle turned inside out).
BLAST_HD inline Mat2 triangle_stress(const Mat2& inv_F0, const Mat2& FX, const Mat2& LX, double lambda, double mu,
                                     double eta) {
  const Mat2 F = FX * inv_F0;
  const double J = F.det();
  if (!(J > 0.0)) {  // an inverted or flattened triangle has no stress: NaN, which stops the rock step on it
    const double bad = nan("");
    return {bad, bad, bad, bad};
  }
  const Mat2 B = F * F.transposed();
  const Mat2 L = LX * FX.inverse();
  const double volumetric = 0.5 * lambda * (J - 1.0 / J);
  const double dxy = 0.5 * (L.b + L.c);
  return {mu * (B.a - 1.0) / J + volumetric + eta * L.a, mu * B.b / J + eta * dxy, mu * B.c / J + eta * dxy,
          mu * (B.d - 1.0) / J + volumetric + eta * L.d};
}

//! Elastic energy per unit initial area [J/m2] whose derivative is triangle_stress() without damping:
//! W = mu/2 (tr B - 2 - 2 ln J) + lambda/4 (J^2 - 1 - 2 ln J) (a compressible neo-Hookean solid; the
//! Kirchhoff stress 2 B dW/dB gives T J = mu (B - I) + lambda/2 (J^2 - 1) I).
BLAST_HD inline double triangle_strain_energy_density(const Mat2& inv_F0, const Mat2& FX, double lambda, double mu) {
  // Written in H = F - I and j = J - 1 so that a body at rest gives round-off squared, not round-off.
  const Mat2 F = FX * inv_F0;
  const double ha = F.a - 1.0, hb = F.b, hc = F.c, hd = F.d - 1.0;
  const double j = ha + hd + ha * hd - hb * hc;
  const double ln_j = log1p(j);
  const double dev = 2.0 * (ha + hd - ln_j) + ha * ha + hb * hb + hc * hc + hd * hd;  // tr B - 2 - 2 ln J
  const double vol = 2.0 * (j - ln_j) + j * j;                                       // J^2 - 1 - 2 ln J
  return 0.5 * mu * dev + 0.25 * lambda * vol;
}

//! Forces [N per m depth] that a triangle under Cauchy stress T exerts on its three nodes (current
//! positions p0, p1, p2, counter-clockwise): f_i = T n_i / 2, n_i the outward normal of the edge opposite
//! node i scaled by its length. They sum to zero.
BLAST_HD inline void triangle_nodal_forces(const Mat2& T, const Vec2& p0, const Vec2& p1, const Vec2& p2, Vec2 f[3]) {
  const Vec2 p[3] = {p0, p1, p2};
  for (int i = 0; i < 3; ++i) {
    const Vec2& a = p[(i + 1) % 3];
    const Vec2& b = p[(i + 2) % 3];
    const Vec2 n{b.y - a.y, -(b.x - a.x)};  // outward for a counter-clockwise triangle, |n| = edge length
    f[i] = {0.5 * (T.a * n.x + T.b * n.y), 0.5 * (T.c * n.x + T.d * n.y)};
  }
}

//! In-plane principal stresses of a symmetric stress: s1 >= s2 [Pa], tension positive; s2 is the minimum
//! (most compressive) in-plane principal stress, the paper's "PS3" of its 2-D figures.
BLAST_HD inline void principal_stresses(const Mat2& T, double& s1, double& s2) {
  const double mean = 0.5 * (T.a + T.d);
  const double radius = sqrt(0.25 * (T.a - T.d) * (T.a - T.d) + T.b * T.b);
  s1 = mean + radius;
  s2 = mean - radius;
}

}  // namespace blastsim::fdem
