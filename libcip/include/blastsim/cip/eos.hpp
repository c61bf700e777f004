//! \file eos.hpp
//! \brief Equations of state of the gas: ideal gas (air, the paper's gas) and JWL detonation products, both in
//! Mie-Gruneisen form p = p_ref(rho) + Gamma rho (e - e_ref(rho)).
#pragma once

#include "blastsim/core/macros.hpp"

#include <cmath>

namespace blastsim::cip {

enum class EosKind { ideal_gas, jwl };

//! Jones-Wilkins-Lee parameters of detonation products (Lee, Hornig & Kury 1968, UCRL-50422):
//!   p = A (1 - w/(R1 V)) exp(-R1 V) + B (1 - w/(R2 V)) exp(-R2 V) + w rho e,   V = rho0 / rho,
//! with e the specific internal energy [J/kg]. C is the third coefficient of the principal isentrope
//! (isentrope_pressure()); it fixes the energy the products hold at each expansion.
struct JwlParameters {
  double A = 0;       //!< [Pa]
  double B = 0;       //!< [Pa]
  double C = 0;       //!< [Pa], principal isentrope only
  double R1 = 0;      //!< [-]
  double R2 = 0;      //!< [-]
  double omega = 0;   //!< Gruneisen coefficient w [-]
  double rho0 = 0;    //!< density of the unreacted explosive [kg/m3]

  //! Pressure on the principal isentrope p_s(V) = A e^(-R1 V) + B e^(-R2 V) + C V^-(1+w) [Pa].
  BLAST_HD double isentrope_pressure(double V) const {
    return A * exp(-R1 * V) + B * exp(-R2 * V) + C * pow(V, -(1.0 + omega));
  }
  //! Internal energy per unit initial volume on the principal isentrope,
  //! E_s(V) = A/R1 e^(-R1 V) + B/R2 e^(-R2 V) + C/w V^-w [J/m3] (so that dE_s/dV = -p_s).
  BLAST_HD double isentrope_energy(double V) const {
    return A / R1 * exp(-R1 * V) + B / R2 * exp(-R2 * V) + C / omega * pow(V, -omega);
  }
};

//! The Chapman-Jouguet state of the explosive whose products a JWL set describes, derived from the principal
//! isentrope alone: the isentrope through the CJ point is tangent there to the Rayleigh line
//! p = rho0 D^2 (1 - V), so V_CJ solves p_s(V) + (1 - V) p_s'(V) = 0; then D^2 = p_s(V_CJ) / (rho0 (1 - V_CJ)),
//! and the Hugoniot energy relation E_CJ - E0 = p_CJ (1 - V_CJ) / 2 with E_CJ = E_s(V_CJ) gives the detonation
//! energy E0 per unit initial volume (Fickett and Davis 1979, Detonation, ch. 2; Lee, Hornig and Kury 1968,
//! UCRL-50422, on fitting JWL to the cylinder test with the CJ state as a constraint).
struct ChapmanJouguet {
  double relative_volume = 0;      //!< V_CJ = rho0 / rho_CJ [-]
  double detonation_velocity = 0;  //!< D [m/s]
  double pressure = 0;             //!< p_CJ [Pa]
  double detonation_energy = 0;    //!< E0 [J/m3] per unit volume of unreacted explosive
};
//! Solves the tangency condition by bisection on (0, 1); throws InputError when the set has no CJ point there.
ChapmanJouguet chapman_jouguet(const JwlParameters& p);

//! The published parameter sets (presets of the input's `explosive` key).
struct JwlPreset {
  const char* name;
  const char* source;
  JwlParameters p;
};
//! ANFO: Sanchidrian, Castedo, Lopez, Segarra & Lopez, "Determination of the JWL constants for ANFO and
//! emulsion explosives from cylinder test data", Central European Journal of Energetic Materials 12(2)
//! (2015) 177-194. TNT: Dobratz & Crawford, LLNL Explosives Handbook, UCRL-52997 Change 2 (1985).
inline constexpr JwlPreset kJwlPresets[] = {
    {"ANFO", "Sanchidrian et al. 2015, CEJEM 12(2) 177",
     {203.582e9, 2.973e9, 0.389e9, 6.651, 1.127, 0.39, 800.0}},
    {"TNT", "Dobratz & Crawford 1985, LLNL Explosives Handbook UCRL-52997",
     {371.2e9, 3.231e9, 1.045e9, 4.15, 0.95, 0.30, 1630.0}},
};

//! Plain-data equation of state, copied by value into kernels: p(rho, e), the sound speed c(rho, e) and the
//! inverse e(rho, p). Both kinds are of Mie-Gruneisen form p = p_ref(rho) + Gamma rho (e - e_ref(rho)):
//! - ideal gas: Gamma = gamma - 1, p_ref = e_ref = 0 (paper, Table 1: gamma = 1 + p/(rho e) = 1.40);
//! - JWL: Gamma = w, p_ref = A e^(-R1 V) + B e^(-R2 V), e_ref = A/(R1 rho0) e^(-R1 V) + B/(R2 rho0) e^(-R2 V).
struct EquationOfState {
  EosKind kind = EosKind::ideal_gas;
  double gamma = 1.4;  //!< [-] ratio of specific heats, > 1 (ideal gas)
  JwlParameters jwl;   //!< JWL parameters (kind == jwl)

