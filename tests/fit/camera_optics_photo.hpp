#pragma once
// Photographs of conoscopic figures through real optics, for the fitting tests: the figure rendered by the
// conoscope renderer (sine condition, finer than the photo) and resampled through a camera's projection of
// directions (sine, tangent or equidistant, with radial distortion) about a centre that need not be the
// frame's, without a field stop; an analyzer turned from crossed that leaks a fraction of the light it
// should block; the light falling off about its own centre; then blur, white balance, a tone curve, noise,
// 8-bit quantisation and JPEG (synthetic_photo.hpp's camera_image).
#include "synthetic_photo.hpp"

#include "petroscope/io/jpeg_encoding.hpp"

#include <numbers>

namespace petroscope::testing {

/// A photo parameter's position in PhotoParameters and in the fit's flags and results.
constexpr std::size_t index_of(PhotoParameter p) { return static_cast<std::size_t>(p); }

/// The hidden truth of a photo through real optics.
struct OpticsTruth {
    double thickness_um = 50.0;
    Projection projection = Projection::tangent;
    double center_dx_px = 0.0, center_dy_px = 0.0;  // the figure's centre from the frame's
    double field_radius_px = 60.0;                  // where the photo shows the direction of sin θ_air = NA
    double rotation_deg = 0.0;
    double tilt_deg = 0.0, azimuth_deg = 0.0;  // the cut's direction tilted away from the microscope axis
    double distortion = 0.0;
    double envelope_dx_px = 0.0, envelope_dy_px = 0.0;  // the light's centre from the frame's
    double envelope_radius_px = 80.0, envelope_power = 2.0;
    double analyzer_offset_deg = 0.0, extinction_ratio = 0.0;
    Eigen::Vector3d gains{1.0, 1.0, 1.0};
    double gamma = 2.2;
    double blur_px = 1.0;
    double noise = 2.0 / 255.0;
    int jpeg_quality = 85;
};

/// `truth` for a photo `factor` times as wide: the same figure and light, every length on the photo scaled.
inline OpticsTruth scaled_truth(OpticsTruth truth, double factor) {
    for (double* length : {&truth.center_dx_px, &truth.center_dy_px, &truth.field_radius_px, &truth.envelope_dx_px, &truth.envelope_dy_px,
                           &truth.envelope_radius_px}) {
        *length *= factor;
    }
    return truth;
}

/// |ξ| = sin θ_air of the light a photo shows u field radii from the figure's centre: the projection's law
/// written with angles (u = sin θ/sin θ_NA, tan θ/tan θ_NA or θ/θ_NA, after distortion); −1 (dark) beyond
/// grazing.
inline double projected_xi(Projection projection, double na, double u) {
    const double edge = std::asin(na);
    switch (projection) {
    case Projection::sine: return u * na < 1.0 ? u * na : -1.0;
    case Projection::tangent: return std::sin(std::atan(u * std::tan(edge)));
    case Projection::equidistant: return u * edge < 0.5 * std::numbers::pi ? std::sin(u * edge) : -1.0;
    }
    return -1.0;
}

/// Linear RGB (display colours) of a rendered figure at ξ by bilinear interpolation between its pixels.
inline Eigen::Vector3d figure_at(const Image& figure, const ConoscopeSettings& settings, const PhotoLight& light, const Eigen::Vector2d& xi) {
    const double half = 0.5 * settings.size_px;
    // conoscope_tangential_wavevector inverted: ξ = NA·((column + ½ − half)/half, −(row + ½ − half)/half).
    const double column = xi.x() / settings.numerical_aperture * half + half - 0.5, row = -xi.y() / settings.numerical_aperture * half + half - 0.5;
    const int c0 = static_cast<int>(std::floor(column)), r0 = static_cast<int>(std::floor(row));
    if (c0 < 0 || r0 < 0 || c0 + 1 >= figure.width || r0 + 1 >= figure.height) return Eigen::Vector3d::Zero();
    const double fc = column - c0, fr = row - r0;
    Eigen::Vector3d value = Eigen::Vector3d::Zero();
    for (int dr = 0; dr < 2; ++dr) {
        for (int dc = 0; dc < 2; ++dc) {
            const double weight = (dc ? fc : 1.0 - fc) * (dr ? fr : 1.0 - fr);
            for (int c = 0; c < 3; ++c) value[c] += weight * figure.at(c0 + dc, r0 + dr, light.integrator ? c : 0);
        }
    }
    return light.integrator ? Eigen::Vector3d(light.display * value) : value;
}

/// Linear display RGB (CV_64FC3, channels R, G, B) of the `size_px`² photo that `truth` describes through
/// `model`'s crystal, polars and light, before the optics' blur and the camera.
inline cv::Mat light_through_optics(const ConoscopePhotoModel& model, const PhotoLight& light, const OpticsTruth& truth, int size_px) {
    const double na = model.settings.numerical_aperture;
    const Eigen::Vector2d centre(0.5 * size_px + truth.center_dx_px, 0.5 * size_px + truth.center_dy_px);
    const Eigen::Vector2d light_centre(0.5 * size_px + truth.envelope_dx_px, 0.5 * size_px + truth.envelope_dy_px);
    // The render reaches the farthest corner's direction (or grazing light) and has 3 pixels per photo pixel
    // at the centre, where the projections spread directions most.
    double reach = 0.0;
    for (const double x : {0.0, double(size_px)}) {
        for (const double y : {0.0, double(size_px)}) {
            const double u = (Eigen::Vector2d(x, y) - centre).norm() / truth.field_radius_px;
            const double xi = projected_xi(truth.projection, na, u * (1.0 + truth.distortion * u * u));
            reach = std::max(reach, xi < 0.0 ? 1.0 : xi);  // a corner beyond grazing: the frame shows every direction
        }
    }
    ConoscopeSettings settings = model.settings;
    settings.numerical_aperture = std::min(reach + 0.02, 0.999);
    const double xi_per_px = 1.1 * std::tan(std::asin(na)) / truth.field_radius_px;
    settings.size_px = std::clamp(static_cast<int>(std::ceil(3.0 * 2.0 * settings.numerical_aperture / xi_per_px)), 64, 4096);
    settings.thickness_um = truth.thickness_um;
    settings.crystal_axes = model.orientation(truth.tilt_deg, truth.azimuth_deg);
    // A camera turned by ρ sees polarizers and crystal turned by ρ; the analyzer is off by its offset, and
    // the light it should block is the figure with the analyzer a further 90° on.
    settings.polarizer_deg += truth.rotation_deg;
    settings.analyzer_deg += truth.rotation_deg + truth.analyzer_offset_deg;
    settings.stage_deg += truth.rotation_deg;
    const Image passed = render_conoscope(settings, model.principal_n, light.integrator.get());
    settings.analyzer_deg += 90.0;
    const Image blocked = truth.extinction_ratio > 0.0 ? render_conoscope(settings, model.principal_n, light.integrator.get()) : Image();

    constexpr int kSubsamples = 3;  // per pixel side: a camera pixel integrates light over its area
    cv::Mat linear(size_px, size_px, CV_64FC3, cv::Scalar(0, 0, 0));
    for (int y = 0; y < size_px; ++y) {
        for (int x = 0; x < size_px; ++x) {
            Eigen::Vector3d value = Eigen::Vector3d::Zero();
            for (int sy = 0; sy < kSubsamples; ++sy) {
                for (int sx = 0; sx < kSubsamples; ++sx) {
                    const Eigen::Vector2d point(x + (sx + 0.5) / kSubsamples, y + (sy + 0.5) / kSubsamples);
                    const Eigen::Vector2d offset(point.x() - centre.x(), centre.y() - point.y());
                    const double u = offset.norm() / truth.field_radius_px;
                    const double xi = projected_xi(truth.projection, na, u * (1.0 + truth.distortion * u * u));
                    if (xi < 0.0 || u == 0.0) continue;
                    const double light_r = (point - light_centre).norm() / truth.envelope_radius_px;
                    const double envelope = std::exp(-std::pow(light_r, truth.envelope_power));
                    const Eigen::Vector2d direction = xi / offset.norm() * offset;
                    Eigen::Vector3d shown = figure_at(passed, settings, light, direction);
                    if (truth.extinction_ratio > 0.0) shown += truth.extinction_ratio * figure_at(blocked, settings, light, direction);
                    value += envelope * shown;
                }
            }
            value /= kSubsamples * kSubsamples;
            linear.at<cv::Vec3d>(y, x) = cv::Vec3d(value[0], value[1], value[2]);
        }
    }
    return linear;
}

/// The photo (camera values 0 … 1, 3 channels) of `size_px`² that `truth` describes through `model`'s
/// crystal, polars and light, through truth's camera (white-balance gains and a pure gamma); `seed` for the
/// noise; the JPEG file's bytes to `jpeg_file` when given.
inline Image photo_through_optics(const ConoscopePhotoModel& model, const PhotoLight& light, const OpticsTruth& truth, int size_px,
                                  unsigned seed, std::vector<std::uint8_t>* jpeg_file = nullptr) {
    return blurred_camera_image(light_through_optics(model, light, truth, size_px), truth.blur_px, truth.gains, truth.gamma, truth.noise,
                                truth.jpeg_quality, seed, jpeg_file);
}

/// What the fit is told of a `size_px`² photo through real optics: `model` set to the photo's projection,
/// no field stop and the light falling off; options starting from the defaults with the known field radius
/// and, for a JPEG photo (`jpeg_file` not empty), as the CLI does, the encoding read from the file, repeated on
/// the best fit for its systematic error. Which parameters are free is the caller's.
inline ConoscopeFitOptions real_optics_fit(ConoscopePhotoModel& model, const OpticsTruth& truth, const std::vector<std::uint8_t>& jpeg_file,
                                           int size_px) {
    model.projection = truth.projection;
    model.field_stop = FieldStop::none;
    model.illumination = IlluminationProfile::falloff;
    ConoscopeFitOptions options;
    if (!jpeg_file.empty()) {
        const JpegEncoding file_encoding = jpeg_encoding_of(jpeg_file, "photo.jpg").value();
        options.photo_encoding = [file_encoding](const Image& image) { return encode_like_jpeg(image, file_encoding); };
    }
    options.initial = default_photo_parameters(size_px, size_px);
    at(options.initial, PhotoParameter::field_radius_px) = truth.field_radius_px;
    return options;
}

}  // namespace petroscope::testing
