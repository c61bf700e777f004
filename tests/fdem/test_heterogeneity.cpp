//! \file test_heterogeneity.cpp
//! \brief H1-H3: heterogeneous joint strength. The drawn factors follow their distribution (mean, Weibull modulus
//! by maximum likelihood, log-normal coefficient of variation), the draw is reproducible from its seed, and the
//! solver's joints carry exactly the material's values times the draw.
#include "blastsim/fdem/heterogeneity.hpp"
#include "blastsim/fdem/mesh.hpp"
#include "blastsim/fdem/rock_solver.hpp"
#include "blastsim/core/error.hpp"
#include "catch.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <numeric>
#include <vector>

using namespace blastsim;
using namespace blastsim::fdem;

namespace {

double mean_of(const std::vector<double>& x) { return std::accumulate(x.begin(), x.end(), 0.0) / x.size(); }

double cov_of(const std::vector<double>& x) {
  const double m = mean_of(x);
  double s = 0;
  for (double v : x) s += (v - m) * (v - m);
  return std::sqrt(s / (x.size() - 1)) / m;
}

//! Maximum-likelihood Weibull modulus of a sample: the root m of
//! sum(x^m ln x) / sum(x^m) - 1/m - mean(ln x) = 0 (increasing in m), found by bisection.
double weibull_modulus_mle(const std::vector<double>& x) {
  double mean_log = 0;
  for (double v : x) mean_log += std::log(v);
  mean_log /= x.size();
  auto g = [&](double m) {
    double a = 0, b = 0;
    for (double v : x) {
      const double w = std::pow(v, m);
      a += w * std::log(v), b += w;
    }
    return a / b - 1.0 / m - mean_log;
  };
  double lo = 0.05, hi = 500.0;
  for (int k = 0; k < 60; ++k) {  // 2^-60 of the log-range: far below the sampling error
    const double mid = std::sqrt(lo * hi);
    (g(mid) > 0 ? hi : lo) = mid;
  }
  return std::sqrt(lo * hi);
}

}  // namespace

TEST_CASE("H1 heterogeneity: Weibull strengths keep the material's mean and the modulus asked for",
          "[fdem][heterogeneity][H1]") {
  // N = 20,000 joints. Tolerances from the sampling errors: the mean's standard error is cov / sqrt(N) with
  // cov = sqrt(Gamma(1 + 2/m) / Gamma(1 + 1/m)^2 - 1) (0.229 at m = 5: 0.16 %), so 1 % is over 6 standard
  // errors; the maximum-likelihood modulus has a relative standard error of about 0.78 / sqrt(N) (0.55 %), so
  // 5 % is over 9.
  const RockMaterial mat = RockMaterial::paper_table2();
  const int n = 20000;
  for (double m : {3.0, 5.0, 10.0}) {
    StrengthHeterogeneity h;
    h.weibull_modulus = m;
    h.seed = 2026;
    const std::vector<JointProperties> joints = heterogeneous_joints(mat, h, n);
    std::vector<double> ft(n), x(n);
    for (int j = 0; j < n; ++j) ft[j] = joints[j].tensile_strength, x[j] = ft[j] / mat.tensile_strength;
    const double mean_ratio = mean_of(ft) / mat.tensile_strength;
    const double m_fit = weibull_modulus_mle(x);
    const double cov_exact = std::sqrt(std::tgamma(1 + 2 / m) / std::pow(std::tgamma(1 + 1 / m), 2) - 1);
    std::printf("H1 Weibull m = %g: mean f_t / material %.5f (tolerance 1 %%), fitted modulus %.4f (%+.2f %%, "
                "tolerance 5 %%), cov %.4f (exact %.4f)\n",
                m, mean_ratio, m_fit, 100 * (m_fit / m - 1), cov_of(x), cov_exact);
    CHECK(std::abs(mean_ratio - 1) < 0.01);
    CHECK(std::abs(m_fit / m - 1) < 0.05);
    // One factor per joint scales every selected property alike.
    for (int j = 0; j < n; j += 997) {
      CHECK(joints[j].cohesion / mat.cohesion == Approx(x[j]).epsilon(1e-14));
      CHECK(joints[j].fracture_energy_mode1 / mat.fracture_energy_mode1 == Approx(x[j]).epsilon(1e-14));
      CHECK(joints[j].fracture_energy_mode2 / mat.fracture_energy_mode2 == Approx(x[j]).epsilon(1e-14));
      CHECK(joints[j].friction_angle == mat.friction_angle);
    }
  }
}

