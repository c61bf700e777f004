//! \file test_two_materials.cpp
//! \brief docs/validation.md G11: JWL detonation products beside air (GasMaterials): a material interface keeps p and u
//! uniform, shock tubes of products into air against the exact two-material Riemann solution, positivity at a density
//! ratio of 1e4, each material's mass and the total energy conserved, checkpoint and restart bit for bit.
#include "blastsim/core/checkpoint.hpp"
#include "validation_courant.hpp"
#include "blastsim/core/error.hpp"
#include "catch.hpp"
#include "five_equation_hllc.hpp"
#include "gas_cases.hpp"
#include "mie_gruneisen_riemann.hpp"
#include "muscl_hancock.hpp"
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

//! Air with the JWL products of a preset ("ANFO", "TNT"; G10).
cip::GasMaterials preset_and_air(const char* preset) {
  cip::GasMaterials m = anfo_and_air();
  m.products = cip::EquationOfState::jwl_products(cip::EquationOfState::jwl_preset(preset).p);
  return m;
}

//! A tube of n x 3 cells over [0, 1] m: products (state L) left of x0, air (state R) right of it (the other way
//! round with products_right); outflow ends.
cip::GasSolver products_tube(int n, const Primitive& L, const Primitive& R, double x0, bool products_right = false,
                             const cip::GasMaterials& mat = anfo_and_air()) {
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

//! Largest errors of an interface that should move unchanged (G11): |dp/p| and |du/u| over four times, and at the
//! end a cell's density against alpha rho1 + (1 - alpha) rho2 (the phase densities uniform).
struct InterfaceErrors {
  double p = 0, u = 0, rho = 0;
};

//! A products | air interface at uniform p [Pa] and u [m/s] in a tube of n cells, products (rho1) behind it: at
//! x = 0.3 with the products left when u > 0, at 0.7 with them right otherwise; run until it has moved `distance`
//! [m], the errors sampled at a quarter, half, three quarters and all of that time.
InterfaceErrors moving_interface(int n, double rho1, double rho2, double p, double u, double distance,
                                 const cip::GasMaterials& mat) {
  const bool left = u > 0;
  cip::GasSolver s = left ? products_tube(n, {rho1, u, p}, {rho2, u, p}, 0.3, false, mat)
                          : products_tube(n, {rho2, u, p}, {rho1, u, p}, 0.7, true, mat);
  const double t_end = distance / std::fabs(u);
  InterfaceErrors e;
  for (int k = 1; k <= 4; ++k) {
    run_to(s, k * t_end / 4, blastsim::test::validation_courant(s.options().transport));
    const cip::HostGasFields h = s.to_host();
    const std::vector<double> pp = strip(h, h.p, Axis::x), uu = strip(h, h.u, Axis::x);
    for (int i = 0; i < n; ++i) {
      e.p = std::max(e.p, std::fabs(pp[i] / p - 1));
      e.u = std::max(e.u, std::fabs(uu[i] / u - 1));
    }
  }
  const cip::HostGasFields h = s.to_host();
  const std::vector<double> alpha = strip(h, h.alpha, Axis::x), rho = strip(h, h.rho, Axis::x);
  for (int i = 0; i < n; ++i)
    e.rho = std::max(e.rho, std::fabs(rho[i] / (alpha[i] * rho1 + (1 - alpha[i]) * rho2) - 1));
  return e;
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
      // the interface crosses 30 % of the tube
      const InterfaceErrors e = moving_interface(200, rho_air * ratio, rho_air, p, u, 0.3, anfo_and_air());
      std::printf("G11 products | air interface moving %s, density ratio %g, %d cells: max |dp/p| %.1e, |du/u| %.1e, "
                  "density against alpha rho1 + (1 - alpha) rho2 %.1e\n",
                  u > 0 ? "right" : "left", ratio, 200, e.p, e.u, e.rho);
      CHECK(e.p <= 1e-6);
      CHECK(e.u <= 1e-6);
      CHECK(e.rho <= 1e-8);  // round-off over about 6000 steps
    }
}

