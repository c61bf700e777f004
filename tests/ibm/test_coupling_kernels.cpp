//! \file test_coupling_kernels.cpp
//! \brief The coupling kernels (coupling_step_kernels.hpp) called directly on a few cells of host arrays: the
//! gas moved between cells that change state, and the work a crack's gas does on its walls.
#include "blastsim/ibm/coupling_step_kernels.hpp"
#include "catch.hpp"

#include <cmath>
#include <cstdio>
#include <vector>

using namespace blastsim;

namespace {
//! A small grid's cell arrays on the host (rho, e, u, v, masks, outputs, ledger).
struct Patch {
  static constexpr int n = 5;
  PaddedShape shape{n + 1, n + 1, 2};
  std::vector<double> rho, e, u, v, rho_next, e_next, ledger;
  std::vector<std::uint8_t> old_active, new_active, changed;
  Patch()
      : rho(shape.size(), 0.0), e(shape.size(), 0.0), u(shape.size(), 0.0), v(shape.size(), 0.0),
        rho_next(shape.size(), 0.0), e_next(shape.size(), 0.0), ledger(4 * n * n, 0.0), old_active(shape.size(), 1),
        new_active(shape.size(), 1), changed(shape.size(), 0) {
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) rho[shape.offset(i, j)] = 1.0 + 0.1 * i + 0.01 * j, e[shape.offset(i, j)] = 2e5 + 1e3 * j;
  }
  template <class T>
  Field2D<const T> in(const std::vector<T>& a) const { return {a.data(), shape}; }
  template <class T>
  Field2D<T> out(std::vector<T>& a) { return {a.data(), shape}; }
  void run(double area, double rho_ambient, double e_ambient) {
    const ibm::TransitionKernel k{in(old_active), in(new_active), in(rho), in(e), in(u), in(v), out(rho_next),
                                  out(e_next), false, cip::MaterialReadView{}, cip::MaterialView{}, out(changed),
                                  ledger.data(), n, n, area, rho_ambient, e_ambient, false};
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) k(i, j);
  }
  //! Mass and internal energy per unit depth of the cells active in `mask`, from (r, s).
  std::array<double, 2> totals(const std::vector<std::uint8_t>& mask, const std::vector<double>& r,
                               const std::vector<double>& s, double area) const {
    std::array<double, 2> t{0, 0};
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        if (mask[shape.offset(i, j)]) t[0] += r[shape.offset(i, j)] * area, t[1] += r[shape.offset(i, j)] * s[shape.offset(i, j)] * area;
    return t;
  }
};
}  // namespace

TEST_CASE("Coupling kernels: a covered cell hands its gas to its neighbours, mass and energy kept exactly",
          "[ibm][kernels][transitions]") {
  // Gas at rest (no face kinetic energy): the covered cell's mass and internal energy go in equal shares to
  // its four edge neighbours that stay active, so the totals over the active cells do not change.
  Patch p;
  const double area = 1e-4;
  p.new_active[p.shape.offset(2, 2)] = 0;
  const std::array<double, 2> before = p.totals(p.old_active, p.rho, p.e, area);
  p.run(area, 1.2, 2.09e5);
  const std::array<double, 2> after = p.totals(p.new_active, p.rho_next, p.e_next, area);
  CHECK_THAT(after[0], Catch::Matchers::WithinRel(before[0], 1e-14));
  CHECK_THAT(after[1], Catch::Matchers::WithinRel(before[1], 1e-14));
  // Each of the four neighbours got a quarter of the covered cell's mass.
  const double given = p.rho[p.shape.offset(2, 2)];
  CHECK_THAT(p.rho_next[p.shape.offset(1, 2)], Catch::Matchers::WithinRel(p.rho[p.shape.offset(1, 2)] + 0.25 * given, 1e-14));
  CHECK_THAT(p.rho_next[p.shape.offset(2, 3)], Catch::Matchers::WithinRel(p.rho[p.shape.offset(2, 3)] + 0.25 * given, 1e-14));
  CHECK(p.rho_next[p.shape.offset(0, 0)] == p.rho[p.shape.offset(0, 0)]);  // far cells untouched
  // The covered cell holds the ambient state; the ledger counts one covered cell and creates nothing.
  CHECK(p.rho_next[p.shape.offset(2, 2)] == 1.2);
  double covered = 0, mass_created = 0;
  for (int c = 0; c < Patch::n * Patch::n; ++c) covered += p.ledger[4 * c], mass_created += p.ledger[4 * c + 2];
  CHECK(covered == 1.0);
  CHECK(mass_created == 0.0);
}