TEST_CASE("H2 heterogeneity: log-normal strengths keep the mean and the coefficient of variation, and the draw is the "
          "seed's",
          "[fdem][heterogeneity][H2]") {
  // N = 20,000: the mean's standard error is cov / sqrt(N) (0.21 % at cov 0.3), the sample cov's about
  // cov / sqrt(2 N) relative (0.5 %) for a near-normal sample; tolerances 1 % and 5 %.
  const int n = 20000;
  StrengthHeterogeneity h;
  h.distribution = StrengthDistribution::lognormal;
  h.cov = 0.3;
  h.seed = 11;
  const std::vector<double> x = strength_factors(h, n);
  std::printf("H2 log-normal cov 0.3: mean %.5f (tolerance 1 %%), cov %.4f (tolerance 5 %%)\n", mean_of(x), cov_of(x));
  CHECK(std::abs(mean_of(x) - 1) < 0.01);
  CHECK(std::abs(cov_of(x) / 0.3 - 1) < 0.05);
  for (double v : x) REQUIRE((v > 0 && std::isfinite(v)));
  // The same seed gives the same factors, another seed others; the first factors do not depend on the count.
  CHECK(strength_factors(h, n) == x);
  const std::vector<double> head = strength_factors(h, 100);
  CHECK(std::equal(head.begin(), head.end(), x.begin()));
  h.seed = 12;
  CHECK(strength_factors(h, n) != x);
  // Only the selected properties scatter.
  h.tensile_strength = false, h.fracture_energy = false;
  const RockMaterial mat = RockMaterial::paper_table2();
  const std::vector<JointProperties> j = heterogeneous_joints(mat, h, 10);
  for (const JointProperties& q : j) {
    CHECK(q.tensile_strength == mat.tensile_strength);
    CHECK(q.fracture_energy_mode1 == mat.fracture_energy_mode1);
  }
  CHECK(j[0].cohesion != mat.cohesion);
  // Bad parameters are refused naming them.
  StrengthHeterogeneity bad;
  bad.weibull_modulus = 0;
  CHECK_THROWS_WITH(bad.validate(), Catch::Contains("rock.heterogeneity.modulus"));
  bad.distribution = StrengthDistribution::lognormal;
  CHECK_THROWS_WITH(bad.validate(), Catch::Contains("rock.heterogeneity.cov"));
}

TEST_CASE("H3 heterogeneity: the solver's joints hold the material's strength times the draw, in joint order",
          "[fdem][heterogeneity][H3]") {
  const FdemTopology topo = build_topology(structured_rectangle(20, 8, 0.0, 0.2, 0.0, 0.08));
  const int joints = static_cast<int>(topo.joints.size());
  const RockMaterial mat = RockMaterial::paper_table2();
  RockOptions opt;
  StrengthHeterogeneity h;
  h.weibull_modulus = 4;
  h.seed = 5;
  const std::vector<double> x = strength_factors(h, joints);
  const RockSolver het(topo, mat, opt, heterogeneous_joints(mat, h, joints));
  const RockSolver uniform(topo, mat, opt);
  const std::vector<JointStrength> a = het.joint_strengths(), b = uniform.joint_strengths();
  REQUIRE(a.size() == static_cast<std::size_t>(joints));
  for (int j = 0; j < joints; ++j) {
    CHECK(b[j].tensile_strength == mat.tensile_strength);
    CHECK(a[j].tensile_strength == Approx(mat.tensile_strength * x[j]).epsilon(1e-15));
    CHECK(a[j].cohesion == Approx(mat.cohesion * x[j]).epsilon(1e-15));
    // The peak opening 2 h f_t / p scales with f_t, as the joint law needs.
    CHECK(a[j].peak_opening / b[j].peak_opening == Approx(x[j]).epsilon(1e-12));
  }
  CHECK(het.stable_dt() == uniform.stable_dt());  // strength does not enter the stable step
  // A list of the wrong length is refused.
  CHECK_THROWS_AS(RockSolver(topo, mat, opt, std::vector<JointProperties>(3)), InputError);
}

