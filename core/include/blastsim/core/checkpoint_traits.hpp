//! \file checkpoint_traits.hpp
//! \brief Which checkpoint records hold only real numbers: their values are checked for NaN when read (a plain
//! trait, so that kernel headers can mark their all-double structs without the host checkpoint code).
#pragma once

#include <type_traits>

namespace blastsim {

//! True for a record element made of doubles only (double itself, and structs marked by
//! BLASTSIM_CHECKPOINT_REALS): CheckpointReader refuses such a record when any of its values is NaN.
template <class T>
struct CheckpointReals : std::is_same<T, double> {};

}  // namespace blastsim

//! Marks `Type`, a struct of doubles only, as a record of real numbers (CheckpointReals); at namespace scope.
#define BLASTSIM_CHECKPOINT_REALS(Type)                                                 \
  template <>                                                                           \
  struct blastsim::CheckpointReals<Type> : std::true_type {                             \
    static_assert(sizeof(Type) % sizeof(double) == 0, #Type " must hold doubles only"); \
  };
