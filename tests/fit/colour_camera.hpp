#pragma once
// A camera that renders colour the way real ones do, not the way the fits model it: light falling off across
// the field, sensor colours that the camera's colour correction leaves slightly off (a colour matrix, applied at
// the sensor) and a white balance slightly off, shot and read noise on a Bayer sensor demosaiced bilinearly, the
// sRGB curve and an S-shaped "look" curve after it, JPEG. The steps follow a camera's own pipeline, which
// demosaics the linear raw values before the tone curve (raw sensor → white balance → demosaicing → colour
// correction → tone curve → JPEG; Ramanath et al., "Color image processing pipeline", IEEE Signal Processing
// Magazine 22(1), 34 (2005)).
#include "petroscope/core/image.hpp"
#include "petroscope/microscope/thin_section.hpp"
#include "petroscope/spectral/color.hpp"

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

namespace petroscope::testing {

struct ColourCamera {
    double exposure = 1.0;                                     // on the linear display values
    Eigen::Vector3d white_balance{1.0, 1.0, 1.0};              // what the auto white balance left, per channel
    Eigen::Matrix3d colour_matrix = Eigen::Matrix3d::Identity();  // the sensor's colours unlike the observer's; rows sum to 1
    double look_steepness = 0.0;  // the S curve's logistic steepness k after the sRGB curve (0: none)
    Eigen::Vector2d light_centre_px{0.0, 0.0};
    double light_falloff = 0.0;  // illumination 1 − falloff·(r / frame width)² about light_centre_px
    // The sensor's noise: shot noise of a well holding `full_well_electrons` at full scale and read noise, in
    // electrons rms (about 2 code levels rms at mid-grey with these values), then a 12-bit raw value.
    double full_well_electrons = 4000.0;
    double read_noise_electrons = 2.0;
    int jpeg_quality = 75;  // 0: no JPEG

    /// A random camera of the kind a petrographer's is: white balance within ±15%, a colour matrix with
    /// off-diagonal terms within ±4%, a look curve of steepness 0 … 4, exposure 0.8 … 1.05, the light 0 … 25%
    /// darker at the frame's edge than at its centre, which lies anywhere within the frame's middle half.
    static ColourCamera random(std::mt19937_64& rng, int width_px, int height_px) {
        ColourCamera camera;
        camera.exposure = 0.8 + 0.25 * uniform_unit_interval(rng);
        for (int c = 0; c < 3; ++c) camera.white_balance[c] = 0.85 + 0.3 * uniform_unit_interval(rng);
        for (int r = 0; r < 3; ++r) {
            for (int c = 0; c < 3; ++c) {
                if (r != c) camera.colour_matrix(r, c) = -0.04 + 0.08 * uniform_unit_interval(rng);
            }
            camera.colour_matrix(r, r) = 1.0 - (camera.colour_matrix.row(r).sum() - camera.colour_matrix(r, r));
        }
        camera.look_steepness = 4.0 * uniform_unit_interval(rng);
        camera.light_centre_px = {width_px * (0.25 + 0.5 * uniform_unit_interval(rng)), height_px * (0.25 + 0.5 * uniform_unit_interval(rng))};
        camera.light_falloff = 0.25 * uniform_unit_interval(rng);
        return camera;
    }

    /// The look curve: a logistic S of steepness k through (0, 0), (½, ½) and (1, 1); the identity at k = 0.
    double look(double code) const {
        if (look_steepness < 1e-6) return code;
        const auto logistic = [this](double x) { return 1.0 / (1.0 + std::exp(-look_steepness * (x - 0.5))); };
        return (logistic(code) - logistic(0.0)) / (logistic(1.0) - logistic(0.0));
    }

    /// The photo (camera values 0 … 1, 3 channels) of linear display RGB (CV_64FC3, channels R, G, B); the
    /// JPEG file's bytes to `jpeg_file` when given.
    Image photograph(const cv::Mat& linear, unsigned seed, std::vector<std::uint8_t>* jpeg_file = nullptr) const {
        std::mt19937 random(seed);
        std::normal_distribution<double> unit_noise(0.0, 1.0);
        constexpr double kRawFullScale = 4095.0;  // a 12-bit raw file
        // The sensor: one colour per pixel, RGGB (R at even rows and columns), shot and read noise.
        cv::Mat raw(linear.rows, linear.cols, CV_16UC1);
        for (int y = 0; y < linear.rows; ++y) {
            for (int x = 0; x < linear.cols; ++x) {
                const cv::Vec3d& pixel = linear.at<cv::Vec3d>(y, x);
                const double light = 1.0 - light_falloff * (Eigen::Vector2d(x + 0.5, y + 0.5) - light_centre_px).squaredNorm() /
                                               (static_cast<double>(linear.cols) * linear.cols);
                const Eigen::Vector3d rgb = colour_matrix * white_balance.cwiseProduct(exposure * light * Eigen::Vector3d(pixel[0], pixel[1], pixel[2]));
                const int channel = (y % 2 == 0 && x % 2 == 0) ? 0 : (y % 2 == 1 && x % 2 == 1) ? 2 : 1;
                const double electrons = std::clamp(rgb[channel], 0.0, 1.0) * full_well_electrons;
                const double noisy = electrons + std::sqrt(electrons + read_noise_electrons * read_noise_electrons) * unit_noise(random);
                raw.at<std::uint16_t>(y, x) = static_cast<std::uint16_t>(std::lround(std::clamp(noisy / full_well_electrons, 0.0, 1.0) * kRawFullScale));
            }
        }
        cv::Mat demosaiced;
        cv::cvtColor(raw, demosaiced, cv::COLOR_BayerBG2BGR);  // bilinear; OpenCV names the RGGB layout above "BG"
        cv::Mat bgr(linear.rows, linear.cols, CV_8UC3);
        for (int y = 0; y < linear.rows; ++y) {
            for (int x = 0; x < linear.cols; ++x) {
                for (int c = 0; c < 3; ++c) {
                    const double code = look(encode_srgb(demosaiced.at<cv::Vec3w>(y, x)[c] / kRawFullScale));
                    bgr.at<cv::Vec3b>(y, x)[c] = static_cast<unsigned char>(std::lround(std::clamp(code, 0.0, 1.0) * 255.0));
                }
            }
        }
        if (jpeg_quality > 0) {
            std::vector<unsigned char> bytes;
            cv::imencode(".jpg", bgr, bytes, {cv::IMWRITE_JPEG_QUALITY, jpeg_quality});
            bgr = cv::imdecode(bytes, cv::IMREAD_COLOR);
            if (jpeg_file != nullptr) *jpeg_file = std::move(bytes);
        }
        Image photo(linear.cols, linear.rows, 3);
        for (int y = 0; y < linear.rows; ++y) {
            for (int x = 0; x < linear.cols; ++x) {
                for (int c = 0; c < 3; ++c) photo.at(x, y, c) = static_cast<float>(bgr.at<cv::Vec3b>(y, x)[2 - c] / 255.0);
            }
        }
        return photo;
    }
};

}  // namespace petroscope::testing
