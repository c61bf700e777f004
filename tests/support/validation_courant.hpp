//! \file validation_courant.hpp
//! \brief The Courant number the gas and coupled validations run at: the paper's 0.1, or the value of the
//! environment variable BLASTSIM_TEST_COURANT for the Courant study of docs/performance.md (the bounds stay).
#pragma once

#include <cstdlib>
#include <stdexcept>
#include <string>

namespace blastsim::test {

inline double validation_courant() {
  static const double courant = [] {
    const char* text = std::getenv("BLASTSIM_TEST_COURANT");
    if (!text) return 0.1;
    char* end = nullptr;
    const double c = std::strtod(text, &end);
    if (end == text || *end != '\0' || !(c > 0 && c <= 1))
      throw std::invalid_argument(std::string("BLASTSIM_TEST_COURANT = ") + text + ": must be a number in (0, 1]");
    return c;
  }();
  return courant;
}

}  // namespace blastsim::test
