//! \file input_reader.cpp
//! \brief Strict TOML input reading: ranges, types, unknown keys, command-line overrides.
#include "input_reader.hpp"

#include "blastsim/core/error.hpp"

#include <cerrno>
#include <cstdlib>
#include <fmt/format.h>

#include <filesystem>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace blastsim::app {

namespace {
std::string show(double v) { return fmt::format("{:g}", v); }
const char* type_name(const toml::node& n) {
  switch (n.type()) {
    case toml::node_type::string: return "a string";
    case toml::node_type::integer: return "an integer";
    case toml::node_type::floating_point: return "a number";
    case toml::node_type::boolean: return "a boolean";
    case toml::node_type::array: return "an array";
    case toml::node_type::table: return "a table";
    default: return "a date/time";
  }
}
std::string with_unit(const std::string& v, const char* unit) {
  return unit && *unit ? v + " " + unit : v;
}
}  // namespace

bool Range::contains(double v) const {
  if (!std::isfinite(v)) return false;
  const bool lo_ok = lo_open ? v > lo : v >= lo;
  const bool hi_ok = hi_open ? v < hi : v <= hi;
  return lo_ok && hi_ok;
}

std::string Range::describe() const {
  const bool has_lo = lo > -1e307, has_hi = hi < 1e307;
  if (has_lo && has_hi)
    return fmt::format("in {}{}, {}{}", lo_open ? "(" : "[", show(lo), show(hi), hi_open ? ")" : "]");
  if (has_lo) return fmt::format("{} {}", lo_open ? ">" : ">=", show(lo));
  if (has_hi) return fmt::format("{} {}", hi_open ? "<" : "<=", show(hi));
  return "any finite number";
}

TableReader::TableReader(const toml::table& table, std::string path, std::vector<EchoLine>& echo)
    : table_(&table), path_(std::move(path)), echo_(&echo) {}

void TableReader::echo(const std::string& key, std::string line) { echo_->push_back({key_path(key), std::move(line)}); }

const toml::node* TableReader::find(const std::string& key) {
  known_.push_back(key);
  return table_->get(key);
}

bool TableReader::has(const std::string& key) const { return table_->get(key) != nullptr; }

void TableReader::same_as_absent(const std::string& key, bool same) {
  const std::string full = key_path(key);
  for (auto line = echo_->rbegin(); line != echo_->rend(); ++line)
    if (line->key == full) {
      line->same_as_absent = same;
      return;
    }
}

const toml::node* TableReader::lookup(const std::string& key, bool has_fallback, const std::string& what) {
  const toml::node* n = find(key);
  if (!n && !has_fallback) missing(key, what);
  return n;
}

void TableReader::missing(const std::string& key, const std::string& what) const {
  throw InputError(fmt::format("missing required key '{}' ({})", key_path(key), what));
}

void TableReader::wrong_type(const std::string& key, const std::string& what, const toml::node& n) const {
  throw InputError(fmt::format("{} must be {}, got {}", key_path(key), what, type_name(n)));
}

void TableReader::echo_value(const std::string& key, const std::string& value, bool given) {
  echo(key, fmt::format("{} = {}{}", key_path(key), value, given ? "" : kDefaultMark));
}

double TableReader::number(const std::string& key, const char* unit, Range range, std::optional<double> fallback) {
  const toml::node* n =
      lookup(key, fallback.has_value(), fmt::format("a number {}{}", range.describe(), unit && *unit ? std::string(" [") + unit + "]" : ""));
  const std::optional<double> d = n ? n->value<double>() : fallback;
  if (n && (!d || !(n->is_floating_point() || n->is_integer()))) wrong_type(key, "a number", *n);
  if (!range.contains(*d))
    throw InputError(fmt::format("{} = {}: must be {}", key_path(key), with_unit(show(*d), unit), range.describe()));
  echo_value(key, with_unit(show(*d), unit), n);
  return *d;
}

std::optional<double> TableReader::optional_number(const std::string& key, const char* unit, Range range) {
  if (!has(key)) {
    known_.push_back(key);
    return std::nullopt;
  }
  return number(key, unit, range);
}

long long TableReader::integer(const std::string& key, const char* unit, long long min_value,
                               std::optional<long long> fallback, long long max_value) {
  const toml::node* n = lookup(key, fallback.has_value(), fmt::format("an integer >= {}", min_value));
  if (n && !n->is_integer()) wrong_type(key, "an integer", *n);
  const long long v = n ? *n->value<long long>() : *fallback;
  if (v < min_value || v > max_value)
    throw InputError(fmt::format("{} = {}: must be an integer {} {}", key_path(key), v, v < min_value ? ">=" : "<=",
                                 v < min_value ? min_value : max_value));
  echo_value(key, with_unit(std::to_string(v), unit), n);
  return v;
}

