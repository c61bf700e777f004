//! \file input_time.cpp
//! \brief [time]: the end time, a fixed step, a step limit; the rock's step fraction (cases with rock) and its
//! subcycling (coupled cases); docs/input.md.
#include "blastsim/core/error.hpp"
#include "case.hpp"

#include <fmt/format.h>

namespace blastsim::app {

void read_time(TableReader& root, Case& c) {
  TimeSettings& k = c.time;
  TableReader time = root.table("time", true);
  k.end = time.number("end", "s", Range::positive());
  k.dt = time.optional_number("dt", "s", Range::positive());
  if (k.dt && !(*k.dt >= 1e-9 * k.end))
    throw InputError(fmt::format("time.dt = {:g} s: must be at least 1e-9 x time.end = {:g} s (at most 1e9 steps a run)",
                                 *k.dt, 1e-9 * k.end));
  k.max_steps = time.integer("max_steps", "", 0, 0);
  if (c.kind != CaseKind::gas) k.step_fraction = time.number("step_fraction", "", Range::half_open(0.0, 1.0), 0.9);
  if (c.kind == CaseKind::coupled) k.rock_subcycling = time.boolean("rock_subcycling", false);
  time.finish();
}

}  // namespace blastsim::app
