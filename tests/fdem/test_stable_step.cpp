//! \file test_stable_step.cpp
//! \brief The rock's stable step with many contacts at once (docs/fdem-solver.md, "Time integration and stable
//! step"): the bound, which allows for one contact pair per triangle, against the highest frequency of crowded
//! triangles (every touching pair's contact springs and the triangles' elasticity, linearised).
#include "blastsim/fdem/mesh.hpp"
#include "blastsim/fdem/rock_solver.hpp"
#include "blastsim/fdem/rock_step_kernels.hpp"
#include "catch.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#if defined(BLASTSIM_TEST_HAVE_EIGEN)
#include <Eigen/Dense>
#endif

using namespace blastsim::fdem;

namespace {

//! A central equilateral triangle (side a) with two loose triangles on each of its edges, their bases along
//! the edge (at 2-48 % and 52-98 % of it) pushed `depth` into it, their apexes a out: the centre touches six
//! pairs, each loose triangle one, and the centre's bound is the largest. No joints, no shared vertices.
struct Crowd {
  static constexpr double a = 0.02;  // [m]
  std::vector<Vec2> nodes;           // 3 per triangle, counter-clockwise; triangle 0 is the centre
  explicit Crowd(double depth) {
    const Vec2 c[3] = {{0, 0}, {a, 0}, {a / 2, a * std::sqrt(3.0) / 2}};
    add(c[0], c[1], c[2]);
    for (int e = 0; e < 3; ++e) {
      const Vec2 A = c[e], B = c[(e + 1) % 3];
      const Vec2 t{(B.x - A.x) / a, (B.y - A.y) / a}, n{t.y, -t.x};  // n: outward (the centre lies on the left)
      for (const auto& [s0, s1] : {std::array<double, 2>{0.02, 0.48}, std::array<double, 2>{0.52, 0.98}}) {
        const Vec2 q0{A.x + s0 * a * t.x - depth * n.x, A.y + s0 * a * t.y - depth * n.y};
        const Vec2 q1{A.x + s1 * a * t.x - depth * n.x, A.y + s1 * a * t.y - depth * n.y};
        const double sm = 0.5 * (s0 + s1), h = a;
        const Vec2 apex{A.x + sm * a * t.x + h * n.x, A.y + sm * a * t.y + h * n.y};
        add(q1, q0, apex);  // counter-clockwise seen from outside the centre
      }
    }
  }
  void add(Vec2 p0, Vec2 p1, Vec2 p2) { nodes.push_back(p0), nodes.push_back(p1), nodes.push_back(p2); }
};

//! A crushed zone: the 4 x 4 squares of 10 mm of a structured mesh (vertices moved by up to `jitter` of their
//! shortest edge), every triangle on its own and grown about its centroid by the factor 1 + `grow`, so that it
//! overlaps its three edge neighbours along whole edges and its vertex neighbours at the corners.
std::vector<Vec2> crushed(double jitter, double grow) {
  TriangleMesh mesh = structured_rectangle(4, 4, 0.0, 0.04, 0.0, 0.04);
  if (jitter > 0) perturb_mesh(mesh, jitter, 7);
  const FdemTopology topo = build_topology(mesh);
  const auto& q = topo.node_positions;
  std::vector<Vec2> x;
  for (int t = 0; t < topo.triangle_count(); ++t) {
    const double cx = (q[3 * t][0] + q[3 * t + 1][0] + q[3 * t + 2][0]) / 3;
    const double cy = (q[3 * t][1] + q[3 * t + 1][1] + q[3 * t + 2][1]) / 3;
    for (int k = 0; k < 3; ++k)
      x.push_back({cx + (1 + grow) * (q[3 * t + k][0] - cx), cy + (1 + grow) * (q[3 * t + k][1] - cy)});
  }
  return x;
}

double area(const Vec2 p[3]) {
  return 0.5 * ((p[1].x - p[0].x) * (p[2].y - p[0].y) - (p[2].x - p[0].x) * (p[1].y - p[0].y));
}

//! The stable step's bound of omega^2 [1/s2] for one triangle (docs/fdem-solver.md), from its formula, with its
//! contact term counted `pairs` times (the solver counts it once; more: a row-sum bound over touching pairs).
double omega2_bound(const RockMaterial& m, const RockOptions& o, const Vec2 p[3], int pairs = 1) {
  const double A = area(p), l01 = std::hypot(p[1].x - p[0].x, p[1].y - p[0].y),
               l12 = std::hypot(p[2].x - p[1].x, p[2].y - p[1].y), l20 = std::hypot(p[0].x - p[2].x, p[0].y - p[2].y);
  const double h = 2 * A / std::max({l01, l12, l20}), rho = m.density, cp = m.p_wave_speed();
  const double pj = o.joint_penalty_factor * m.youngs_modulus, pc = o.contact_penalty_factor * m.youngs_modulus;
  return 4 * cp * cp / (h * h) + 6 * std::sqrt(2.0) * pj / (rho * A) + std::max(1, pairs) * 36 * pc / (rho * h * h);
}

//! Pairs that touch in the configuration `x` (3 nodes per triangle), every pair tried.
std::vector<std::array<int, 2>> touching_pairs(const std::vector<Vec2>& x, double penalty) {
  std::vector<std::array<int, 2>> out;
  const int n = static_cast<int>(x.size() / 3);
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j) {
      const Vec2 p[2][3] = {{x[3 * i], x[3 * i + 1], x[3 * i + 2]}, {x[3 * j], x[3 * j + 1], x[3 * j + 2]}};
      const Vec2 v[2][3] = {};
      const double m[2][3] = {{1, 1, 1}, {1, 1, 1}};
      if (pair_contact(p, v, m, penalty, 0.0, 1e-9, 0.0).touching) out.push_back({i, j});
    }
  return out;
}

}  // namespace

