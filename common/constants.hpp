#pragma once
// The constants the tool's sources share, once for all of them: each library is compiled in a few unity batches
// (CMakeLists.txt), where a constant defined again in every source of a batch would be defined twice.
#include <numbers>

namespace sw {

inline constexpr double kPi = std::numbers::pi;
inline constexpr double kDeg = 180.0 / std::numbers::pi;            ///< degrees per radian
inline constexpr double kArcmin = 10800.0 / std::numbers::pi;       ///< arc minutes per radian
inline constexpr double kRpmPerRadS = 30.0 / std::numbers::pi;      ///< rpm per rad/s

}  // namespace sw
