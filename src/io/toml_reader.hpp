#pragma once
// Typed reading of one TOML table for the scene reader (scene_reader/):
// getters that refuse a wrong type or a non-finite number with the key's
// line, and finish(), which refuses the keys nobody asked for. Each reader
// also keeps the table's echo, the resolved scene (Scene::resolved_json):
// every key read with the value read, or the default a `_or` getter or a
// fallback gave. The echo is made by the reads, so it cannot drift from
// what the reader takes. Internal to src/io; toml++ is included by the
// scene reader and, to write scenes, scene_export.cpp.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <set>
#include <span>
#include <sstream>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>
#include <toml++/toml.h>

#include "gjkdem/io/scene.hpp"
#include "gjkdem/math/quat.hpp"
#include "gjkdem/math/vec3.hpp"
#include "gjkdem/tolerances.hpp"

namespace gjkdem::io::detail {

using Json = nlohmann::ordered_json;

inline Json to_json(const Vec3& v) { return Json::array({v.x, v.y, v.z}); }
inline Json to_json(const Quat& q) { return Json::array({q.w, q.x, q.y, q.z}); }

// A TOML value as it is written: tables, arrays, numbers, strings and
// booleans as themselves, a date or time as its TOML text.
inline Json to_json(const toml::node& n) {
  if (const toml::table* t = n.as_table()) {
    Json j = Json::object();
    for (const auto& [k, v] : *t) j[std::string(k.str())] = to_json(v);
    return j;
  }
  if (const toml::array* a = n.as_array()) {
    Json j = Json::array();
    for (const toml::node& e : *a) j.push_back(to_json(e));
    return j;
  }
  if (const auto i = n.value_exact<std::int64_t>()) return *i;
  if (const auto d = n.value_exact<double>()) return *d;
  if (const auto b = n.value_exact<bool>()) return *b;
  if (const auto s = n.value_exact<std::string>()) return *s;
  std::ostringstream text;
  n.visit([&](const auto& v) { text << v; });
  return text.str();
}

// A TOML number as a double: integers of any size convert (rounded to the
// nearest double), so 9007199254740993 is read, not refused obscurely.
inline Real as_real(const toml::node& n) {
  if (const auto i = n.value_exact<std::int64_t>()) return static_cast<Real>(*i);
  return n.value_exact<double>().value_or(std::numeric_limits<Real>::quiet_NaN());
}

/// The deepest a scene may nest tables: toml++ caps nested values, not
/// dotted keys and table headers, whose depth it follows recursively.
inline constexpr int kMaxKeyDepth = 64;

/// Refuses a table header or key with more than kMaxKeyDepth dotted parts
/// ("[a.b.c...]", "a.b.c... = 1", and keys of inline tables), naming its
/// line, before toml++ reads it. Dots in quoted keys and in values do not
/// count; the dots of one statement's keys (inline tables' included) add up.
inline void check_key_depth(std::string_view text, const std::string& source) {
  int line = 1, dots = 0;
  bool key = true;          // in a key or a table header (before its '=' or ']')
  std::string quote;        // the quotes a string or quoted key is in: one or three of " or '
  bool comment = false;
  std::string open;         // the '{' and '[' of values not yet closed
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '\n') {
      ++line, comment = false;
      if (quote.size() == 1) quote.clear();  // one-line strings end with their line (an error toml++ reports)
      if (open.empty() && quote.empty()) dots = 0, key = true;
      continue;
    }
    if (comment) continue;
    if (!quote.empty()) {
      if (c == '\\' && quote[0] == '"') ++i;  // an escape in a basic string
      else if (text.substr(i, quote.size()) == quote) i += quote.size() - 1, quote.clear();
      continue;
    }
    switch (c) {
      case '"': case '\'':
        quote = text.substr(i, 3) == std::string(3, c) ? std::string(3, c) : std::string(1, c);
        i += quote.size() - 1;
        break;
      case '#': comment = true; break;
      case '=': key = false; break;
      case '{': open.push_back(c), key = true; break;
      case '[': if (!key) open.push_back(c); break;  // a value's array (in a key: a table header)
      case ']': if (key) key = false; else if (!open.empty()) open.pop_back(); break;
      case '}': if (!open.empty()) open.pop_back(); break;
      case ',': if (!open.empty() && open.back() == '{') key = true; break;
      case '.':
        if (key && ++dots > kMaxKeyDepth)
          throw SceneError(source + ": a key or table header nested deeper than " + std::to_string(kMaxKeyDepth) +
                           " levels (line " + std::to_string(line) + ")");
        break;
      default: break;
    }
  }
}

