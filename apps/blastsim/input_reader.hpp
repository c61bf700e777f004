//! \file input_reader.hpp
//! \brief Strict reading of TOML input: typed keys with units and ranges, unknown-key detection, overrides, echo.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#define TOML_HEADER_ONLY 1
#include <toml++/toml.h>

namespace blastsim::app {

//! Allowed interval of a number; the text is used in error messages ("> 1", "in (0, 1]").
struct Range {
  double lo = -1e308, hi = 1e308;
  bool lo_open = false, hi_open = false;
  static Range any() { return {}; }
  static Range positive() { return {0.0, 1e308, true, false}; }
  static Range non_negative() { return {0.0, 1e308, false, false}; }
  static Range above(double v) { return {v, 1e308, true, false}; }
  static Range at_least(double v) { return {v, 1e308, false, false}; }
  static Range half_open(double lo_excl, double hi_incl) { return {lo_excl, hi_incl, true, false}; }
  bool contains(double v) const;
  std::string describe() const;
};

//! The mark that ends the echo line of a key left at its default.
inline constexpr const char* kDefaultMark = "   (default)";

//! One line of the resolved configuration: the full key and "key = value unit" (defaults marked).
struct EchoLine {
  std::string key;
  std::string text;
  //! The value is the one that leaving the key out gives (a key echoed only when given): the checkpoint's case
  //! leaves the line out, so a default written out restarts the same checkpoint (TableReader::same_as_absent()).
  bool same_as_absent = false;
};

//! Reads one TOML table. Every getter records the key as known; finish() rejects the keys nobody asked
//! for. Errors are InputError with the full key path, the value and what is allowed. Every value read is
//! added to the shared echo list with its unit.
class TableReader {
 public:
  TableReader(const toml::table& table, std::string path, std::vector<EchoLine>& echo);

  double number(const std::string& key, const char* unit, Range range, std::optional<double> fallback = {});
  std::optional<double> optional_number(const std::string& key, const char* unit, Range range);
  //! An integer in [min_value, max_value] (64-bit; an out-of-range value is refused, never wrapped).
  long long integer(const std::string& key, const char* unit, long long min_value,
                    std::optional<long long> fallback = {}, long long max_value = (1LL << 62));
  bool boolean(const std::string& key, std::optional<bool> fallback = {});
  std::string text(const std::string& key, const std::vector<std::string>& allowed, std::optional<std::string> fallback = {});
  //! Marks keys as allowed in this table without reading them (keys read only in some cases), so that
  //! finish()'s list of the allowed keys names them too.
  void allow(const std::vector<std::string>& keys);
  std::array<double, 2> pair(const std::string& key, const char* unit, std::optional<std::array<double, 2>> fallback = {});
  std::vector<double> number_list(const std::string& key, const char* unit, Range range);
  //! An array of strings (may be empty), each a name the caller checks.
  std::vector<std::string> text_list(const std::string& key);
  bool has(const std::string& key) const;
  //! For a key read only when the input gives it: marks its echo line (the last one of `key`) as the input that
  //! leaving the key out gives when `same` is true (e.g. rotation = 0), so that writing a default out is the same
  //! case to a restart.
  void same_as_absent(const std::string& key, bool same);
  //! Sub-table (empty when absent and not required).
  TableReader table(const std::string& key, bool required = false);
  //! Array of tables (zero or more entries; an empty array `[]` is none).
  std::vector<TableReader> table_array(const std::string& key);
  const std::string& path() const { return path_; }
  std::string key_path(const std::string& key) const { return path_.empty() ? key : path_ + "." + key; }
  //! Throws InputError naming the first key of this table that no getter asked for.
  void finish() const;

 private:
  const toml::node* find(const std::string& key);
  //! The node of `key` (recorded as known); nullptr when absent and `has_fallback`, missing() when absent without.
  const toml::node* lookup(const std::string& key, bool has_fallback, const std::string& what);
  [[noreturn]] void missing(const std::string& key, const std::string& what) const;
  [[noreturn]] void wrong_type(const std::string& key, const std::string& what, const toml::node& n) const;
  //! Echoes "key = value", marked "(default)" unless `given`.
  void echo_value(const std::string& key, const std::string& value, bool given);
  void echo(const std::string& key, std::string line);
  const toml::table* table_;
  toml::table empty_;
  std::string path_;
  std::vector<EchoLine>* echo_;
  std::vector<std::string> known_;
};

//! Applies "section.key=value" overrides to a parsed input (value in TOML syntax; bare words are strings).
//! A numeric path element indexes an array of tables (gas.region.0.radius=0.1).
void apply_override(toml::table& root, const std::string& assignment);

//! Parses a file; syntax errors become InputError with file, line and column.
toml::table parse_input_file(const std::string& path);
//! Parses a case file and applies the "section.key=value" overrides in order.
toml::table load_input(const std::string& input_path, const std::vector<std::string>& overrides);

}  // namespace blastsim::app
