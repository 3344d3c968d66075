#pragma once
// The JSON files the tool writes (result.json, backlash.json, contact.json) and reads back, as typed values: one
// field table per struct serves the writer and the reader. Each value read knows its file and key path, so bad input
// is one line naming the file, the key and the value. Internal to io/: nlohmann-json stays out of the public headers.
#include <array>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <tuple>
#include <type_traits>
#include <vector>

#include <nlohmann/json.hpp>

#include "io/provenance.hpp"

namespace sw {

/// A value of a JSON file being read, with the file and key path that lead to it.
class JsonIn {
 public:
  /// The top-level object of `path`. Throws InputError "FILE: <cannot_open>" when the file cannot be read, "FILE: not
  /// valid JSON (...)", or "FILE: not a JSON object; expected <expected>". `expected` names the file's kind in every
  /// later message ("the result.json of `strainwave fem`").
  static JsonIn open(const std::filesystem::path& path, const std::string& cannot_open, const std::string& expected);

  /// The same for a text already read (`file` names it in messages).
  static JsonIn parse(const std::string& text, const std::string& file, const std::string& expected);

  bool has(const std::string& key) const;                    ///< an object holding `key`
  bool is_null() const;                                      ///< null (a figure the writer marks as absent)
  JsonIn operator[](const std::string& key) const;           ///< the member; InputError when missing or not an object
  std::optional<JsonIn> find(const std::string& key) const;  ///< the member when present
  std::vector<JsonIn> elements() const;                      ///< an array's elements; InputError when not an array
  std::vector<JsonIn> elements(std::size_t size) const;      ///< the same, of exactly `size` elements

  double number() const;         ///< a number; null (how the writer writes NaN and infinity) reads as NaN
  double finite() const;         ///< a finite number (null refused)
  std::int64_t integer() const;  ///< a whole number
  std::uint64_t count() const;   ///< a whole number >= 0
  std::string text() const;      ///< a string
  bool flag() const;             ///< true or false
  std::vector<double> numbers() const;  ///< an array of numbers (null as NaN)

  std::optional<double> optional_number(const std::string& key) const;  ///< number() of the member when present

  const nlohmann::json& value() const { return *value_; }  ///< the value itself
  const std::string& file() const { return doc_->file; }
  const std::string& key_path() const { return path_; }  ///< "solver.equations", "torque_twist[3].twist_rad"
  /// Throws InputError "FILE: KEY = VALUE; expected <what> in <the file's kind>".
  [[noreturn]] void fail(const std::string& what) const;

 private:
  struct Document {
    nlohmann::json root;
    std::string file, expected;
  };
  JsonIn(std::shared_ptr<const Document> doc, const nlohmann::json* value, std::string path)
      : doc_(std::move(doc)), value_(value), path_(std::move(path)) {}
  static JsonIn top(std::shared_ptr<Document> doc);

