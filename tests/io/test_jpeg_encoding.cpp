// Reading how a JPEG was encoded from its quantization tables and frame header, and repeating that
// encoding: files written by libjpeg (through OpenCV) at known settings must be read back exactly, and
// encode_like_jpeg must then reproduce the file's decoded pixels bit for bit.
#include "petroscope/core/error.hpp"
#include "petroscope/io/jpeg_encoding.hpp"

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include <cmath>
#include <cstdint>
#include <vector>

namespace petroscope {
namespace {

/// A colourful 8-bit test card (BGR): smooth gradients and sharp edges, so that both subsampling and
/// quantization change it.
cv::Mat test_card(int width, int height) {
    cv::Mat card(height, width, CV_8UC3);
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            const double r = std::hypot(x - 0.4 * width, y - 0.6 * height);
            card.at<cv::Vec3b>(y, x) = cv::Vec3b(static_cast<std::uint8_t>(127.5 + 127.0 * std::cos(0.21 * r)),
                                                 static_cast<std::uint8_t>((x * 255) / width),
                                                 static_cast<std::uint8_t>(((x / 7 + y / 5) % 2) * 200 + 20));
        }
    }
    return card;
}

std::vector<std::uint8_t> encode(const cv::Mat& image, const std::vector<int>& parameters) {
    std::vector<std::uint8_t> bytes;
    EXPECT_TRUE(cv::imencode(".jpg", image, bytes, parameters));
    return bytes;
}

Image to_camera_values(const cv::Mat& bgr) {
    Image image(bgr.cols, bgr.rows, 3);
    for (int y = 0; y < bgr.rows; ++y) {
        for (int x = 0; x < bgr.cols; ++x) {
            for (int c = 0; c < 3; ++c) image.at(x, y, c) = static_cast<float>(bgr.at<cv::Vec3b>(y, x)[2 - c] / 255.0);
        }
    }
    return image;
}

TEST(JpegEncoding, QualityAndSubsamplingOfLibjpegFilesAreReadExactly) {
    const cv::Mat card = test_card(64, 48);
    for (const int quality : {10, 50, 75, 85, 95, 100}) {
        const std::optional<JpegEncoding> encoding = jpeg_encoding_of(encode(card, {cv::IMWRITE_JPEG_QUALITY, quality}), "card.jpg");
        ASSERT_TRUE(encoding.has_value());
        EXPECT_EQ(encoding->luma_quality, quality);
        EXPECT_EQ(encoding->chroma_quality, quality);
        EXPECT_TRUE(encoding->standard_tables);
        EXPECT_EQ(encoding->components, 3);
        EXPECT_EQ(encoding->chroma_step_x, 2);
        EXPECT_EQ(encoding->chroma_step_y, 2);
        EXPECT_TRUE(reproducible(*encoding));
        EXPECT_EQ(describe(*encoding), "quality " + std::to_string(quality) + ", 4:2:0");
    }
    // Grayscale.
    cv::Mat grey;
    cv::extractChannel(card, grey, 1);
    const std::optional<JpegEncoding> mono = jpeg_encoding_of(encode(grey, {cv::IMWRITE_JPEG_QUALITY, 60}), "grey.jpg");
    ASSERT_TRUE(mono.has_value());
    EXPECT_EQ(mono->components, 1);
    EXPECT_EQ(mono->luma_quality, 60);
    EXPECT_EQ(describe(*mono), "quality 60, grayscale");
    // A file with tables of its own (a camera's): the nearest quality, marked as such, and not
    // reproducible. Scale every entry of the quality-80 tables by 1.1 in place.
    std::vector<std::uint8_t> own = encode(card, {cv::IMWRITE_JPEG_QUALITY, 80});
    std::size_t dqt = 2;
    while (!(own[dqt] == 0xFF && own[dqt + 1] == 0xDB)) ++dqt;
    const std::size_t length = (std::size_t{own[dqt + 2]} << 8) | own[dqt + 3];
    for (std::size_t i = dqt + 4; i < dqt + 2 + length; i += 65) {
        for (std::size_t k = 1; k <= 64; ++k) own[i + k] = static_cast<std::uint8_t>(std::min(255.0, std::round(own[i + k] * 1.1)));
    }
    const std::optional<JpegEncoding> camera = jpeg_encoding_of(own, "camera.jpg");
    ASSERT_TRUE(camera.has_value());
    EXPECT_FALSE(camera->standard_tables);
    EXPECT_FALSE(reproducible(*camera));
    EXPECT_NEAR(camera->luma_quality, 78, 1);  // the scale factor 40 becomes 44: quality 78
    EXPECT_NE(describe(*camera).find("nearest IJG quality"), std::string::npos);
}

