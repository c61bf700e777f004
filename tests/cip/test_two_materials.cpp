//! \file test_two_materials.cpp
//! \brief docs/validation.md G11: JWL detonation products beside air (GasMaterials): a material interface keeps p and u
//! uniform, shock tubes of products into air against the exact two-material Riemann solution, positivity at a density
//! ratio of 1e4, each material's mass and the total energy conserved, checkpoint and restart bit for bit.
#include "blastsim/core/checkpoint.hpp"
#include "validation_courant.hpp"
#include "blastsim/core/error.hpp"
#include "catch.hpp"
#include "gas_cases.hpp"
#include "mie_gruneisen_riemann.hpp"
#include "temp_files.hpp"

#include <algorithm>
#include <cstdlib>
#include <fstream>

using namespace blastsim;
using namespace blastsim::test;

namespace {

const cip::EquationOfState kAir = cip::EquationOfState::ideal(1.4);

cip::GasMaterials anfo_and_air() {
  cip::GasMaterials m;
  m.air = kAir;
  m.products = cip::EquationOfState::jwl_products(cip::EquationOfState::jwl_preset("ANFO").p);
  m.two = true;
  return m;
}

//! A tube of n x 3 cells over [0, 1] m: products (state L) left of x0, air (state R) right of it (the other way
//! round with products_right); outflow ends.
cip::GasSolver products_tube(int n, const Primitive& L, const Primitive& R, double x0, bool products_right = false) {
  const cip::GasMaterials mat = anfo_and_air();
  cip::GasSolverOptions opt;
  opt.boundaries = cip::BoundaryConditions::all(cip::BoundaryKind::wall)
                       .set(cip::left, cip::BoundaryKind::outflow)
                       .set(cip::right, cip::BoundaryKind::outflow);
  cip::GasSolver s(cip::GasGrid::from_box(n, 3, 0, 1, 0, 3.0 / n), mat, opt);
  s.initialise([&](double x, double) {
    const bool products = (x < x0) != products_right;
    const Primitive& q = x < x0 ? L : R;
    const cip::EquationOfState& eos = products ? mat.products : mat.air;
    return cip::GasPoint{q.rho, eos.internal_energy(q.rho, q.p), q.u, 0.0, products ? 1.0 : 0.0};
  });
  return s;
}

}  // namespace

TEST_CASE("G11 the two-material exact Riemann solver reproduces Toro's ideal-gas solution", "[cip][G11]") {
  // Both sides ideal: the isentrope integration and the Hugoniot root must give the closed-form answers.
  const Primitive L{1.0, 0.0, 1.0}, R{0.125, 0.0, 0.1};
  const MieGruneisenRiemann mg(kAir, L, kAir, R);
  const ExactRiemann exact(L, R, 1.4);
  CHECK_THAT(mg.p_star(), WithinRel(exact.p_star(), 1e-6));
  CHECK_THAT(mg.u_star(), WithinRel(exact.u_star(), 1e-6));
  for (double s : {-1.3, -0.8, -0.3, 0.5, 1.2, 1.8}) {
    CHECK_THAT(mg.sample(s).rho, WithinRel(exact.sample(s).rho, 1e-5));
    CHECK_THAT(mg.sample(s).p, WithinRel(exact.sample(s).p, 1e-5));
  }
  // A left-moving shock (Toro's test 4) exercises the Hugoniot side.
  const Primitive L4{1.0, 0.0, 0.01}, R4{1.0, 0.0, 100.0};
  CHECK_THAT(MieGruneisenRiemann(kAir, L4, kAir, R4).p_star(), WithinRel(ExactRiemann(L4, R4, 1.4).p_star(), 1e-6));
}

