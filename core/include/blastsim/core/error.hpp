//! \file error.hpp
//! \brief Exception types shared by the libraries: bad input (user's fault) and instability (the run's).
#pragma once

#include <stdexcept>
#include <string>

namespace blastsim {

//! Invalid user input: the message names the key, the value and what is allowed.
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

//! The simulation became unstable (NaN, negative density, stability limit violated).
class InstabilityError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace blastsim
