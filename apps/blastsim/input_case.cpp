//! \file input_case.cpp
//! \brief A case from its input: the sections in order (each in its input_<section>.cpp), the checks that span
//! sections, and the checks the readers share.
#include "blastsim/core/error.hpp"
#include "case.hpp"

#include <fmt/format.h>

#include <unistd.h>

namespace blastsim::app {

CaseKind case_kind(const toml::table& input) {
  const bool rock = input.contains("rock"), gas = input.contains("gas");
  return rock && gas ? CaseKind::coupled : (rock ? CaseKind::rock : CaseKind::gas);
}

Case read_case(const toml::table& input) {
  Case c;
  c.kind = case_kind(input);
  TableReader root(input, "", c.echo);
  if (c.kind != CaseKind::rock) read_domain(root, c), read_gas(root, c), read_probe(root, c);
  if (c.kind != CaseKind::gas) read_rock(root, c), read_analysis(root, c);
  if (c.kind == CaseKind::coupled) read_charges(root, c);  // checks the mesh's holes with the charges'
  if (c.kind != CaseKind::rock && c.gas.materials().two) {  // the products are the blast gas (the traced gas)
    for (std::size_t k = 0; k < c.gas.regions.size(); ++k) {
      if (c.gas.regions[k].blast_gas_given)
        throw InputError(fmt::format("gas.region.{}.blast_gas: in a run with detonation products the products are the "
                                     "blast gas; remove the key", k));
      c.gas.regions[k].state.tracer = 0.0;
    }
  }
  if (c.kind == CaseKind::rock) {
    // An initial aperture is room for the crack gas (a coupled case's); the rock's faces start touching.
    auto no_aperture = [](const std::string& label, double aperture) {
      if (aperture > 0)
        throw InputError(fmt::format("{}.initial_aperture = {:g} m: room for the gas in the crack, and a rock-only case "
                                     "has no gas (the faces start touching); remove the key, or give the case a gas "
                                     "and [crack_gas] enabled = true", label, aperture));
    };
    for (const fdem::PreCutCrack& cut : c.rock.model.cracks) no_aperture(cut.label, cut.initial_aperture);
    for (const fdem::JointSetSpec& set : c.rock.model.joint_sets) no_aperture(set.label, set.initial_aperture);
    std::vector<std::string> labels;
    for (std::size_t k = 0; k < c.rock.model.mesh.holes.size(); ++k) labels.push_back(fmt::format("rock.mesh.hole.{}", k));
    if (c.rock.model.mesh.has_holes() && labels.empty())
      throw InputError(fmt::format("rock.mesh.shape = \"{}\": needs at least one hole ([[rock.mesh.hole]])",
                                   fdem::mesh_shape_name(c.rock.model.mesh.shape)));
    fdem::check_mesh_holes(c.rock.model.mesh, labels);
  }
  read_time(root, c);
  read_output(root, c);
  if (c.kind == CaseKind::rock) read_probe(root, c);
  if (c.kind == CaseKind::coupled) read_monitor(root, c), read_coupling(root, c);
  if (c.kind == CaseKind::coupled && !c.gas.courant_given) {  // a coupled run's default follows its gas load too
    c.gas.courant = ibm::recommended_courant(c.gas.solver.transport, c.coupling.gas_load);
    for (EchoLine& e : c.echo)
      if (e.key == "gas.courant") e.text = fmt::format("gas.courant = {:g}{}", c.gas.courant, kDefaultMark);
  }
  // Sampling intervals against the end time.
  check_interval("output.interval", c.output.interval, c.time.end, true);
  for (size_t k = 0; k < c.probes.points.size(); ++k)
    check_interval(fmt::format("probe.point.{}.interval", k), c.probes.points[k].interval, c.time.end, false);
  if (c.monitor.blasthole) check_interval("monitor.blasthole.interval", c.monitor.blasthole->interval, c.time.end, false);
  // A delay the step cannot resolve would shorten the step to it (the stepper lands on every initiation).
  for (size_t k = 0; k < c.coupling.charges.size(); ++k) {
    const double t = c.coupling.charges[k].initiation_time;
    if (t > 0 && t < 1e-9 * c.time.end)
      throw InputError(fmt::format("charge.{}.initiation_time = {:g} s: must be 0 or at least 1e-9 x time.end = {:g} s",
                                   k, t, 1e-9 * c.time.end));
  }
  root.finish();
  return c;
}

Case load_case(const std::string& input_path, const std::vector<std::string>& overrides) {
  return read_case(load_input(input_path, overrides));
}

cip::CellRegion read_region_shape(TableReader& t) {
  if (t.text("shape", {"box", "circle"}) == "circle") {
    const std::array<double, 2> centre = t.pair("center", "m");
    return cip::CellRegion::circle(centre[0], centre[1], t.number("radius", "m", Range::positive()));
  }
  const std::array<double, 2> lo = t.pair("min", "m"), hi = t.pair("max", "m");
  if (!(hi[0] > lo[0]) || !(hi[1] > lo[1])) throw InputError(fmt::format("{}: box needs max > min in x and y", t.path()));
  return cip::CellRegion::box(lo[0], lo[1], hi[0], hi[1]);
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

}  // namespace blastsim::app