  std::shared_ptr<const Document> doc_;
  const nlohmann::json* value_;
  std::string path_;
};

// ---- Field tables: one list of (key, member) per struct of a file serves its writer and its reader alike, so the
// reader reads exactly the keys the writer writes. A struct takes part by a function found by argument-dependent
// lookup, `static auto fields(std::type_identity<S>)`, returning a std::tuple of the fields below in the file's order.

/// How a member stands in the file.
enum class Presence {
  kAsTyped,          ///< always written; an empty std::optional is left out
  kNullWhenAbsent,   ///< an empty std::optional is written as null
  kOmittedWhenEmpty, ///< an empty list is left out (and reads back empty)
  kFlattened,        ///< a struct whose keys stand in the enclosing object (a std::optional one: by its first key)
  kObjectText,       ///< a std::string holding a JSON object's text, written as the object (read back as its text)
};

template <class S, class M, Presence P>
struct Field {
  const char* key;
  M S::*member;
};

template <class S, class M>
Field<S, M, Presence::kAsTyped> field(const char* key, M S::*member) {
  return {key, member};
}
template <class S, class M>
Field<S, M, Presence::kNullWhenAbsent> null_when_absent(const char* key, M S::*member) {
  return {key, member};
}
template <class S, class M>
Field<S, M, Presence::kOmittedWhenEmpty> omitted_when_empty(const char* key, M S::*member) {
  return {key, member};
}
template <class S, class M>
Field<S, M, Presence::kFlattened> flattened(M S::*member) {
  return {"", member};
}
template <class S>
Field<S, std::string, Presence::kObjectText> object_text(const char* key, std::string S::*member) {
  return {key, member};
}

namespace json_detail {
template <class T> struct is_optional : std::false_type {};
template <class T> struct is_optional<std::optional<T>> : std::true_type {};
template <class T> struct is_list : std::false_type {};
template <class T> struct is_list<std::vector<T>> : std::true_type {};
template <class T, std::size_t N> struct is_list<std::array<T, N>> : std::true_type {};
template <class T> struct list_size {};
template <class T, std::size_t N> struct list_size<std::array<T, N>> : std::integral_constant<std::size_t, N> {};
}  // namespace json_detail

template <class S>
concept Described = requires { fields(std::type_identity<S>{}); };

template <Described S>
nlohmann::json to_json_object(const S& s);

/// A member's value as JSON: numbers (NaN and infinity as null), strings, true/false, lists, described structs.
template <class T>
nlohmann::json to_json_value(const T& v) {
  if constexpr (json_detail::is_list<T>::value) {
    nlohmann::json a = nlohmann::json::array();
    for (const auto& e : v) a.push_back(to_json_value(e));
    return a;
  } else if constexpr (Described<T>) {
    return to_json_object(v);
  } else {
    return nlohmann::json(v);
  }
}

template <class S, class M, Presence P>
void write_field(nlohmann::json& j, const S& s, const Field<S, M, P>& f) {
  const M& v = s.*f.member;
  if constexpr (P == Presence::kFlattened && json_detail::is_optional<M>::value) {
    if (v) j.update(to_json_object(*v));
  } else if constexpr (P == Presence::kFlattened) {
    j.update(to_json_object(v));
  } else if constexpr (P == Presence::kObjectText) {
    j[f.key] = nlohmann::json::parse(v);
  } else if constexpr (json_detail::is_optional<M>::value) {
    if (v) j[f.key] = to_json_value(*v);
    else if (P == Presence::kNullWhenAbsent) j[f.key] = nullptr;
  } else if constexpr (P == Presence::kOmittedWhenEmpty) {
    if (!v.empty()) j[f.key] = to_json_value(v);
  } else {
    j[f.key] = to_json_value(v);
  }
}

/// The struct as a JSON object, by its field table.
template <Described S>
nlohmann::json to_json_object(const S& s) {
  nlohmann::json j = nlohmann::json::object();
  std::apply([&](const auto&... f) { (write_field(j, s, f), ...); }, fields(std::type_identity<S>{}));
  return j;
}

template <Described S>
S read_object(const JsonIn& j);

/// A value of type T read from `j`; InputError naming the file, key and value when it is of another kind.
template <class T>
T read_value(const JsonIn& j) {
  if constexpr (std::is_same_v<T, bool>) {
    return j.flag();
  } else if constexpr (std::is_floating_point_v<T>) {
    return j.number();
  } else if constexpr (std::is_integral_v<T> && std::is_unsigned_v<T>) {
    return static_cast<T>(j.count());
  } else if constexpr (std::is_integral_v<T>) {
    const std::int64_t v = j.integer();
    if (v < std::numeric_limits<T>::min() || v > std::numeric_limits<T>::max()) j.fail("a whole number in range");
    return static_cast<T>(v);
  } else if constexpr (std::is_same_v<T, std::string>) {
    return j.text();
  } else if constexpr (json_detail::is_list<T>::value) {
    T out{};
    if constexpr (requires { out.push_back(out.front()); }) {
      for (const JsonIn& e : j.elements()) out.push_back(read_value<typename T::value_type>(e));
    } else {
      const std::vector<JsonIn> e = j.elements(json_detail::list_size<T>::value);
      for (std::size_t i = 0; i < e.size(); ++i) out[i] = read_value<typename T::value_type>(e[i]);
    }
    return out;
  } else {
    return read_object<T>(j);
  }
}

template <class S, class M, Presence P>
void read_field(const JsonIn& j, S& s, const Field<S, M, P>& f) {
  M& v = s.*f.member;
  if constexpr (P == Presence::kFlattened && json_detail::is_optional<M>::value) {
    using X = typename M::value_type;
    if (j.has(std::get<0>(fields(std::type_identity<X>{})).key)) v = read_object<X>(j);
  } else if constexpr (P == Presence::kFlattened) {
    v = read_object<M>(j);
  } else if constexpr (P == Presence::kObjectText) {
    const JsonIn e = j[f.key];
    if (!e.value().is_object()) e.fail("an object");
    v = e.value().dump();
  } else if constexpr (P == Presence::kNullWhenAbsent) {
    if (const JsonIn e = j[f.key]; !e.is_null()) v = read_value<typename M::value_type>(e);
  } else if constexpr (json_detail::is_optional<M>::value) {
    if (const std::optional<JsonIn> e = j.find(f.key)) v = read_value<typename M::value_type>(*e);
  } else if constexpr (P == Presence::kOmittedWhenEmpty) {
    if (const std::optional<JsonIn> e = j.find(f.key)) v = read_value<M>(*e);
  } else {
    v = read_value<M>(j[f.key]);
  }
}

/// The struct read from a JSON object by its field table; every key it always writes must be there.
template <Described S>
S read_object(const JsonIn& j) {
  S s{};
  std::apply([&](const auto&... f) { (read_field(j, s, f), ...); }, fields(std::type_identity<S>{}));
  return s;
}

/// An output's provenance: "case" (the resolved case) and "version", beside the output's own keys (flattened).
inline auto fields(std::type_identity<Provenance>) {
  return std::tuple{object_text("case", &Provenance::resolved_case), field("version", &Provenance::version)};
}

}  // namespace sw
