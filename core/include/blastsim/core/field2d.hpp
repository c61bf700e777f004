//! \file field2d.hpp
//! \brief Non-owning 2-D view of a padded, row-major array (i fastest) with ghost layers: the type kernels take.
//! Plain data with no backend dependency; make_field_view() in backend.hpp builds one over a device vector.
#pragma once

#include "blastsim/core/macros.hpp"

#include <cassert>
#include <type_traits>

namespace blastsim {

//! Shape of a padded 2-D array: logical indices i in [-ghost, ni + ghost), j in [-ghost, nj + ghost).
struct PaddedShape {
  int ni = 0;     //!< logical points along x
  int nj = 0;     //!< logical points along y
  int ghost = 0;  //!< ghost layers on each side
  BLAST_HD int stride() const { return ni + 2 * ghost; }
  BLAST_HD index_t size() const { return static_cast<index_t>(ni + 2 * ghost) * (nj + 2 * ghost); }
  BLAST_HD index_t offset(int i, int j) const {
    return static_cast<index_t>(j + ghost) * stride() + (i + ghost);
  }
  BLAST_HD bool contains(int i, int j) const {
    return i >= -ghost && i < ni + ghost && j >= -ghost && j < nj + ghost;
  }
};

//! View {pointer, shape}; operator()(i, j) addresses logical point (i, j). Copied by value into kernels.
template <class T>
struct Field2D {
  T* data = nullptr;
  PaddedShape shape;
  BLAST_HD T& operator()(int i, int j) const {
#if !defined(NDEBUG) && !defined(__CUDA_ARCH__)
    assert(shape.contains(i, j));
#endif
    return data[shape.offset(i, j)];
  }
  //! A view of T converts to a read-only view of the same array.
  template <class U = T, class = std::enable_if_t<!std::is_const_v<U>>>
  BLAST_HD operator Field2D<const U>() const {
    return Field2D<const U>{data, shape};
  }
};


}  // namespace blastsim
