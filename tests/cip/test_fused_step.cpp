//! \file test_fused_step.cpp
//! \brief docs/validation.md G12: the gas step with its independent kernels fused (GasSolverOptions::fusion, the
//! GPU's default) gives the same bytes as with every kernel launched alone (the host threads' default), in fewer
//! launches, and it never makes the host wait.
#include "blastsim/cip/gas_solver.hpp"
#include "blastsim/cip/transport_kernels.hpp"
#include "blastsim/core/backend.hpp"
#include "catch.hpp"
#include "same_bytes.hpp"

#include <cmath>
#include <cstdio>
#include <cstring>
#include <vector>

#if !defined(__CUDACC__)
#include <omp.h>
#endif

using namespace blastsim;
using blastsim::test::same_bytes;

namespace {

struct Case {
  const char* name;
  cip::GasMaterials materials;
  cip::GasSolverOptions options;
  bool solid;  // an immersed static solid in the middle (prescribed faces, inactive cells)
};

//! A box over [-1, 1]^2 with a high-pressure disc off the centre (products in a two-material case), an optional
//! static solid beside it, run for `steps` steps at Courant 0.2.
struct Run {
  cip::HostGasFields fields;
  cip::BoundaryOutflow outflow;
  double solid_work, positivity;
  LaunchCounts per_step;
};

Run run(const Case& c, bool fuse, int steps) {
  cip::GasSolverOptions opt = c.options;
  opt.fusion = fuse ? cip::KernelFusion::fused : cip::KernelFusion::separate;
  cip::GasSolver s(cip::GasGrid::from_box(64, 48, -1, 1, -0.75, 0.75), c.materials, opt);
  const cip::GasMaterials& m = c.materials;
  s.initialise([&](double x, double y) {
    const bool hot = (x + 0.3) * (x + 0.3) + y * y < 0.25 * 0.25;
    if (hot && m.two) return cip::GasPoint{300.0, m.products.internal_energy(300.0, 2e8), 0, 0, 1.0};
    if (hot) return cip::GasPoint{5.0, m.air.internal_energy(5.0, 5e6), 0, 0, 0.0};
    return cip::GasPoint{1.2, m.air.internal_energy(1.2, 1e5), 30.0 * y, -20.0 * x, 0.0};
  });
  if (c.solid) mark_static_solid(s, [](double x, double y) { return std::fabs(x - 0.25) < 0.12 && std::fabs(y) < 0.3; });
  const double dt = 0.2 / s.max_signal_rate();  // one dt: the counts below are of the steps alone
  const LaunchCounts before = LaunchCounts::instance();
  for (int k = 0; k < steps; ++k) s.step(dt);
  const LaunchCounts after = LaunchCounts::instance();
  Run r{s.to_host(), s.boundary_outflow(), s.immersed_face_work(), s.positivity_energy(), {}};
  r.per_step.launches = (after.launches - before.launches) / steps;
  r.per_step.host_waits = (after.host_waits - before.host_waits) / steps;
  REQUIRE((after.launches - before.launches) % steps == 0);  // every step launches the same kernels
  return r;
}

double largest_change(const std::vector<double>& now, double initial_min, double initial_max) {
  double d = 0;
  for (double v : now) d = std::fmax(d, std::fmax(v - initial_max, initial_min - v));
  return d;
}

}  // namespace