  //! Gruneisen coefficient Gamma [-].
  BLAST_HD double gruneisen() const { return kind == EosKind::jwl ? jwl.omega : gamma - 1.0; }
  //! Reference pressure p_ref(rho) [Pa].
  BLAST_HD double reference_pressure(double density) const {
    if (kind != EosKind::jwl) return 0.0;
    const double V = jwl.rho0 / density;
    return jwl.A * exp(-jwl.R1 * V) + jwl.B * exp(-jwl.R2 * V);
  }
  //! Reference specific internal energy e_ref(rho) [J/kg].
  BLAST_HD double reference_energy(double density) const {
    if (kind != EosKind::jwl) return 0.0;
    const double V = jwl.rho0 / density;
    return (jwl.A / jwl.R1 * exp(-jwl.R1 * V) + jwl.B / jwl.R2 * exp(-jwl.R2 * V)) / jwl.rho0;
  }

  //! [Pa] from density [kg/m3] and specific internal energy [J/kg].
  BLAST_HD double pressure(double density, double internal_energy) const {
    if (kind != EosKind::jwl) return (gamma - 1.0) * density * internal_energy;
    return reference_pressure(density) + jwl.omega * density * (internal_energy - reference_energy(density));
  }
  //! [m/s]; NaN when c^2 < 0 (callers treat that as an instability).
  //! c^2 = (dp/drho)_e + p/rho^2 (dp/de)_rho.
  BLAST_HD double sound_speed(double density, double internal_energy) const {
    if (kind != EosKind::jwl) return std::sqrt(gamma * (gamma - 1.0) * internal_energy);
    const double V = jwl.rho0 / density, w = jwl.omega;
    // d/drho of A (1 - w/(R V)) e^(-R V) = (V/rho) A e^(-R V) (R - w/V - w/(R V^2)).
    auto term = [&](double A, double R) {
      return V / density * A * exp(-R * V) * (R - w / V - w / (R * V * V));
    };
    const double p = pressure(density, internal_energy);
    return std::sqrt(term(jwl.A, jwl.R1) + term(jwl.B, jwl.R2) + w * internal_energy + w * p / density);
  }
  //! [J/kg] specific internal energy that gives pressure p at density rho.
  BLAST_HD double internal_energy(double density, double pressure_pa) const {
    if (kind != EosKind::jwl) return pressure_pa / ((gamma - 1.0) * density);
    return reference_energy(density) + (pressure_pa - reference_pressure(density)) / (jwl.omega * density);
  }

