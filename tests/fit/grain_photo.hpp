#pragma once
// Orthoscopic photos of grains for the orthoscope fit's tests: the gypsum plate, a grain of maximum
// birefringence, a section rendered between the fit's polars at one stage angle.
#include "synthetic_photo.hpp"

#include "petroscope/fit/orthoscope_fit.hpp"
#include "petroscope/microscope/orthoscope.hpp"
#include "petroscope/optics/orientation.hpp"

namespace petroscope::testing {

/// The gypsum plate with its slow direction at 45°.
inline AccessoryPlate gypsum_plate() { return make_accessory_plate(PlateKind::gypsum, fit_minerals().find("gypsum"), 45.0); }

/// The indicatrix axes of a grain of maximum birefringence (X and Z in the section, Y down the microscope
/// axis) with X at `angle_deg` on the stage, from E toward N.
inline Eigen::Matrix3d max_birefringence_axes(double angle_deg) {
    Eigen::Matrix3d in_plane;
    in_plane << 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, -1.0, 0.0;
    return rotation_z_deg(angle_deg) * in_plane;
}

/// Linear display RGB (CV_64FC3) of `section` through the microscope of `options` at `stage_deg`, with the
/// gypsum plate when `gypsum`, in `light`.
inline cv::Mat section_linear(const ThinSection& section, const OrthoscopeFitOptions& options, const PhotoLight& light, double stage_deg, bool gypsum) {
    OrthoscopeSettings settings;
    settings.microscope = options.microscope;
    settings.microscope.stage_deg = stage_deg;
    if (gypsum) settings.microscope.plate = gypsum_plate();
    settings.mounting = options.mounting;
    return display_linear(render_orthoscope(section, fit_minerals(), settings, light.integrator.get()), light.display);
}

}  // namespace petroscope::testing
