#pragma once
// The camera of `fit orthoscope` (docs/fitting.md, "Calibrating the camera"): gains on the linear display
// channels, the sRGB curve, then a contrast curve; and the gains that a reference region showing no
// birefringence fixes.
#include <Eigen/Core>

#include <array>
#include <cstddef>
#include <vector>

namespace petroscope::detail {

/// The camera's code of a linear display value x: C_a(encode_srgb(x)) with x clamped to 0 … 1 and the
/// contrast curve C_a(y) = yᵃ / (yᵃ + (1 − y)ᵃ), an S through (0, 0), (½, ½), (1, 1) of slope a at ½
/// (a = 1: the plain sRGB camera).
double camera_tone(double linear, double contrast);
/// camera_tone of each channel of a linear display colour.
Eigen::Vector3d camera_code(const Eigen::Vector3d& linear, double contrast);

/// The reference region's colours: per photo that gives it, the model's linear colour (the microscope
/// without the crystal) and the photo's mean code.
struct ReferenceColours {
    std::vector<std::size_t> photos;
    std::vector<Eigen::Vector3d> model_linear, measured_code;
    std::array<bool, 3> lit{};  // channels some reference lights: the only ones it calibrates
};

/// Marks the lit channels (a model value of 0.02 or more in some photo); false when none is lit.
bool mark_lit_channels(ReferenceColours& references);

/// The gains that carry the references' model colours to their measured codes through camera_tone at
/// `contrast`, per lit channel by Gauss–Newton on Σ_k (tone(g·L_k) − m_k)²; an unlit channel takes the mean
/// gain of the lit ones (a camera balanced on its light).
Eigen::Vector3d reference_gains(const ReferenceColours& references, double contrast);

}  // namespace petroscope::detail
