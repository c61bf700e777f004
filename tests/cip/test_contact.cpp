//! \file test_contact.cpp
//! \brief docs/validation.md G8-G9: contact discontinuities stay monotone with uniform pressure and velocity; Toro's
//! Riemann tests 1, 2, 4, 5 against a MUSCL-Hancock/HLLC reference on the same grid; Sod's order of convergence.
#include "catch.hpp"
#include "validation_courant.hpp"
#include "gas_cases.hpp"
#include "muscl_hancock.hpp"

#include <algorithm>

using namespace blastsim;
using namespace blastsim::test;

namespace {

struct ContactError {
  double p_rel = 0, u_rel = 0;  // largest |p/p0 - 1|, |u/u0 - 1| over the tube
  double over = 0, under = 0;   // density above the larger / below the smaller initial value, by the jump
};

//! A contact between densities rho_l and rho_r at p = 2.466, u = 1.528 (G8's data) in a tube of n cells,
//! x0 = 0.3, run with the driver's default scheme; the worst errors seen at four times up to t = 0.14.
ContactError advect_contact(int n, double rho_l, double rho_r, cip::Transport transport = cip::Transport::conservative) {
  const double p = 2.466, u = 1.528;
  cip::GasSolverOptions opt;
  opt.transport = transport;
  opt.viscosity = cip::recommended_viscosity(transport);
  cip::GasSolver s = make_shock_tube(n, Axis::x, {rho_l, u, p}, {rho_r, u, p}, 0.3, 1.0, 1.4, opt);
  const double lo = std::min(rho_l, rho_r), hi = std::max(rho_l, rho_r), jump = hi - lo;
  ContactError worst;
  for (double t : {0.01, 0.035, 0.07, 0.14}) {
    run_to(s, t, blastsim::test::validation_courant(s.options().transport));
    const cip::HostGasFields h = s.to_host();
    const std::vector<double> rho = strip(h, h.rho, Axis::x), pp = strip(h, h.p, Axis::x), uu = strip(h, h.u, Axis::x);
    for (int i = 0; i < n; ++i) {
      worst.p_rel = std::max(worst.p_rel, std::fabs(pp[i] / p - 1));
      worst.u_rel = std::max(worst.u_rel, std::fabs(uu[i] / u - 1));
      worst.over = std::max(worst.over, (rho[i] - hi) / jump);
      worst.under = std::max(worst.under, (lo - rho[i]) / jump);
    }
  }
  return worst;
}

//! Density L1 error (mean over the unit tube) of a Riemann problem at time t, diaphragm at x0, with n cells.
double blastsim_l1(int n, const Primitive& L, const Primitive& R, double x0, double t,
                   cip::Transport transport = cip::Transport::conservative) {
  cip::GasSolverOptions opt;
  opt.transport = transport;
  opt.viscosity = cip::recommended_viscosity(transport);
  cip::GasSolver s = make_shock_tube(n, Axis::x, L, R, x0, 1.0, 1.4, opt);
  run_to(s, t, blastsim::test::validation_courant(s.options().transport));
  const ExactRiemann exact(L, R, 1.4);
  const cip::HostGasFields h = s.to_host();
  const std::vector<double> rho = strip(h, h.rho, Axis::x);
  double err = 0;
  for (int i = 0; i < n; ++i) err += std::fabs(rho[i] - exact.sample(((i + 0.5) / n - x0) / t).rho);
  return err / n;
}

double reference_l1(int n, const Primitive& L, const Primitive& R, double x0, double t) {
  MusclHancock m(n, 1.0, x0, L, R, 1.4);
  m.run_to(t);
  const ExactRiemann exact(L, R, 1.4);
  double err = 0;
  for (int i = 0; i < n; ++i) err += std::fabs(m.density(i) - exact.sample(((i + 0.5) / n - x0) / t).rho);
  return err / n;
}

}  // namespace

TEST_CASE("G8 contact discontinuity: uniform p and u stay uniform, density stays within its data", "[long][cip][G8]") {
  const double rho0 = 0.345;
  for (double ratio : {10.0, 1000.0}) {
    for (bool dense_upstream : {false, true}) {
      for (int n : {100, 200, 400, 800}) {
        const double rl = dense_upstream ? rho0 * ratio : rho0, rr = dense_upstream ? rho0 : rho0 * ratio;
        const ContactError e = advect_contact(n, rl, rr);
        std::printf("G8 contact ratio %g, %s upstream, %d cells: max |dp/p| %.1e, |du/u| %.1e, density over %.2e, "
                    "under %.2e of the jump\n",
                    ratio, dense_upstream ? "dense" : "light", n, e.p_rel, e.u_rel, e.over, e.under);
        CHECK(e.p_rel <= 1e-10);
        CHECK(e.u_rel <= 1e-10);
        CHECK(e.over <= 0.01);
        CHECK(e.under <= 0.01);
      }
    }
  }
  // The paper's transport, for the table in docs/gas-solver.md (reported, not checked).
  for (double ratio : {10.0, 1000.0}) {
    const ContactError e = advect_contact(400, rho0, rho0 * ratio, cip::Transport::paper);
    std::printf("G8 paper transport: contact ratio %g, light upstream, 400 cells: max |dp/p| %.1e, |du/u| %.1e, density "
                "over %.2e, under %.2e of the jump\n",
                ratio, e.p_rel, e.u_rel, e.over, e.under);
  }
}

