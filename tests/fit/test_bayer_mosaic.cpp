// The Bayer sensor's check of the conoscope fit (bayer_mosaic.hpp): an RGGB mosaic demosaiced bilinearly on the raw
// (linear) values, against OpenCV's own bilinear demosaicing and against what a mosaic must leave unchanged.
#include "bayer_mosaic.hpp"

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include <cmath>
#include <cstdint>
#include <random>

namespace petroscope {
namespace {

Image random_image(int width, int height, unsigned seed) {
    std::mt19937 random(seed);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    Image image(width, height, 3);
    for (float& value : image.pixels) value = unit(random);
    return image;
}

// Each pixel's own channel of the RGGB mosaic (red at even rows and columns, blue at odd ones).
int measured_channel(int x, int y) { return (x % 2 == 0 && y % 2 == 0) ? 0 : (x % 2 == 1 && y % 2 == 1) ? 2 : 1; }

TEST(BayerMosaic, AgreesWithOpenCvsBilinearDemosaicingAwayFromTheEdges) {
    // Linear values (black 0, γ 1) on the 16-bit raw's codes, so that both see the same numbers.
    Image linear = random_image(20, 14, 3);
    for (float& value : linear.pixels) value = std::round(value * 65535.0f) / 65535.0f;
    cv::Mat raw(linear.height, linear.width, CV_16UC1);
    for (int y = 0; y < linear.height; ++y) {
        for (int x = 0; x < linear.width; ++x) raw.at<std::uint16_t>(y, x) = static_cast<std::uint16_t>(std::lround(linear.at(x, y, measured_channel(x, y)) * 65535.0f));
    }
    cv::Mat opencv;
    cv::cvtColor(raw, opencv, cv::COLOR_BayerBG2BGR);  // OpenCV names this layout (R at the even rows and columns) "BG"
    const Image ours = detail::through_bayer_mosaic(linear, 0.0, 1.0);
    // OpenCV fills its one-pixel border by copying its neighbours; inside it, both interpolate bilinearly.
    for (int y = 1; y < linear.height - 1; ++y) {
        for (int x = 1; x < linear.width - 1; ++x) {
            for (int c = 0; c < 3; ++c) {
                EXPECT_NEAR(ours.at(x, y, c), opencv.at<cv::Vec3w>(y, x)[2 - c] / 65535.0, 0.51 / 65535.0) << "pixel (" << x << ", " << y << "), channel " << c;
            }
        }
    }
}

TEST(BayerMosaic, KeepsAnEvenFieldAndEveryPixelsOwnChannelThroughTheCamerasCurve) {
    constexpr double kBlack = 0.02, kGamma = 2.2;
    Image even(9, 7, 3);
    for (int y = 0; y < even.height; ++y) {
        for (int x = 0; x < even.width; ++x) {
            for (int c = 0; c < 3; ++c) even.at(x, y, c) = static_cast<float>(0.3 + 0.2 * c);
        }
    }
    const Image even_out = detail::through_bayer_mosaic(even, kBlack, kGamma);
    for (std::size_t k = 0; k < even.pixels.size(); ++k) EXPECT_NEAR(even_out.pixels[k], even.pixels[k], 1e-6);

    Image photo = random_image(9, 7, 5);
    for (float& value : photo.pixels) value = static_cast<float>(kBlack + (1.0 - kBlack) * value);
    const Image out = detail::through_bayer_mosaic(photo, kBlack, kGamma);
    double changed = 0.0;
    for (int y = 0; y < photo.height; ++y) {
        for (int x = 0; x < photo.width; ++x) {
            const int own = measured_channel(x, y);
            EXPECT_NEAR(out.at(x, y, own), photo.at(x, y, own), 1e-6) << "pixel (" << x << ", " << y << ")";
            for (int c = 0; c < 3; ++c) changed += std::abs(out.at(x, y, c) - photo.at(x, y, c));
        }
    }
    EXPECT_GT(changed, 1.0);  // the other two channels are interpolated, not copied through
}

}  // namespace
}  // namespace petroscope
