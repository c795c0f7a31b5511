#pragma once
// Orthoscopic photos of grains for the orthoscope fit's tests: the gypsum plate, a grain of maximum
// birefringence, a section rendered between the fit's polars at one stage angle.
#include "synthetic_photo.hpp"

#include "petroscope/fit/orthoscope_fit.hpp"
#include "petroscope/microscope/orthoscope.hpp"
#include "petroscope/optics/orientation.hpp"

#include <algorithm>
#include <string>
#include <vector>

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

constexpr int kGrainPhotoSize = 32;  // the photo, px; the grain fills it, the region is its central 12 px

struct GrainShot {
    double stage_deg = 0.0;
    bool gypsum = false;
};

/// A camera on a microscope that photographs one-grain sections (sRGB, noise σ = 2/255, JPEG quality 85) in
/// the white light of white_light(), and the fit options of that microscope.
class GrainPhotos {
public:
    GrainPhotos()
        : light_(white_light()), options_() {
        options_.microscope.wavelengths_nm = light_.wavelengths_nm;
        options_.mounting = standard_mounting(fit_minerals());
    }

    const OrthoscopeFitOptions& options() const { return options_; }
    OrthoscopeFitOptions& options() { return options_; }
    const SpectralIntegrator& integrator() const { return *light_.integrator; }

    /// Photos of a grain of `mineral`, `thickness_um` thick, with indicatrix axes `axes` at stage 0.
    std::vector<GrainPhoto> take(const std::string& mineral, double thickness_um, const Eigen::Matrix3d& axes,
                                 const std::vector<GrainShot>& shots, unsigned seed) const {
        ThinSection section;
        section.name = "grain";
        section.width_px = section.height_px = kGrainPhotoSize;
        section.pixel_size_um = 10.0;
        section.labels.assign(kGrainPhotoSize * kGrainPhotoSize, 1);
        section.grains.push_back({1, mineral, axes, std::nullopt, 0});
        section.thickness_um = thickness_um;
        section.validate();
        std::vector<GrainPhoto> photos;
        for (const GrainShot& shot : shots) {
            const cv::Mat linear = section_linear(section, options_, light_, shot.stage_deg, shot.gypsum);
            const Image photo = camera_image(
                linear, [](int, double value) { return encode_srgb(std::clamp(value, 0.0, 1.0)); }, 2.0 / 255.0, 85, seed++);
            GrainPhoto grain;
            grain.colour = grain_colour(photo, rectangle_mask(kGrainPhotoSize, kGrainPhotoSize, 10, 10, 12, 12));
            grain.stage_deg = shot.stage_deg;
            if (shot.gypsum) grain.plate = gypsum_plate();
            photos.push_back(grain);
        }
        return photos;
    }

private:
    PhotoLight light_;
    OrthoscopeFitOptions options_;
};

}  // namespace petroscope::testing
