//! \file access.hpp
//! \brief Access intent of the non-owning views that kernels take (MFEM's Read()/ReadWrite(), AMReX's
//! Array4<const T>): a view made for reading holds const pointers, so a kernel's members say what it reads
//! and what it writes. Plain header: no backend dependency.
#pragma once

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

}  // namespace blastsim

//! Helpers for field lists written once as X-macros `X(type, name, comment)` (see libfdem's rock_fields.hpp):
//! BLASTSIM_VIEW_MEMBER declares a view's pointer member of access A, BLASTSIM_CONST_VIEW_MEMBER a const one.
#define BLASTSIM_VIEW_MEMBER(type, name, comment) ::blastsim::access_ptr<type, A> name;
#define BLASTSIM_CONST_VIEW_MEMBER(type, name, comment) const type* name;
