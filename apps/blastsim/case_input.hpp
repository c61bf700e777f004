//! \file case_input.hpp
//! \brief Reading a CaseConfig from a TOML case file (with command-line overrides).
#pragma once

#include "case_config.hpp"
#include "coupled_config.hpp"
#include "rock_config.hpp"
#include "input_reader.hpp"

#include <optional>
#include <string>
#include <vector>

namespace blastsim::app {

//! Reads and validates a case; `overrides` are "section.key=value" strings applied first. Throws
//! InputError (one line naming the key, the value and what is allowed) on any bad input.
CaseConfig load_case(const std::string& input_path, const std::vector<std::string>& overrides);

//! Same from an already parsed table (tests).
CaseConfig read_case(const toml::table& input);

//! What a parsed input describes: [gas] alone, [rock] alone, or both (a coupled gas-rock case).
enum class CaseKind { gas, rock, coupled };

//! The [time] keys, read in one place for every kind of case: end, dt and max_steps always; step_fraction
//! for cases with rock; rock_subcycling for coupled cases (a key of another kind is refused as unknown).
struct TimeKeys {
  double end = 0;                 //!< time.end [s]
  std::optional<double> dt;       //!< time.dt [s]
  long long max_steps = 0;        //!< time.max_steps, 0: no limit
  double step_fraction = 0.9;     //!< time.step_fraction [-] (rock)
  bool rock_subcycling = false;   //!< time.rock_subcycling (coupled)
};
TimeKeys read_time_keys(TableReader& root, CaseKind kind);

//! Output keys shared by gas and rock cases ([output] directory, interval, vtk, progress_interval,
//! monitor_interval); the caller reads its own keys and calls finish().
struct OutputBasics {
  std::string directory;
  double interval = 0;
  std::vector<double> times;  //!< output.times: extra snapshot times [s], ascending
  bool vtk = true;
  double progress_interval = 2;
  long long monitor_interval = 1;
};
OutputBasics read_output_basics(TableReader& out, long long monitor_default);

//! Copies the shared output keys into a gas or rock case configuration.
template <class Config>
void assign_output_basics(const OutputBasics& b, Config& c) {
  c.output_directory = b.directory;
  c.output_interval = b.interval;
  c.output_times = b.times;
  c.vtk = b.vtk;
  c.progress_interval = b.progress_interval;
  c.monitor_interval = b.monitor_interval;
}

//! Parses a case file and applies the overrides (the first half of load_case()).
toml::table load_input(const std::string& input_path, const std::vector<std::string>& overrides);

CaseKind case_kind(const toml::table& input);

//! Reads and validates a rock-only case; InputError names the key, the value and what is allowed.
RockCaseConfig read_rock_case(const toml::table& input);

//! Reads and validates a coupled case: [domain], [gas], [probe] as for gas cases, [rock] as for rock cases
//! (no [[rock.pressure]]: the gas loads the rock), [time], [output] and [[monitor.region]].
CoupledCaseConfig read_coupled_case(const toml::table& input);

//! The sections of one solver, read through a caller's root table (so a coupled case can read both).
//! [domain], [gas], [probe]; with `rock` (a coupled case) also the rock's probes ([[probe.rock_point]]).
void read_gas_sections(TableReader& root, CaseConfig& c, RockCaseConfig* rock = nullptr);
void read_rock_section(TableReader& root, RockCaseConfig& c);  //!< [rock], then [analysis]
void read_analysis_section(TableReader& root, RockCaseConfig& c);  //!< [analysis] (after [rock]: its mesh sets defaults)
void read_rock_probes(TableReader& probe, RockCaseConfig& c);      //!< [[probe.rock_point]] of the table [probe]
//! [[charge]] of a coupled case (after [gas] and [rock]): the charges, their holes put first into the rock mesh's
//! holes, the damage-zone holes defaulted to them; every error names the key.
void read_charges(TableReader& root, CoupledCaseConfig& c);
//! The holes of a rectangle_with_holes / disc_with_holes mesh: at least one, each inside the rock with half an
//! element to spare, none overlapping; names[k] is hole k's key in messages.
void check_mesh_holes(const RockMeshSpec& s, const std::vector<std::string>& names);

//! Throws InputError unless `name` (used in file names) is letters, digits, '_' and '-'.
void check_output_name(const std::string& kind, const std::string& name);

//! check_interval() of output.interval and every probe.point interval of a gas (or coupled) case.
void check_gas_intervals(const CaseConfig& c);

//! InputError when the output names of one kind repeat (two probes would write one file): `kind` is the
//! table ("probe.point"), `names` in input order.
void check_unique_names(const std::string& kind, const std::vector<std::string>& names);

//! InputError when a sampling interval [s] would give more than 1e9 samples in the run (or could not advance
//! the time): `key` = `interval` must be 0 (when `zero_allowed`) or at least 1e-9 x time.end.
void check_interval(const std::string& key, double interval, double end_time, bool zero_allowed);

//! InputError when `bytes`, the memory a case needs for what `what` names, exceeds the machine's memory.
void check_memory_need(const std::string& what, double bytes);

}  // namespace blastsim::app
