#include "io/provenance.hpp"

#include <nlohmann/json.hpp>

namespace sw {

Provenance provenance_of(const Case& c) {
  return {nlohmann::json::parse(case_json(c)).dump(), tool_version()};
}

}  // namespace sw
