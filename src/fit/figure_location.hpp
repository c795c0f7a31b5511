#pragma once
// Where a conoscopic figure lies in a photo, before any model is fitted (docs/fitting.md, "Finding the figure").
#include "petroscope/core/image.hpp"

#include <Eigen/Core>

#include <optional>

namespace petroscope::detail {

/// The point c (pixel coordinates, a pixel's centre at k + ½) about which `photo` is most nearly symmetric under
/// a half turn p → 2c − p: the centre of the figure of a cut whose indicatrix has a two-fold axis along the
/// microscope's (an optic axis or a bisectrix, not tilted), which stays symmetric through the camera's response,
/// wherever the frame cuts it. The measure is the normalised correlation of the luminance with its half-turned
/// copy over their overlap, which must cover at least a third of the frame (a figure may lie a fifth of the frame
/// off centre each way); it is maximised over every c on a
/// grid of about 64 px, then near the best on one of about 128 px (so to within about 1/128 of the frame). None
/// where the photo is flat.
std::optional<Eigen::Vector2d> half_turn_symmetry_centre_px(const Image& photo);

}  // namespace petroscope::detail