namespace {

//! Sample correlation of two equally long series.
double correlation_of(const std::vector<double>& a, const std::vector<double>& b) {
  const double ma = mean_of(a), mb = mean_of(b);
  double ab = 0, aa = 0, bb = 0;
  for (std::size_t i = 0; i < a.size(); ++i)
    ab += (a[i] - ma) * (b[i] - mb), aa += (a[i] - ma) * (a[i] - ma), bb += (b[i] - mb) * (b[i] - mb);
  return ab / std::sqrt(aa * bb);
}

}  // namespace

TEST_CASE("H4 heterogeneity: a correlated strength field has unit variance, the correlation exp(-r^2/l^2) and the "
          "distribution asked for",
          "[fdem][heterogeneity][H4]") {
  // (a) The Gaussian field G on a 128 x 128 grid of spacing l / 2 (64 correlation lengths a side), four seeds.
  // Its sample correlation at lag r along x and y, averaged over the seeds, against exp(-r^2 / l^2). Errors: one
  // draw of N = 2048 modes departs from the covariance by about 1 / sqrt(2 N) = 0.016 (a standard deviation); the spatial
  // average over (64 l)^2 adds about sqrt(pi) l / (64 l) = 0.028; over four seeds about 0.016. Tolerance 0.05
  // (3 of those), for the mean 0 and variance 1 alike (0.05 and 0.1).
  const double l = 0.03;
  const int n = 128, seeds = 4;
  const double s = 0.5 * l;
  double corr[5] = {0, 0, 0, 0, 0}, mean = 0, var = 0;
  for (int seed = 1; seed <= seeds; ++seed) {
    const GaussianField g(l, static_cast<std::uint64_t>(seed));
    std::vector<double> v(n * n);
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) v[j * n + i] = g(i * s, j * s);
    const double m = mean_of(v);
    double s2 = 0;
    for (double x : v) s2 += (x - m) * (x - m);
    s2 /= v.size();
    mean += m / seeds, var += s2 / seeds;
    for (int k = 1; k <= 4; ++k) {
      double c = 0;
      int count = 0;
      for (int j = 0; j < n; ++j)
        for (int i = 0; i + k < n; ++i) c += (v[j * n + i] - m) * (v[j * n + i + k] - m), ++count;  // along x
      for (int j = 0; j + k < n; ++j)
        for (int i = 0; i < n; ++i) c += (v[j * n + i] - m) * (v[(j + k) * n + i] - m), ++count;  // along y
      corr[k] += c / count / s2 / seeds;
    }
  }
  std::printf("H4 field: mean %.4f (tolerance 0.05), variance %.4f (tolerance 0.1)\n", mean, var);
  CHECK(std::abs(mean) < 0.05);
  CHECK(std::abs(var - 1) < 0.1);
  for (int k = 1; k <= 4; ++k) {
    const double r = k * s, exact = std::exp(-r * r / (l * l));
    std::printf("H4 field: correlation at r = %.2f l: %.4f, exp(-r^2/l^2) = %.4f (tolerance 0.05)\n", r / l, corr[k],
                exact);
    CHECK(std::abs(corr[k] - exact) < 0.05);
  }
  // (b) The factors: X = F^-1(Phi(G)) at every point, to round-off, for both laws; on 10,000 points 3 l apart
  // (correlation exp(-9) = 1.2e-4: near independent) the mean and the Weibull modulus meet H1's tolerances (with
  // half H1's sample: standard errors 0.23 % and 0.78 %, so 1 % and 5 % are over 4 and 6 of them).
  StrengthHeterogeneity h;
  h.weibull_modulus = 5;
  h.seed = 7;
  h.correlation_length = l;
  std::vector<std::array<double, 2>> pts;
  for (int j = 0; j < 100; ++j)
    for (int i = 0; i < 100; ++i) pts.push_back({3 * l * i, 3 * l * j});
  const std::vector<double> x = strength_field(h, pts);
  const GaussianField g(l, h.seed);
  const double lambda = 1.0 / std::tgamma(1.0 + 1.0 / h.weibull_modulus);
  double worst = 0;
  for (std::size_t i = 0; i < pts.size(); i += 101) {
    const double phi = 0.5 * std::erfc(-g(pts[i][0], pts[i][1]) / std::sqrt(2.0));  // Phi(G)
    worst = std::max(worst, std::abs(1 - std::exp(-std::pow(x[i] / lambda, h.weibull_modulus)) - phi));
  }
  const double m_fit = weibull_modulus_mle(x);
  std::printf("H4 Weibull m = 5 field: |F(X) - Phi(G)| <= %.2e, mean %.5f (tolerance 1 %%), fitted modulus %.4f "
              "(%+.2f %%, tolerance 5 %%)\n",
              worst, mean_of(x), m_fit, 100 * (m_fit / 5 - 1));
  CHECK(worst < 1e-12);
  CHECK(std::abs(mean_of(x) - 1) < 0.01);
  CHECK(std::abs(m_fit / 5 - 1) < 0.05);
  h.distribution = StrengthDistribution::lognormal;
  h.cov = 0.3;
  const std::vector<double> y = strength_field(h, pts);
  const double s2 = std::log(1.0 + 0.09);
  for (std::size_t i = 0; i < pts.size(); i += 101)
    CHECK(std::log(y[i]) == Approx(-0.5 * s2 + std::sqrt(s2) * g(pts[i][0], pts[i][1])).margin(1e-12));
  std::printf("H4 log-normal cov 0.3 field: mean %.5f, cov %.4f (tolerance 1 %% and 5 %%)\n", mean_of(y), cov_of(y));
  CHECK(std::abs(mean_of(y) - 1) < 0.01);
  CHECK(std::abs(cov_of(y) / 0.3 - 1) < 0.05);
  // A field needs a length; a negative one is refused naming the key.
  CHECK_THROWS_AS(GaussianField(0.0, 1), InputError);
  h.correlation_length = -1;
  CHECK_THROWS_WITH(h.validate(), Catch::Contains("rock.heterogeneity.correlation_length"));
}

