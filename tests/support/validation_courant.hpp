//! \file validation_courant.hpp
//! \brief The Courant number the gas and coupled validations run at: the recommended number of the solver's
//! transport (cip::recommended_courant()) or of the coupler (GasRockCoupler::courant()), or the value of the
//! environment variable BLASTSIM_TEST_COURANT for the Courant study of docs/performance.md (the bounds stay).
#pragma once

#include "blastsim/cip/gas_types.hpp"

#include <cstdlib>
#include <optional>
#include <stdexcept>
#include <string>

namespace blastsim::test {

//! BLASTSIM_TEST_COURANT when set (a number in (0, 1]), else `recommended`.
inline double validation_courant(double recommended) {
  static const std::optional<double> given = []() -> std::optional<double> {
    const char* text = std::getenv("BLASTSIM_TEST_COURANT");
    if (!text) return std::nullopt;
    char* end = nullptr;
    const double c = std::strtod(text, &end);
    if (end == text || *end != '\0' || !(c > 0 && c <= 1))
      throw std::invalid_argument(std::string("BLASTSIM_TEST_COURANT = ") + text + ": must be a number in (0, 1]");
    return c;
  }();
  return given.value_or(recommended);
}

//! The validations' Courant number of a gas solved with transport t.
inline double validation_courant(cip::Transport t) { return validation_courant(cip::recommended_courant(t)); }

}  // namespace blastsim::test
