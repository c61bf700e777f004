//! \file test_heterogeneity.cpp
//! \brief H1-H3: heterogeneous joint strength. The drawn factors follow their distribution (mean, Weibull modulus
//! by maximum likelihood, log-normal coefficient of variation), the draw is reproducible from its seed, and the
//! solver's joints carry exactly the material's values times the draw.
#include "blastsim/fdem/heterogeneity.hpp"
#include "blastsim/fdem/mesh.hpp"
#include "blastsim/fdem/rock_solver.hpp"
#include "blastsim/core/error.hpp"
#include "catch.hpp"

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
