//! \file test_eos.cpp
//! \brief docs/validation.md G10: the JWL equation of state of detonation products against its closed forms (principal
//! isentrope, ideal-gas limit, sound speed as the isentropic derivative) and its parameter checks.
#include "blastsim/cip/eos.hpp"
#include "blastsim/core/error.hpp"
#include "catch.hpp"
#include "isentrope.hpp"

#include <cmath>
#include <cstdio>
#include <string>

using namespace blastsim;

using test::isentrope_energy_at;

TEST_CASE("G10 JWL products: isentrope, ideal-gas limit, sound speed, inverse", "[cip][G10][eos]") {
  for (const cip::JwlPreset& preset : cip::kJwlPresets) {
    const cip::EquationOfState eos = cip::EquationOfState::jwl_products(preset.p);
    const cip::JwlParameters& j = preset.p;
    // Along the principal isentrope the JWL pressure at rho0/V with the isentrope's energy E_s(V)/rho0 is
    // p_s(V): the closed forms of the isentrope and of p(rho, e) agree.
    for (double V : {0.8, 1.0, 2.0, 7.0}) {
      const double rho = j.rho0 / V, e = j.isentrope_energy(V) / j.rho0;
      CHECK_THAT(eos.pressure(rho, e), WithinRel(j.isentrope_pressure(V), 1e-12));
    }
    // Far expanded (V = 200) the products are an ideal gas with gamma = 1 + w.
    const double rho_far = j.rho0 / 200, e_far = 1e5;
    const double gamma_far = 1 + eos.pressure(rho_far, e_far) / (rho_far * e_far);
    const double c_far = eos.sound_speed(rho_far, e_far);
    CHECK_THAT(gamma_far, WithinRel(1 + j.omega, 1e-9));
    CHECK_THAT(c_far * c_far, WithinRel((1 + j.omega) * eos.pressure(rho_far, e_far) / rho_far, 1e-9));
    // c^2 = (dp/drho) along an isentrope: central difference over +-1e-4 rho, the isentrope integrated by RK4, at
    // states on and off the principal isentrope (a shocked, hotter state: 1.5 times its energy).
    double worst = 0;
    for (double V : {1.0, 3.0, 20.0}) {
      for (double heat : {1.0, 1.5}) {
        const double rho = j.rho0 / V, e = heat * j.isentrope_energy(V) / j.rho0, d = 1e-4 * rho;
        const double p_hi = eos.pressure(rho + d, isentrope_energy_at(eos, rho, e, rho + d));
        const double p_lo = eos.pressure(rho - d, isentrope_energy_at(eos, rho, e, rho - d));
        const double c = eos.sound_speed(rho, e);
        const double rel = std::fabs((p_hi - p_lo) / (2 * d) / (c * c) - 1);
        worst = std::fmax(worst, rel);
        CHECK(rel <= 1e-6);
        // The inverse e(rho, p).
        CHECK_THAT(eos.internal_energy(rho, eos.pressure(rho, e)), WithinRel(e, 1e-12));
      }
    }
    std::printf("G10 %s (%s): p_s(V=1) = %.4f GPa, gamma at V = 200: %.6f (1 + w = %.2f), sound speed against the "
                "isentropic derivative: worst %.1e\n",
                preset.name, preset.source, j.isentrope_pressure(1.0) / 1e9, gamma_far, 1 + j.omega, worst);
  }
  // The expected figure for ANFO: p_s(V = 1) = 1.61 GPa (docs/validation.md G10).
  CHECK_THAT(cip::EquationOfState::jwl_preset("ANFO").p.isentrope_pressure(1.0), WithinRel(1.61e9, 0.01));
}

TEST_CASE("G10 JWL parameters: bad values are refused by name", "[cip][G10][eos]") {
  const cip::JwlParameters anfo = cip::EquationOfState::jwl_preset("ANFO").p;
  auto refused = [&](cip::JwlParameters p, const char* what) {
    try {
      cip::EquationOfState::jwl_products(p);
    } catch (const InputError& e) {
      return std::string(e.what()).find(what) != std::string::npos;
    }
    return false;
  };
  cip::JwlParameters p = anfo;
  p.R1 = p.R2;
  CHECK(refused(p, "R1"));
  p = anfo;
  p.omega = 0;
  CHECK(refused(p, "w ="));
  p = anfo;
  p.rho0 = -800;
  CHECK(refused(p, "rho0"));
  p = anfo;
  p.A = NAN;
  CHECK(refused(p, "A ="));
  CHECK_NOTHROW(cip::EquationOfState::jwl_products(anfo));
  CHECK_THROWS_AS(cip::EquationOfState::jwl_preset("dynamite"), InputError);
}

TEST_CASE("G10 Chapman-Jouguet state from a JWL set: TNT against the LLNL handbook", "[cip][G10][eos]") {
  // Dobratz and Crawford (1985), LLNL Explosives Handbook UCRL-52997, JWL table for TNT at 1630 kg/m3:
  // D = 6930 m/s, p_CJ = 21.0 GPa, E0 = 7.0 GPa (0.070 Mbar cc/cc). The set was fitted with that CJ state, so
  // the tangency of its isentrope to the Rayleigh line must give it back.
  const cip::JwlParameters tnt = cip::EquationOfState::jwl_preset("TNT").p;
  const cip::ChapmanJouguet cj = cip::chapman_jouguet(tnt);
  std::printf("G10 CJ state of TNT from its JWL set: V_CJ %.4f, D %.1f m/s (6930), p_CJ %.3f GPa (21.0), E0 %.4f GPa "
              "(7.0)\n", cj.relative_volume, cj.detonation_velocity, cj.pressure / 1e9, cj.detonation_energy / 1e9);
  CHECK(std::fabs(cj.detonation_velocity / 6930.0 - 1) < 0.005);
  CHECK(std::fabs(cj.pressure / 21.0e9 - 1) < 0.005);
  CHECK(std::fabs(cj.detonation_energy / 7.0e9 - 1) < 0.005);
  // The state is on the Rayleigh line and the isentrope: p_CJ = rho0 D^2 (1 - V_CJ).
  CHECK(std::fabs(cj.pressure - tnt.rho0 * std::pow(cj.detonation_velocity, 2) * (1 - cj.relative_volume)) <
        1e-9 * cj.pressure);
  const cip::ChapmanJouguet anfo = cip::chapman_jouguet(cip::EquationOfState::jwl_preset("ANFO").p);
  std::printf("G10 CJ state of ANFO (Sanchidrian et al. 2015 set): V_CJ %.4f, D %.1f m/s, p_CJ %.3f GPa, E0 %.4f GPa "
              "(%.3f MJ/kg)\n", anfo.relative_volume, anfo.detonation_velocity, anfo.pressure / 1e9,
              anfo.detonation_energy / 1e9, anfo.detonation_energy / 800.0 / 1e6);
  CHECK(anfo.relative_volume > 0.5);
  CHECK(anfo.relative_volume < 1.0);
}
