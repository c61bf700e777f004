//! \file checkpoint.hpp
//! \brief Binary checkpoint files: named, typed records that a reader looks up by name, closed by a trailer
//! with the record count and a CRC-32 (zlib) of everything before it. Written under a temporary name and
//! renamed into place, so a crash never leaves a partial checkpoint (the previous one stays valid until the
//! rename); a reader refuses a file whose checksum, structure, record types or sizes do not match, and
//! records it does not know (finish()).
//!
//! Host code only: the solvers write their device arrays through write_array() / read_array() of
//! core/device_groups.hpp, so a file that only passes a checkpoint to the solvers needs no backend.
//!
//! Layout (little-endian as written by the machine): "BLSTCKP2", u32 version; then per record u64 name
//! length, the name, u64 element size, u64 count, the data; then "BLSTEND2", u64 record count, u32 CRC-32 of
//! all bytes before the trailer.
#pragma once

#include "blastsim/core/checkpoint_traits.hpp"
#include "blastsim/core/error.hpp"

#include <zlib.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <set>
#include <string>
#include <type_traits>
#include <vector>

namespace blastsim {

namespace detail {
inline constexpr char kCheckpointMagic[8] = {'B', 'L', 'S', 'T', 'C', 'K', 'P', '2'};
inline constexpr char kCheckpointEnd[8] = {'B', 'L', 'S', 'T', 'E', 'N', 'D', '2'};
inline constexpr std::uint32_t kCheckpointVersion = 2;
inline constexpr std::uint64_t kCheckpointMaxName = 256;
inline constexpr std::uint64_t kCheckpointTrailer = 8 + 8 + 4;
//! CRC-32 of n bytes continuing `crc` (zlib's, in pieces that fit its uInt length).
inline std::uint32_t crc32_of(std::uint32_t crc, const char* data, std::uint64_t n) {
  while (n > 0) {
    const uInt piece = static_cast<uInt>(n < (1u << 30) ? n : (1u << 30));
    crc = static_cast<std::uint32_t>(crc32(crc, reinterpret_cast<const Bytef*>(data), piece));
    data += piece, n -= piece;
  }
  return crc;
}
}  // namespace detail

//! Writes a checkpoint: value(), host_array() and text() add records (write_array() a device array); commit() closes the file with
//! its trailer and renames it into place.
class CheckpointWriter {
 public:
  explicit CheckpointWriter(std::string path) : path_(std::move(path)), tmp_(path_ + ".tmp") {
    out_.open(tmp_, std::ios::binary | std::ios::trunc);
    if (!out_) throw OutputError("cannot write checkpoint " + tmp_ + ": " + std::strerror(errno));
    put(detail::kCheckpointMagic, sizeof detail::kCheckpointMagic);
    put(&detail::kCheckpointVersion, sizeof detail::kCheckpointVersion);
  }
  template <class T>
  void host_array(const std::string& name, const std::vector<T>& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    if (!names_.insert(name).second) throw std::logic_error("checkpoint record '" + name + "' written twice");
    const std::uint64_t n = name.size(), size = sizeof(T), count = v.size();
    put(&n, sizeof n);
    put(name.data(), n);
    put(&size, sizeof size);
    put(&count, sizeof count);
    put(v.data(), count * sizeof(T));
  }
  template <class T>
  void value(const std::string& name, const T& v) {
    host_array(name, std::vector<T>{v});
  }
  void text(const std::string& name, const std::string& s) { host_array(name, std::vector<char>(s.begin(), s.end())); }
  //! Appends the trailer, flushes, closes, checks and renames the temporary file over the checkpoint.
  void commit() {
    const std::uint32_t crc = crc_;
    const std::uint64_t records = names_.size();
    out_.write(detail::kCheckpointEnd, sizeof detail::kCheckpointEnd);
    out_.write(reinterpret_cast<const char*>(&records), sizeof records);
    out_.write(reinterpret_cast<const char*>(&crc), sizeof crc);
    out_.flush();
    out_.close();
    if (!out_) throw OutputError("writing checkpoint " + tmp_ + " failed: " + std::strerror(errno));
    std::error_code ec;
    std::filesystem::rename(tmp_, path_, ec);
    if (ec) throw OutputError("cannot rename " + tmp_ + " to " + path_ + ": " + ec.message());
  }

