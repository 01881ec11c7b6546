#pragma once
// Pi and the degree-radian factors, once for the whole engine and its tests (C++17 has no
// std::numbers).
namespace orthosim {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDeg = kPi / 180.0;        // one degree in radians: 10 * kDeg
constexpr double kDegPerRad = 180.0 / kPi;  // radians to degrees

}  // namespace orthosim
