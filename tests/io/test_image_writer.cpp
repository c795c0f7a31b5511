// PNG output: every linear value is written as the 8-bit code of the sRGB curve, round(255·encode(v)).
// Photo input: 16-bit PNG and TIFF (cameras and raw converters write them) read as code / 65535.
#include "petroscope/io/image_writer.hpp"
#include "petroscope/spectral/color.hpp"

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <random>

namespace petroscope {
namespace {

TEST(PngWriter, WritesTheSrgbCodeOfEveryValue) {
    // Values on both sides of every code boundary, random values, and the ends (clamped).
    std::vector<float> values{-1.0f, 0.0f, 1.0f, 2.0f, 1e-7f};
    for (int code = 0; code < 256; ++code) {
        const double target = (code + 0.5) / 255.0;
        // Invert the curve near the boundary, then step a few floats either way.
        const double linear = target <= 0.04045 ? target / 12.92 : std::pow((target + 0.055) / 1.055, 2.4);
        float value = static_cast<float>(linear);
        for (int k = 0; k < 4; ++k) value = std::nextafter(value, -1.0f);
        for (int k = 0; k < 9; ++k, value = std::nextafter(value, 2.0f)) values.push_back(value);
    }
    std::mt19937 random(7);
    std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
    while (values.size() % 3 != 0 || values.size() < 30000) values.push_back(uniform(random));
    const int pixels = static_cast<int>(values.size() / 3);
    Image image(pixels, 1, 3);
    image.pixels = values;
    const std::filesystem::path path = std::filesystem::path(PETROSCOPE_TEST_OUTPUT_DIR) / "srgb-codes.png";
    std::filesystem::create_directories(path.parent_path());
    write_image(image, path, ImageFormat::png);
    const Image read = read_image(path);
    ASSERT_EQ(read.pixels.size(), values.size());
    int mismatches = 0;
    for (std::size_t i = 0; i < values.size(); ++i) {
        const double clamped = std::clamp(static_cast<double>(values[i]), 0.0, 1.0);
        const long expected = std::lround(255.0 * encode_srgb(clamped));
        mismatches += std::lround(255.0 * read.pixels[i]) != expected;
    }
    EXPECT_EQ(mismatches, 0);
}

TEST(ImageReader, ReadsSixteenBitPhotosAsCodeOver65535) {
    std::vector<std::uint16_t> codes;
    for (int i = 0; i < 4 * 3 * 3; ++i) codes.push_back(static_cast<std::uint16_t>((i * 2731 + 17) % 65536));
    codes[0] = 0;
    codes[1] = 65535;
    for (const char* name : {"sixteen.tif", "sixteen.png"}) {
        const std::filesystem::path path = std::filesystem::path(PETROSCOPE_TEST_OUTPUT_DIR) / name;
        std::filesystem::create_directories(path.parent_path());
        auto output = OIIO::ImageOutput::create(path.string());
        ASSERT_TRUE(output) << name;
        ASSERT_TRUE(output->open(path.string(), OIIO::ImageSpec(4, 3, 3, OIIO::TypeDesc::UINT16)));
        ASSERT_TRUE(output->write_image(OIIO::TypeDesc::UINT16, codes.data()));
        ASSERT_TRUE(output->close());
        const Image image = read_image(path);
        ASSERT_EQ(image.width, 4);
        ASSERT_EQ(image.height, 3);
        ASSERT_EQ(image.channels, 3);
        for (std::size_t i = 0; i < codes.size(); ++i) EXPECT_FLOAT_EQ(image.pixels[i], static_cast<float>(codes[i] / 65535.0)) << name << " value " << i;
    }
}

}  // namespace
}  // namespace petroscope
