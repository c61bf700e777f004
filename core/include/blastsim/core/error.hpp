//! \file error.hpp
//! \brief Exception types shared by the libraries: bad input (the user's), a failed write (the machine's) and
//! instability (the run's).
#pragma once

#include <stdexcept>
#include <string>

namespace blastsim {

//! Invalid user input: the message names the key, the value and what is allowed.
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

//! Writing an output file failed (disk full, permissions): the message names the file and the OS error.
class OutputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

//! The simulation became unstable (NaN, negative density, stability limit violated).
class InstabilityError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

//! A value about to be written is not finite (CsvRecord): the run stops before writing it.
class NonFiniteValue : public InstabilityError {
 public:
  using InstabilityError::InstabilityError;
};

}  // namespace blastsim
