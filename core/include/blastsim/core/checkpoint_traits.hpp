//! \file checkpoint_traits.hpp
//! \brief Which checkpoint records hold only real numbers: their values are checked for NaN when read (a plain
//! trait, so that kernel headers can mark their all-double structs without the host checkpoint code).
#pragma once

#include <type_traits>

namespace blastsim {

//! True for a record element made of doubles only (double itself, and structs marked by
//! BLASTSIM_CHECKPOINT_REALS): CheckpointReader refuses such a record when any of its values is NaN, and a
//! struct's when any is infinite (a plain double may hold an infinity as a sentinel; a ledger, a total or an
//! event record never does). `finite` says which.
template <class T>
struct CheckpointReals : std::is_same<T, double> {
  static constexpr bool finite = false;
};

}  // namespace blastsim

//! Marks `Type`, a struct of doubles only, as a record of finite real numbers (CheckpointReals); at namespace
//! scope.
#define BLASTSIM_CHECKPOINT_REALS(Type)                                                 \
  template <>                                                                           \
  struct blastsim::CheckpointReals<Type> : std::true_type {                             \
    static_assert(sizeof(Type) % sizeof(double) == 0, #Type " must hold doubles only"); \
    static constexpr bool finite = true;                                                \
  };
