// The sweep's GIF encoder, decoded by an independent reader (OpenImageIO's GIF plugin, giflib): every frame
// comes back as the palette image that was encoded, across LZW table resets.
#include "animation_writer.hpp"

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <random>

namespace petroscope {
namespace {

std::filesystem::path scratch_file(const std::string& name) {
    std::filesystem::create_directories(PETROSCOPE_TEST_OUTPUT_DIR);
    return std::filesystem::path(PETROSCOPE_TEST_OUTPUT_DIR) / name;
}

// A colourful frame: a smooth gradient with noise in one corner (so the LZW table fills and restarts).
cv::Mat test_frame(int width, int height, unsigned seed) {
    std::mt19937 random(seed);
    cv::Mat image(height, width, CV_8UC3);
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            const bool noisy = x < width / 2 && y < height / 2;
            image.at<cv::Vec3b>(y, x) = noisy ? cv::Vec3b(static_cast<uchar>(random()), static_cast<uchar>(random()), static_cast<uchar>(random()))
                                              : cv::Vec3b(static_cast<uchar>(255 * x / width), static_cast<uchar>(255 * y / height),
                                                          static_cast<uchar>((seed * 40 + x + y) % 256));
        }
    }
    return image;
}

TEST(GifAnimation, DecodesToTheEncodedPaletteImagesFrameByFrame) {
    const int width = 150, height = 97;
    const std::vector<cv::Mat> frames{test_frame(width, height, 1), test_frame(width, height, 2), test_frame(width, height, 3)};
    const std::filesystem::path path = scratch_file("animation-test.gif");
    AnimationWriter writer(path, "gif", 10.0, width, height);
    for (const cv::Mat& frame : frames) writer.add(frame, writer.prepare(frame));
    writer.finish();

    auto input = OIIO::ImageInput::open(path.string());
    ASSERT_TRUE(input) << OIIO::geterror();
    int subimage = 0;
    for (; input->seek_subimage(subimage, 0); ++subimage) {
        ASSERT_LT(subimage, 3);
        const OIIO::ImageSpec& spec = input->spec();
        ASSERT_EQ(spec.width, width);
        ASSERT_EQ(spec.height, height);
        std::vector<unsigned char> decoded(static_cast<std::size_t>(width) * height * spec.nchannels);
        ASSERT_TRUE(input->read_image(subimage, 0, 0, -1, OIIO::TypeDesc::UINT8, decoded.data()));
        const PalettedImage expected = median_cut_palette(frames[static_cast<std::size_t>(subimage)]);
        int mismatches = 0;
        for (std::size_t pixel = 0; pixel < expected.indices.size(); ++pixel) {
            for (std::size_t c = 0; c < 3; ++c) {
                mismatches += decoded[pixel * spec.nchannels + c] != expected.palette_rgb[3 * expected.indices[pixel] + c];
            }
        }
        EXPECT_EQ(mismatches, 0) << "frame " << subimage;
    }
    EXPECT_EQ(subimage, 3);
}

TEST(GifAnimation, PaletteKeepsAnImageOfFewColoursExactly) {
    // Up to 256 colours in distinct 5-bit bins are reproduced exactly.
    cv::Mat image(64, 64, CV_8UC3);
    for (int y = 0; y < 64; ++y) {
        for (int x = 0; x < 64; ++x) {
            const int colour = (y / 4) * 16 + x / 4;  // 256 colours
            image.at<cv::Vec3b>(y, x) = cv::Vec3b(static_cast<uchar>(8 * (colour % 8)), static_cast<uchar>(8 * ((colour / 8) % 8) + 64),
                                                  static_cast<uchar>(8 * (colour / 64) + 128));
        }
    }
    const PalettedImage paletted = median_cut_palette(image);
    for (int y = 0; y < 64; ++y) {
        for (int x = 0; x < 64; ++x) {
            const std::size_t index = paletted.indices[static_cast<std::size_t>(y) * 64 + x];
            for (int c = 0; c < 3; ++c) ASSERT_EQ(paletted.palette_rgb[3 * index + c], image.at<cv::Vec3b>(y, x)[2 - c]) << x << "," << y;
        }
    }
}

TEST(GifAnimation, RejectsAnUnknownFormatAndARateOutOfRange) {
    EXPECT_ANY_THROW(AnimationWriter(scratch_file("a.avi"), "avi", 10.0, 8, 8));
    EXPECT_ANY_THROW(AnimationWriter(scratch_file("a.gif"), "gif", 0.0, 8, 8));
}

}  // namespace
}  // namespace petroscope