TEST_CASE("G9 Toro's Riemann tests 1, 2, 4, 5: density L1 within 1.5 x MUSCL-Hancock/HLLC on 400 cells",
          "[long][cip][G9]") {
  // Toro (2009), Table 4.1, gamma = 1.4, diaphragm at 0.5 of the unit tube, output times of sec. 4.3.3.
  struct Case {
    int number;
    Primitive L, R;
    double t;
  };
  const Case cases[] = {{1, {1.0, 0.0, 1.0}, {0.125, 0.0, 0.1}, 0.25},
                        {2, {1.0, -2.0, 0.4}, {1.0, 2.0, 0.4}, 0.15},
                        {4, {1.0, 0.0, 0.01}, {1.0, 0.0, 100.0}, 0.035},
                        {5, {5.99924, 19.5975, 460.894}, {5.99242, -6.19633, 46.0950}, 0.035}};
  for (const Case& c : cases) {
    const double ours = blastsim_l1(400, c.L, c.R, 0.5, c.t), ref = reference_l1(400, c.L, c.R, 0.5, c.t);
    std::printf("G9 Toro test %d, 400 cells: density L1 %.3e (blastsim) %.3e (MUSCL-Hancock HLLC minmod), ratio %.2f\n",
                c.number, ours, ref, ours / ref);
    CHECK(ours <= 1.5 * ref);
    // The paper's transport, reported for docs/gas-solver.md.
    try {
      std::printf("G9 Toro test %d, 400 cells, paper transport: density L1 %.3e\n", c.number,
                  blastsim_l1(400, c.L, c.R, 0.5, c.t, cip::Transport::paper));
    } catch (const std::runtime_error& e) {
      std::printf("G9 Toro test %d, 400 cells, paper transport: %s\n", c.number, e.what());
    }
  }
}

TEST_CASE("G9 Toro's test 2: the specific internal energy of the near-vacuum centre within 1.5 x MUSCL-Hancock/HLLC",
          "[cip][G9]") {
  // Toro (2009), Table 4.1, test 2 (two rarefactions, 400 cells, t = 0.15): the centre empties to rho* = 0.0219
  // at p* = 0.00189, so its exact specific internal energy e* = p* / ((gamma - 1) rho*) is a fifth of the data's.
  // The kinetic energy the transport removes from the faces beside the centre becomes heat there; shared by
  // volume it gave the nearly empty cells as much as their dense neighbours (docs/gas-solver.md, "Troubled
  // cells"). Bound: the L1 error of e over the star region (between the rarefactions' tails) within G9's 1.5 x
  // that of the MUSCL-Hancock/HLLC reference on the same grid.
  const Primitive L{1.0, -2.0, 0.4}, R{1.0, 2.0, 0.4};
  const int n = 400;
  const double t = 0.15, gamma = 1.4, x0 = 0.5;
  const ExactRiemann exact(L, R, gamma);
  cip::GasSolverOptions opt;
  opt.viscosity = cip::recommended_viscosity(cip::Transport::conservative);
  cip::GasSolver s = make_shock_tube(n, Axis::x, L, R, x0, 1.0, gamma, opt);
  run_to(s, t, blastsim::test::validation_courant(s.options().transport));
  const cip::HostGasFields h = s.to_host();
  const std::vector<double> e = strip(h, h.e, Axis::x);
  MusclHancock m(n, 1.0, x0, L, R, gamma);
  m.run_to(t);
  // The star region: |x - x0| / t below the tails' speed u* - c* (right) and its mirror (left).
  const Primitive star = exact.sample(0.0);
  const double tail = std::fabs(std::fabs(star.u) - std::sqrt(gamma * star.p / star.rho));
  double ours = 0, ref = 0, ours_max = 0;
  int cells = 0;
  for (int i = 0; i < n; ++i) {
    const double xi = ((i + 0.5) / n - x0) / t;
    if (std::fabs(xi) >= tail) continue;
    const Primitive w = exact.sample(xi);
    const double e_exact = w.p / ((gamma - 1) * w.rho);
    ours += std::fabs(e[i] - e_exact);
    ref += std::fabs(m.internal_energy(i) - e_exact);
    ours_max = std::max(ours_max, e[i] / e_exact);
    ++cells;
  }
  ours /= cells, ref /= cells;
  std::printf("G9 Toro test 2, 400 cells, star region (%d cells, exact e* = %.4f J/kg): L1(e) %.3e (blastsim) %.3e "
              "(MUSCL-Hancock HLLC minmod), ratio %.2f; largest e / e* %.2f\n",
              cells, star.p / ((gamma - 1) * star.rho), ours, ref, ours / ref, ours_max);
  CHECK(cells > 0);
  CHECK(ours <= 1.5 * ref);
}