TEST(JpegEncoding, RepeatingTheEncodingReproducesTheFileBitForBit) {
    const cv::Mat card = test_card(61, 45);  // not a multiple of the 16-pixel MCU
    for (const std::vector<int>& parameters : std::vector<std::vector<int>>{
             {cv::IMWRITE_JPEG_QUALITY, 85},
             {cv::IMWRITE_JPEG_QUALITY, 40},
             {cv::IMWRITE_JPEG_QUALITY, 100}}) {
        const std::vector<std::uint8_t> file = encode(card, parameters);
        const cv::Mat decoded = cv::imdecode(file, cv::IMREAD_COLOR);
        const JpegEncoding encoding = jpeg_encoding_of(file, "card.jpg").value();
        const Image repeated = encode_like_jpeg(to_camera_values(card), encoding);
        const Image expected = to_camera_values(decoded);
        ASSERT_EQ(repeated.pixels.size(), expected.pixels.size());
        int differing = 0, changed = 0;
        const Image original = to_camera_values(card);
        for (std::size_t k = 0; k < expected.pixels.size(); ++k) {
            differing += repeated.pixels[k] != expected.pixels[k];
            changed += original.pixels[k] != expected.pixels[k];
        }
        EXPECT_EQ(differing, 0) << describe(encoding);
        EXPECT_GT(changed, static_cast<int>(expected.pixels.size() / 4)) << "the encoding should change the card";
    }
}

TEST(JpegEncoding, OtherFilesAndBrokenJpegs) {
    // Not a JPEG: no encoding, no error.
    std::vector<std::uint8_t> png;
    ASSERT_TRUE(cv::imencode(".png", test_card(16, 16), png));
    EXPECT_FALSE(jpeg_encoding_of(png, "card.png").has_value());
    EXPECT_FALSE(jpeg_encoding_of({}, "empty").has_value());
    // A JPEG cut short before its frame header, and one with a truncated segment: InputError naming it.
    const std::vector<std::uint8_t> file = encode(test_card(32, 32), {cv::IMWRITE_JPEG_QUALITY, 85});
    const auto message_of = [](const std::vector<std::uint8_t>& bytes) {
        try {
            (void)jpeg_encoding_of(bytes, "broken.jpg");
        } catch (const InputError& error) {
            return std::string(error.what());
        }
        return std::string("no error");
    };
    EXPECT_NE(message_of({0xFF, 0xD8}).find("broken.jpg: not a readable JPEG: no frame header"), std::string::npos);
    std::size_t dqt = 2;
    while (!(file[dqt] == 0xFF && file[dqt + 1] == 0xDB)) ++dqt;
    EXPECT_NE(message_of(std::vector<std::uint8_t>(file.begin(), file.begin() + static_cast<std::ptrdiff_t>(dqt) + 20)).find("truncated"),
              std::string::npos);
    std::vector<std::uint8_t> no_table = file;
    no_table[dqt + 1] = 0xFE;  // the DQT segment becomes a comment: the tables are missing
    EXPECT_NE(message_of(no_table).find("quantization table is missing"), std::string::npos);
    EXPECT_THROW((void)read_jpeg_encoding("/nonexistent/photo.jpg"), InputError);
}

}  // namespace
}  // namespace petroscope
