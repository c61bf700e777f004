//! \file device_groups.hpp
//! \brief Owning device storage generated from the field lists that kernels take as views (X-macro lists
//! `X(element type, name, comment)`, e.g. libfdem's rock_fields.hpp): one DeviceVector per entry, the group's
//! views, and a visitor over its arrays (checkpoints, sizing). For the libraries' sources only: it includes
//! the backend.
//!
//! - BLASTSIM_CONST_STORAGE(Group, LIST): `Group##Arrays` whose view() is a `Group` of const pointers (params);
//! - BLASTSIM_STATE_STORAGE(Group, LIST): view<A>() gives `Group<A>` (default read_write), read() the read view;
//! - BLASTSIM_FIELD_STORAGE(Group, LIST): the same for Field2D views on a padded grid shape, view<A>(shape) and
//!   read(shape).
//! Every storage has for_each(fn): fn(name, array) for each entry, in list order. write_array() and
//! read_array() put one array in a checkpoint and back.
#pragma once

#include "blastsim/core/access.hpp"
#include "blastsim/core/backend.hpp"
#include "blastsim/core/checkpoint.hpp"

#include <string>

namespace blastsim {
//! A device array as the checkpoint record `name`.
template <class T>
void write_array(CheckpointWriter& w, const std::string& name, const DeviceVector<T>& v) {
  w.host_array(name, to_host(v));
}
//! Fills a device array from the checkpoint record `name`; `expected` (when not 0) is the size it must have.
template <class T>
void read_array(CheckpointReader& r, const std::string& name, DeviceVector<T>& v, std::size_t expected = 0) {
  copy_from_host(v, r.host_array<T>(name, expected));
}
}  // namespace blastsim

#define BLASTSIM_STORAGE_MEMBER(type, name, comment) DeviceVector<type> name;
#define BLASTSIM_STORAGE_POINTER(type, name, comment) device_ptr(name),
#define BLASTSIM_STORAGE_FIELD(type, name, comment) make_field_view(name, shape),
#define BLASTSIM_STORAGE_VISIT(type, name, comment) fn(#name, name);

#define BLASTSIM_STORAGE_VISITORS(LIST)    \
  template <class Fn>                      \
  void for_each(Fn&& fn) {                 \
    LIST(BLASTSIM_STORAGE_VISIT)           \
  }                                        \
  template <class Fn>                      \
  void for_each(Fn&& fn) const {           \
    LIST(BLASTSIM_STORAGE_VISIT)           \
  }

#define BLASTSIM_CONST_STORAGE(Group, LIST)                             \
  struct Group##Arrays {                                                \
    LIST(BLASTSIM_STORAGE_MEMBER)                                       \
    Group view() const { return Group{LIST(BLASTSIM_STORAGE_POINTER)}; } \
    BLASTSIM_STORAGE_VISITORS(LIST)                                     \
  };

#define BLASTSIM_STATE_STORAGE(Group, LIST)                                                          \
  struct Group##Arrays {                                                                             \
    LIST(BLASTSIM_STORAGE_MEMBER)                                                                    \
    template <::blastsim::Access A = ::blastsim::Access::read_write>                                 \
    Group<A> view() {                                                                                \
      return Group<A>{LIST(BLASTSIM_STORAGE_POINTER)};                                               \
    }                                                                                                \
    Group<::blastsim::Access::read> read() const {                                                   \
      return Group<::blastsim::Access::read>{LIST(BLASTSIM_STORAGE_POINTER)};                        \
    }                                                                                                \
    BLASTSIM_STORAGE_VISITORS(LIST)                                                                  \
  };

#define BLASTSIM_FIELD_STORAGE(Group, LIST)                                                          \
  struct Group##Arrays {                                                                             \
    LIST(BLASTSIM_STORAGE_MEMBER)                                                                    \
    template <::blastsim::Access A = ::blastsim::Access::read_write>                                 \
    Group<A> view(::blastsim::PaddedShape shape) {                                                   \
      return Group<A>{LIST(BLASTSIM_STORAGE_FIELD)};                                                 \
    }                                                                                                \
    Group<::blastsim::Access::read> read(::blastsim::PaddedShape shape) const {                      \
      return Group<::blastsim::Access::read>{LIST(BLASTSIM_STORAGE_FIELD)};                          \
    }                                                                                                \
    BLASTSIM_STORAGE_VISITORS(LIST)                                                                  \
  };