TEST_CASE("G9 Sod: density L1 falls at order >= 0.8 from 200 to 1600 cells", "[long][cip][G9]") {
  const Primitive L{1.0, 0.0, 1.0}, R{0.125, 0.0, 0.1};
  const double e200 = blastsim_l1(200, L, R, 0.5, 0.2), e1600 = blastsim_l1(1600, L, R, 0.5, 0.2);
  const double order = std::log2(e200 / e1600) / 3;
  const double r200 = reference_l1(200, L, R, 0.5, 0.2), r1600 = reference_l1(1600, L, R, 0.5, 0.2);
  std::printf("G9 Sod order: L1(rho) %.3e (200) %.3e (1600) cells, order %.3f; MUSCL-Hancock HLLC minmod %.3e / %.3e, "
              "order %.3f\n",
              e200, e1600, order, r200, r1600, std::log2(r200 / r1600) / 3);
  CHECK(order >= 0.8);
}
TEST_CASE("G16 contacts born in shock tubes: density within 2 % of the jump beyond the two star densities",
          "[cip][G16][heavy]") {
  // Toro (2009), Table 4.1, tests 1, 3, 4, 5 (test 2 has no density jump at its contact), Lax's tube (Lax 1954;
  // unit tube, diaphragm at 0.5, t = 0.14) and Sod's tube at 100 : 1 in density and pressure; 400 cells. A
  // contact that forms from the Riemann problem separates the exact star densities rho*_L and rho*_R; within
  // 15 cells of the exact contact x0 + u* t no cell may lie more than 2 % of |rho*_R - rho*_L| above the larger
  // or below the smaller (the MUSCL-Hancock/HLLC reference of G9 stays within 0.2 %).
  struct Case {
    const char* name;
    Primitive L, R;
    double t;
  };
  const Case cases[] = {{"Toro 1 (Sod)", {1.0, 0.0, 1.0}, {0.125, 0.0, 0.1}, 0.25},
                        {"Toro 3", {1.0, 0.0, 1000.0}, {1.0, 0.0, 0.01}, 0.012},
                        {"Toro 4", {1.0, 0.0, 0.01}, {1.0, 0.0, 100.0}, 0.035},
                        {"Toro 5", {5.99924, 19.5975, 460.894}, {5.99242, -6.19633, 46.0950}, 0.035},
                        {"Lax", {0.445, 0.698, 3.528}, {0.5, 0.0, 0.571}, 0.14},
                        {"Sod 100:1", {1.0, 0.0, 1.0}, {0.01, 0.0, 0.01}, 0.2}};
  const int n = 400;
  for (const Case& c : cases) {
    cip::GasSolverOptions opt;
    opt.viscosity = cip::recommended_viscosity(cip::Transport::conservative);
    cip::GasSolver s = make_shock_tube(n, Axis::x, c.L, c.R, 0.5, 1.0, 1.4, opt);
    run_to(s, c.t, blastsim::test::validation_courant(s.options().transport));
    const ExactRiemann exact(c.L, c.R, 1.4);
    const cip::HostGasFields h = s.to_host();
    const std::vector<double> rho = strip(h, h.rho, Axis::x);
    const double lo = std::min(exact.rho_star_left(), exact.rho_star_right());
    const double hi = std::max(exact.rho_star_left(), exact.rho_star_right()), jump = hi - lo;
    const double xc = 0.5 + exact.u_star() * c.t;
    double over = 0, under = 0;
    for (int i = 0; i < n; ++i) {
      if (std::fabs((i + 0.5) / n - xc) > 15.0 / n) continue;
      over = std::max(over, (rho[i] - hi) / jump);
      under = std::max(under, (lo - rho[i]) / jump);
    }
    MusclHancock m(n, 1.0, 0.5, c.L, c.R, 1.4);
    m.run_to(c.t);
    double ref = 0;
    for (int i = 0; i < n; ++i)
      if (std::fabs((i + 0.5) / n - xc) <= 15.0 / n)
        ref = std::max({ref, (m.density(i) - hi) / jump, (lo - m.density(i)) / jump});
    std::printf("G16 %-12s 400 cells: star densities %.4g | %.4g; above %.2f %%, below %.2f %% of the jump "
                "(MUSCL-Hancock HLLC minmod: %.2f %%)\n",
                c.name, exact.rho_star_left(), exact.rho_star_right(), 100 * over, 100 * under, 100 * ref);
    CHECK(over <= 0.02);
    CHECK(under <= 0.02);
  }
}