bool TableReader::boolean(const std::string& key, std::optional<bool> fallback) {
  const toml::node* n = lookup(key, fallback.has_value(), "true or false");
  if (n && !n->is_boolean()) wrong_type(key, "true or false", *n);
  const bool v = n ? *n->value<bool>() : *fallback;
  echo_value(key, v ? "true" : "false", n);
  return v;
}

std::string TableReader::text(const std::string& key, const std::vector<std::string>& allowed,
                              std::optional<std::string> fallback) {
  std::string list;
  for (const std::string& a : allowed) list += (list.empty() ? "\"" : ", \"") + a + "\"";
  const std::string expected = allowed.empty() ? std::string("a string") : "one of " + list;
  const toml::node* n = lookup(key, fallback.has_value(), expected);
  if (n && !n->is_string()) wrong_type(key, allowed.empty() ? expected : "a string (" + expected + ")", *n);
  const std::string v = n ? *n->value<std::string>() : *fallback;
  if (!allowed.empty() && std::find(allowed.begin(), allowed.end(), v) == allowed.end())
    throw InputError(fmt::format("{} = \"{}\": must be one of {}", key_path(key), v, list));
  echo_value(key, "\"" + v + "\"", n);
  return v;
}

std::array<double, 2> TableReader::pair(const std::string& key, const char* unit,
                                        std::optional<std::array<double, 2>> fallback) {
  const toml::node* n = lookup(key, fallback.has_value(), fmt::format("[x, y]{}", unit && *unit ? std::string(" [") + unit + "]" : ""));
  std::array<double, 2> v = fallback.value_or(std::array<double, 2>{});
  if (n) {
    const toml::array* a = n->as_array();
    if (!a || a->size() != 2 || !(*a)[0].value<double>() || !(*a)[1].value<double>())
      throw InputError(fmt::format("{} must be an array of two numbers [x, y]", key_path(key)));
    v = {*(*a)[0].value<double>(), *(*a)[1].value<double>()};
    if (!std::isfinite(v[0]) || !std::isfinite(v[1]))
      throw InputError(fmt::format("{} must hold finite numbers", key_path(key)));
  }
  echo_value(key, fmt::format("[{}, {}]{}", show(v[0]), show(v[1]), unit && *unit ? std::string(" ") + unit : ""), n);
  return v;
}

std::vector<double> TableReader::number_list(const std::string& key, const char* unit, Range range) {
  const toml::node* n = find(key);
  std::vector<double> out;
  if (!n) missing(key, fmt::format("an array of numbers {}", range.describe()));
  const toml::array* a = n->as_array();
  if (!a) throw InputError(fmt::format("{} must be an array of numbers", key_path(key)));
  std::string shown;
  for (const toml::node& e : *a) {
    const auto d = e.value<double>();
    if (!d) throw InputError(fmt::format("{} must be an array of numbers, found {}", key_path(key), type_name(e)));
    if (!range.contains(*d))
      throw InputError(fmt::format("{} holds {}: every entry must be {}", key_path(key), with_unit(show(*d), unit),
                                   range.describe()));
    out.push_back(*d);
    shown += (shown.empty() ? "" : ", ") + show(*d);
  }
  echo(key, fmt::format("{} = [{}]{}", key_path(key), shown, unit && *unit ? std::string(" ") + unit : ""));
  return out;
}

std::vector<std::string> TableReader::text_list(const std::string& key) {
  const toml::node* n = find(key);
  if (!n) missing(key, "an array of strings");
  const toml::array* a = n->as_array();
  if (!a) throw InputError(fmt::format("{} must be an array of strings", key_path(key)));
  std::vector<std::string> out;
  std::string shown;
  for (const toml::node& e : *a) {
    if (!e.is_string()) throw InputError(fmt::format("{} must be an array of strings, found {}", key_path(key), type_name(e)));
    out.push_back(*e.value<std::string>());
    shown += (shown.empty() ? "\"" : ", \"") + out.back() + "\"";
  }
  echo(key, fmt::format("{} = [{}]", key_path(key), shown));
  return out;
}

TableReader TableReader::table(const std::string& key, bool required) {
  const toml::node* n = find(key);
  if (!n) {
    if (required) missing(key, "a table");
    return TableReader(empty_, key_path(key), *echo_);
  }
  if (!n->is_table()) throw InputError(fmt::format("{} must be a table, got {}", key_path(key), type_name(*n)));
  return TableReader(*n->as_table(), key_path(key), *echo_);
}