TEST_CASE("G11 a products | air interface moving at uniform p and u keeps them uniform", "[long][cip][G11]") {
  const double p = 2e8, speed = 3000.0, rho_air = 0.3;  // [Pa], [m/s], [kg/m3]
  for (double ratio : {100.0, 1000.0})
  for (double u : {speed, -speed}) {  // products behind the interface, moving right; or moving left
    const int n = 200;
    const bool left = u > 0;
    cip::GasSolver s = left ? products_tube(n, {rho_air * ratio, u, p}, {rho_air, u, p}, 0.3)
                            : products_tube(n, {rho_air, u, p}, {rho_air * ratio, u, p}, 0.7, true);
    const double t_end = 0.3 / speed;  // the interface crosses 30 % of the tube
    double worst_p = 0, worst_u = 0, worst_rho1 = 0;
    for (int k = 1; k <= 4; ++k) {
      run_to(s, k * t_end / 4, blastsim::test::validation_courant());
      const cip::HostGasFields h = s.to_host();
      const std::vector<double> pp = strip(h, h.p, Axis::x), uu = strip(h, h.u, Axis::x);
      for (int i = 0; i < n; ++i) {
        worst_p = std::max(worst_p, std::fabs(pp[i] / p - 1));
        worst_u = std::max(worst_u, std::fabs(uu[i] / u - 1));
      }
    }
    // The phase densities stay uniform: every cell's density is that of its volume fraction.
    const cip::HostGasFields h = s.to_host();
    const std::vector<double> alpha = strip(h, h.alpha, Axis::x), rho = strip(h, h.rho, Axis::x);
    for (int i = 0; i < n; ++i)
      worst_rho1 = std::max(worst_rho1, std::fabs(rho[i] / (alpha[i] * rho_air * ratio + (1 - alpha[i]) * rho_air) - 1));
    std::printf("G11 products | air interface moving %s, density ratio %g, %d cells: max |dp/p| %.1e, |du/u| %.1e, "
                "density against alpha rho1 + (1 - alpha) rho2 %.1e\n",
                left ? "right" : "left", ratio, n, worst_p, worst_u, worst_rho1);
    CHECK(worst_p <= 1e-6);
    CHECK(worst_u <= 1e-6);
    CHECK(worst_rho1 <= 1e-8);  // round-off over about 6000 steps
  }
}

TEST_CASE("G11 shock tubes of ANFO products into air against the exact solution", "[long][cip][G11]") {
  const cip::GasMaterials mat = anfo_and_air();
  const Primitive air{1.2, 0.0, 1.0e5};
  struct Case {
    double rho, p;  // products [kg/m3], [Pa]
  };
  for (const Case c : {Case{400.0, 1e9}, Case{800.0, 1e10}}) {
    const Primitive L{c.rho, 0.0, c.p};
    const MieGruneisenRiemann exact(mat.products, L, mat.air, air);
    const double x0 = 0.4;
    // Until the fastest wave is 0.05 m from an end.
    const double t = std::fmin((x0 - 0.05) / -exact.leftmost_speed(), (0.95 - x0) / exact.rightmost_speed());
    const int n = 800;
    cip::GasSolver s = products_tube(n, L, air, x0);
    run_to(s, t, blastsim::test::validation_courant());
    const cip::HostGasFields h = s.to_host();
    const std::vector<double> rho = strip(h, h.rho, Axis::x), p = strip(h, h.p, Axis::x);
    double err = 0, norm = 0, p_sum = 0;
    int p_count = 0;
    const double x_contact = x0 + exact.u_star() * t;
    for (int i = 0; i < n; ++i) {
      const double x = (i + 0.5) / n;
      const Primitive e = exact.sample((x - x0) / t);
      err += std::fabs(rho[i] - e.rho);
      norm += e.rho;
      // Star pressure: mean over the cells of the star region 10 cells or more from the contact and 20 % of
      // the star region from its ends.
      if (e.p == exact.p_star() && std::fabs(x - x_contact) > 10.0 / n) {
        p_sum += p[i];
        ++p_count;
      }
    }
    const double rel_l1 = err / norm, p_num = p_sum / p_count;
    // With BLASTSIM_FIGURE_DIR set, the profiles for docs/figures (scripts/plot-products-shock-tube.py).
    if (const char* dir = std::getenv("BLASTSIM_FIGURE_DIR")) {
      const std::vector<double> u = strip(h, h.u, Axis::x), alpha = strip(h, h.alpha, Axis::x);
      std::ofstream out(std::string(dir) + "/products_shock_tube_" + std::to_string(static_cast<int>(c.p / 1e6)) + "MPa.csv");
      out << "x_m,rho,rho_exact,p_Pa,p_exact,u_m_per_s,u_exact,alpha,t_s\n";
      for (int i = 0; i < n; ++i) {
        const double x = (i + 0.5) / n;
        const Primitive e = exact.sample((x - x0) / t);
        out << x << "," << rho[i] << "," << e.rho << "," << p[i] << "," << e.p << "," << u[i] << "," << e.u << ","
            << alpha[i] << "," << t << "\n";
      }
    }
    std::printf("G11 ANFO products %.0f kg/m3 at %.0f MPa into air, %d cells, t = %.3e s: p* %.4e Pa (exact %.4e, "
                "%+.2f %%), u* exact %.1f m/s, relative density L1 %.2f %%\n",
                c.rho, c.p / 1e6, n, t, p_num, exact.p_star(), 100 * (p_num / exact.p_star() - 1), exact.u_star(),
                100 * rel_l1);
    CHECK(p_count > 10);
    CHECK_THAT(p_num, WithinRel(exact.p_star(), 0.02));
    CHECK(rel_l1 <= 0.02);
  }
}

