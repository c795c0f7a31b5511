#pragma once
// The realistic-camera test bed of the conoscope fit (issue 18, item 4), shared by its test and bench_fit:
// seeded random cases, each a figure through real optics (camera_optics_photo.hpp: sine or tangent
// projection, off the frame's centre and cut by it, the light falling off about its own centre) and a camera
// the fit does not model exactly (colour_camera.hpp: vignetting, white balance and colour matrix off, shot and read
// noise on an RGGB Bayer sensor demosaiced before the tone curve, an S-shaped look curve after the sRGB curve, JPEG 75).
#include "camera_optics_photo.hpp"
#include "colour_camera.hpp"

#include <cmath>
#include <cstdint>
#include <iterator>
#include <random>
#include <vector>

namespace petroscope::testing {

/// A mineral, its cut, and the thicknesses whose figure a 128² photo resolves (log-uniform between them).
struct MineralRange {
    const char* mineral;
    Cut cut;
    double thinnest_um, thickest_um;
};

// Uniaxial and biaxial, birefringence 0.009 … 0.17: together 20 µm … 5 mm.
inline constexpr MineralRange kMineralRanges[] = {
    {"calcite", Cut::optic_axis, 20.0, 150.0},          {"quartz", Cut::optic_axis, 300.0, 5000.0},
    {"muscovite", Cut::acute_bisectrix, 20.0, 200.0},   {"aragonite", Cut::acute_bisectrix, 20.0, 100.0},
    {"sillimanite", Cut::acute_bisectrix, 100.0, 1000.0},
};

struct CameraCase {
    MineralRange mineral;
    OpticsTruth optics;
    ColourCamera camera;
    bool centred = false;
};

/// Case `index` of the random test bed for `size_px`² photos: the minerals in turn, sine and tangent
/// projections in turn, every fourth figure centred and the others off the frame's centre by up to 20% of the
/// frame each way; the field radius 0.5 … 0.7 frames (the frame cuts the figure); the light's centre up to
/// 15% of the frame from the frame's, its radius 0.5 … 0.9 frames, its power 2 … 4; the camera turned by up
/// to ±10°, blur 0.6 … 1.2 px, and a random ColourCamera.
inline CameraCase random_case(int index, int size_px) {
    std::mt19937_64 rng(1000 + static_cast<unsigned>(index));
    const auto uniform = [&rng](double low, double high) { return low + (high - low) * uniform_unit_interval(rng); };
    CameraCase c{kMineralRanges[static_cast<std::size_t>(index) % std::size(kMineralRanges)], {}, {}, index % 4 == 0};
    OpticsTruth& truth = c.optics;
    truth.thickness_um = std::exp(uniform(std::log(c.mineral.thinnest_um), std::log(c.mineral.thickest_um)));
    truth.projection = index % 2 == 0 ? Projection::sine : Projection::tangent;
    truth.center_dx_px = c.centred ? 0.0 : uniform(-0.2, 0.2) * size_px;
    truth.center_dy_px = c.centred ? 0.0 : uniform(-0.2, 0.2) * size_px;
    truth.field_radius_px = uniform(0.5, 0.7) * size_px;
    truth.rotation_deg = uniform(-10.0, 10.0);
    truth.envelope_dx_px = uniform(-0.15, 0.15) * size_px;
    truth.envelope_dy_px = uniform(-0.15, 0.15) * size_px;
    truth.envelope_radius_px = uniform(0.5, 0.9) * size_px;
    truth.envelope_power = uniform(2.0, 4.0);
    truth.blur_px = uniform(0.6, 1.2);
    c.camera = ColourCamera::random(rng, size_px, size_px);
    return c;
}

/// Case `c` (number `index`) with its cut tilted by 2 … 8° toward a random azimuth, drawn apart from the case's own
/// numbers so that the rest of the case stays as it is.
inline CameraCase tilted_case(int index, CameraCase c) {
    std::mt19937_64 rng(5000 + static_cast<unsigned>(index));
    c.optics.tilt_deg = 2.0 + 6.0 * uniform_unit_interval(rng);
    c.optics.azimuth_deg = 360.0 * uniform_unit_interval(rng);
    return c;
}

struct CameraCasePhoto {
    ConoscopePhotoModel model;
    Image photo;
    ConoscopeFitOptions options;
};

/// Whether the fit is told the scale (the field radius), or starts it where it starts for a user who does not know
/// it (default_photo_parameters: half the frame) and fits it.
enum class Scale { known, unknown };

/// Whether the fit holds the cut's tilt at 0 or fits it (and its azimuth) from 0.
enum class Tilt { held, free };

/// A photo of case `c` (number `index`, which seeds its noise) and what the fit is told of it: the thickness
/// searched over the default range, every other term free but the distortion and polars, the field radius unless
/// `scale` is unknown and the tilt unless `tilt` is free.
inline CameraCasePhoto photograph_case(int index, const CameraCase& c, int size_px, Scale scale = Scale::known, Tilt tilt = Tilt::held) {
    static const PhotoLight light = white_light();
    CameraCasePhoto shot{photo_model(fit_minerals().find(c.mineral.mineral), c.mineral.cut), {}, {}};
    cv::Mat linear = light_through_optics(shot.model, light, c.optics, size_px);
    cv::GaussianBlur(linear, linear, cv::Size(0, 0), c.optics.blur_px);
    std::vector<std::uint8_t> jpeg_file;
    shot.photo = c.camera.photograph(linear, 7 + static_cast<unsigned>(index), &jpeg_file);
    shot.options = real_optics_fit(shot.model, c.optics, jpeg_file, size_px);
    shot.options.sensor = ColourSensor::bayer;  // the camera's, as the command line assumes for a JPEG photo
    shot.options.free.fill(true);
    for (const PhotoParameter fixed : {PhotoParameter::field_radius_px, PhotoParameter::tilt_deg, PhotoParameter::azimuth_deg,
                                       PhotoParameter::distortion, PhotoParameter::analyzer_offset_deg, PhotoParameter::extinction_ratio}) {
        shot.options.free[index_of(fixed)] = false;
    }
    if (scale == Scale::unknown) {
        shot.options.free[index_of(PhotoParameter::field_radius_px)] = true;
        at(shot.options.initial, PhotoParameter::field_radius_px) = at(default_photo_parameters(size_px, size_px), PhotoParameter::field_radius_px);
    }
    if (tilt == Tilt::free) {
        for (const PhotoParameter p : {PhotoParameter::tilt_deg, PhotoParameter::azimuth_deg}) shot.options.free[index_of(p)] = true;
    }
    return shot;
}

}  // namespace petroscope::testing