TEST_CASE("G11 the interface at the explosives' own states, density ratios 10 to 1e4, keeps p and u uniform",
          "[long][cip][G11]") {
  // Each preset's products at their constant-volume explosion state (rho0, E0 / rho0: 1.68 GPa for ANFO, 8.38 GPa
  // for TNT) beside air at the same pressure and rho0 / ratio (so air as hot as the pressure requires), the
  // whole tube moving at +-1000 m/s. Exact: the interface is a contact, p and u stay as they were and each
  // cell's density is that of its volume fraction; asserted as in the test above.
  for (const char* preset : {"ANFO", "TNT"}) {
    const cip::JwlParameters jp = cip::EquationOfState::jwl_preset(preset).p;
    const cip::GasMaterials mat = preset_and_air(preset);
    const double rho0 = jp.rho0, p = mat.products.pressure(rho0, cip::chapman_jouguet(jp).detonation_energy / rho0);
    for (double ratio : {10.0, 100.0, 1e3, 1e4})
      for (double u : {1000.0, -1000.0}) {
        // The interface moves 10 cells (0.05 m): the hot air of the larger ratios (sound speed up to 5e5 m/s) sets
        // a step of about 1e-9 s.
        const InterfaceErrors e = moving_interface(200, rho0, rho0 / ratio, p, u, 0.05, mat);
        std::printf("G11 %s products at %.3e Pa | air, interface moving %s, density ratio %g, %d cells: max |dp/p| "
                    "%.1e, |du/u| %.1e, density against alpha rho1 + (1 - alpha) rho2 %.1e\n",
                    preset, p, u > 0 ? "right" : "left", ratio, 200, e.p, e.u, e.rho);
        CHECK(e.p <= 1e-6);
        CHECK(e.u <= 1e-6);
        CHECK(e.rho <= 1e-8);
      }
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
    run_to(s, t, blastsim::test::validation_courant(s.options().transport));
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
    run_to(s, k * t / 10, blastsim::test::validation_courant(s.options().transport));
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
  // Also with the pressure predictor (docs/gas-solver.md "Time centring of the pressure"): its term enters the
  // momentum and the work alike, so the energy identity must hold with it, in mixed cells too.
  const bool predictor = GENERATE(false, true);
  const cip::GasMaterials mat = anfo_and_air();
  const int n = 48;
  auto make = [&] {
    cip::GasSolverOptions opt;
    opt.boundaries = cip::BoundaryConditions::all(cip::BoundaryKind::wall);
    opt.pressure_predictor = predictor;
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
    for (int k = 0; k < steps; ++k) g.step(g.courant_dt(blastsim::test::validation_courant(g.options().transport)));
  };
  advance(s, 100);
  // Checkpoint after 100 steps, then 100 more; a solver restarted from the checkpoint must end identical.
  const std::filesystem::path dir = testing::fresh_dir(predictor ? "two_materials_predictor" : "two_materials");
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
  std::printf("G11 closed box%s, 200 steps: total mass %.1e, products mass %.1e, energy %.1e relative change; "
              "energy added by the positivity bound %.1e J/m\n",
              predictor ? " with the pressure predictor" : " without the pressure predictor", dm, dm1, dE, s.positivity_energy());
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

TEST_CASE("G15 pressure relaxation of a mixed cell: ideal gases in closed form, JWL products to one pressure",
          "[cip][G15]") {
  // Two ideal gases (Gamma_k = gamma_k - 1, no reference curves): with the exchange work P (a_k - a0_k), each
  // material's pressure after relaxation is P = Gamma_k (E_k - P (a_k - a0_k)) / a_k, so
  // a_k = Gamma_k (E_k / P + a0_k) / (1 + Gamma_k); a_1 + a_2 = 1 gives P in closed form:
  //   P = (G1 E1 / (1 + G1) + G2 E2 / (1 + G2)) / (1 - G1 a0 / (1 + G1) - G2 (1 - a0) / (1 + G2)).
  cip::GasMaterials ideal;
  ideal.two = true;
  ideal.air = kAir;
  ideal.products = cip::EquationOfState::ideal(3.0);
  const double G1 = 2.0, G2 = 0.4;
  struct Case {
    double a0, E1, E2;  // [-], [J/m3], [J/m3]
  };
  for (const Case c : {Case{0.3, 1e9, 1e5}, Case{0.7, 1e3, 1e8}, Case{0.01, 5e6, 2e6}, Case{0.999, 2e9, 1e2}}) {
    const double P = (G1 * c.E1 / (1 + G1) + G2 * c.E2 / (1 + G2)) / (1 - G1 * c.a0 / (1 + G1) - G2 * (1 - c.a0) / (1 + G2));
    const double a = G1 * (c.E1 / P + c.a0) / (1 + G1);
    const double got = ideal.relaxed_fraction(c.a0, 1.0, 1.0, c.E1, c.E2);
    std::printf("G15 ideal gases, alpha %.3g, E1 %.3g, E2 %.3g J/m3: relaxed alpha %.15g (closed form %.15g), P %.6e Pa\n",
                c.a0, c.E1, c.E2, got, a, P);
    CHECK_THAT(got, WithinRel(a, 1e-12));
  }

  // JWL products (ANFO) beside air: after relaxation both materials, each on its own equation of state at its
  // own density m_k / a_k and energy E_k - P (a_k - a0_k), hold the mixture's pressure; masses and the total
  // energy are untouched, so the mixture closure GasMaterials::pressure() returns the same P.
  const cip::GasMaterials mat = anfo_and_air();
  struct Mixed {
    double a0, rho1, p1, rho2, p2;  // the two materials' states before relaxation
  };
  for (const Mixed c : {Mixed{0.2, 800.0, 1.68e9, 1.2, 1e5}, Mixed{0.5, 50.0, 1e7, 5.0, 5e7}, Mixed{0.9, 400.0, 3e8, 30.0, 1e6}}) {
    const double m1 = c.a0 * c.rho1, m2 = (1 - c.a0) * c.rho2;
    const double E1 = m1 * mat.products.internal_energy(c.rho1, c.p1), E2 = m2 * mat.air.internal_energy(c.rho2, c.p2);
    const double a = mat.relaxed_fraction(c.a0, m1, m2, E1, E2);
    const double P = mat.pressure(m1 + m2, (E1 + E2) / (m1 + m2), a, m1);
    const double pk1 = mat.products.pressure(m1 / a, (E1 - P * (a - c.a0)) / m1);
    const double pk2 = mat.air.pressure(m2 / (1 - a), (E2 + P * (a - c.a0)) / m2);
    std::printf("G15 ANFO products %.0f kg/m3 at %.3g Pa beside air %.1f kg/m3 at %.3g Pa, alpha %.2f: relaxed alpha %.6f, "
                "P %.6e Pa, products %.6e Pa, air %.6e Pa\n",
                c.rho1, c.p1, c.rho2, c.p2, c.a0, a, P, pk1, pk2);
    CHECK(a != c.a0);
    CHECK_THAT(pk1, WithinRel(P, 1e-9));
    CHECK_THAT(pk2, WithinRel(P, 1e-9));
    // The higher-pressure material expands.
    CHECK((a > c.a0) == (c.p1 > c.p2));
  }
}

namespace {

//! What G15 measures beside the contact of a products | air tube, from one scheme's cell values: the mean pressure
//! over the cells 2 to 10 cells from the exact contact on each side, relative to p*, and each material's own
//! density over the same cells where it holds more than 1e-6 of the volume (the products' m1 / alpha on their side,
//! the air's (rho - m1) / (1 - alpha) on its side), relative to the exact star densities.
struct ContactSides {
  double dp_products = 0, dp_air = 0, drho_products = 0, drho_air = 0;
};
ContactSides contact_sides(const std::vector<double>& rho, const std::vector<double>& p, const std::vector<double>& a,
                           const std::vector<double>& m1, double xc, const MieGruneisenRiemann& exact) {
  const int n = static_cast<int>(rho.size());
  const double trace = 1e-6;
  double p1 = 0, p2 = 0, r1 = 0, r2 = 0;
  int n1 = 0, n2 = 0, k1 = 0, k2 = 0;
  for (int i = 0; i < n; ++i) {
    REQUIRE(std::isfinite(p[i]));
    const double d = ((i + 0.5) / n - xc) * n;  // cells from the exact contact
    if (d <= -2 && d >= -10) {
      p1 += p[i], ++n1;
      if (a[i] > trace) r1 += m1[i] / a[i], ++k1;
    }
    if (d >= 2 && d <= 10) {
      p2 += p[i], ++n2;
      if (a[i] < 1 - trace) r2 += (rho[i] - m1[i]) / (1 - a[i]), ++k2;
    }
  }
  REQUIRE(k1 > 0);
  REQUIRE(k2 > 0);
  return {p1 / n1 / exact.p_star() - 1, p2 / n2 / exact.p_star() - 1, r1 / k1 / exact.rho_star_left() - 1,
          r2 / k2 / exact.rho_star_right() - 1};
}

}  // namespace

TEST_CASE("G15 products | air tubes at density ratios 10 to 1e4: the pressure on each side of the contact and the "
          "phase densities, beside the five-equation reference",
          "[long][cip][G15]") {
  // Each preset's products at their constant-volume explosion state (rho0, E0 / rho0: a fully coupled charge)
  // left of x0 = 0.4, air at rho0 / ratio and 2.1e5 J/kg (293 K) right of it; outflow ends. Against the exact
  // two-material Riemann solution (mie_gruneisen_riemann.hpp) at the time the fastest wave is 0.05 m from an end,
  // and beside the textbook scheme for the same materials on the same grid (five_equation_hllc.hpp: Kapila's
  // five-equation model, MUSCL-Hancock/HLLC, Courant 0.8). Measured (contact_sides()): the pressure and each
  // material's own density 2 to 10 cells either side of the exact contact. Asserted on 800 and 1600 cells:
  // - ratios 10 to 1000: the pressure on each side within 1 % of p*;
  // - ratio 1e4: the pressure error on each side within 1.5 times the reference's (G9's bound); the ratio 1e4 also
  //   on 3200 cells and every ratio on 400 cells reported;
  // - ratios 10 to 1000: each phase density's error within 1.5 times the reference's (at 1e4 reported). The target
  //   is 2 %; neither textbook scheme gives it there (docs/gas-solver.md, "Phase densities beside the contact").
  // Reported: the products' density in the mixed cells (0.01 < alpha < 0.99), largest deviation from rho1*.
  for (const char* preset : {"ANFO", "TNT"}) {
    const cip::JwlParameters jp = cip::EquationOfState::jwl_preset(preset).p;
    const cip::GasMaterials mat = preset_and_air(preset);
    const double rho0 = jp.rho0, E0 = cip::chapman_jouguet(jp).detonation_energy;  // [kg/m3], [J/m3]
    const Primitive L{rho0, 0.0, mat.products.pressure(rho0, E0 / rho0)};
    for (double ratio : {10.0, 100.0, 1e3, 1e4}) {
      const double rho_air = rho0 / ratio;
      const Primitive R{rho_air, 0.0, mat.air.pressure(rho_air, 2.1e5)};
      const MieGruneisenRiemann exact(mat.products, L, mat.air, R);
      const double x0 = 0.4;
      const double t = std::fmin((x0 - 0.05) / -exact.leftmost_speed(), (0.95 - x0) / exact.rightmost_speed());
      const double xc = x0 + exact.u_star() * t;
      for (int n : {400, 800, 1600, 3200}) {
        if (n > 1600 && ratio < 1e4) continue;  // the ratio 1e4 also on 3200 cells (reported: convergence)
        cip::GasSolver s = products_tube(n, L, R, x0, false, mat);
        run_to(s, t, blastsim::test::validation_courant(s.options().transport));
        const cip::HostGasFields h = s.to_host();
        const std::vector<double> rho = strip(h, h.rho, Axis::x), p = strip(h, h.p, Axis::x),
                                  a = strip(h, h.alpha, Axis::x), Y = strip(h, h.traced, Axis::x);
        std::vector<double> m1(n);
        double rho1_worst = 0;
        for (int i = 0; i < n; ++i) {
          m1[i] = Y[i] * rho[i];
          if (a[i] > 0.01 && a[i] < 0.99)
            rho1_worst = std::max(rho1_worst, std::fabs(m1[i] / a[i] / exact.rho_star_left() - 1));
        }
        const ContactSides ours = contact_sides(rho, p, a, m1, xc, exact);
        FiveEquationHllc five(n, 1.0, x0, L, R, mat);
        five.run_to(t);
        std::vector<double> rho_r(n), p_r(n), a_r(n), m1_r(n);
        for (int i = 0; i < n; ++i)
          rho_r[i] = five.density(i), p_r[i] = five.pressure(i), a_r[i] = five.alpha(i), m1_r[i] = five.m1(i);
        const ContactSides ref = contact_sides(rho_r, p_r, a_r, m1_r, xc, exact);
        // With BLASTSIM_FIGURE_DIR set, the profiles against the exact solution.
        if (const char* dir = std::getenv("BLASTSIM_FIGURE_DIR")) {
          const std::vector<double> u = strip(h, h.u, Axis::x);
          std::ofstream out(std::string(dir) + "/g15_" + preset + "_" + std::to_string(static_cast<int>(ratio)) + "_" +
                            std::to_string(n) + ".csv");
          out << "x_m,rho,rho_exact,p_Pa,p_exact,u_m_per_s,u_exact,alpha,traced,t_s,rho_five_eq,alpha_five_eq\n";
          for (int i = 0; i < n; ++i) {
            const double x = (i + 0.5) / n;
            const Primitive e = exact.sample((x - x0) / t);
            out << x << "," << rho[i] << "," << e.rho << "," << p[i] << "," << e.p << "," << u[i] << "," << e.u << ","
                << a[i] << "," << Y[i] << "," << t << "," << rho_r[i] << "," << a_r[i] << "\n";
          }
        }
        std::printf("G15 %s products into air, density ratio %g, %d cells: p* %.4e Pa; pressure beside the contact, "
                    "products side %+.2f %% (five-equation reference %+.2f %%), air side %+.2f %% (%+.2f %%); phase "
                    "densities there: products %+.2f %% (%+.2f %%) of rho1* %.4g kg/m3, air %+.2f %% (%+.2f %%) of "
                    "rho2* %.4g kg/m3; products density in mixed cells up to %.1f %% from rho1*\n",
                    preset, ratio, n, exact.p_star(), 100 * ours.dp_products, 100 * ref.dp_products, 100 * ours.dp_air,
                    100 * ref.dp_air, 100 * ours.drho_products, 100 * ref.drho_products, exact.rho_star_left(),
                    100 * ours.drho_air, 100 * ref.drho_air, exact.rho_star_right(), 100 * rho1_worst);
        if (n != 800 && n != 1600) continue;
        if (ratio <= 1e3) {
          CHECK(std::fabs(ours.dp_products) <= 0.01);
          CHECK(std::fabs(ours.dp_air) <= 0.01);
          CHECK(std::fabs(ours.drho_products) <= 1.5 * std::fabs(ref.drho_products));
          CHECK(std::fabs(ours.drho_air) <= 1.5 * std::fabs(ref.drho_air));
        } else {
          CHECK(std::fabs(ours.dp_products) <= 1.5 * std::fabs(ref.dp_products));
          CHECK(std::fabs(ours.dp_air) <= 1.5 * std::fabs(ref.dp_air));
        }
      }
    }
  }
}

TEST_CASE("G15 the five-equation reference: one material on both sides gives MUSCL-Hancock's Sod tube, a moving "
          "products | air interface keeps its pressure",
          "[cip][G15]") {
  // The reference of the test above checked on cases with known answers. (a) Air on both sides of its two materials
  // is one ideal gas: on Sod's tube (Toro's test 1, t = 0.25) the density L1 against the exact solution within 5 %
  // of the one-gas MUSCL-Hancock/HLLC reference's (muscl_hancock.hpp; the two differ only in the variables they
  // limit) on 100 to 800 cells. (b) ANFO products (300 kg/m3) | air (0.3 kg/m3) at 2e8 Pa, moving at 1000 m/s
  // across 30 % of a 200-cell tube: the pressure stays uniform to round-off (1e-12).
  cip::GasMaterials air_air;
  air_air.air = air_air.products = kAir;
  air_air.two = true;
  const Primitive L{1.0, 0.0, 1.0}, R{0.125, 0.0, 0.1};
  const ExactRiemann exact(L, R, 1.4);
  for (int n : {100, 200, 400, 800}) {
    FiveEquationHllc five(n, 1.0, 0.5, L, R, air_air);
    five.run_to(0.25);
    MusclHancock mh(n, 1.0, 0.5, L, R, 1.4);
    mh.run_to(0.25);
    double l1 = 0, l1_mh = 0;
    for (int i = 0; i < n; ++i) {
      const double e = exact.sample(((i + 0.5) / n - 0.5) / 0.25).rho;
      l1 += std::fabs(five.density(i) - e) / n;
      l1_mh += std::fabs(mh.density(i) - e) / n;
    }
    std::printf("G15 five-equation reference, air | air Sod tube, %d cells: density L1 %.4e (MUSCL-Hancock %.4e)\n", n,
                l1, l1_mh);
    CHECK_THAT(l1, WithinRel(l1_mh, 0.05));
  }
  const double p = 2e8, u = 1000.0;
  FiveEquationHllc moving(200, 1.0, 0.3, {300.0, u, p}, {0.3, u, p}, anfo_and_air());
  moving.run_to(0.3 / u);
  double dp = 0;
  for (int i = 0; i < 200; ++i) dp = std::max(dp, std::fabs(moving.pressure(i) / p - 1));
  std::printf("G15 five-equation reference, moving products | air interface: max |dp/p| %.1e\n", dp);
  CHECK(dp <= 1e-12);
}

TEST_CASE("G15 one gas at density ratios of 1e3 and 1e4: the star pressure against the exact solution, beside "
          "MUSCL-Hancock",
          "[long][cip][G15]") {
  // The tubes of the test above at ratios 1e3 and 1e4 with one ideal gas (gamma 1.4) on both sides: 800 kg/m3 at
  // 1.678 GPa (ANFO's constant-volume pressure) left of x0 = 0.4, 800 / ratio kg/m3 at 2.1e5 J/kg right of it,
  // until the exact shock is at 0.9 m. The error of a scheme here is that of the strong expansion and of the
  // contact behind the strong shock, without mixed cells: the size of error that G15's two-material tubes carry
  // at the same ratio whatever their mixed-cell treatment. Measured: the mean pressure over the air's star region
  // (0.02 m inside the exact contact and shock) against the exact p*, and the relative density L1, for blastsim's
  // default step and for the textbook MUSCL-Hancock/HLLC reference (muscl_hancock.hpp, Courant 0.9) on the same
  // grid. Asserted on 800 and 1600 cells: each within 1.5 times the reference's (G9's bound); 400 cells reported.
  // Reported: the expanded gas's density 2 to 10 cells behind the contact (G15's band), both schemes.
  for (double ratio : {1e3, 1e4}) {
    const double gamma = 1.4, rho_right = 800.0 / ratio;
    const Primitive L{800.0, 0.0, 1.678e9}, R{rho_right, 0.0, (gamma - 1) * rho_right * 2.1e5};
    const ExactRiemann exact(L, R, gamma);
    const double x0 = 0.4, t = 0.5 / exact.right_shock_speed();
    const double x_contact = x0 + exact.u_star() * t, x_shock = x0 + exact.right_shock_speed() * t;
    for (int n : {400, 800, 1600}) {
      cip::GasSolver s = make_shock_tube(n, Axis::x, L, R, x0, 1.0, gamma);
      run_to(s, t, blastsim::test::validation_courant(s.options().transport));
      const cip::HostGasFields h = s.to_host();
      const std::vector<double> rho = strip(h, h.rho, Axis::x), p = strip(h, h.p, Axis::x);
      MusclHancock ref(n, 1.0, x0, L, R, gamma);
      ref.run_to(t);
      double p_sum = 0, p_ref = 0, l1 = 0, l1_ref = 0, norm = 0, layer = 0, layer_ref = 0;
      int count = 0, n_layer = 0;
      for (int i = 0; i < n; ++i) {
        const double x = (i + 0.5) / n, rho_exact = exact.sample((x - x0) / t).rho;
        l1 += std::fabs(rho[i] - rho_exact);
        l1_ref += std::fabs(ref.density(i) - rho_exact);
        norm += rho_exact;
        if (x > x_contact + 0.02 && x < x_shock - 0.02) p_sum += p[i], p_ref += ref.pressure(i), ++count;
        // The expanded gas 2 to 10 cells behind the contact (G15's band): the start-up's entropy layer.
        const double d = (x - x_contact) * n;
        if (d <= -2 && d >= -10) layer += rho[i], layer_ref += ref.density(i), ++n_layer;
      }
      REQUIRE(count > 10);
      const double dp = p_sum / count / exact.p_star() - 1, dp_ref = p_ref / count / exact.p_star() - 1;
      const double rho_left = exact.sample((x_contact - 1e-9 - x0) / t).rho;
      std::printf("G15 one gas, density ratio %g, %d cells: air's star pressure %+.2f %% (MUSCL-Hancock %+.2f %%) of "
                  "p* %.4e Pa; relative density L1 %.3e (MUSCL-Hancock %.3e); the expanded gas's density 2-10 cells "
                  "behind the contact %+.2f %% (MUSCL-Hancock %+.2f %%) of %.4g kg/m3\n",
                  ratio, n, 100 * dp, 100 * dp_ref, exact.p_star(), l1 / norm, l1_ref / norm,
                  100 * (layer / n_layer / rho_left - 1), 100 * (layer_ref / n_layer / rho_left - 1), rho_left);
      if (n >= 800) {
        CHECK(std::fabs(dp) <= 1.5 * std::fabs(dp_ref));
        CHECK(l1 <= 1.5 * l1_ref);
      }
    }
  }
}