TEST_CASE("Stable step: the solver's bound is the formula's, the largest over the triangles", "[fdem][stable_step]") {
  const RockMaterial mat = RockMaterial::paper_table2();
  for (const bool contact : {true, false}) {
    for (const double jitter : {0.0, 0.25}) {
      TriangleMesh mesh = structured_rectangle(4, 4, 0.0, 0.04, 0.0, 0.04);
      if (jitter > 0) perturb_mesh(mesh, jitter, 7);
      const FdemTopology topo = build_topology(mesh);
      RockOptions opt;
      opt.contact = contact;
      if (!contact) opt.contact_penalty_factor = 1e-300;  // the formula's contact term vanishes with contact off
      double w = 0;
      for (int t = 0; t < topo.triangle_count(); ++t) {
        Vec2 p[3];
        for (int k = 0; k < 3; ++k) p[k] = {topo.node_positions[3 * t + k][0], topo.node_positions[3 * t + k][1]};
        w = std::max(w, omega2_bound(mat, opt, p));
      }
      const double dt = RockSolver(topo, mat, opt).stable_dt();
      std::printf("stable step, contact %s, jitter %.2f: %.9e s, formula %.9e s\n", contact ? "on" : "off", jitter, dt,
                  2 / std::sqrt(w));
      CHECK(std::fabs(dt * std::sqrt(w) / 2 - 1) < 1e-12);
    }
  }
}