  //! Ideal gas; throws InputError unless gamma > 1.
  static EquationOfState ideal(double gamma);
  //! JWL products; throws InputError naming the parameter unless A, B, C >= 0, A + B > 0, R1 > R2 > 0, w > 0
  //! and rho0 > 0 (all finite).
  static EquationOfState jwl_products(const JwlParameters& p);
  //! The preset `name` of kJwlPresets (case-sensitive); throws InputError listing the presets otherwise.
  static const JwlPreset& jwl_preset(const char* name);
};

//! The gas's materials (docs/gas-solver.md, "Two materials"): air (material 2) everywhere and, in a run with
//! an explosive, detonation products (material 1) where the products' volume fraction alpha > 0. A cell holds
//! the mixture density rho, the mixture specific internal energy e, alpha and the products' partial density
//! m1 = alpha rho1. The two share one pressure (the five-equation model of Allaire, Clerc & Kokh, JCP 181
//! (2002) 577, without the compaction term): with Mie-Gruneisen materials
//!   rho e = sum_k alpha_k (p / Gamma_k + K_k(rho_k)),   K_k = rho_k e_ref,k - p_ref,k / Gamma_k,
//! so p = (rho e - sum_k alpha_k K_k) / sum_k (alpha_k / Gamma_k): no iteration. A cell without products is
//! computed by the air's equation of state itself (the same bytes as a one-material run).
struct GasMaterials {
  EquationOfState air;
  EquationOfState products;
  bool two = false;  //!< products present in this run
  //! A one-gas run that traces part of its gas (docs/gas-solver.md, "Tracer"): m1 holds the partial density of
  //! the traced gas (the blast gas of a hole), carried with the flow as a passive scalar; the equation of state
  //! ignores it. In a two-material run the products are the traced gas and this flag is off.
  bool tracer = false;
  //! The partial density field m1 exists: the products' (two) or the traced gas's (tracer).
  BLAST_HD bool traced() const { return two || tracer; }

  //! Volume fractions below this are pure air (or, 1 minus it, pure products) to the equation of state: the
  //! transport smears alpha ahead of an interface down to denormal numbers, where m1 / alpha is no density.
  //! Their products mass is still carried.
  static constexpr double kMinFraction = 1e-10;
  //! Relative pressure difference of a mixed cell's materials below which relaxed_fraction() leaves alpha.
  static constexpr double kRelaxTolerance = 1e-9;
  //! Volume fractions (of either material) below which relaxed_fraction() leaves alpha: there the transported
  //! energy of the scarce material is round-off of its neighbours' and gives it no pressure of its own.
  static constexpr double kRelaxMinFraction = 1e-6;

