//! \file input_probe.cpp
//! \brief [probe]: gas values along lines and at points (gas and coupled cases), rock velocity probes (rock and
//! coupled cases); docs/input.md.
#include "case.hpp"

#include <fmt/format.h>

namespace blastsim::app {

void read_probe(TableReader& root, Case& c) {
  TableReader probe = root.table("probe");
  ProbeSettings& p = c.probes;
  std::vector<std::string> lines, points, rock;
  if (c.kind != CaseKind::rock) {
    for (TableReader& t : probe.table_array("line")) {
      ProbeSettings::Line l;
      l.name = t.text("name", {});
      l.start = t.pair("start", "m");
      l.end = t.pair("end", "m");
      l.points = static_cast<int>(t.integer("points", "", 2, 101, 1000000));
      l.times = t.number_list("times", "s", Range::non_negative());
      t.finish();
      check_output_name("probe.line", l.name);
      lines.push_back(l.name);
      p.lines.push_back(l);
    }
    for (TableReader& t : probe.table_array("point")) {
      ProbeSettings::Point q;
      q.name = t.text("name", {});
      q.position = t.pair("position", "m");
      q.interval = t.number("interval", "s", Range::positive());
      t.finish();
      check_output_name("probe.point", q.name);
      points.push_back(q.name);
      p.points.push_back(q);
    }
  }
  if (c.kind != CaseKind::gas) {
    for (TableReader& t : probe.table_array("rock_point")) {
      ProbeSettings::RockPoint q;
      q.name = t.text("name", {});
      q.position = t.pair("position", "m");
      if (t.has("until")) q.until = t.number("until", "s", Range::positive());
      t.allow({"until"});
      t.finish();
      check_output_name("probe.rock_point", q.name);
      rock.push_back(q.name);
      p.rock_points.push_back(q);
    }
  }
  probe.finish();
  check_unique_names("probe.line", lines);
  check_unique_names("probe.point", points);
  check_unique_names("probe.rock_point", rock);
}

}  // namespace blastsim::app