TEST_CASE("Coupling kernels: an uncovered cell starts from the ambient state and the ledger counts it",
          "[ibm][kernels][transitions]") {
  Patch p;
  const double area = 1e-4, rho_amb = 1.2, e_amb = 2.09e5;
  p.old_active[p.shape.offset(3, 1)] = 0;
  p.run(area, rho_amb, e_amb);
  CHECK(p.rho_next[p.shape.offset(3, 1)] == rho_amb);
  CHECK(p.e_next[p.shape.offset(3, 1)] == e_amb);
  const int c = 1 * Patch::n + 3;
  CHECK(p.ledger[4 * c + 1] == 1.0);
  CHECK_THAT(p.ledger[4 * c + 2], Catch::Matchers::WithinRel(rho_amb * area, 1e-15));
  CHECK_THAT(p.ledger[4 * c + 3], Catch::Matchers::WithinRel(rho_amb * e_amb * area, 1e-15));
  // Its neighbours keep their gas: the gas flows in through the solver, not by the transition.
  CHECK(p.rho_next[p.shape.offset(2, 1)] == p.rho[p.shape.offset(2, 1)]);
}

TEST_CASE("Coupling kernels: a crack's gas does p dV on its walls, and never more than keeps it positive",
          "[ibm][kernels][crack]") {
  // An ideal gas (gamma 1.4) at rest in a segment: 1e-3 kg/m at 2e5 J/kg in V0 = 1e-5 m2/m, so U = 200 J/m and
  // p = 0.4 rho e = 8e6 Pa. A small opening (1 %): the explicit work p dV exactly. An opening to 10 times the
  // volume, where p dV = 7.2e2 J/m would exceed U: the isentropic expansion's work U (1 - (V0 / V1)^(gamma - 1)),
  // exact for an ideal gas, with U after it U (V0 / V1)^0.4 > 0. Compression is not limited.
  const ibm::ChannelConserved c{1e-3, 0.0, 200.0, 0.0, 0.0};
  const double V0 = 1e-5, p = 0.4 * (1e-3 / V0) * 2e5;
  CHECK_THAT(ibm::expansion_work(c, p, V0, 1.01 * V0), Catch::Matchers::WithinRel(p * 0.01 * V0, 1e-14));
  CHECK_THAT(ibm::expansion_work(c, p, V0, 0.5 * V0), Catch::Matchers::WithinRel(-p * 0.5 * V0, 1e-14));
  const double W = ibm::expansion_work(c, p, V0, 10 * V0);
  std::printf("crack expansion: p dV %.4e J/m, work taken %.6e J/m (isentropic %.6e J/m), internal energy left %.4e J/m\n",
              p * 9 * V0, W, 200.0 * (1 - std::pow(0.1, 0.4)), 200.0 - W);
  CHECK_THAT(W, Catch::Matchers::WithinRel(200.0 * (1 - std::pow(0.1, 0.4)), 1e-12));
  CHECK(200.0 - W > 0.0);
  // Moving gas: only its internal energy E - q^2 / 2m counts.
  const ibm::ChannelConserved moving{1e-3, 1e-3 * 300.0, 200.0 + 0.5 * 1e-3 * 300.0 * 300.0, 0.0, 0.0};
  CHECK_THAT(ibm::expansion_work(moving, p, V0, 10 * V0), Catch::Matchers::WithinRel(W, 1e-12));
}
