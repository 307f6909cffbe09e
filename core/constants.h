// Mathematical constants used across prism.
#pragma once

#include <limits>

namespace prism {

inline constexpr float kPi = 3.14159265358979323846f;
inline constexpr float kInvPi = 0.31830988618379067154f;
inline constexpr float kTwoPi = 6.28318530717958647692f;
inline constexpr float kInvTwoPi = 0.15915494309189533577f;
inline constexpr float kInvFourPi = 0.07957747154594766788f;
inline constexpr float kPiOver2 = 1.57079632679489661923f;
inline constexpr float kPiOver4 = 0.78539816339744830962f;
inline constexpr float kInfinity = std::numeric_limits<float>::infinity();
// Largest float below 1: keeps [0,1) samples away from 1.
inline constexpr float kOneMinusEpsilon = 0x1.fffffep-1f;

}  // namespace prism