std::vector<TableReader> TableReader::table_array(const std::string& key) {
  const toml::node* n = find(key);
  std::vector<TableReader> out;
  if (!n) return out;
  const toml::array* a = n->as_array();
  if (!a || (!a->empty() && !a->is_array_of_tables()))  // an empty array ([]) is none
    throw InputError(fmt::format("{} must be an array of tables ([[{}]] entries)", key_path(key), key_path(key)));
  for (size_t k = 0; k < a->size(); ++k)
    out.emplace_back(*(*a)[k].as_table(), fmt::format("{}.{}", key_path(key), k), *echo_);
  return out;
}

void TableReader::allow(const std::vector<std::string>& keys) {
  for (const std::string& k : keys)
    if (std::find(known_.begin(), known_.end(), k) == known_.end()) known_.push_back(k);
}

void TableReader::finish() const {
  for (auto&& [k, v] : *table_) {
    const std::string key(k.str());
    if (std::find(known_.begin(), known_.end(), key) == known_.end()) {
      std::string list;
      for (const std::string& a : known_) list += (list.empty() ? "" : ", ") + a;
      throw InputError(fmt::format("unknown key '{}' (allowed here: {})", key_path(key), list));
    }
  }
}

void apply_override(toml::table& root, const std::string& assignment) {
  const size_t eq = assignment.find('=');
  if (eq == std::string::npos || eq == 0)
    throw InputError(fmt::format("override '{}' must have the form section.key=value", assignment));
  const std::string path = assignment.substr(0, eq), text = assignment.substr(eq + 1);
  // The value in TOML syntax; a bare word that is not valid TOML is taken as a string.
  toml::table parsed;
  try {
    parsed = toml::parse("v = " + text);
  } catch (const toml::parse_error&) {
    char* end = nullptr;
    errno = 0;
    std::strtod(text.c_str(), &end);
    if (!text.empty() && end && *end == '\0' && errno == ERANGE)  // a number, but not one a double holds
      throw InputError(fmt::format("override '{}': {} is a number outside the range of a double (about 1e-308 to "
                                   "1e308 in magnitude)", assignment, text));
    parsed = toml::table{{"v", text}};
  }
  std::vector<std::string> parts;
  std::stringstream ss(path);
  for (std::string p; std::getline(ss, p, '.');) {
    if (p.empty()) throw InputError(fmt::format("override '{}': empty key in the path", assignment));
    parts.push_back(p);
  }
  toml::table* t = &root;
  std::string prefix;  // path walked so far, for messages
  for (size_t k = 0; k + 1 < parts.size(); ++k) {
    prefix += (prefix.empty() ? "" : ".") + parts[k];
    toml::node* n = t->get(parts[k]);
    if (!n) {
      t->insert(parts[k], toml::table{});
      n = t->get(parts[k]);
    }
    if (toml::array* a = n->as_array()) {
      if (k + 2 >= parts.size() || parts[k + 1].find_first_not_of("0123456789") != std::string::npos)
        throw InputError(fmt::format("override '{}': {} is an array; give an index ({}.0.key=value)", assignment,
                                     prefix, prefix));
      // Compare as text first: an index of any length that does not fit is out of range, not an overflow.
      const std::string& digits = parts[k + 1];
      const bool fits = digits.size() <= 9;
      const size_t index = fits ? static_cast<size_t>(std::stoul(digits)) : a->size();
      if (index >= a->size() || !(*a)[index].is_table())
        throw InputError(fmt::format("override '{}': {} has {} entries", assignment, prefix, a->size()));
      t = (*a)[index].as_table();
      prefix += "." + parts[++k];
      continue;
    }
    if (!n->is_table()) throw InputError(fmt::format("override '{}': {} is not a table", assignment, prefix));
    t = n->as_table();
  }
  t->insert_or_assign(parts.back(), *parsed.get("v"));
}

toml::table load_input(const std::string& input_path, const std::vector<std::string>& overrides) {
  toml::table input = parse_input_file(input_path);
  for (const std::string& o : overrides) apply_override(input, o);
  return input;
}

toml::table parse_input_file(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec))
    throw InputError(fmt::format("input file '{}' is a directory; give the case file (TOML)", path));
  try {
    return toml::parse_file(path);
  } catch (const toml::parse_error& e) {
    const auto& src = e.source();
    if (!src.begin) throw InputError(fmt::format("cannot read input file '{}': {}", path, e.description()));
    throw InputError(fmt::format("{}:{}:{}: {}", path, src.begin.line, src.begin.column, e.description()));
  }
}

}  // namespace blastsim::app
