//! \file checkpoint.hpp
//! \brief Binary checkpoint files: a sequence of named, typed sections that each solver writes and reads in
//! the same order; written under a temporary name and renamed into place, so a crash never leaves a partial
//! checkpoint (the previous one stays valid until the rename).
#pragma once

#include "blastsim/core/backend.hpp"
#include "blastsim/core/error.hpp"

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <type_traits>
#include <vector>

namespace blastsim {

namespace detail {
inline constexpr char kCheckpointMagic[8] = {'B', 'L', 'S', 'T', 'C', 'K', 'P', '1'};
}

//! Writes a checkpoint: value(), host_array() and array() append sections; commit() renames the file into place.
class CheckpointWriter {
 public:
  explicit CheckpointWriter(std::string path) : path_(std::move(path)), tmp_(path_ + ".tmp") {
    out_.open(tmp_, std::ios::binary | std::ios::trunc);
    if (!out_) throw std::runtime_error("cannot write checkpoint " + tmp_);
    out_.write(detail::kCheckpointMagic, sizeof(detail::kCheckpointMagic));
  }
  template <class T>
  void host_array(const std::string& name, const std::vector<T>& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    section(name, sizeof(T), v.size());
    out_.write(reinterpret_cast<const char*>(v.data()), static_cast<std::streamsize>(v.size() * sizeof(T)));
  }
  template <class T>
  void value(const std::string& name, const T& v) {
    host_array(name, std::vector<T>{v});
  }
  template <class T>
  void array(const std::string& name, const DeviceVector<T>& v) {
    host_array(name, to_host(v));
  }
  void text(const std::string& name, const std::string& s) { host_array(name, std::vector<char>(s.begin(), s.end())); }
  //! Flushes, closes and renames the temporary file over the checkpoint.
  void commit() {
    out_.flush();
    out_.close();
    if (!out_) throw std::runtime_error("writing checkpoint " + tmp_ + " failed");
    std::filesystem::rename(tmp_, path_);
  }

 private:
  void section(const std::string& name, std::uint64_t element_size, std::uint64_t count) {
    const std::uint64_t n = name.size();
    out_.write(reinterpret_cast<const char*>(&n), sizeof n);
    out_.write(name.data(), static_cast<std::streamsize>(n));
    out_.write(reinterpret_cast<const char*>(&element_size), sizeof element_size);
    out_.write(reinterpret_cast<const char*>(&count), sizeof count);
  }
  std::string path_, tmp_;
  std::ofstream out_;
};

//! Reads a checkpoint section by section, in the order it was written; any mismatch (name, element size,
//! an expected count) is an InputError naming the file and the section.
class CheckpointReader {
 public:
  explicit CheckpointReader(std::string path) : path_(std::move(path)) {
    in_.open(path_, std::ios::binary);
    if (!in_) throw InputError("checkpoint " + path_ + ": cannot be opened (no checkpoint written there yet?)");
    char magic[sizeof(detail::kCheckpointMagic)] = {};
    in_.read(magic, sizeof magic);
    if (!in_ || std::string(magic, sizeof magic) != std::string(detail::kCheckpointMagic, sizeof magic))
      throw InputError("checkpoint " + path_ + ": not a blastsim checkpoint (or another version)");
  }
  template <class T>
  std::vector<T> host_array(const std::string& name) {
    static_assert(std::is_trivially_copyable_v<T>);
    const std::uint64_t count = section(name, sizeof(T));
    std::vector<T> v(count);
    in_.read(reinterpret_cast<char*>(v.data()), static_cast<std::streamsize>(count * sizeof(T)));
    if (!in_) fail(name, "truncated");
    return v;
  }
  template <class T>
  T value(const std::string& name) {
    const std::vector<T> v = host_array<T>(name);
    if (v.size() != 1) fail(name, "not a single value");
    return v[0];
  }
  //! Fills a device vector; `expected` (when not 0) is the size it must have.
  template <class T>
  void array(const std::string& name, DeviceVector<T>& v, std::size_t expected = 0) {
    const std::vector<T> h = host_array<T>(name);
    if (expected != 0 && h.size() != expected)
      fail(name, "holds " + std::to_string(h.size()) + " values, this case needs " + std::to_string(expected) +
                     " (a checkpoint of another case?)");
    copy_from_host(v, h);
  }
  std::string text(const std::string& name) {
    const std::vector<char> c = host_array<char>(name);
    return std::string(c.begin(), c.end());
  }
  const std::string& path() const { return path_; }

 private:
  std::uint64_t section(const std::string& name, std::uint64_t element_size) {
    std::uint64_t n = 0, size = 0, count = 0;
    in_.read(reinterpret_cast<char*>(&n), sizeof n);
    if (!in_ || n > 4096) fail(name, "missing");
    std::string found(n, '\0');
    in_.read(found.data(), static_cast<std::streamsize>(n));
    in_.read(reinterpret_cast<char*>(&size), sizeof size);
    in_.read(reinterpret_cast<char*>(&count), sizeof count);
    if (!in_) fail(name, "truncated");
    if (found != name) fail(name, "found section '" + found + "' instead");
    if (size != element_size) fail(name, "element size differs");
    return count;
  }
  [[noreturn]] void fail(const std::string& name, const std::string& what) const {
    throw InputError("checkpoint " + path_ + ", section '" + name + "': " + what);
  }
  std::string path_;
  std::ifstream in_;
};

}  // namespace blastsim
