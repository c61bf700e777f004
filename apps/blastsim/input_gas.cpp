//! \file input_gas.cpp
//! \brief [gas]: the air, the explosive's products, the initial regions and how the gas is solved
//! (docs/input.md); the GasSettings queries.
#include "blastsim/core/error.hpp"
#include "case.hpp"

#include <fmt/format.h>

#include <cmath>

namespace blastsim::app {

cip::GasPoint GasSettings::initial_state(double x, double y) const {
  for (auto it = regions.rbegin(); it != regions.rend(); ++it)
    if (it->where.contains(x, y)) return it->state;
  return ambient;
}

cip::GasMaterials GasSettings::materials() const {
  cip::GasMaterials m;
  m.air = eos;
  m.products = explosive.value_or(eos);
  for (const Region& r : regions) m.two = m.two || r.state.products_fraction > 0.0;
  m.two = m.two || charges;
  for (const Region& r : regions) m.tracer = m.tracer || (!m.two && r.state.tracer > 0.0);
  return m;
}

double GasSettings::ambient_pressure() const { return eos.pressure(ambient.density, ambient.internal_energy); }

namespace {

//! [m/s] the detonation velocities an explosive may have: commercial and military explosives detonate at about
//! 1,500 to 9,000 m/s; outside these bounds a value is a typing error (it sets a point initiation's front).
constexpr double kMinDetonationVelocity = 100.0, kMaxDetonationVelocity = 20000.0;

//! [gas.explosive]: a preset (explosive = "ANFO") or the seven JWL parameters; checked by jwl_products(). Also
//! the detonation velocity and energy of the explosive (given, or those of the JWL set's CJ state).
cip::EquationOfState read_explosive(TableReader& x, GasSettings& g) {
  cip::JwlParameters p;
  const char* keys[] = {"A", "B", "C", "R1", "R2", "w", "rho0"};
  if (x.has("preset")) {
    std::vector<std::string> names;
    for (const cip::JwlPreset& preset : cip::kJwlPresets) names.push_back(preset.name);
    p = cip::EquationOfState::jwl_preset(x.text("preset", names).c_str()).p;
    for (const char* k : keys)
      if (x.has(k))
        throw InputError(fmt::format("{}: give either 'preset' or the JWL parameters, not both ('{}' given)", x.path(), k));
    x.allow({keys, keys + 7});
  } else {
    x.allow({"preset"});
    p.A = x.number("A", "Pa", Range::non_negative());
    p.B = x.number("B", "Pa", Range::non_negative());
    p.C = x.number("C", "Pa", Range::non_negative());
    p.R1 = x.number("R1", "", Range::positive());
    p.R2 = x.number("R2", "", Range::positive());
    p.omega = x.number("w", "", Range::positive());
    p.rho0 = x.number("rho0", "kg/m3", Range::positive());
  }
  cip::EquationOfState eos;
  cip::ChapmanJouguet cj;
  const bool both = x.has("detonation_velocity") && x.has("detonation_energy");
  try {
    eos = cip::EquationOfState::jwl_products(p);
    if (!both) cj = cip::chapman_jouguet(p);
  } catch (const InputError& e) {
    throw InputError(fmt::format("{}: {}", x.path(), e.what()));
  }
  // The CJ state's D and E0 are defaults of keys the user may not have set: a set without a usable CJ state
  // is named by its parameters.
  const bool cj_ok = both || (cj.detonation_velocity >= kMinDetonationVelocity &&
                              cj.detonation_velocity <= kMaxDetonationVelocity && cj.detonation_energy > 0 &&
                              std::isfinite(cj.detonation_energy));
  if (!cj_ok)
    throw InputError(fmt::format("{}: the JWL set (A = {:g} Pa, B = {:g} Pa, C = {:g} Pa, R1 = {:g}, R2 = {:g}, w = {:g}, "
                                 "rho0 = {:g} kg/m3) gives a Chapman-Jouguet state with D = {:g} m/s and E0 / rho0 = {:g} "
                                 "J/kg, not an explosive's (D from {:g} to {:g} m/s, E0 > 0): check the parameters, or give "
                                 "detonation_velocity and detonation_energy", x.path(), p.A, p.B, p.C, p.R1, p.R2, p.omega,
                                 p.rho0, cj.detonation_velocity, cj.detonation_energy / p.rho0, kMinDetonationVelocity,
                                 kMaxDetonationVelocity));
  g.detonation_velocity = x.number("detonation_velocity", "m/s", Range{kMinDetonationVelocity, kMaxDetonationVelocity, false, false},
                                   both ? std::optional<double>() : cj.detonation_velocity);
  g.detonation_energy = x.number("detonation_energy", "J/kg", Range::positive(),
                                 both ? std::optional<double>() : cj.detonation_energy / p.rho0);
  x.finish();
  return eos;
}

//! A gas state: density and exactly one of internal_energy / pressure, optional velocity.
cip::GasPoint read_state(TableReader& t, const cip::EquationOfState& eos) {
  cip::GasPoint s{};
  s.density = t.number("density", "kg/m3", Range::positive());
  const bool has_e = t.has("internal_energy"), has_p = t.has("pressure");
  if (has_e == has_p)
    throw InputError(fmt::format("{}: give exactly one of 'internal_energy' [J/kg] or 'pressure' [Pa]", t.path()));
  if (has_e) {
    s.internal_energy = t.number("internal_energy", "J/kg", Range::positive());
    t.optional_number("pressure", "Pa", Range::positive());
  } else {
    t.optional_number("internal_energy", "J/kg", Range::positive());
    s.internal_energy = eos.internal_energy(s.density, t.number("pressure", "Pa", Range::positive()));
  }
  const std::array<double, 2> v = t.pair("velocity", "m/s", std::array<double, 2>{0.0, 0.0});
  s.velocity_x = v[0];
  s.velocity_y = v[1];
  return s;
}

cip::BoundaryKind read_boundary(TableReader& t, const char* side) {
  cip::BoundaryKind k{};
  cip::parse_boundary_kind(t.text(side, {"outflow", "wall", "periodic"}, std::string("outflow")), k);
  return k;
}

}  // namespace

void read_gas(TableReader& root, Case& c) {
  GasSettings& g = c.gas;
  TableReader gas = root.table("gas", true);
  g.eos = cip::EquationOfState::ideal(gas.number("gamma", "", Range::above(1.0), 1.4));
  g.solver.transport = gas.text("transport", {"conservative", "paper"}, std::string("conservative")) == "paper"
                           ? cip::Transport::paper
                           : cip::Transport::conservative;
  // below 1e-6 a run never ends; a coupled run's default also depends on its gas load (read_case())
  g.courant_given = gas.has("courant");
  g.courant = gas.number("courant", "", Range{1e-6, 1.0, false, false}, cip::recommended_courant(g.solver.transport));
  const cip::ArtificialViscosity q = cip::recommended_viscosity(g.solver.transport);
  g.solver.viscosity.linear = gas.number("viscosity_linear", "", Range::non_negative(), q.linear);
  g.solver.viscosity.quadratic = gas.number("viscosity_quadratic", "", Range::non_negative(), q.quadratic);
  g.solver.pressure_predictor = gas.boolean("pressure_predictor", true);
  g.solver.limiter =
      gas.text("limiter", {"minmax", "none"}, std::string("minmax")) == "none" ? cip::Limiter::none : cip::Limiter::minmax;
  TableReader bc = gas.table("boundary");
  g.solver.boundaries.set(cip::left, read_boundary(bc, "left")).set(cip::right, read_boundary(bc, "right"));
  g.solver.boundaries.set(cip::bottom, read_boundary(bc, "bottom")).set(cip::top, read_boundary(bc, "top"));
  bc.finish();
  if (const int a = g.solver.boundaries.unpaired_periodic_axis(); a >= 0)
    throw InputError(fmt::format("gas.boundary.{} and gas.boundary.{} must both be \"periodic\" or neither",
                                 a == 0 ? "left" : "bottom", a == 0 ? "right" : "top"));
  TableReader ambient = gas.table("ambient", true);
  g.ambient = read_state(ambient, g.eos);
  ambient.finish();
  if (gas.has("explosive")) {
    TableReader x = gas.table("explosive");
    g.explosive = read_explosive(x, g);
  }
  for (TableReader& r : gas.table_array("region")) {
    GasSettings::Region region;
    region.where = read_region_shape(r);
    const bool products = r.text("material", {"air", "products"}, std::string("air")) == "products";
    if (products && !g.explosive)
      throw InputError(fmt::format("{}.material = \"products\" needs a [gas.explosive] table (the products' equation of "
                                   "state)", r.path()));
    region.state = read_state(r, products ? *g.explosive : g.eos);
    region.state.products_fraction = products ? 1.0 : 0.0;
    // The blast gas a one-gas run traces (docs/analysis.md "Blast gas"); with products, the products are.
    region.blast_gas_given = r.has("blast_gas");
    // Traced by default where the transport can carry a tracer (the conservative one).
    region.state.tracer = r.boolean("blast_gas", g.solver.transport == cip::Transport::conservative) ? 1.0 : 0.0;
    const cip::EquationOfState& eos = products ? *g.explosive : g.eos;
    const double p = eos.pressure(region.state.density, region.state.internal_energy),
                 a = eos.sound_speed(region.state.density, region.state.internal_energy);
    if (!(p > 0) || !(a > 0) || !std::isfinite(p) || !std::isfinite(a))
      throw InputError(fmt::format("{}: the state (density {:g} kg/m3, internal energy {:g} J/kg) has pressure {:g} Pa and "
                                   "sound speed {:g} m/s under the {}'s equation of state; a gas state needs both positive "
                                   "and finite", r.path(), region.state.density, region.state.internal_energy, p, a,
                                   products ? "products" : "air"));
    bool holds_cell = false;
    for (int j = 0; j < g.grid.ny && !holds_cell; ++j)
      for (int i = 0; i < g.grid.nx && !holds_cell; ++i) holds_cell = region.where.contains(g.grid.cell_x(i), g.grid.cell_y(j));
    if (!holds_cell)
      throw InputError(fmt::format("{}: the region holds no cell centre of the grid (it lies outside [domain], or is "
                                   "smaller than a cell)", r.path()));
    r.finish();
    g.regions.push_back(region);
  }
  if (g.materials().two && g.solver.transport != cip::Transport::conservative)
    throw InputError("gas.transport = \"paper\": the paper's transport carries one gas; a [[gas.region]] of detonation "
                     "products needs \"conservative\"");
  if (g.materials().tracer && g.solver.transport != cip::Transport::conservative)
    throw InputError("gas.transport = \"paper\": the paper's transport carries no tracer of the blast gas; remove "
                     "blast_gas = true from the [[gas.region]] tables, or use \"conservative\"");
  gas.finish();
}

}  // namespace blastsim::app
