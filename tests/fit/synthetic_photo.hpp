#pragma once
// Photographs of conoscopic figures made the way a camera makes them, for the fitting tests: the figure
// rendered by the conoscope renderer with the field's centre, scale and the camera's rotation applied,
// averaged over each pixel's area, then blur, white balance, a tone curve, noise, 8-bit quantisation and JPEG compression (OpenCV).
#include "petroscope/api/conoscope_photo_model.hpp"
#include "petroscope/io/data_files.hpp"
#include "petroscope/spectral/color.hpp"
#include "petroscope/spectral/wavelength_grid.hpp"

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <cmath>
#include <cstdint>
#include <functional>
#include <random>
#include <string>

namespace petroscope::testing {

inline const MineralCatalog& fit_minerals() {
    static const MineralCatalog catalog = load_mineral_catalog(std::filesystem::path(PETROSCOPE_SOURCE_DIR) / "minerals");
    return catalog;
}

/// The hidden truth of a synthetic photo.
struct PhotoTruth {
    double thickness_um = 30.0;
    int center_dx_px = 0, center_dy_px = 0;  // from the image centre
    double radius_scale = 1.0;               // field radius / (size / 2)
    double rotation_deg = 0.0;
    double tilt_deg = 0.0, azimuth_deg = 0.0;
    Eigen::Vector3d gains{1.0, 1.0, 1.0};
    double gamma = 2.2;
    double blur_px = 1.0;
    double noise = 2.0 / 255.0;
    int jpeg_quality = 85;  // 0: no compression
    int supersampling = 4;  // rendered samples per pixel side: a camera pixel integrates light over its area
};

/// White light (D65, 380 … 780 nm by 5 nm) or one wavelength.
struct PhotoLight {
    std::vector<double> wavelengths_nm;
    std::shared_ptr<SpectralIntegrator> integrator;  // white light only
    Eigen::Matrix3d display = Eigen::Matrix3d::Identity();
};

/// D65 over 380 … 780 nm by 5 nm, white balanced: the default Light.
inline PhotoLight white_light() {
    PhotoLight light;
    light.wavelengths_nm = Light{}.wavelengths_nm();
    light.integrator = std::make_shared<SpectralIntegrator>(light.wavelengths_nm, load_cie_1931_observer(), load_light_source("D65"));
    light.display = xyz_to_display_matrix(light.integrator->white_xyz(), true, 1.0);
    return light;
}

/// The fit's model of photos of `mineral` in `cut`, crossed polars, NA 0.85, balsam around the slab, in the
/// white light of white_light().
inline ConoscopePhotoModel photo_model(const Mineral& mineral, Cut cut) {
    ConoscopePhotoSetup setup;
    setup.cut = cut;
    return conoscope_photo_model(mineral, setup);
}

/// The parameters a photo through a microscope leaves unknown: thickness … blur. The terms of other optics
/// (the envelope, the distortion, the analyzer's offset and leak) stay at their neutral values.
inline PhotoParameterFlags microscope_unknowns() {
    PhotoParameterFlags free{};
    for (std::size_t j = 0; j <= static_cast<std::size_t>(PhotoParameter::blur_variance_px2); ++j) free[j] = true;
    return free;
}

/// Linear display RGB (CV_64FC3, channels R, G, B) of an XYZ image (3 channels) through `display`.
inline cv::Mat display_linear(const Image& xyz, const Eigen::Matrix3d& display) {
    cv::Mat linear(xyz.height, xyz.width, CV_64FC3);
    for (int y = 0; y < xyz.height; ++y) {
        for (int x = 0; x < xyz.width; ++x) {
            const Eigen::Vector3d rgb = display * Eigen::Vector3d(xyz.at(x, y, 0), xyz.at(x, y, 1), xyz.at(x, y, 2));
            linear.at<cv::Vec3d>(y, x) = cv::Vec3d(rgb[0], rgb[1], rgb[2]);
        }
    }
    return linear;
}

/// What a camera makes of linear RGB (CV_64FC3, channels R, G, B): `tone` per channel, Gaussian noise of
/// σ = `noise`, 8-bit quantisation and JPEG at `jpeg_quality` (0: none); camera values 0 … 1. The JPEG
/// file's bytes go to `jpeg_file` when given.
inline Image camera_image(const cv::Mat& linear, const std::function<double(int, double)>& tone, double noise_sigma, int jpeg_quality,
                          unsigned seed, std::vector<std::uint8_t>* jpeg_file = nullptr) {
    std::mt19937 random(seed);
    std::normal_distribution<double> noise(0.0, noise_sigma);
    cv::Mat encoded(linear.rows, linear.cols, CV_8UC3);
    for (int y = 0; y < linear.rows; ++y) {
        for (int x = 0; x < linear.cols; ++x) {
            for (int c = 0; c < 3; ++c) {
                const double value = tone(c, linear.at<cv::Vec3d>(y, x)[c]) + noise(random);
                encoded.at<cv::Vec3b>(y, x)[2 - c] = static_cast<unsigned char>(std::lround(std::clamp(value, 0.0, 1.0) * 255.0));
            }
        }
    }
    if (jpeg_quality > 0) {
        std::vector<unsigned char> bytes;
        cv::imencode(".jpg", encoded, bytes, {cv::IMWRITE_JPEG_QUALITY, jpeg_quality});
        encoded = cv::imdecode(bytes, cv::IMREAD_COLOR);
        if (jpeg_file != nullptr) *jpeg_file = std::move(bytes);
    }
    Image photo(linear.cols, linear.rows, 3);
    for (int y = 0; y < linear.rows; ++y) {
        for (int x = 0; x < linear.cols; ++x) {
            for (int c = 0; c < 3; ++c) photo.at(x, y, c) = static_cast<float>(encoded.at<cv::Vec3b>(y, x)[2 - c] / 255.0);
        }
    }
    return photo;
}

/// camera_image of `linear` blurred by a Gaussian of σ = `blur_px` (the optics), through white-balance gains and
/// a pure gamma: value = (gain·linear)^(1/γ).
inline Image blurred_camera_image(cv::Mat linear, double blur_px, const Eigen::Vector3d& gains, double gamma, double noise_sigma,
                                  int jpeg_quality, unsigned seed, std::vector<std::uint8_t>* jpeg_file) {
    if (blur_px > 0.0) cv::GaussianBlur(linear, linear, cv::Size(0, 0), blur_px);
    return camera_image(
        linear, [&gains, gamma](int c, double value) { return std::pow(std::max(gains[c] * value, 0.0), 1.0 / gamma); }, noise_sigma,
        jpeg_quality, seed, jpeg_file);
}

/// The photo (camera values 0 … 1, 3 channels) of `size_px`² that `truth` describes; `seed` for the noise;
/// the JPEG file's bytes to `jpeg_file` when given.
inline Image synthesize_photo(const ConoscopePhotoModel& model, const PhotoLight& light, const PhotoTruth& truth, int size_px,
                              unsigned seed, std::vector<std::uint8_t>* jpeg_file = nullptr) {
    // Render only the field: a square of side 2⌈R⌉ + 2 around it, with the NA scaled to match.
    const double radius_px = truth.radius_scale * 0.5 * size_px;
    const int render_size = 2 * static_cast<int>(std::ceil(radius_px)) + 2;
    const int samples = std::max(truth.supersampling, 1);
    ConoscopeSettings settings = model.settings;
    settings.size_px = render_size * samples;
    settings.numerical_aperture = model.settings.numerical_aperture * (0.5 * render_size) / radius_px;
    settings.thickness_um = truth.thickness_um;
    settings.crystal_axes = model.orientation(truth.tilt_deg, truth.azimuth_deg);
    // A camera turned by ρ sees polarizers and crystal turned by ρ.
    settings.polarizer_deg += truth.rotation_deg;
    settings.analyzer_deg += truth.rotation_deg;
    settings.stage_deg += truth.rotation_deg;
    const Image figure = render_conoscope(settings, model.principal_n, light.integrator.get());

    cv::Mat linear(size_px, size_px, CV_64FC3, cv::Scalar(0, 0, 0));
    const int origin_x = size_px / 2 + truth.center_dx_px - render_size / 2, origin_y = size_px / 2 + truth.center_dy_px - render_size / 2;
    for (int row = 0; row < render_size; ++row) {
        for (int column = 0; column < render_size; ++column) {
            const int x = origin_x + column, y = origin_y + row;
            if (x < 0 || y < 0 || x >= size_px || y >= size_px) continue;
            if (std::hypot(column + 0.5 - 0.5 * render_size, row + 0.5 - 0.5 * render_size) > radius_px) continue;
            Eigen::Vector3d value = Eigen::Vector3d::Zero();
            for (int sy = 0; sy < samples; ++sy) {
                for (int sx = 0; sx < samples; ++sx) {
                    for (int c = 0; c < 3; ++c) value[c] += figure.at(column * samples + sx, row * samples + sy, light.integrator ? c : 0);
                }
            }
            value /= samples * samples;
            const Eigen::Vector3d rgb = light.integrator ? Eigen::Vector3d(light.display * value) : value;
            linear.at<cv::Vec3d>(y, x) = cv::Vec3d(rgb[0], rgb[1], rgb[2]);
        }
    }
    return blurred_camera_image(linear, truth.blur_px, truth.gains, truth.gamma, truth.noise, truth.jpeg_quality, seed, jpeg_file);
}

}  // namespace petroscope::testing