  //! alpha_k K_k(rho_k) [J/m3] from the volume fraction and the partial density m_k = alpha_k rho_k, written
  //! so that it stays bounded as alpha_k -> 0 (zero for an ideal gas).
  BLAST_HD static double offset(const EquationOfState& eos, double alpha_k, double m_k) {
    if (eos.kind != EosKind::jwl || !(alpha_k > kMinFraction) || !(m_k > 0.0)) return 0.0;
    const double r = m_k / alpha_k;
    return m_k * eos.reference_energy(r) - alpha_k * eos.reference_pressure(r) / eos.gruneisen();
  }
  //! True when a cell of products volume fraction alpha [-] takes the air's equation of state alone: one-gas
  //! runs, and alpha at or below kMinFraction (the rule of pressure() and of everything that inverts it).
  BLAST_HD bool air_only(double alpha) const { return !two || !(alpha > kMinFraction); }
  //! Mixture pressure [Pa] from rho [kg/m3], e [J/kg], alpha [-] and m1 [kg/m3].
  BLAST_HD double pressure(double rho, double e, double alpha, double m1) const {
    if (air_only(alpha)) return air.pressure(rho, e);
    const double a2 = 1.0 - alpha;
    const double xi = alpha / products.gruneisen() + a2 / air.gruneisen();
    return (rho * e - offset(products, alpha, m1) - offset(air, a2, rho - m1)) / xi;
  }
  //! Mixture sound speed [m/s] of the five-equation model: xi c^2 = sum_k Y_k c_k^2 / Gamma_k (Allaire et al.
  //! 2002, eq. 2.9), c_k at the phase density and the common pressure; NaN for an invalid state.
  BLAST_HD double sound_speed(double rho, double e, double alpha, double m1) const {
    if (air_only(alpha)) return air.sound_speed(rho, e);
    return mixture_sound_speed(rho, alpha, m1, pressure(rho, e, alpha, m1));
  }
  //! The mixture sound speed of a cell with products (alpha > kMinFraction) whose pressure p [Pa] is known.
  //! In a mixed cell one phase's density m_k / alpha_k can leave the range where its equation of state has a
  //! real sound speed at the common pressure (the transport smears alpha and m1 apart: a products density far
  //! above rho0 at a pressure near the air's); that phase then takes the other phase's sound speed. NaN only
  //! when no phase present has a real one.
  BLAST_HD double mixture_sound_speed(double rho, double alpha, double m1, double p) const {
    const double a2 = 1.0 - alpha, m2 = rho - m1;
    const double xi = alpha / products.gruneisen() + a2 / air.gruneisen();
    const bool has1 = m1 > 0.0, has2 = a2 > kMinFraction && m2 > 0.0;
    double c1 = NAN, c2 = NAN;
    if (has1) {
      const double r1 = m1 / alpha;
      c1 = products.sound_speed(r1, products.internal_energy(r1, p));
    }
    if (has2) {
      const double r2 = m2 / a2;
      c2 = air.sound_speed(r2, air.internal_energy(r2, p));
    }
    if (has1 && has2) {
      if (!(c1 == c1)) c1 = c2;
      if (!(c2 == c2)) c2 = c1;
    }
    double sum = 0.0;
    if (has1) sum += m1 / rho * c1 * c1 / products.gruneisen();
    if (has2) sum += m2 / rho * c2 * c2 / air.gruneisen();
    return sqrt(sum / xi);
  }
  //! Effective Gruneisen coefficient of a mixture with products volume fraction alpha [-],
  //! 1 / (alpha / Gamma1 + (1 - alpha) / Gamma2): p = Gamma (rho e - offsets); the air's without products.
  BLAST_HD double mixture_gruneisen(double alpha) const {
    if (!two) return air.gruneisen();
    return 1.0 / (alpha / products.gruneisen() + (1.0 - alpha) / air.gruneisen());
  }
  //! The Gruneisen coefficient of a cell's pressure(): the mixture's with products, the air's below kMinFraction.
  BLAST_HD double cell_gruneisen(double alpha) const {
    return air_only(alpha) ? air.gruneisen() : mixture_gruneisen(alpha);
  }
  //! Internal energy per unit volume rho e [J/m3] of a mixture at density rho [kg/m3], pressure p [Pa],
  //! products volume fraction alpha [-] and mass fraction Y [-] (the inverse of pressure(); pure air below
  //! kMinFraction).
  BLAST_HD double internal_energy_density(double rho, double p, double alpha, double Y) const {
    if (air_only(alpha)) return rho * air.internal_energy(rho, p);
    const double a2 = 1.0 - alpha;
    const double rho1 = Y * rho / alpha, rho2 = a2 > kMinFraction ? (1.0 - Y) * rho / a2 : 0.0;
    return energy_density(p, alpha, rho1, rho2);
  }
  //! Mixture internal energy per unit volume rho e [J/m3] at pressure p, volume fraction alpha and phase
  //! densities rho1, rho2 (the inverse of pressure()).
  BLAST_HD double energy_density(double p, double alpha, double rho1, double rho2) const {
    const double a2 = 1.0 - alpha;
    return alpha * p / products.gruneisen() + a2 * p / air.gruneisen() + offset(products, alpha, alpha * rho1) +
           offset(air, a2, a2 * rho2);
  }
  //! The products' share alpha rho1 e1 [J/m3] of energy_density(): their internal energy per unit mixture volume
  //! at pressure p, volume fraction alpha and partial density m1 = alpha rho1.
  BLAST_HD double products_energy(double p, double alpha, double m1) const {
    return alpha * p / products.gruneisen() + offset(products, alpha, m1);
  }