#if defined(BLASTSIM_TEST_HAVE_EIGEN)
TEST_CASE("Stable step: the bound covers the highest frequency of triangles crowded by up to 14 touching pairs",
          "[fdem][contact][stable_step]") {
  // Exact reference: omega_max^2, the largest |eigenvalue| of M^-1 K, K the stiffness of the linearised system
  // (each triangle's elasticity and every touching pair's Munjiza contact load without offsets, by central
  // differences of the kernels' forces), M the lumped masses; the explicit step is stable for dt <= 2 /
  // omega_max. The solver's bound allows for one contact pair per triangle; a piece in a crushed zone touches
  // many at once (docs/fdem-solver.md, "Known limit"). Asserted: the bound is at least omega_max^2 in every
  // configuration. Reported beside it: the bound with the contact term counted for every touching pair (a
  // row sum over pairs), which is safe but much larger.
  const RockMaterial mat = RockMaterial::paper_table2();
  const RockOptions opt;
  const double penalty = opt.contact_penalty_factor * mat.youngs_modulus;
  struct Config {
    std::string name;
    std::vector<Vec2> nodes;
    double depth;  // [m] of the overlaps
  };
  std::vector<Config> configs;
  for (const double depth : {1e-6, 2e-5}) configs.push_back({"six pairs on one triangle", Crowd(depth).nodes, depth});
  for (const double jitter : {0.0, 0.15, 0.25})
    for (const double grow : {1e-4, 1e-2, 5e-2})  // overlap depth about grow x 10 mm / 3
      configs.push_back(
          {"crushed zone, jitter " + std::to_string(jitter).substr(0, 4), crushed(jitter, grow), grow * 0.01 / 3});
  for (const Config& cfg : configs) {
    const std::vector<Vec2>& x0 = cfg.nodes;
    const int N = static_cast<int>(x0.size()), T = N / 3;
    const std::vector<std::array<int, 2>> pairs = touching_pairs(x0, penalty);
    std::vector<int> count(T, 0);
    for (const auto& p : pairs) ++count[p[0]], ++count[p[1]];
    std::vector<Mat2> inv_f0(T);
    std::vector<double> mass(N);
    for (int t = 0; t < T; ++t) {
      const Vec2* p = &x0[3 * t];
      inv_f0[t] = edge_matrix(p[0], p[1], p[2]).inverse();
      for (int k = 0; k < 3; ++k) mass[3 * t + k] = mat.density * area(p) / 3;
    }
    // Forces on every node [N/m] at positions x: the triangles' elastic forces and the touching pairs' loads.
    auto forces = [&](const std::vector<Vec2>& x) {
      std::vector<Vec2> f(N, Vec2{0, 0});
      for (int t = 0; t < T; ++t) {
        const Mat2 S = triangle_stress(inv_f0[t], edge_matrix(x[3 * t], x[3 * t + 1], x[3 * t + 2]), Mat2{0, 0, 0, 0},
                                       mat.lame_lambda(), mat.shear_modulus(), 0.0);
        Vec2 g[3];
        triangle_nodal_forces(S, x[3 * t], x[3 * t + 1], x[3 * t + 2], g);
        for (int k = 0; k < 3; ++k) f[3 * t + k] = {f[3 * t + k].x - g[k].x, f[3 * t + k].y - g[k].y};
      }
      for (const auto& [i, j] : pairs) {
        const Vec2 p[2][3] = {{x[3 * i], x[3 * i + 1], x[3 * i + 2]}, {x[3 * j], x[3 * j + 1], x[3 * j + 2]}};
        const Vec2 v[2][3] = {};
        const double m[2][3] = {{1, 1, 1}, {1, 1, 1}};
        const PairContact c = pair_contact(p, v, m, penalty, 0.0, 1e-9, 0.0);
        for (int k = 0; k < 3; ++k) {
          f[3 * i + k] = {f[3 * i + k].x + c.f[0][k].x, f[3 * i + k].y + c.f[0][k].y};
          f[3 * j + k] = {f[3 * j + k].x + c.f[1][k].x, f[3 * j + k].y + c.f[1][k].y};
        }
      }
      return f;
    };
    const double eps = 1e-3 * cfg.depth;
    Eigen::MatrixXd K(2 * N, 2 * N);
    for (int d = 0; d < 2 * N; ++d) {
      std::vector<Vec2> xp = x0, xm = x0;
      (d % 2 ? xp[d / 2].y : xp[d / 2].x) += eps;
      (d % 2 ? xm[d / 2].y : xm[d / 2].x) -= eps;
      const std::vector<Vec2> fp = forces(xp), fm = forces(xm);
      for (int r = 0; r < N; ++r) {
        K(2 * r, d) = -(fp[r].x - fm[r].x) / (2 * eps) / mass[r];  // M^-1 K
        K(2 * r + 1, d) = -(fp[r].y - fm[r].y) / (2 * eps) / mass[r];
      }
    }
    const Eigen::VectorXcd lambda = Eigen::EigenSolver<Eigen::MatrixXd>(K, false).eigenvalues();
    double exact = 0;
    for (int k = 0; k < lambda.size(); ++k) exact = std::max(exact, std::abs(lambda[k]));
    double bound = 0, counted = 0;
    for (int t = 0; t < T; ++t) {
      bound = std::max(bound, omega2_bound(mat, opt, &x0[3 * t]));
      counted = std::max(counted, omega2_bound(mat, opt, &x0[3 * t], count[t]));
    }
    std::printf("%s, overlaps %.0e m: %zu touching pairs, at most %d on a triangle; omega_max^2 %.4e 1/s2, the "
                "solver's bound %.4e (x %.2f), each pair counted %.4e (x %.2f); largest stable step %.4e s, the "
                "solver's %.4e s\n",
                cfg.name.c_str(), cfg.depth, pairs.size(), *std::max_element(count.begin(), count.end()), exact, bound,
                bound / exact, counted, counted / exact, 2 / std::sqrt(exact), 2 / std::sqrt(bound));
    CHECK(bound >= exact);
  }
}
#endif