inline std::string line_of(const toml::node& n) {
  const auto line = n.source().begin.line;
  return line > 0 ? " (line " + std::to_string(line) + ")" : "";
}

// Reads one table: typed getters, then finish() refuses the keys nobody
// asked for and completes the echo. A getter records the value it returns:
// the optional ones a value given, the `_or` ones and those with a fallback
// the default too (a getter's sentinel, as `number(k).value_or(-1)` for a
// required key, is not a default and is not recorded).
class TableReader {
 public:
  TableReader(const toml::table& t, std::string where) : table_(t), where_(std::move(where)) {}
  /// A sub-table's reader: finish() puts its echo into `parent`'s under
  /// `key` (appended to an array there for an array of tables).
  enum class Echo { Under, Appended };
  TableReader(const toml::table& t, std::string where, TableReader& parent, std::string key, Echo how = Echo::Under)
      : table_(t), where_(std::move(where)), parent_(&parent), key_in_parent_(std::move(key)), how_(how) {}
  TableReader(const TableReader&) = delete;
  TableReader& operator=(const TableReader&) = delete;

  const std::string& where() const { return where_; }
  const toml::node* find(const std::string& key) {
    used_.insert(key);
    return table_.get(key);
  }
  /// `key` may be a dotted path into sub-tables ("stress.x"); the line is
  /// the key's where it is written, else the table's.
  [[noreturn]] void fail(const std::string& key, const std::string& what) const {
    const toml::node* n = table_.at_path(key).node();
    throw SceneError(where_ + "." + key + ": " + what + (n ? line_of(*n) : line_of(table_)));
  }
  bool has(const std::string& key) const { return table_.contains(key); }
  [[noreturn]] void missing(const std::string& key) const {
    throw SceneError(where_ + ": missing required key '" + key + "'" + line_of(table_));
  }

  /// Puts a value the reader worked out into the echo (a resolved "auto").
  void record(const std::string& key, Json value) { echo_[key] = std::move(value); }

