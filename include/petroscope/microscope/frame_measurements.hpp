#pragma once
// Measurements made on a rendered image, as one would make them on a photograph: its mean colour, and the
// dark spot of a melatope; and where the exact model puts the optic axes in a conoscopic figure.
#include "petroscope/core/image.hpp"
#include "petroscope/microscope/conoscope.hpp"

#include <Eigen/Core>

#include <optional>
#include <vector>

namespace petroscope {

/// Mean linear sRGB and luminance Y = 0.2126 R + 0.7152 G + 0.0722 B (IEC 61966-2-1, the sRGB primaries'
/// Y) over the image, or over the inscribed circle (a conoscopic field) when `circular_field`.
struct MeanColour {
    double r = 0.0, g = 0.0, b = 0.0, luminance = 0.0;
};
MeanColour mean_colour(const Image& linear_rgb, bool circular_field);

/// Field points (x, y) of a conoscopic figure (x to the E, y to the N, 1 = the edge of the field, as in
/// conoscope_tangential_wavevector) of the optic axes: the wave normal along a binormal b̂ has index nβ
/// (ω for a uniaxial crystal), so its tangential wavevector nβ·(b_x, b_y) is kept into air and it is imaged
/// at nβ·(b_x, b_y)/NA (Mallard's law, docs/theory.md §5). One point for a uniaxial crystal, two for a biaxial
/// one; an axis lying in the plane of the slab (a flash figure) has none. Points may lie outside the field.
std::vector<Eigen::Vector2d> conoscope_optic_axis_points(const ConoscopeSettings& settings, const Eigen::Vector3d& principal_n);

/// The darkest point of the image's luminance, smoothed by a Gaussian of `blur_px`, within `window_px` of
/// `guess` (a field point as above), refined to a fraction of a pixel by a parabola in x and in y. Between
/// crossed polars a melatope is a zero of both the isogyres and the retardation, so it is the minimum of
/// the smoothed image; an arm of an isogyre alone is not. Empty when the minimum lies on the window's edge
/// (no dark spot there) or the window leaves the field.
std::optional<Eigen::Vector2d> dark_spot_near(const Image& linear_rgb, const Eigen::Vector2d& guess, int window_px,
                                              double blur_px);

}  // namespace petroscope
