#pragma once
// Drawing the Michel-Lévy chart: the interference colours as bands, the birefringence lines Γ = Δn·d
// radiating from the origin, the order boundaries, axes and labels (OpenCV's Hershey fonts).
#include "petroscope/core/image.hpp"
#include "petroscope/microscope/michel_levy.hpp"

#include <vector>

namespace petroscope {

struct MichelLevyChartLayout {
    double max_thickness_um = 50.0;      // the vertical axis, 0 at the bottom
    double section_thickness_um = 30.0;  // drawn as a dashed horizontal line (standard thin section)
    int plot_width_px = 1400;
    int plot_height_px = 560;
};

/// The chart as a linear-RGB image: `linear_srgb[k]` is the display colour of `steps[k]` (equally spaced
/// in retardation from 0). Throws InputError when the two lists differ in length or are too short.
Image draw_michel_levy_chart(const std::vector<MichelLevyStep>& steps, const std::vector<Eigen::Vector3d>& linear_srgb,
                             const MichelLevyChartLayout& layout);

}  // namespace petroscope
