//! \file eos.cpp
//! \brief Checked constructors of the equations of state (eos.hpp): ideal gas, JWL products, JWL presets.
#include "blastsim/cip/eos.hpp"

#include "blastsim/core/error.hpp"

#include <cmath>
#include <cstring>
#include <string>

namespace blastsim::cip {

EquationOfState EquationOfState::ideal(double gamma) {
  if (!(gamma > 1.0) || !std::isfinite(gamma)) throw InputError("ideal-gas gamma must be > 1");
  EquationOfState e;
  e.kind = EosKind::ideal_gas;
  e.gamma = gamma;
  return e;
}

namespace {
void require(bool ok, const char* name, double value, const char* allowed) {
  if (!ok) throw InputError(std::string("JWL parameter ") + name + " = " + std::to_string(value) + ": must be " + allowed);
}
}  // namespace

EquationOfState EquationOfState::jwl_products(const JwlParameters& p) {
  const std::pair<const char*, double> all[] = {{"A", p.A},   {"B", p.B},   {"C", p.C},         {"R1", p.R1},
                                                {"R2", p.R2}, {"w", p.omega}, {"rho0", p.rho0}};
  for (const auto& [name, value] : all) require(std::isfinite(value), name, value, "finite");
  require(p.A >= 0, "A", p.A, ">= 0 [Pa]");
  require(p.B >= 0, "B", p.B, ">= 0 [Pa]");
  require(p.C >= 0, "C", p.C, ">= 0 [Pa]");
  require(p.A + p.B > 0, "A + B", p.A + p.B, "> 0 [Pa]");
  require(p.R2 > 0, "R2", p.R2, "> 0");
  require(p.R1 > p.R2, "R1", p.R1, "> R2");
  require(p.omega > 0, "w", p.omega, "> 0");
  require(p.rho0 > 0, "rho0", p.rho0, "> 0 [kg/m3]");
  EquationOfState e;
  e.kind = EosKind::jwl;
  e.gamma = 1.0 + p.omega;  // the ideal gas the products tend to at large expansion
  e.jwl = p;
  return e;
}

ChapmanJouguet chapman_jouguet(const JwlParameters& p) {
  const auto slope = [&](double V) {  // p_s'(V)
    return -p.R1 * p.A * std::exp(-p.R1 * V) - p.R2 * p.B * std::exp(-p.R2 * V) -
           (1.0 + p.omega) * p.C * std::pow(V, -(2.0 + p.omega));
  };
  const auto tangency = [&](double V) { return p.isentrope_pressure(V) + (1.0 - V) * slope(V); };
  // p_s > 0 at V = 1, so the condition is positive there; step down to the first sign change.
  double hi = 1.0, lo = 1.0;
  while (tangency(lo) > 0.0) {
    hi = lo;
    lo -= 0.01;
    if (lo <= 0.01) throw InputError("JWL parameters: no Chapman-Jouguet point (the isentrope never meets a Rayleigh "
                                     "line tangentially for V in (0, 1)); give detonation_velocity and "
                                     "detonation_energy");
  }
  for (int k = 0; k < 200 && hi - lo > 1e-15; ++k) {
    const double mid = 0.5 * (lo + hi);
    (tangency(mid) > 0.0 ? hi : lo) = mid;
  }
  ChapmanJouguet cj;
  cj.relative_volume = 0.5 * (lo + hi);
  const double V = cj.relative_volume;
  cj.pressure = p.isentrope_pressure(V);
  cj.detonation_velocity = std::sqrt(cj.pressure / (p.rho0 * (1.0 - V)));
  cj.detonation_energy = p.isentrope_energy(V) - 0.5 * cj.pressure * (1.0 - V);
  return cj;
}

const JwlPreset& EquationOfState::jwl_preset(const char* name) {
  std::string known;
  for (const JwlPreset& preset : kJwlPresets) {
    if (std::strcmp(preset.name, name) == 0) return preset;
    known += known.empty() ? "" : ", ";
    known += preset.name;
  }
  throw InputError(std::string("unknown explosive '") + name + "' (presets: " + known + ")");
}

}  // namespace blastsim::cip
