//! \file test_triangle.cpp
//! \brief The large-deformation triangle against Hooke's law (patch test), rigid motions and force balance.
#include "blastsim/fdem/material.hpp"
#include "blastsim/fdem/triangle_kernels.hpp"
#include "catch.hpp"

#include <cmath>

using namespace blastsim::fdem;

namespace {
const Vec2 P0{0.0, 0.0}, P1{0.01, 0.0}, P2{0.003, 0.008};  // an arbitrary counter-clockwise triangle [m]
Vec2 map(const Mat2& A, const Vec2& p) { return {A.a * p.x + A.b * p.y, A.c * p.x + A.d * p.y}; }
}  // namespace

TEST_CASE("Patch test: a small uniform strain gives Hooke's plane-strain stress", "[fdem][triangle]") {
  const RockMaterial rock = RockMaterial::paper_table2();
  const double lambda = rock.lame_lambda(), mu = rock.shear_modulus();
  // Displacement gradient H (small): x -> (I + H) x. Strain eps = sym(H).
  const double hxx = 2e-6, hxy = 1e-6, hyx = -0.5e-6, hyy = -1.5e-6;
  const Mat2 F{1 + hxx, hxy, hyx, 1 + hyy};
  const Mat2 inv_F0 = edge_matrix(P0, P1, P2).inverse();
  const Mat2 FX = edge_matrix(map(F, P0), map(F, P1), map(F, P2));
  const Mat2 T = triangle_stress(inv_F0, FX, Mat2{0, 0, 0, 0}, lambda, mu, 0.0);
  const double exx = hxx, eyy = hyy, exy = 0.5 * (hxy + hyx);
  const double sxx = 2 * mu * exx + lambda * (exx + eyy), syy = 2 * mu * eyy + lambda * (exx + eyy);
  const double sxy = 2 * mu * exy;
  // Geometric non-linearity enters at order |H|^2 ~ 1e-12 relative to 1e-6 strains: 1e-5 relative.
  CHECK_THAT(T.a, WithinRel(sxx, 1e-5));
  CHECK_THAT(T.d, WithinRel(syy, 1e-5));
  CHECK_THAT(T.b, WithinRel(sxy, 1e-5));
  CHECK(T.b == T.c);
}

TEST_CASE("A rigid rotation by 90 degrees leaves the triangle unstressed (objectivity)", "[fdem][triangle]") {
  const RockMaterial rock = RockMaterial::paper_table2();
  const Mat2 R{0.0, -1.0, 1.0, 0.0};
  const Mat2 T = triangle_stress(edge_matrix(P0, P1, P2).inverse(),
                                 edge_matrix(map(R, P0), map(R, P1), map(R, P2)), Mat2{0, 0, 0, 0},
                                 rock.lame_lambda(), rock.shear_modulus(), 0.0);
  const double scale = rock.youngs_modulus;
  CHECK(std::fabs(T.a) < 1e-12 * scale);
  CHECK(std::fabs(T.b) < 1e-12 * scale);
  CHECK(std::fabs(T.d) < 1e-12 * scale);
}

TEST_CASE("An inverted or flattened triangle has no stress: NaN, which stops the rock step", "[fdem][triangle]") {
  const RockMaterial rock = RockMaterial::paper_table2();
  const Mat2 inv_F0 = edge_matrix(P0, P1, P2).inverse();
  const Vec2 flipped{P2.x, -P2.y}, flat{0.5 * (P0.x + P1.x), 0.0};  // the apex through the base, and onto it
  for (const Vec2& apex : {flipped, flat}) {
    const Mat2 T = triangle_stress(inv_F0, edge_matrix(P0, P1, apex), Mat2{0, 0, 0, 0}, rock.lame_lambda(),
                                   rock.shear_modulus(), 0.0);
    CHECK(std::isnan(T.a));
    CHECK(std::isnan(T.b));
    CHECK(std::isnan(T.d));
  }
  // Just before the apex reaches the base (J = 1e-6) the stress is finite, and strongly compressive.
  const Vec2 low{P2.x, 1e-6 * P2.y};
  const Mat2 T = triangle_stress(inv_F0, edge_matrix(P0, P1, low), Mat2{0, 0, 0, 0}, rock.lame_lambda(),
                                 rock.shear_modulus(), 0.0);
  CHECK(std::isfinite(T.d));
  CHECK(T.d < -1e3 * rock.youngs_modulus);
}

TEST_CASE("Nodal forces balance and equal the traction on the edges", "[fdem][triangle]") {
  // Uniaxial tension sigma along x on the right triangle (0,0), (L,0), (0,L).
  const double L = 0.02, sigma = 3e6;
  const Mat2 T{sigma, 0.0, 0.0, 0.0};
  Vec2 f[3];
  triangle_nodal_forces(T, {0, 0}, {L, 0}, {0, L}, f);
  CHECK_THAT(f[0].x + f[1].x + f[2].x, WithinAbs(0.0, 1e-9));
  CHECK_THAT(f[0].y + f[1].y + f[2].y, WithinAbs(0.0, 1e-9));
  // Node 1 at (L, 0): the opposite edge is the leg x = 0, outward normal (-L, 0): f_1 = -sigma L / 2 along x,
  // pulling node 1 towards the triangle as tension should.
  CHECK_THAT(f[1].x, WithinRel(-0.5 * sigma * L, 1e-14));
  CHECK_THAT(f[1].y, WithinAbs(0.0, 1e-9));
  // Node 0 (the corner): opposite edge the hypotenuse, outward normal (L, L): f_0 = (sigma L / 2, 0).
  CHECK_THAT(f[0].x, WithinRel(0.5 * sigma * L, 1e-14));
}

TEST_CASE("Principal stresses of a symmetric stress", "[fdem][triangle]") {
  double s1, s2;
  principal_stresses(Mat2{3e6, 4e6, 4e6, -3e6}, s1, s2);  // eigenvalues +-5e6
  CHECK_THAT(s1, WithinRel(5e6, 1e-14));
  CHECK_THAT(s2, WithinRel(-5e6, 1e-14));
}

TEST_CASE("The paper's rock (Table 2) and its wave speeds", "[fdem][material]") {
  const RockMaterial rock = RockMaterial::paper_table2();
  REQUIRE_NOTHROW(rock.validate());
  // docs/fdem-solver.md, "The paper's rock (Table 2)": plane-strain P-wave 5336 m/s, S-wave 2852 m/s.
  CHECK_THAT(rock.p_wave_speed(), WithinAbs(5336.0, 1.0));
  CHECK_THAT(rock.s_wave_speed(), WithinAbs(2852.0, 1.0));
  RockMaterial bad = rock;
  bad.poisson_ratio = 0.5;
  CHECK_THROWS_WITH(bad.validate(), Catch::Contains("poisson_ratio") && Catch::Contains("[0, 0.5)"));
}
