#pragma once
// Angles in degrees, and directions in the lab's (x, y) plane (docs/conventions.md: x to the East, y to
// the North, angles from East toward North).
#include <Eigen/Core>

#include <cmath>
#include <numbers>

namespace petroscope {

/// Radians per degree.
inline constexpr double kDegree = std::numbers::pi / 180.0;

/// The unit vector at `angle_deg` from +x toward +y.
inline Eigen::Vector2d unit_at(double angle_deg) {
    return {std::cos(angle_deg * kDegree), std::sin(angle_deg * kDegree)};
}

}  // namespace petroscope
