//! \file access.hpp
//! \brief Access intent of the non-owning views that kernels take (MFEM's Read()/ReadWrite(), AMReX's
//! Array4<const T>): a view made for reading holds const pointers, so a kernel's members say what it reads
//! and what it writes. Plain header: no backend dependency.
#pragma once

#include "blastsim/core/field2d.hpp"

#include <type_traits>

namespace blastsim {

//! What a kernel may do with the arrays of a view.
enum class Access {
  read,        //!< const pointers: the kernel only reads
  read_write,  //!< the kernel writes (and may read)
};

//! Pointer to T with the constness of access A.
template <class T, Access A>
using access_ptr = std::conditional_t<A == Access::read, const T*, T*>;
//! 2-D view of a padded array of T with the constness of access A.
template <class T, Access A>
using access_field = Field2D<std::conditional_t<A == Access::read, const T, T>>;

}  // namespace blastsim

//! Helpers for field lists written once as X-macros `X(type, name, comment)` (see libfdem's rock_fields.hpp):
//! BLASTSIM_VIEW_MEMBER declares a view's pointer member of access A, BLASTSIM_CONST_VIEW_MEMBER a const one,
//! BLASTSIM_FIELD_MEMBER a 2-D view (Field2D, on a padded grid shape) of access A. The owning storage comes
//! from the same lists (core/device_groups.hpp).
#define BLASTSIM_VIEW_MEMBER(type, name, comment) ::blastsim::access_ptr<type, A> name;
#define BLASTSIM_CONST_VIEW_MEMBER(type, name, comment) const type* name;
#define BLASTSIM_FIELD_MEMBER(type, name, comment) ::blastsim::access_field<type, A> name;
//! Inside a view template Group<A> (any of the above): a read_write view converts to the read view of the same
//! arrays; NAMES lists the members, e.g. LIST(BLASTSIM_MEMBER_NAME).
#define BLASTSIM_MEMBER_NAME(type, name, comment) name,
#define BLASTSIM_COMMA ,
#define BLASTSIM_READ_CONVERSION(Group, NAMES)                                                          \
  template <::blastsim::Access B = A, class = std::enable_if_t<B == ::blastsim::Access::read_write>>    \
  BLAST_HD operator Group<::blastsim::Access::read>() const {                                           \
    return {NAMES};                                                                                     \
  }

//! Declares the view of a field list: Group<A> with one member of access A per entry (a pointer, or for
//! BLASTSIM_FIELD_GROUP a Field2D on a padded grid shape) and the conversion of its read_write view to its
//! read view; BLASTSIM_CONST_GROUP a plain Group of const pointers (params).
#define BLASTSIM_VIEW_GROUP(Group, LIST)                                 \
  template <::blastsim::Access A>                                      \
  struct Group {                                                        \
    LIST(BLASTSIM_VIEW_MEMBER)                                          \
    BLASTSIM_READ_CONVERSION(Group, LIST(BLASTSIM_MEMBER_NAME))         \
  };
#define BLASTSIM_FIELD_GROUP(Group, LIST)                                \
  template <::blastsim::Access A>                                      \
  struct Group {                                                        \
    LIST(BLASTSIM_FIELD_MEMBER)                                         \
    BLASTSIM_READ_CONVERSION(Group, LIST(BLASTSIM_MEMBER_NAME))         \
  };
#define BLASTSIM_CONST_GROUP(Group, LIST) \
  struct Group {                          \
    LIST(BLASTSIM_CONST_VIEW_MEMBER)      \
  };
