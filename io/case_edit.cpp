#include "io/case_edit.hpp"

#include <cmath>
#include <cstdint>
#include <sstream>

#include <toml++/toml.h>

#include "common/error.hpp"

namespace sw {

namespace {

toml::table parse_text(const std::string& text, const std::string& path) {
  try {
    return toml::parse(text, path);
  } catch (const toml::parse_error& e) {
    throw InputError(path + ": malformed TOML: " + std::string(e.description()));
  }
}

}  // namespace

std::string case_text_with(const std::string& toml_text, const std::string& path, const CaseKeyValues& values,
                           const std::string& option) {
  toml::table t = parse_text(toml_text, path);
  for (const auto& [name, v] : values) {
    const auto dot = name.find('.');
    if (dot == std::string::npos || dot == 0 || dot + 1 == name.size() || name.find('.', dot + 1) != std::string::npos)
      throw InputError(option + " " + name + ": expected TABLE.KEY (e.g. flexspline.wall_thickness_mm)");
    const std::string table_name = name.substr(0, dot), key = name.substr(dot + 1);
    toml::node* table = t.get(table_name);
    if (!table) {
      t.insert(table_name, toml::table{});
      table = t.get(table_name);
    }
    if (!table->is_table()) throw InputError(option + " " + name + ": " + table_name + " is not a table of the case");
    auto& tt = *table->as_table();
    const toml::node* old = tt.get(key);
    if (old && old->is_integer() && v == std::round(v)) tt.insert_or_assign(key, static_cast<int64_t>(std::llround(v)));
    else tt.insert_or_assign(key, v);
  }
  std::ostringstream s;
  s << t << "\n";
  return s.str();
}

std::optional<double> case_number(const Case& c, const std::string& key) {
  const toml::table t = parse_text(describe_case(c), c.path);
  const toml::node_view<const toml::node> node = t.at_path(key);
  if (const auto* f = node.as_floating_point()) return f->get();
  if (const auto* i = node.as_integer()) return static_cast<double>(i->get());
  return std::nullopt;
}

}  // namespace sw
