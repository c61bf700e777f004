//! \file input_monitor.cpp
//! \brief [monitor] (coupled cases): the blasthole monitor ([monitor.blasthole]: wall_series.csv, summary.txt)
//! and the gas regions of coupling_series.csv ([[monitor.region]]); docs/input.md.
#include "blastsim/core/error.hpp"
#include "case.hpp"

#include <fmt/format.h>

namespace blastsim::app {

void read_monitor(TableReader& root, Case& c) {
  TableReader monitor = root.table("monitor");
  if (monitor.has("interval"))
    throw InputError("monitor.interval: moved to monitor.blasthole.interval [s]; the blasthole monitor (wall_series.csv, "
                     "summary.txt) runs when the input has a [monitor.blasthole] table with center, hole_radius, "
                     "outer_radius and interval (docs/input.md)");
  if (monitor.has("blasthole")) {
    TableReader b = monitor.table("blasthole");
    MonitorSettings::Blasthole spec;
    spec.geometry.center = b.pair("center", "m");
    spec.geometry.hole_radius = b.number("hole_radius", "m", Range::positive());
    spec.geometry.outer_radius = b.number("outer_radius", "m", Range::positive());
    if (!(spec.geometry.outer_radius > spec.geometry.hole_radius))
      throw InputError(fmt::format("monitor.blasthole.outer_radius = {} m: must exceed monitor.blasthole.hole_radius = {} m",
                                   spec.geometry.outer_radius, spec.geometry.hole_radius));
    spec.interval = b.number("interval", "s", Range::positive(), 1e-6);
    b.finish();
    c.monitor.blasthole = spec;
  }
  std::vector<std::string> names;
  for (TableReader& r : monitor.table_array("region")) {
    MonitorSettings::Region m;
    m.name = r.text("name", {});
    m.where = read_region_shape(r);
    r.finish();
    check_output_name("monitor.region", m.name);
    names.push_back(m.name);
    c.monitor.regions.push_back(m);
  }
  monitor.finish();
  check_unique_names("monitor.region", names);
}

}  // namespace blastsim::app
