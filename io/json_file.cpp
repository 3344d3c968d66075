#include "io/json_file.hpp"

#include <cmath>
#include <fstream>
#include <limits>

#include "common/error.hpp"

namespace sw {
namespace {

constexpr std::size_t kValueShown = 40;  ///< characters of a bad value quoted in a message

std::string shown(const nlohmann::json& v) {
  const std::string s = v.dump();
  return s.size() <= kValueShown ? s : s.substr(0, kValueShown) + "...";
}

}  // namespace

JsonIn JsonIn::top(std::shared_ptr<Document> doc) {
  if (!doc->root.is_object())
    throw InputError(doc->file + ": not a JSON object; expected " + doc->expected);
  const nlohmann::json* root = &doc->root;
  return JsonIn(std::move(doc), root, "");
}

JsonIn JsonIn::open(const std::filesystem::path& path, const std::string& cannot_open, const std::string& expected) {
  auto doc = std::make_shared<Document>();
  doc->file = path.string();
  doc->expected = expected;
  std::ifstream in(path);
  if (!in) throw InputError(doc->file + ": " + cannot_open);
  try {
    in >> doc->root;
  } catch (const std::exception& e) {
    throw InputError(doc->file + ": not valid JSON (" + std::string(e.what()) + ")");
  }
  return top(std::move(doc));
}

JsonIn JsonIn::parse(const std::string& text, const std::string& file, const std::string& expected) {
  auto doc = std::make_shared<Document>();
  doc->file = file;
  doc->expected = expected;
  try {
    doc->root = nlohmann::json::parse(text);
  } catch (const std::exception& e) {
    throw InputError(file + ": not valid JSON (" + std::string(e.what()) + ")");
  }
  return top(std::move(doc));
}

void JsonIn::fail(const std::string& what) const {
  throw InputError(doc_->file + ": " + (path_.empty() ? "the file" : path_) + " = " + shown(*value_) + "; expected " +
                   what + " in " + doc_->expected);
}

bool JsonIn::is_null() const { return value_->is_null(); }

bool JsonIn::has(const std::string& key) const { return value_->is_object() && value_->contains(key); }

std::optional<JsonIn> JsonIn::find(const std::string& key) const {
  if (!value_->is_object()) fail("an object");
  const auto it = value_->find(key);
  if (it == value_->end()) return std::nullopt;
  return JsonIn(doc_, &*it, path_.empty() ? key : path_ + "." + key);
}

JsonIn JsonIn::operator[](const std::string& key) const {
  std::optional<JsonIn> v = find(key);
  if (!v)
    throw InputError(doc_->file + ": " + (path_.empty() ? key : path_ + "." + key) + " is missing; expected " +
                     doc_->expected);
  return *v;
}

std::vector<JsonIn> JsonIn::elements() const {
  if (!value_->is_array()) fail("a list");
  std::vector<JsonIn> out;
  for (std::size_t i = 0; i < value_->size(); ++i)
    out.push_back(JsonIn(doc_, &(*value_)[i], path_ + "[" + std::to_string(i) + "]"));
  return out;
}

std::vector<JsonIn> JsonIn::elements(std::size_t size) const {
  if (!value_->is_array() || value_->size() != size) fail("a list of " + std::to_string(size));
  return elements();
}

double JsonIn::number() const {
  if (value_->is_null()) return std::numeric_limits<double>::quiet_NaN();
  if (!value_->is_number()) fail("a number");
  return value_->get<double>();
}

double JsonIn::finite() const {
  if (!value_->is_number() || !std::isfinite(value_->get<double>())) fail("a finite number");
  return value_->get<double>();
}

std::int64_t JsonIn::integer() const {
  if (!value_->is_number_integer()) fail("a whole number");
  return value_->get<std::int64_t>();
}

std::uint64_t JsonIn::count() const {
  if (!value_->is_number_unsigned() && !(value_->is_number_integer() && value_->get<std::int64_t>() >= 0))
    fail("a whole number >= 0");
  return value_->get<std::uint64_t>();
}

std::string JsonIn::text() const {
  if (!value_->is_string()) fail("a string");
  return value_->get<std::string>();
}

bool JsonIn::flag() const {
  if (!value_->is_boolean()) fail("true or false");
  return value_->get<bool>();
}

std::vector<double> JsonIn::numbers() const {
  std::vector<double> out;
  for (const JsonIn& e : elements()) out.push_back(e.number());
  return out;
}

std::optional<double> JsonIn::optional_number(const std::string& key) const {
  const std::optional<JsonIn> v = find(key);
  if (!v) return std::nullopt;
  return v->number();
}

}  // namespace sw