 private:
  void put(const void* data, std::uint64_t n) {
    out_.write(static_cast<const char*>(data), static_cast<std::streamsize>(n));
    crc_ = detail::crc32_of(crc_, static_cast<const char*>(data), n);
  }
  std::string path_, tmp_;
  std::ofstream out_;
  std::uint32_t crc_ = 0;
  std::set<std::string> names_;
};

//! Reads a checkpoint: the constructor checks the header, the trailer and the checksum and indexes the
//! records; host_array(), value() and text() (and read_array() for a device array) look records up by name and
//! check their element size (and read_array() the count); finish() refuses records that nothing read. Every problem is an InputError
//! naming the file and the record.
//! The most steps a checkpointed run may have taken (a larger count is a damaged or forged record).
inline constexpr long long kMaxCheckpointSteps = 1000000000000000LL;

class CheckpointReader {
 public:
  explicit CheckpointReader(std::string path) : path_(std::move(path)) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path_, ec))
      throw InputError("checkpoint " + path_ + ": not found (no checkpoint written there yet?)");
    const std::uint64_t size = std::filesystem::file_size(path_, ec);
    in_.open(path_, std::ios::binary);
    if (!in_ || ec) throw InputError("checkpoint " + path_ + ": cannot be opened");
    const std::uint64_t header = sizeof detail::kCheckpointMagic + sizeof detail::kCheckpointVersion;
    if (size < header + detail::kCheckpointTrailer) fail_file("too short to be a blastsim checkpoint");
    char magic[sizeof detail::kCheckpointMagic] = {};
    std::uint32_t version = 0;
    in_.read(magic, sizeof magic);
    in_.read(reinterpret_cast<char*>(&version), sizeof version);
    if (std::memcmp(magic, detail::kCheckpointMagic, sizeof magic) != 0 || version != detail::kCheckpointVersion)
      fail_file("not a blastsim checkpoint of format " + std::to_string(detail::kCheckpointVersion) +
                " (written by another version, or another file)");
    // Trailer, then the checksum of everything before it.
    const std::uint64_t body_end = size - detail::kCheckpointTrailer;
    char end[sizeof detail::kCheckpointEnd] = {};
    std::uint64_t records = 0;
    std::uint32_t stored_crc = 0;
    in_.seekg(static_cast<std::streamoff>(body_end));
    in_.read(end, sizeof end);
    in_.read(reinterpret_cast<char*>(&records), sizeof records);
    in_.read(reinterpret_cast<char*>(&stored_crc), sizeof stored_crc);
    if (!in_ || std::memcmp(end, detail::kCheckpointEnd, sizeof end) != 0)
      fail_file("its end marker is missing (a truncated or damaged file)");
    in_.seekg(0);
    std::uint32_t crc = 0;
    std::vector<char> chunk(1 << 20);
    for (std::uint64_t at = 0; at < body_end;) {
      const std::uint64_t n = std::min<std::uint64_t>(chunk.size(), body_end - at);
      in_.read(chunk.data(), static_cast<std::streamsize>(n));
      if (!in_) fail_file("cannot be read");
      crc = detail::crc32_of(crc, chunk.data(), n);
      at += n;
    }
    if (crc != stored_crc) fail_file("checksum mismatch (the file is damaged or was edited)");
    // Index the records.
    in_.seekg(static_cast<std::streamoff>(header));
    std::uint64_t at = header;
    while (at < body_end) {
      std::uint64_t n = 0, element = 0, count = 0;
      if (body_end - at < sizeof n) fail_file("a record header runs past the end");
      in_.read(reinterpret_cast<char*>(&n), sizeof n);
      if (n == 0 || n > detail::kCheckpointMaxName || body_end - at - sizeof n < n + 16)
        fail_file("a record header is malformed");
      std::string name(n, '\0');
      in_.read(name.data(), static_cast<std::streamsize>(n));
      in_.read(reinterpret_cast<char*>(&element), sizeof element);
      in_.read(reinterpret_cast<char*>(&count), sizeof count);
      at += sizeof n + n + 16;
      if (!in_ || element == 0 || element > 4096 || count > (body_end - at) / element)
        fail(name, "its size runs past the end of the file");
      if (!index_.emplace(name, Record{at, element, count}).second) fail(name, "appears twice");
      at += element * count;
      in_.seekg(static_cast<std::streamoff>(at));
    }
    if (index_.size() != records)
      fail_file("holds " + std::to_string(index_.size()) + " records, its trailer says " + std::to_string(records));
  }

  bool has(const std::string& name) const { return index_.count(name) > 0; }

  template <class T>
  std::vector<T> host_array(const std::string& name) {
    static_assert(std::is_trivially_copyable_v<T>);
    const auto it = index_.find(name);
    if (it == index_.end()) fail(name, "missing (a checkpoint of another version or another case?)");
    const Record& r = it->second;
    if (r.element != sizeof(T))
      fail(name, "element size " + std::to_string(r.element) + " bytes, expected " + std::to_string(sizeof(T)));
    std::vector<T> v(r.count);
    in_.clear();
    in_.seekg(static_cast<std::streamoff>(r.offset));
    in_.read(reinterpret_cast<char*>(v.data()), static_cast<std::streamsize>(r.count * sizeof(T)));
    if (!in_) fail(name, "cannot be read");
    if constexpr (CheckpointReals<T>::value) {  // no state of a run is NaN (CheckpointReals: when infinite)
      std::vector<double> reals(v.size() * sizeof(T) / sizeof(double));
      if (!reals.empty()) std::memcpy(reals.data(), v.data(), reals.size() * sizeof(double));
      for (double x : reals)
        if (x != x || (CheckpointReals<T>::finite && !std::isfinite(x)))
          fail(name, CheckpointReals<T>::finite ? "holds a value that is not finite" : "holds NaN");
    }
    used_.insert(name);
    return v;
  }
  template <class T>
  T value(const std::string& name) {
    const std::vector<T> v = host_array<T>(name);
    if (v.size() != 1) fail(name, "holds " + std::to_string(v.size()) + " values, expected one");
    return v[0];
  }
  //! The scalar record `name`, refused (naming it) unless it is finite and not negative (a time, a length, a scale).
  double non_negative(const std::string& name) {
    const double v = value<double>(name);
    if (!std::isfinite(v) || v < 0) fail(name, "not a finite value >= 0");
    return v;
  }

  //! host_array(), and InputError unless it holds `expected` values (when not 0).
  template <class T>
  std::vector<T> host_array(const std::string& name, std::size_t expected) {
    std::vector<T> h = host_array<T>(name);
    if (expected != 0 && h.size() != expected)
      fail(name, "holds " + std::to_string(h.size()) + " values, this case needs " + std::to_string(expected) +
                     " (a checkpoint of another case?)");
    return h;
  }
  std::string text(const std::string& name) {
    const std::vector<char> c = host_array<char>(name);
    return std::string(c.begin(), c.end());
  }
  //! Refuses the checkpoint when it holds records that nothing read (another version's, or added by hand);
  //! then, the checkpoint accepted, runs what on_accept() deferred, in order, unless `apply` is false (a
  //! restart with nothing to continue changes no file).
  void finish(bool apply = true) {
    for (const auto& [name, record] : index_)
      if (!used_.count(name)) fail(name, "is not a record this version reads");
    if (apply)
      for (const std::function<void()>& action : on_accept_) action();
    on_accept_.clear();
  }
  //! Defers a change to the files a restart continues (cutting a CSV back, rewriting a collection) until
  //! finish() has accepted the whole checkpoint: a refused restart changes nothing.
  void on_accept(std::function<void()> action) { on_accept_.push_back(std::move(action)); }
  //! InputError naming the file and the record.
  [[noreturn]] void fail(const std::string& name, const std::string& what) const {
    throw InputError("checkpoint " + path_ + ", record '" + name + "': " + what);
  }
  //! fail() naming the record unless every value of v (indices, flags read back from record `name`) lies in
  //! [lo, hi].
  template <class T>
  void check_range(const std::string& name, const std::vector<T>& v, double lo, double hi) const {
    for (std::size_t k = 0; k < v.size(); ++k)
      if (!(static_cast<double>(v[k]) >= lo && static_cast<double>(v[k]) <= hi))
        fail(name, "entry " + std::to_string(k) + " = " + std::to_string(static_cast<double>(v[k])) + " outside [" +
                       std::to_string(lo) + ", " + std::to_string(hi) + "]");
  }
  const std::string& path() const { return path_; }

 private:
  struct Record {
    std::uint64_t offset, element, count;
  };
  [[noreturn]] void fail_file(const std::string& what) const { throw InputError("checkpoint " + path_ + ": " + what); }
  std::string path_;
  std::ifstream in_;
  std::map<std::string, Record> index_;
  std::set<std::string> used_;
  std::vector<std::function<void()>> on_accept_;
};

}  // namespace blastsim
