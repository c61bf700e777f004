//! \file test_input.cpp
//! \brief Driver input: every kind of bad input gives one InputError naming the key, value and allowed range.
#include "blastsim/core/error.hpp"
#include "case.hpp"
#include "catch.hpp"

#include <string>

using namespace blastsim;

namespace {

// A valid minimal gas case; each test breaks one thing.
const char* kValid = R"(
[domain]
nx = 20
ny = 10
x_min = 0.0
x_max = 1.0
y_min = 0.0
y_max = 0.5
[gas]
gamma = 1.4
[gas.ambient]
density = 1.2
pressure = 1.0e5
[[gas.region]]
shape = "circle"
center = [0.5, 0.25]
radius = 0.1
density = 163.0
internal_energy = 4.29e5
[time]
end = 1.0e-4
)";

app::Case read(const std::string& text, const std::vector<std::string>& overrides = {}) {
  toml::table t = toml::parse(text);
  for (const std::string& o : overrides) app::apply_override(t, o);
  return app::read_case(t);
}

//! The InputError message of reading kValid with `overrides`, or "" when it is accepted.
std::string error_of(const std::vector<std::string>& overrides, const std::string& text = kValid) {
  try {
    read(text, overrides);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

}  // namespace

TEST_CASE("A valid case is read with its defaults and echoed with units", "[app][input]") {
  const app::Case c = read(kValid);
  CHECK(c.gas.grid.nx == 20);
  CHECK_THAT(c.gas.grid.dx, WithinRel(0.05, 1e-14));
  CHECK(c.gas.courant == cip::kConservativeCourant);  // the conservative transport's recommended number
  CHECK(c.gas.solver.transport == cip::Transport::conservative);
  CHECK(c.gas.solver.viscosity.linear == 0.25);  // the conservative transport's coefficients (with the predictor)
  CHECK(c.gas.solver.viscosity.quadratic == 0.5);
  CHECK(c.gas.solver.pressure_predictor);
  const app::Case paper = read(kValid, {"gas.transport=paper"});
  CHECK(paper.gas.solver.transport == cip::Transport::paper);
  CHECK(paper.gas.solver.viscosity.linear == 1.0);  // the paper's transport's coefficients
  CHECK(paper.gas.solver.viscosity.quadratic == 2.0);
  CHECK(paper.gas.courant == cip::kPaperCourant);  // the paper's transport at the paper's number
  CHECK(read(kValid, {"gas.transport=paper", "gas.courant=0.3"}).gas.courant == 0.3);  // a given number is kept
  CHECK_THAT(c.gas.ambient.internal_energy, WithinRel(1.0e5 / (0.4 * 1.2), 1e-14));  // from the pressure
  CHECK(c.gas.regions.size() == 1);
  CHECK(c.gas.initial_state(0.5, 0.25).density == 163.0);
  CHECK(c.gas.initial_state(0.9, 0.25).density == 1.2);
  bool echoed_units = false, echoed_default = false;
  for (const app::EchoLine& e : c.echo) {
    echoed_units |= e.text == "domain.x_max = 1 m" && e.key == "domain.x_max";
    echoed_default |= contains(e.text, "gas.courant = 0.4") && contains(e.text, "(default)");
  }
  CHECK(echoed_units);
  CHECK(echoed_default);
}

TEST_CASE("Command-line overrides replace values, reach array entries and create keys", "[app][input]") {
  const app::Case c =
      read(kValid, {"domain.nx=40", "gas.region.0.radius=0.2", "gas.boundary.left=wall", "time.dt=1e-7"});
  CHECK(c.gas.grid.nx == 40);
  CHECK(c.gas.regions[0].where.radius == 0.2);
  CHECK(c.gas.solver.boundaries.kind(cip::left) == cip::BoundaryKind::wall);
  REQUIRE(c.time.dt);
  CHECK(*c.time.dt == 1e-7);
  CHECK(contains(error_of({"gas.region.3.radius=1"}), "gas.region has 1 entries"));
  CHECK(contains(error_of({"novalue"}), "section.key=value"));
}

TEST_CASE("An empty array of tables is none", "[app][input]") {
  // `gas.region = []` replaces the file's one region by none; `probe.point = []` and `probe.line = []` give no probes.
  const app::Case c = read(kValid, {"gas.region=[]", "probe.point=[]", "probe.line=[]"});
  CHECK(c.gas.regions.empty());
  CHECK(c.probes.points.empty());
  CHECK(c.probes.lines.empty());
  CHECK(c.gas.initial_state(0.5, 0.25).density == 1.2);  // the ambient state everywhere
  // An array of something else is still refused, naming the key.
  CHECK(contains(error_of({"probe.point=[1, 2]"}), "probe.point must be an array of tables"));
}

TEST_CASE("Bad input: unknown keys", "[app][input][bad]") {
  CHECK(contains(error_of({"gas.gama=1.4"}), "unknown key 'gas.gama'"));
  CHECK(contains(error_of({"gas.gama=1.4"}), "allowed here: gamma"));
  CHECK(contains(error_of({"extra.key=1"}), "unknown key 'extra'"));
  CHECK(contains(error_of({"gas.region.0.colour=1"}), "unknown key 'gas.region.0.colour'"));
}

TEST_CASE("Bad input: missing required keys", "[app][input][bad]") {
  const std::string no_nx = std::string(kValid).replace(std::string(kValid).find("nx = 20"), 7, "");
  CHECK(contains(error_of({}, no_nx), "missing required key 'domain.nx'"));
  const std::string no_end = std::string(kValid).replace(std::string(kValid).find("end = 1.0e-4"), 12, "");
  CHECK(contains(error_of({}, no_end), "missing required key 'time.end'"));
  const std::string no_rho = std::string(kValid).replace(std::string(kValid).find("density = 1.2"), 13, "");
  CHECK(contains(error_of({}, no_rho), "missing required key 'gas.ambient.density'"));
}

TEST_CASE("Bad input: wrong types", "[app][input][bad]") {
  CHECK(contains(error_of({"domain.nx=20.5"}), "domain.nx must be an integer, got a number"));
  CHECK(contains(error_of({"gas.gamma=\"air\""}), "gas.gamma must be a number, got a string"));
  CHECK(contains(error_of({"gas.region.0.center=1.0"}), "gas.region.0.center must be an array of two numbers"));
  CHECK(contains(error_of({"output.vtk=1"}), "output.vtk must be true or false"));
  CHECK(contains(error_of({"gas.boundary.left=sticky"}), "gas.boundary.left = \"sticky\": must be one of"));
}

TEST_CASE("Bad input: non-physical values name the key, the value and the allowed range", "[app][input][bad]") {
  CHECK(error_of({"gas.ambient.density=-1.2"}) == "gas.ambient.density = -1.2 kg/m3: must be > 0");
  CHECK(error_of({"gas.gamma=1.0"}) == "gas.gamma = 1: must be > 1");
  CHECK(error_of({"gas.gamma=0.9"}) == "gas.gamma = 0.9: must be > 1");
  CHECK(error_of({"domain.nx=2"}) == "domain.nx = 2: must be an integer >= 3");
  CHECK(error_of({"domain.ny=0"}) == "domain.ny = 0: must be an integer >= 3");
  CHECK(error_of({"gas.courant=0"}) == "gas.courant = 0: must be in [1e-06, 1]");
  CHECK(error_of({"gas.courant=1.5"}) == "gas.courant = 1.5: must be in [1e-06, 1]");
  CHECK(error_of({"gas.region.0.internal_energy=-5"}) == "gas.region.0.internal_energy = -5 J/kg: must be > 0");
  CHECK(error_of({"time.end=-1"}) == "time.end = -1 s: must be > 0");
  CHECK(error_of({"domain.x_max=-1"}) == "domain.x_max = -1 m: must be > 0");
  CHECK(contains(error_of({"gas.region.0.pressure=1e7"}), "exactly one of 'internal_energy'"));
  CHECK(contains(error_of({"gas.boundary.left=periodic"}), "must both be \"periodic\""));
}

TEST_CASE("Bad input file: a missing file is named", "[app][input][bad]") {
  try {
    app::load_case("/nonexistent/case.toml", {});
    FAIL("no error for a missing file");
  } catch (const InputError& e) {
    CHECK(contains(e.what(), "/nonexistent/case.toml"));
  }
}

TEST_CASE("Detonation products: an explosive preset or JWL parameters, products regions, and their errors",
          "[app][input][explosive]") {
  // A preset and a products region: two materials, the region's energy from the products' equation of state.
  const app::Case c = read(kValid, {"gas.explosive.preset=\"ANFO\"", "gas.region.0.material=\"products\"",
                                          "gas.region.0.density=800.0", "gas.region.0.internal_energy=2.0e6"});
  REQUIRE(c.gas.explosive.has_value());
  CHECK(c.gas.materials().two);
  CHECK(c.gas.explosive->jwl.rho0 == 800.0);
  CHECK(c.gas.initial_state(0.5, 0.25).products_fraction == 1.0);
  CHECK(c.gas.initial_state(0.05, 0.05).products_fraction == 0.0);
  // The seven parameters instead of a preset.
  const app::Case u = read(kValid, {"gas.explosive.A=3.712e11", "gas.explosive.B=3.231e9", "gas.explosive.C=1.045e9",
                                          "gas.explosive.R1=4.15", "gas.explosive.R2=0.95", "gas.explosive.w=0.3",
                                          "gas.explosive.rho0=1630.0", "gas.region.0.material=\"products\""});
  CHECK(u.gas.explosive->jwl.R1 == 4.15);
  // Errors name the key: a products region without an explosive, R1 <= R2, an unknown preset, both forms.
  CHECK(contains(error_of({"gas.region.0.material=\"products\""}), "gas.region.0.material = \"products\" needs a "
                                                                   "[gas.explosive]"));
  CHECK(contains(error_of({"gas.explosive.A=3.712e11", "gas.explosive.B=3.231e9", "gas.explosive.C=1.045e9",
                           "gas.explosive.R1=0.9", "gas.explosive.R2=0.95", "gas.explosive.w=0.3",
                           "gas.explosive.rho0=1630.0"}),
                 "gas.explosive: JWL parameter R1 = 0.9"));
  CHECK(contains(error_of({"gas.explosive.preset=\"dynamite\""}), "dynamite"));
  CHECK(contains(error_of({"gas.explosive.preset=\"ANFO\"", "gas.explosive.w=0.3"}), "either 'preset'"));
  CHECK(contains(error_of({"gas.explosive.preset=\"ANFO\"", "gas.region.0.material=\"products\"",
                           "gas.transport=\"paper\""}),
                 "conservative"));
}