TEST_CASE("H5 heterogeneity: with a correlation length two meshes of one rock get the same strength where they overlap, "
          "independent draws do not",
          "[fdem][heterogeneity][H5]") {
  // The same 0.6 x 0.3 m rock meshed with squares of 20 mm and 10 mm (two triangles each), correlation length
  // 0.1 m. Every joint's factor is the field's at its midpoint, computed alone (exact). The mean tensile strength
  // of the joints whose midpoints lie in each of the 6 x 3 blocks of 0.1 m: with the field the two meshes' block
  // means follow one another (the field varies over 0.1 m, the block means by about the factor's spread, while
  // the two meshes sample each block's field at 75 and 300 points), so their correlation over the blocks must
  // exceed 0.9; with independent draws they are two unrelated samples (correlation near 0, standard error
  // about 1 / sqrt(18) = 0.24), so theirs must stay below 0.7 (near 3 standard errors).
  const RockMaterial mat = RockMaterial::paper_table2();
  StrengthHeterogeneity h;
  h.weibull_modulus = 4;
  h.seed = 3;
  auto block_means = [&](int per_block, bool field) {
    const FdemTopology topo = build_topology(structured_rectangle(6 * per_block, 3 * per_block, 0.0, 0.6, 0.0, 0.3));
    const std::vector<std::array<double, 2>> mid = joint_midpoints(topo);
    StrengthHeterogeneity hh = h;
    hh.correlation_length = field ? 0.1 : 0.0;
    const std::vector<JointProperties> joints = heterogeneous_joints(mat, hh, mid);
    if (field)
      for (std::size_t j = 0; j < mid.size(); j += 37)
        CHECK(joints[j].tensile_strength == mat.tensile_strength * strength_field(hh, {mid[j]})[0]);
    std::vector<double> sum(18, 0.0), count(18, 0.0);
    for (std::size_t j = 0; j < mid.size(); ++j) {
      const int b = std::min(5, static_cast<int>(mid[j][0] / 0.1)) + 6 * std::min(2, static_cast<int>(mid[j][1] / 0.1));
      sum[b] += joints[j].tensile_strength, count[b] += 1;
    }
    for (int b = 0; b < 18; ++b) sum[b] /= count[b];
    return sum;
  };
  const double r_field = correlation_of(block_means(5, true), block_means(10, true));
  const double r_iid = correlation_of(block_means(5, false), block_means(10, false));
  std::printf("H5 block means of f_t on 20 and 10 mm meshes: correlation %.4f with the field (> 0.9), %.4f with "
              "independent draws (< 0.7)\n",
              r_field, r_iid);
  CHECK(r_field > 0.9);
  CHECK(r_iid < 0.7);
}