  std::optional<Real> number(const std::string& key) {
    const toml::node* n = find(key);
    if (!n) return std::nullopt;
    if (!n->is_number()) fail(key, "must be a number");
    const Real v = as_real(*n);
    if (!std::isfinite(v)) fail(key, "must be finite");
    record(key, v);
    return v;
  }
  Real number_or(const std::string& key, Real fallback) { return recorded(key, number(key), fallback); }
  Real required_number(const std::string& key) {
    const auto v = number(key);
    if (!v) missing(key);
    return *v;
  }
  Real positive(const std::string& key, std::optional<Real> fallback = std::nullopt) {
    const auto v = number(key);
    if (!v && fallback) return recorded(key, v, *fallback);
    if (!v) missing(key);
    if (!(*v > 0)) fail(key, "must be > 0");
    return *v;
  }
  std::optional<std::int64_t> integer(const std::string& key) {
    const toml::node* n = find(key);
    if (!n) return std::nullopt;
    if (!n->is_integer()) fail(key, "must be an integer");
    const std::int64_t v = n->value<std::int64_t>().value();
    record(key, v);
    return v;
  }
  std::int64_t integer_or(const std::string& key, std::int64_t fallback) {
    return recorded(key, integer(key), fallback);
  }
  std::optional<std::string> string(const std::string& key) {
    const toml::node* n = find(key);
    if (!n) return std::nullopt;
    if (!n->is_string()) fail(key, "must be a string");
    std::string v = n->value<std::string>().value();
    record(key, v);
    return v;
  }
  std::string string_or(const std::string& key, const std::string& fallback) {
    return recorded(key, string(key), fallback);
  }
  std::string required_string(const std::string& key) {
    const auto v = string(key);
    if (!v) missing(key);
    return *v;
  }
  bool boolean(const std::string& key, bool fallback) {
    const toml::node* n = find(key);
    if (n && !n->is_boolean()) fail(key, "must be true or false");
    const bool v = n ? n->value<bool>().value() : fallback;
    record(key, v);
    return v;
  }
  std::vector<Real> numbers(const std::string& key, std::size_t count) {
    const toml::node* n = find(key);
    const toml::array* a = n ? n->as_array() : nullptr;
    if (n && !a) fail(key, "must be an array of " + std::to_string(count) + " numbers");
    if (!a) return {};
    if (a->size() != count) fail(key, "must have " + std::to_string(count) + " numbers");
    std::vector<Real> out;
    for (const toml::node& e : *a) {
      if (!e.is_number()) fail(key, "must hold numbers only");
      out.push_back(as_real(e));
      if (!std::isfinite(out.back())) fail(key, "must be finite");
    }
    record(key, out);
    return out;
  }
  // An array of rows of `width` finite numbers, e.g. [time, x, y, z] (empty
  // when absent); `row` says what a row holds, for messages.
  std::vector<std::vector<Real>> rows(const std::string& key, std::size_t width, const std::string& row) {
    const toml::node* n = find(key);
    if (!n) return {};
    const toml::array* rows = n->as_array();
    if (!rows || rows->empty()) fail(key, "must be an array of rows " + row);
    std::vector<std::vector<Real>> out;
    for (const toml::node& r : *rows) {
      const toml::array* a = r.as_array();
      if (!a || a->size() != width) fail(key, "must be an array of rows " + row);
      out.emplace_back();
      for (const toml::node& e : *a) {
        if (!e.is_number()) fail(key, "rows must hold numbers only");
        out.back().push_back(as_real(e));
        if (!std::isfinite(out.back().back())) fail(key, "must be finite");
      }
    }
    record(key, out);
    return out;
  }
  std::optional<Vec3> vec3(const std::string& key) {
    const auto v = numbers(key, 3);
    if (v.empty()) return std::nullopt;
    return Vec3{v[0], v[1], v[2]};
  }
  Vec3 vec3_or(const std::string& key, const Vec3& fallback) { return recorded(key, vec3(key), fallback); }
  std::optional<Quat> rotation(const std::string& key) {
    const auto v = numbers(key, 4);
    if (v.empty()) return std::nullopt;
    const Quat q{v[0], v[1], v[2], v[3]};
    const Real norm = std::sqrt(q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z);
    if (std::fabs(norm - 1) > kUnitQuaternionTol) fail(key, "must be a unit quaternion [w, x, y, z]");
    return normalized(q);
  }
  Quat rotation_or(const std::string& key, const Quat& fallback) { return recorded(key, rotation(key), fallback); }
  const toml::table& table_node() const { return table_; }
  const toml::table* table(const std::string& key) {
    const toml::node* n = find(key);
    if (!n) return nullptr;
    if (!n->is_table()) fail(key, "must be a table, e.g. { type = \"box\", ... }");
    return n->as_table();
  }
  /// Refuses at once a key not among `known` (as finish() would, later): a
  /// scene's misspelt section before any of its bodies is cut or placed.
  void refuse_keys_but(std::span<const std::string_view> known) const {
    for (const auto& [k, v] : table_)
      if (std::find(known.begin(), known.end(), k.str()) == known.end())
        throw SceneError(where_ + ": unknown key '" + std::string(k.str()) + "'" + line_of(v));
  }
  /// Refuses the keys nobody asked for; echoes the keys asked for that no
  /// getter recorded (a SHAPE table, a list of parts) as they are written,
  /// and hands the echo to the parent reader, if any.
  void finish() {
    for (const auto& [k, v] : table_) {
      const std::string key(k.str());
      if (!used_.count(key)) throw SceneError(where_ + ": unknown key '" + key + "'" + line_of(v));
      if (!echo_.contains(key)) echo_[key] = to_json(v);
    }
    if (!parent_) return;
    if (how_ == Echo::Appended) parent_->echo_[key_in_parent_].push_back(std::move(echo_));
    else parent_->echo_[key_in_parent_] = std::move(echo_);
    echo_ = Json::object();
  }
  /// The echo so far (the whole of it once finish() ran), for a reader
  /// without a parent.
  Json take_echo() { return std::exchange(echo_, Json::object()); }

 private:
  template <class T>
  T recorded(const std::string& key, const std::optional<T>& given, const T& fallback) {
    if (given) return *given;
    if constexpr (std::is_same_v<T, Vec3> || std::is_same_v<T, Quat>) record(key, to_json(fallback));
    else record(key, fallback);
    return fallback;
  }

  const toml::table& table_;
  std::string where_;
  std::set<std::string> used_;
  Json echo_ = Json::object();
  TableReader* parent_ = nullptr;
  std::string key_in_parent_;
  Echo how_ = Echo::Under;
};

}  // namespace gjkdem::io::detail
