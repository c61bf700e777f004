//! \file input_output.cpp
//! \brief [output]: the output folder, the snapshot schedule, VTK, progress, the CSV rows, the balance warning
//! (gas and coupled cases) and the checkpoint (coupled cases); docs/input.md.
#include "blastsim/core/error.hpp"
#include "case.hpp"

#include <fmt/format.h>

namespace blastsim::app {

void read_output(TableReader& root, Case& c) {
  OutputSettings& o = c.output;
  TableReader out = root.table("output");
  o.directory = out.text("directory", {}, std::string("output"));
  if (o.directory.empty()) throw InputError("output.directory must not be empty");
  o.interval = out.number("interval", "s", Range::non_negative(), 0.0);
  if (out.has("times")) {
    o.times = out.number_list("times", "s", Range::positive());
    out.same_as_absent("times", o.times.empty());
    for (size_t k = 1; k < o.times.size(); ++k)
      if (!(o.times[k] > o.times[k - 1]))
        throw InputError(fmt::format("output.times: {} s follows {} s: the times must be given in ascending order",
                                     o.times[k], o.times[k - 1]));
  }
  o.vtk = out.boolean("vtk", true);
  o.progress_interval = out.number("progress_interval", "s (wall)", Range::non_negative(), 2.0);
  o.monitor_interval = out.integer("monitor_interval", "steps", 1, c.kind == CaseKind::gas ? 1 : 10);
  if (c.kind != CaseKind::rock) o.drift_warning = out.number("drift_warning", "", Range::positive(), 0.01);
  if (c.kind == CaseKind::coupled) o.checkpoint = out.boolean("checkpoint", true);
  out.finish();
}

}  // namespace blastsim::app