TEST_CASE("G12 fused gas step: the unfused step's bytes in fewer launches, no host wait", "[cip][G12]") {
  cip::GasMaterials air;
  air.air = cip::EquationOfState::ideal(1.4);
  air.products = air.air;
  cip::GasMaterials two;
  two.air = air.air;
  two.products = cip::EquationOfState::jwl_products(cip::EquationOfState::jwl_preset("ANFO").p);
  two.two = true;

  cip::GasSolverOptions mixed;  // outflow left and top, walls right and bottom
  mixed.boundaries = cip::BoundaryConditions::all(cip::BoundaryKind::outflow)
                         .set(cip::Side::right, cip::BoundaryKind::wall)
                         .set(cip::Side::bottom, cip::BoundaryKind::wall);
  cip::GasSolverOptions periodic_x = mixed;
  periodic_x.boundaries.set(cip::Side::left, cip::BoundaryKind::periodic).set(cip::Side::right, cip::BoundaryKind::periodic);
  cip::GasSolverOptions paper = mixed;
  paper.transport = cip::Transport::paper;
  paper.viscosity = cip::recommended_viscosity(cip::Transport::paper);

  const Case cases[] = {{"conservative, one gas, solid, outflow + walls", air, mixed, true},
                        {"conservative, one gas, periodic x", air, periodic_x, false},
                        {"paper's transport, solid", air, paper, true},
                        {"ANFO products beside air, solid", two, mixed, true}};
  const int steps = 40;
  for (const Case& c : cases) {
    const Run fused = run(c, true, steps), alone = run(c, false, steps);
    const cip::HostGasFields &f = fused.fields, &a = alone.fields;
    const bool fields_equal = same_bytes(f.rho, a.rho) && same_bytes(f.e, a.e) && same_bytes(f.u, a.u) &&
                              same_bytes(f.v, a.v) && same_bytes(f.p, a.p) && same_bytes(f.alpha, a.alpha);
    const bool ledgers_equal = fused.outflow.mass == alone.outflow.mass && fused.outflow.energy == alone.outflow.energy &&
                               fused.outflow.momentum_x == alone.outflow.momentum_x &&
                               fused.outflow.products_mass == alone.outflow.products_mass &&
                               fused.solid_work == alone.solid_work && fused.positivity == alone.positivity;
    // The case is not idle: the pressure moved well away from its initial values, gas left the box.
    const double moved = largest_change(f.p, 1e5, c.materials.two ? 2e8 : 5e6);
    std::printf("G12 %-46s %d steps: fields %s, ledgers %s; launches a step %ld fused vs %ld alone; host waits a "
                "step %ld / %ld; outflow mass %.6e kg/m, pressure beyond its initial range by %.3e Pa\n",
                c.name, steps, fields_equal ? "identical" : "DIFFER", ledgers_equal ? "identical" : "DIFFER",
                fused.per_step.launches, alone.per_step.launches, fused.per_step.host_waits, alone.per_step.host_waits,
                fused.outflow.mass, moved);
    CHECK(fields_equal);
    CHECK(ledgers_equal);
    CHECK(fused.outflow.mass != 0.0);
    CHECK(fused.per_step.host_waits == 0);  // the gas step alone never waits (dt is read by the caller)
    CHECK(alone.per_step.host_waits == 0);
    // Fused groups: face velocities (2 -> 1), derivatives (3 -> 1), advection (3 -> 1), and in the conservative
    // transport mass fluxes (2 -> 1) and momentum (6 -> 1: unfused, the dual faces' fluxes of each velocity are
    // computed once in two launches before its momentum launch; fused, each face computes its own); with one gas
    // also the donor-cell fluxes of the troubled-cell passes (2 -> 1, kTroubledPasses times).
    const bool conservative = c.options.transport == cip::Transport::conservative;
    const long saved = conservative ? (c.materials.two ? 11 : 11 + cip::kTroubledPasses) : 5;
    CHECK(alone.per_step.launches - fused.per_step.launches == saved);
  }
}

#if !defined(__CUDACC__)  // host threads only: on CUDA the device fixes the tree
TEST_CASE("Sums give the same bits on any number of host threads", "[cip][G12][determinism]") {
  // reduce_sum()'s tree depends only on n (backend.hpp): blocks of kSumBlock indices summed in index order, then
  // init and the blocks' sums in block order. Reference: that tree, written out here, which names no thread or
  // processor count (Thrust's OpenMP reduction, used before, split [0, n) into one part per processor). Terms
  // of magnitudes from 1e-3 to 1e3 and both signs, so that another order would round differently.
  auto term = [](index_t k) { return std::sin(0.7 * static_cast<double>(k)) * std::pow(10.0, static_cast<double>(k % 7) - 3); };
  const int threads = omp_get_max_threads();
  for (index_t n : {index_t(1), index_t(4095), index_t(4096), index_t(100001)}) {
    double reference = 0.5;
    for (index_t b = 0; b < n; b += kSumBlock) {
      double s = term(b);
      for (index_t k = b + 1; k < std::min(n, b + kSumBlock); ++k) s += term(k);
      reference += s;
    }
    for (int t : {1, 2, 3, 4}) {
      omp_set_num_threads(t);
      const double sum = reduce_sum("test.sum", n, 0.5, [=](index_t k) { return term(k); });
      INFO("n = " << n << ", " << t << " threads");
      CHECK(std::memcmp(&sum, &reference, sizeof sum) == 0);
    }
  }
  omp_set_num_threads(threads);
  CHECK(reduce_sum("test.sum", 0, 0.25, [=](index_t k) { return term(k); }) == 0.25);  // nothing to add
}
#endif