  //! Pressure [Pa] of material k (products or air) holding partial density m_k and internal energy E_k
  //! [J/m3, per unit mixture volume] at volume fraction a_k after it has done the work P (a_k - a0_k) against
  //! the other material at their common pressure P: solving
  //!   a_k P = Gamma_k (E_k - P (a_k - a0_k) - a_k K_k(m_k / a_k))    for P
  //! gives P = num / den with num = Gamma_k (E_k - alpha_k K_k), den = a_k (1 + Gamma_k) - Gamma_k a0_k. Returned as
  //! the pair so that the caller can compare pressures without dividing by a vanishing den.
  struct RelaxedPressure {
    double num, den;
  };
  BLAST_HD static RelaxedPressure relaxed_pressure(const EquationOfState& eos, double a_k, double a0_k, double m_k,
                                                   double E_k) {
    const double G = eos.gruneisen();
    return {G * (E_k - offset(eos, a_k, m_k)), a_k * (1.0 + G) - G * a0_k};
  }

  //! Instantaneous pressure relaxation of a mixed cell (Saurel, Petitpas & Berry, JCP 228 (2009) 1678, sec. 3,
  //! with Mie-Gruneisen materials): the products (partial density m1, internal energy E1 per unit volume) and
  //! the air (m2, E2) at volume fraction a0 = alpha need not share a pressure after the transport mixed states
  //! from different cells into one. The volume fraction moves to the a at which both reach one pressure P, each
  //! material's energy changed by the work P (a_k - a0_k) it does on the other (an isentropic exchange to first
  //! order; masses and the total energy E1 + E2 are untouched, so the mixture pressure of the result is P).
  //! On (a_lo, a_hi), where both denominators of relaxed_pressure() are positive, P1 - P2 runs from +inf to
  //! -inf when both numerators are positive: bisection on the sign of num1 den2 - num2 den1 to round-off.
  //! Returns a0 when a material's thermal energy is not positive (no bracket), when the pressures already agree
  //! to kRelaxTolerance, and in cells where either fraction is below kRelaxMinFraction.
  BLAST_HD double relaxed_fraction(double a0, double m1, double m2, double E1, double E2) const {
    if (!(a0 > kRelaxMinFraction && a0 < 1.0 - kRelaxMinFraction)) return a0;
    const double G1 = products.gruneisen(), G2 = air.gruneisen();
    double lo = G1 * a0 / (1.0 + G1), hi = 1.0 - G2 * (1.0 - a0) / (1.0 + G2);
    auto excess = [&](double a) {  // sign of P1(a) - P2(a) while both den > 0
      const RelaxedPressure p1 = relaxed_pressure(products, a, a0, m1, E1);
      const RelaxedPressure p2 = relaxed_pressure(air, 1.0 - a, 1.0 - a0, m2, E2);
      return p1.num * p2.den - p2.num * p1.den;
    };
    // Phases that already share a pressure to kRelaxTolerance keep their alpha: otherwise round-off in the
    // transported energies would move alpha every step (at a density ratio r a move d alpha changes the
    // mixture density by about r d alpha).
    const RelaxedPressure q1 = relaxed_pressure(products, a0, a0, m1, E1), q2 = relaxed_pressure(air, 1.0 - a0, 1.0 - a0, m2, E2);
    const double p1 = q1.num / q1.den, p2 = q2.num / q2.den;
    if (fabs(p1 - p2) <= kRelaxTolerance * (fabs(p1) + fabs(p2))) return a0;
    if (!(excess(lo) > 0.0) || !(excess(hi) < 0.0)) return a0;
    for (int it = 0; it < 64 && hi - lo > 4e-16 * hi; ++it) {
      const double mid = 0.5 * (lo + hi);
      (excess(mid) > 0.0 ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi);
  }
};

}  // namespace blastsim::cip
