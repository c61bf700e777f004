//! \file case_input.hpp
//! \brief Reading a CaseConfig from a TOML case file (with command-line overrides).
#pragma once

#include "case_config.hpp"
#include "input_reader.hpp"

#include <string>
#include <vector>

namespace blastsim::app {

//! Reads and validates a case; `overrides` are "section.key=value" strings applied first. Throws
//! InputError (one line naming the key, the value and what is allowed) on any bad input.
CaseConfig load_case(const std::string& input_path, const std::vector<std::string>& overrides);

//! Same from an already parsed table (tests).
CaseConfig read_case(const toml::table& input);

}  // namespace blastsim::app
