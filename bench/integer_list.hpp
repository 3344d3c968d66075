#pragma once
// A bench's comma-separated integers on its command line ("14,17,20"), shared by the benches that loop over sizes and
// ratios (bench/datasheet.cpp, bench/design_band.cpp).
#include <sstream>
#include <string>
#include <vector>

namespace sw::bench {

/// The integers of "14,17,20", in order (std::stoi's exceptions on an item that is not one).
inline std::vector<int> integer_list(const std::string& text) {
  std::vector<int> out;
  std::stringstream ss(text);
  std::string item;
  while (std::getline(ss, item, ',')) out.push_back(std::stoi(item));
  return out;
}

}  // namespace sw::bench
