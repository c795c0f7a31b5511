#pragma once
// Measurements on rendered figures, as one would make them on a photograph: sub-pixel minima of
// profiles, and the rotation between two images by registration.
#include "petroscope/core/image.hpp"

#include <vector>

namespace petroscope::testing {

/// Positions (in samples, sub-sample by a parabola through the three samples around each) of the local
/// minima of `profile` whose value is below `threshold`.
std::vector<double> profile_minima(const std::vector<double>& profile, double threshold);

/// Bilinear sample of channel 0 at continuous pixel coordinates (x, y) (pixel centres at i + 0.5).
double sample_bilinear(const Image& image, double x, double y);

/// The angle β (degrees, counter-clockwise as displayed with y up) that best maps `reference` onto
/// `rotated` (rotated(p) ≈ reference(R(−β)p) about the image centre), by golden-section search of the
/// squared difference over the disc of radius 0.9 in [guess − half_width, guess + half_width].
double registered_rotation_deg(const Image& reference, const Image& rotated, double guess_deg, double half_width_deg);

}  // namespace petroscope::testing