TEST_CASE("G11 products into thin air at a density ratio of 1e4: positive and finite", "[cip][G11][heavy]") {
  const cip::GasMaterials mat = anfo_and_air();
  const Primitive L{800.0, 0.0, 1e10}, R{0.08, 0.0, 0.08 * 0.4 * 2.09e5};
  const MieGruneisenRiemann exact(mat.products, L, mat.air, R);
  const double t = (0.95 - 0.4) / exact.rightmost_speed();
  cip::GasSolver s = products_tube(400, L, R, 0.4);
  double rho_min = 1e300, p_min = 1e300, a_min = 1, a_max = 0;
  for (int k = 1; k <= 10; ++k) {
    run_to(s, k * t / 10, blastsim::test::validation_courant());
    const cip::HostGasFields h = s.to_host();
    for (size_t i = 0; i < h.rho.size(); ++i) {
      REQUIRE(std::isfinite(h.rho[i]));
      REQUIRE(std::isfinite(h.p[i]));
      rho_min = std::min(rho_min, h.rho[i]);
      p_min = std::min(p_min, h.p[i]);
      a_min = std::min(a_min, h.alpha[i]);
      a_max = std::max(a_max, h.alpha[i]);
    }
  }
  std::printf("G11 density ratio 1e4: min density %.3e kg/m3, min pressure %.3e Pa, alpha in [%.3g, %.3g]\n", rho_min,
              p_min, a_min, a_max);
  CHECK(rho_min > 0);
  CHECK(p_min > 0);
  CHECK(a_min >= 0);
  CHECK(a_max <= 1);
}

TEST_CASE("G11 closed box with a products disc: each material's mass and the energy conserved, restart bit for bit",
          "[cip][G11]") {
  const cip::GasMaterials mat = anfo_and_air();
  const int n = 48;
  auto make = [&] {
    cip::GasSolverOptions opt;
    opt.boundaries = cip::BoundaryConditions::all(cip::BoundaryKind::wall);
    cip::GasSolver s(cip::GasGrid::from_box(n, n, -1, 1, -1, 1), mat, opt);
    s.initialise([&](double x, double y) {
      const bool products = x * x + y * y < 0.3 * 0.3;
      return products ? cip::GasPoint{300.0, mat.products.internal_energy(300.0, 3e8), 0, 0, 1.0}
                      : cip::GasPoint{1.2, mat.air.internal_energy(1.2, 1e5), 0, 0, 0.0};
    });
    return s;
  };
  cip::GasSolver s = make();
  const cip::GasTotals t0 = s.totals();
  auto advance = [](cip::GasSolver& g, int steps) {
    for (int k = 0; k < steps; ++k) g.step(g.courant_dt(blastsim::test::validation_courant()));
  };
  advance(s, 100);
  // Checkpoint after 100 steps, then 100 more; a solver restarted from the checkpoint must end identical.
  const std::filesystem::path dir = testing::fresh_dir("two_materials");
  std::filesystem::create_directories(dir);
  const std::string path = (dir / "gas.ckpt").string();
  {
    CheckpointWriter w(path);
    s.write_checkpoint(w);
    w.commit();
  }
  advance(s, 100);
  const cip::GasTotals t1 = s.totals();
  const double dm = t1.mass / t0.mass - 1, dm1 = t1.products_mass / t0.products_mass - 1;
  const double dE = t1.total_energy() / t0.total_energy() - 1;
  std::printf("G11 closed box, 200 steps: total mass %.1e, products mass %.1e, energy %.1e relative change; "
              "energy added by the positivity bound %.1e J/m\n",
              dm, dm1, dE, s.positivity_energy());
  CHECK(std::fabs(dm) <= 1e-12);
  CHECK(std::fabs(dm1) <= 1e-12);
  CHECK(std::fabs(dE - s.positivity_energy() / t0.total_energy()) <= 1e-12);

  cip::GasSolver r = make();
  {
    CheckpointReader rd(path);
    r.read_checkpoint(rd);
    rd.finish();
  }
  advance(r, 100);
  // The checkpoint of this two-material run is refused by a one-gas solver of the same grid.
  {
    cip::GasSolverOptions opt;
    opt.boundaries = cip::BoundaryConditions::all(cip::BoundaryKind::wall);
    cip::GasSolver one(cip::GasGrid::from_box(n, n, -1, 1, -1, 1), mat.air, opt);
    CheckpointReader rd(path);
    CHECK_THROWS_AS(one.read_checkpoint(rd), InputError);
  }
  const cip::HostGasFields a = s.to_host(), b = r.to_host();
  CHECK(a.rho == b.rho);
  CHECK(a.e == b.e);
  CHECK(a.alpha == b.alpha);
  CHECK(a.u == b.u);
}
