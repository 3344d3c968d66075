#pragma once
// One schema per input table: for every key its TOML name, the file's unit, its default (the option struct's own, or
// the rule that derives it), its range and one line of meaning, bound to the member that holds it. The stage that owns
// an option struct owns its schema; the case reader and writer (io/case.cpp), the range checks (check_key_ranges, which
// the stage's validation calls) and the keys reference (`strainwave keys`, docs/keys.md) all come from it. Standard
// library only, so that every stage can declare one.
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <limits>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "common/error.hpp"

namespace sw {

/// The closed or open interval a numeric key must lie in, and why when the bound is not obvious.
struct KeyRange {
  double lo = -std::numeric_limits<double>::infinity();
  double hi = std::numeric_limits<double>::infinity();
  bool lo_open = false, hi_open = false;
  std::string why;  ///< appended to the expectation in parentheses ("" for none)

  bool bounded() const { return std::isfinite(lo) || std::isfinite(hi); }
  bool contains(double v) const {
    return (lo_open ? v > lo : v >= lo) && (hi_open ? v < hi : v <= hi) && !std::isnan(v);
  }
  /// "> 0", ">= 1", "in (0, 90)", "" when unbounded.
  std::string text() const {
    auto n = [](double v) {
      std::ostringstream s;
      s << v;
      return s.str();
    };
    if (std::isfinite(lo) && std::isfinite(hi))
      return "in " + std::string(lo_open ? "(" : "[") + n(lo) + ", " + n(hi) + (hi_open ? ")" : "]");
    if (std::isfinite(lo)) return (lo_open ? "> " : ">= ") + n(lo);
    if (std::isfinite(hi)) return (hi_open ? "< " : "<= ") + n(hi);
    return "";
  }
  /// "must be > 0 (why)".
  std::string expectation() const { return "must be " + text() + (why.empty() ? "" : " (" + why + ")"); }
};

inline KeyRange any_value() { return {}; }
inline KeyRange above(double lo, std::string why = "") {
  return {lo, std::numeric_limits<double>::infinity(), true, false, why};
}
inline KeyRange at_least(double lo, std::string why = "") {
  return {lo, std::numeric_limits<double>::infinity(), false, false, why};
}
/// [lo, hi] by default; open ends as asked.
inline KeyRange within(double lo, double hi, bool lo_open = false, bool hi_open = false, std::string why = "") {
  return {lo, hi, lo_open, hi_open, why};
}

/// A key's value in the file's units: a number, an integer or one of a list of words.
using KeyValue = std::variant<double, long long, std::string>;
/// List: an array of inline tables (its elements' keys named in the meaning); Table: one inline table with a schema
/// of its own. The reader reads those two itself.
enum class KeyKind { Number, Integer, Choice, List, Table };

/// The shortest decimal of `si` in the file's unit (`si_per_unit` SI per file unit: 1e-3 for mm) that reads back to
/// `si` exactly once multiplied by the unit. A value no decimal reaches (one derived in SI) becomes the shortest
/// decimal of the value nearest to it that one reaches (1 ulp away), which is written the same again once read back.
inline double file_units(double si, double si_per_unit = 1.0) {
  const double exact = si / si_per_unit;
  for (const double target : {si, exact * si_per_unit})
    for (int digits = 1; digits <= 17; ++digits) {
      char text[32];
      std::snprintf(text, sizeof text, "%.*g", digits, exact);
      if (const double v = std::strtod(text, nullptr); v * si_per_unit == target) return v;
    }
  return exact;  // not reached: `exact` itself, at 17 digits, reaches exact * si_per_unit
}

/// The default rule of a key without default: the file must give it.
inline const std::string kRequired = "required";

/// One key of a table whose values an option struct T holds.
template <class T>
struct CaseKey {
  std::string name;  ///< the TOML key
  KeyKind kind = KeyKind::Number;
  std::string unit;                  ///< the file's unit ("mm", "deg", "N m"), "" for a pure number or a word
  KeyRange range;                    ///< numbers and integers; checked by check_key_ranges
  std::vector<std::string> choices;  ///< the words a choice takes
  std::string meaning;               ///< one line
  /// How the value of a key the file leaves out is found when it is not T{}'s ("" : T{}'s value is the default);
  /// "required" for a key without default.
  std::string default_rule;
  std::string applies_when;  ///< in words, for a key that exists only for some values of others ("" : always)
  std::function<std::optional<KeyValue>(const T&)> get;  ///< in the file's units; nullopt: the object has no value
  std::function<void(T&, const KeyValue&)> set;          ///< from the file's units
  std::function<bool(const T&)> applies;                 ///< empty: always

