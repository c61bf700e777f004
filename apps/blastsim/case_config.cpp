//! \file case_config.cpp
//! \brief Reads the driver's TOML input into a CaseConfig; docs/input.md documents every key read here.
#include "case_input.hpp"

#include "blastsim/core/error.hpp"

#include <fmt/format.h>

#include <unistd.h>

namespace blastsim::app {

bool GasRegion::contains(double x, double y) const {
  if (shape == Shape::circle) {
    const double dx = x - center[0], dy = y - center[1];
    return dx * dx + dy * dy <= radius * radius;
  }
  return x >= min[0] && x <= max[0] && y >= min[1] && y <= max[1];
}

cip::GasPoint CaseConfig::initial_state(double x, double y) const {
  for (auto it = regions.rbegin(); it != regions.rend(); ++it)
    if (it->contains(x, y)) return it->state;
  return ambient;
}

cip::GasMaterials CaseConfig::materials() const {
  cip::GasMaterials m;
  m.air = eos;
  m.products = explosive.value_or(eos);
  for (const GasRegion& r : regions) m.two = m.two || r.state.products_fraction > 0.0;
  m.two = m.two || charges;
  return m;
}

namespace {

//! [gas.explosive]: a preset (explosive = "ANFO") or the seven JWL parameters; checked by jwl_products(). Also
//! the detonation velocity and energy of the explosive (given, or those of the JWL set's CJ state).
cip::EquationOfState read_explosive(TableReader& x, CaseConfig& c) {
  cip::JwlParameters p;
  const char* keys[] = {"A", "B", "C", "R1", "R2", "w", "rho0"};
  if (x.has("preset")) {
    std::vector<std::string> names;
    for (const cip::JwlPreset& preset : cip::kJwlPresets) names.push_back(preset.name);
    p = cip::EquationOfState::jwl_preset(x.text("preset", names).c_str()).p;
    for (const char* k : keys)
      if (x.has(k))
        throw InputError(fmt::format("{}: give either 'preset' or the JWL parameters, not both ('{}' given)", x.path(), k));
  } else {
    p.A = x.number("A", "Pa", Range::non_negative());
    p.B = x.number("B", "Pa", Range::non_negative());
    p.C = x.number("C", "Pa", Range::non_negative());
    p.R1 = x.number("R1", "", Range::positive());
    p.R2 = x.number("R2", "", Range::positive());
    p.omega = x.number("w", "", Range::positive());
    p.rho0 = x.number("rho0", "kg/m3", Range::positive());
  }
  cip::EquationOfState eos;
  try {
    eos = cip::EquationOfState::jwl_products(p);
  } catch (const InputError& e) {
    throw InputError(fmt::format("{}: {}", x.path(), e.what()));
  }
  cip::ChapmanJouguet cj;
  const bool both = x.has("detonation_velocity") && x.has("detonation_energy");
  try {
    if (!both) cj = cip::chapman_jouguet(p);
  } catch (const InputError& e) {
    throw InputError(fmt::format("{}: {}", x.path(), e.what()));
  }
  c.detonation_velocity = x.number("detonation_velocity", "m/s", Range::positive(),
                                   both ? std::optional<double>() : cj.detonation_velocity);
  c.detonation_energy = x.number("detonation_energy", "J/kg", Range::positive(),
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

void read_gas_sections(TableReader& root, CaseConfig& c, RockCaseConfig* rock) {
  TableReader domain = root.table("domain", true);
  const long long nx = domain.integer("nx", "cells", 3, {}, 1000000), ny = domain.integer("ny", "cells", 3, {}, 1000000);
  // The gas arrays hold about 45 doubles a cell (state and derivatives twice, work arrays, coupling).
  check_memory_need(fmt::format("domain.nx x domain.ny = {} x {} cells", nx, ny),
                    45.0 * 8.0 * static_cast<double>(nx + 5) * static_cast<double>(ny + 5));
  const double x0 = domain.number("x_min", "m", Range::any()), x1 = domain.number("x_max", "m", Range::above(x0));
  const double y0 = domain.number("y_min", "m", Range::any()), y1 = domain.number("y_max", "m", Range::above(y0));
  domain.finish();
  c.grid = cip::GasGrid::from_box(static_cast<int>(nx), static_cast<int>(ny), x0, x1, y0, y1);

  TableReader gas = root.table("gas", true);
  c.eos = cip::EquationOfState::ideal(gas.number("gamma", "", Range::above(1.0), 1.4));
  c.courant = gas.number("courant", "", Range{1e-6, 1.0, false, false}, 0.1);  // below 1e-6 a run never ends
  c.solver.transport = gas.text("transport", {"conservative", "paper"}, std::string("conservative")) == "paper"
                           ? cip::Transport::paper
                           : cip::Transport::conservative;
  const cip::ArtificialViscosity q = cip::recommended_viscosity(c.solver.transport);
  c.solver.viscosity.linear = gas.number("viscosity_linear", "", Range::non_negative(), q.linear);
  c.solver.viscosity.quadratic = gas.number("viscosity_quadratic", "", Range::non_negative(), q.quadratic);
  c.solver.limiter =
      gas.text("limiter", {"minmax", "none"}, std::string("minmax")) == "none" ? cip::Limiter::none : cip::Limiter::minmax;
  TableReader bc = gas.table("boundary");
  c.solver.boundaries.set(cip::left, read_boundary(bc, "left")).set(cip::right, read_boundary(bc, "right"));
  c.solver.boundaries.set(cip::bottom, read_boundary(bc, "bottom")).set(cip::top, read_boundary(bc, "top"));
  bc.finish();
  for (int a = 0; a < 2; ++a)
    if ((c.solver.boundaries.kind(2 * a) == cip::BoundaryKind::periodic) !=
        (c.solver.boundaries.kind(2 * a + 1) == cip::BoundaryKind::periodic))
      throw InputError(fmt::format("gas.boundary.{} and gas.boundary.{} must both be \"periodic\" or neither",
                                   a == 0 ? "left" : "bottom", a == 0 ? "right" : "top"));
  TableReader ambient = gas.table("ambient", true);
  c.ambient = read_state(ambient, c.eos);
  ambient.finish();
  if (gas.has("explosive")) {
    TableReader x = gas.table("explosive");
    c.explosive = read_explosive(x, c);
  }
  for (TableReader& r : gas.table_array("region")) {
    GasRegion region;
    const std::string shape = r.text("shape", {"box", "circle"});
    if (shape == "circle") {
      region.shape = GasRegion::Shape::circle;
      region.center = r.pair("center", "m");
      region.radius = r.number("radius", "m", Range::positive());
    } else {
      region.min = r.pair("min", "m");
      region.max = r.pair("max", "m");
      if (!(region.max[0] > region.min[0]) || !(region.max[1] > region.min[1]))
        throw InputError(fmt::format("{}: box needs max > min in x and y", r.path()));
    }
    const bool products = r.text("material", {"air", "products"}, std::string("air")) == "products";
    if (products && !c.explosive)
      throw InputError(fmt::format("{}.material = \"products\" needs a [gas.explosive] table (the products' equation of "
                                   "state)", r.path()));
    region.state = read_state(r, products ? *c.explosive : c.eos);
    region.state.products_fraction = products ? 1.0 : 0.0;
    r.finish();
    c.regions.push_back(region);
  }
  if (c.materials().two && c.solver.transport != cip::Transport::conservative)
    throw InputError("gas.transport = \"paper\": the paper's transport carries one gas; a [[gas.region]] of detonation "
                     "products needs \"conservative\"");
  gas.finish();

  TableReader probe = root.table("probe");
  for (TableReader& p : probe.table_array("line")) {
    LineProbe l;
    l.name = p.text("name", {});
    l.start = p.pair("start", "m");
    l.end = p.pair("end", "m");
    l.points = static_cast<int>(p.integer("points", "", 2, 101, 1000000));
    l.times = p.number_list("times", "s", Range::non_negative());
    p.finish();
    c.line_probes.push_back(l);
  }
  for (TableReader& p : probe.table_array("point")) {
    PointProbe q;
    q.name = p.text("name", {});
    q.position = p.pair("position", "m");
    q.interval = p.number("interval", "s", Range::positive());
    p.finish();
    c.point_probes.push_back(q);
  }
  if (rock) read_rock_probes(probe, *rock);
  probe.finish();
  std::vector<std::string> lines, points;
  for (const LineProbe& l : c.line_probes) check_output_name("probe.line", l.name), lines.push_back(l.name);
  for (const PointProbe& q : c.point_probes) check_output_name("probe.point", q.name), points.push_back(q.name);
  check_unique_names("probe.line", lines);
  check_unique_names("probe.point", points);
}

void check_gas_intervals(const CaseConfig& c) {
  check_interval("output.interval", c.output_interval, c.end_time, true);
  for (size_t k = 0; k < c.point_probes.size(); ++k)
    check_interval(fmt::format("probe.point.{}.interval", k), c.point_probes[k].interval, c.end_time, false);
}

void check_unique_names(const std::string& kind, const std::vector<std::string>& names) {
  for (size_t a = 0; a < names.size(); ++a)
    for (size_t b = a + 1; b < names.size(); ++b)
      if (names[a] == names[b])
        throw InputError(fmt::format("{}.{}.name = \"{}\": the same name as {}.{}; each needs its own (it names its "
                                     "output)", kind, b, names[b], kind, a));
}

void check_interval(const std::string& key, double interval, double end_time, bool zero_allowed) {
  if (zero_allowed && interval == 0) return;
  if (!(interval >= 1e-9 * end_time))
    throw InputError(fmt::format("{} = {:g} s: must be at least 1e-9 x time.end = {:g} s{} (at most 1e9 samples a run)",
                                 key, interval, 1e-9 * end_time, zero_allowed ? ", or 0" : ""));
}

void check_memory_need(const std::string& what, double bytes) {
  const double memory = static_cast<double>(sysconf(_SC_PHYS_PAGES)) * static_cast<double>(sysconf(_SC_PAGE_SIZE));
  if (memory > 0 && bytes > memory)
    throw InputError(fmt::format("{}: needs about {:.3g} GB of memory, this machine has {:.3g} GB", what, bytes / 1e9,
                                 memory / 1e9));
}

void check_output_name(const std::string& kind, const std::string& name) {
  if (name.empty() || name.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_-") !=
                          std::string::npos)
    throw InputError(fmt::format("{} name \"{}\": use letters, digits, '_' or '-' only", kind, name));
}

CaseConfig read_case(const toml::table& input) {
  CaseConfig c;
  TableReader root(input, "", c.echo);
  read_gas_sections(root, c);
  const TimeKeys time = read_time_keys(root, CaseKind::gas);
  c.end_time = time.end;
  c.fixed_dt = time.dt;
  c.max_steps = time.max_steps;

  TableReader out = root.table("output");
  assign_output_basics(read_output_basics(out, 1), c);
  c.drift_warning = out.number("drift_warning", "", Range::positive(), 0.01);
  out.finish();
  check_gas_intervals(c);

  root.finish();
  return c;
}

TimeKeys read_time_keys(TableReader& root, CaseKind kind) {
  TimeKeys k;
  TableReader time = root.table("time", true);
  k.end = time.number("end", "s", Range::positive());
  k.dt = time.optional_number("dt", "s", Range::positive());
  if (k.dt && !(*k.dt >= 1e-9 * k.end))
    throw InputError(fmt::format("time.dt = {:g} s: must be at least 1e-9 x time.end = {:g} s (at most 1e9 steps a run)",
                                 *k.dt, 1e-9 * k.end));
  k.max_steps = time.integer("max_steps", "", 0, 0);
  if (kind != CaseKind::gas) k.step_fraction = time.number("step_fraction", "", Range::half_open(0.0, 1.0), 0.9);
  if (kind == CaseKind::coupled) k.rock_subcycling = time.boolean("rock_subcycling", false);
  time.finish();
  return k;
}

OutputBasics read_output_basics(TableReader& out, long long monitor_default) {
  OutputBasics b;
  b.directory = out.text("directory", {}, std::string("output"));
  if (b.directory.empty()) throw InputError("output.directory must not be empty");
  b.interval = out.number("interval", "s", Range::non_negative(), 0.0);
  if (out.has("times")) {
    b.times = out.number_list("times", "s", Range::positive());
    for (size_t k = 1; k < b.times.size(); ++k)
      if (!(b.times[k] > b.times[k - 1]))
        throw InputError(fmt::format("output.times: {} s follows {} s: the times must be given in ascending order",
                                     b.times[k], b.times[k - 1]));
  }
  b.vtk = out.boolean("vtk", true);
  b.progress_interval = out.number("progress_interval", "s (wall)", Range::non_negative(), 2.0);
  b.monitor_interval = out.integer("monitor_interval", "steps", 1, monitor_default);
  return b;
}

toml::table load_input(const std::string& input_path, const std::vector<std::string>& overrides) {
  toml::table input = parse_input_file(input_path);
  for (const std::string& o : overrides) apply_override(input, o);
  return input;
}

CaseConfig load_case(const std::string& input_path, const std::vector<std::string>& overrides) {
  return read_case(load_input(input_path, overrides));
}

}  // namespace blastsim::app