  bool applies_to(const T& t) const { return !applies || applies(t); }
  /// The key with a condition (read and written only where `when` holds of the object read so far).
  CaseKey only_when(std::function<bool(const T&)> when, std::string in_words) && {
    applies = std::move(when);
    applies_when = std::move(in_words);
    return std::move(*this);
  }
  bool required() const { return default_rule == kRequired; }
  CaseKey with_default(std::string rule) && {
    default_rule = std::move(rule);
    return std::move(*this);
  }
};

/// A number held in SI by `member`, written in the file's unit (`si_per_unit` SI per unit).
template <class T>
CaseKey<T> number_key(std::string name, double T::*member, double si_per_unit, std::string unit, KeyRange range,
                      std::string meaning) {
  CaseKey<T> k{std::move(name), KeyKind::Number, std::move(unit), std::move(range), {}, std::move(meaning)};
  k.get = [=](const T& t) -> std::optional<KeyValue> { return file_units(t.*member, si_per_unit); };
  k.set = [=](T& t, const KeyValue& v) { t.*member = std::get<double>(v) * si_per_unit; };
  return k;
}

/// A number without default (the object holds it only when given).
template <class T>
CaseKey<T> optional_number_key(std::string name, std::optional<double> T::*member, double si_per_unit, std::string unit,
                               KeyRange range, std::string meaning) {
  CaseKey<T> k{std::move(name), KeyKind::Number, std::move(unit), std::move(range), {}, std::move(meaning)};
  k.default_rule = "none";
  k.get = [=](const T& t) -> std::optional<KeyValue> {
    if (!(t.*member)) return std::nullopt;
    return file_units(*(t.*member), si_per_unit);
  };
  k.set = [=](T& t, const KeyValue& v) { t.*member = std::get<double>(v) * si_per_unit; };
  return k;
}

template <class T>
CaseKey<T> integer_key(std::string name, int T::*member, KeyRange range, std::string meaning) {
  CaseKey<T> k{std::move(name), KeyKind::Integer, "", std::move(range), {}, std::move(meaning)};
  k.get = [=](const T& t) -> std::optional<KeyValue> { return static_cast<long long>(t.*member); };
  k.set = [=](T& t, const KeyValue& v) { t.*member = static_cast<int>(std::get<long long>(v)); };
  return k;
}

/// A word naming one value of an enumeration (or a string member) E.
template <class T, class E>
CaseKey<T> choice_key(std::string name, E T::*member, std::vector<std::pair<std::string, E>> words,
                      std::string meaning) {
  CaseKey<T> k{std::move(name), KeyKind::Choice, "", {}, {}, std::move(meaning)};
  for (const auto& w : words) k.choices.push_back(w.first);
  k.get = [=](const T& t) -> std::optional<KeyValue> {
    for (const auto& [word, value] : words)
      if (t.*member == value) return word;
    return std::nullopt;
  };
  k.set = [=](T& t, const KeyValue& v) {
    for (const auto& [word, value] : words)
      if (std::get<std::string>(v) == word) t.*member = value;
  };
  return k;
}

/// A key the reader reads itself (a list of tables, an inline table): name, kind, meaning and when it applies, for the
/// reference; no value of its own in the schema's writer.
template <class T>
CaseKey<T> structured_key(std::string name, KeyKind kind, std::string meaning) {
  CaseKey<T> k{std::move(name), kind, "", {}, {}, std::move(meaning)};
  k.get = [](const T&) -> std::optional<KeyValue> { return std::nullopt; };
  k.set = [](T&, const KeyValue&) {};
  return k;
}

/// The key of `keys` named `name` (std::logic_error when there is none: a caller naming a key its schema lacks).
template <class T>
const CaseKey<T>& key_named(const std::vector<CaseKey<T>>& keys, const std::string& name) {
  for (const CaseKey<T>& k : keys)
    if (k.name == name) return k;
  throw std::logic_error("no case key " + name);
}

/// A key's value as the messages and the reference print it: 6 significant digits, words quoted.
inline std::string key_value_text(const KeyValue& v) {
  if (const auto* s = std::get_if<std::string>(&v)) return "\"" + *s + "\"";
  std::ostringstream o;
  if (const auto* i = std::get_if<long long>(&v))
    o << *i;
  else
    o << std::get<double>(v);
  return o.str();
}

/// A key's value as TOML: a number as the shortest text that reads back to it, a word quoted.
inline std::string key_value_toml(const KeyValue& v) {
  if (const auto* d = std::get_if<double>(&v)) {
    char text[32];
    return std::string(text, std::to_chars(text, text + sizeof text, *d).ptr);
  }
  return key_value_text(v);
}

/// The keys of `t` that apply to it, one "key = value" line each, as a table of a case file holds them.
template <class T>
std::string keys_toml(const T& t, const std::vector<CaseKey<T>>& keys) {
  std::string s;
  for (const CaseKey<T>& k : keys)
    if (k.applies_to(t))
      if (const std::optional<KeyValue> v = k.get(t)) s += k.name + " = " + key_value_toml(*v) + "\n";
  return s;
}

/// Throws InputError "<prefix><table>.<key> = value; must be ..." for the first key of `keys` that applies to `t` and
/// lies outside its range (`prefix`: "file: " or ""). The stage's validation calls it before its rules between keys.
template <class T>
void check_key_ranges(const T& t, const std::vector<CaseKey<T>>& keys, const std::string& table,
                      const std::string& prefix = "") {
  for (const CaseKey<T>& k : keys) {
    if (k.kind != KeyKind::Number && k.kind != KeyKind::Integer) continue;
    if (!k.range.bounded() || !k.applies_to(t)) continue;
    const std::optional<KeyValue> v = k.get(t);
    if (!v) continue;
    const double x = k.kind == KeyKind::Integer ? static_cast<double>(std::get<long long>(*v)) : std::get<double>(*v);
    if (!k.range.contains(x))
      throw InputError(prefix + table + "." + k.name + " = " + key_value_text(*v) + "; " + k.range.expectation());
  }
}

}  // namespace sw
