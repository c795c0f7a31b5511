// The image file codecs (src/io/image_files): exact round trips through our writers and reader, and both
// checked against OpenImageIO, an independent implementation of the same formats: it decodes what we write,
// and we decode what it (or libpng's own API, for layouts neither writer produces) writes.
#include "image_files.hpp"
#include "petroscope/core/error.hpp"
#include "petroscope/io/label_image.hpp"

#include <Imath/half.h>
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <png.h>
#include <tiffio.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <random>
#include <string>
#include <vector>

namespace petroscope {
namespace {

std::filesystem::path codec_test_file(const std::string& name) {
    const std::filesystem::path path = std::filesystem::path(PETROSCOPE_TEST_OUTPUT_DIR) / "image-files" / name;
    std::filesystem::create_directories(path.parent_path());
    return path;
}

// Codes that differ between neighbouring samples, with 0 and the maximum among them.
template <typename Code>
std::vector<Code> codec_test_codes(std::size_t count) {
    const std::uint64_t top = std::numeric_limits<Code>::max();
    std::vector<Code> codes(count);
    for (std::size_t i = 0; i < count; ++i) codes[i] = static_cast<Code>((i * 2654435761u + 12345u) % (top + 1));
    codes.front() = 0;
    codes.back() = static_cast<Code>(top);
    return codes;
}

// Floats of every magnitude and sign: random ones, zeros, a subnormal, the largest.
std::vector<float> codec_test_floats(std::size_t count) {
    std::mt19937 random(11);
    std::uniform_real_distribution<float> exponent(-30.0f, 30.0f);
    std::vector<float> values(count);
    for (std::size_t i = 0; i < count; ++i) values[i] = (i % 2 ? -1.0f : 1.0f) * std::exp(exponent(random));
    values[0] = 0.0f;
    values[1] = -0.0f;
    values[2] = 1e-40f;
    values[3] = std::numeric_limits<float>::max();
    return values;
}

template <typename Code>
std::vector<float> codes_over_max(const std::vector<Code>& codes) {
    std::vector<float> values;
    for (const Code code : codes) values.push_back(static_cast<float>(code / static_cast<double>(std::numeric_limits<Code>::max())));
    return values;
}

// The file as OpenImageIO decodes it, its samples converted to `type` (integers are codes, not rescaled,
// when `type` is the file's own).
template <typename Sample>
std::vector<Sample> reference_samples(const std::filesystem::path& path, OIIO::TypeDesc type, OIIO::ImageSpec& spec) {
    auto input = OIIO::ImageInput::open(path.string());
    if (!input) {
        ADD_FAILURE() << "OpenImageIO cannot open " << path << ": " << OIIO::geterror();
        return {};
    }
    spec = input->spec();
    std::vector<Sample> samples(spec.image_pixels() * static_cast<std::size_t>(spec.nchannels));
    EXPECT_TRUE(input->read_image(0, 0, 0, spec.nchannels, type, samples.data())) << input->geterror();
    return samples;
}

template <typename Sample>
void write_with_reference(const std::filesystem::path& path, OIIO::ImageSpec spec, const std::vector<Sample>& samples) {
    auto output = OIIO::ImageOutput::create(path.string());
    ASSERT_TRUE(output) << path;
    ASSERT_TRUE(output->open(path.string(), spec)) << output->geterror();
    ASSERT_TRUE(output->write_image(spec.format, samples.data())) << output->geterror();
    ASSERT_TRUE(output->close());
}

void expect_shape(const DecodedImage& image, int width, int height, int channels, SampleType stored, int bits) {
    EXPECT_EQ(image.width, width);
    EXPECT_EQ(image.height, height);
    EXPECT_EQ(image.channels, channels);
    EXPECT_EQ(image.stored, stored) << sample_type_name(image.stored);
    EXPECT_EQ(image.bits_per_sample, bits);
}

std::string codec_error(const std::function<void()>& action) {
    try {
        action();
    } catch (const InputError& error) {
        return error.what();
    }
    return "(no error)";
}

// Whether `action` throws an InputError whose message contains `part`.
::testing::AssertionResult fails_with(const std::function<void()>& action, const std::string& part) {
    const std::string error = codec_error(action);
    if (error.find(part) != std::string::npos) return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure() << "'" << part << "' not in: " << error;
}

// Writes codes of `Sample` as a width × height PNG, reads it back with ours and with OpenImageIO (whose spec
// is left in `spec`), and checks both give the codes.
template <typename Sample>
void expect_png_round_trip(const std::string& name, int width, int height, int channels, bool srgb, OIIO::ImageSpec& spec) {
    constexpr int bits = 8 * sizeof(Sample);
    const std::size_t count = static_cast<std::size_t>(width * height * channels);
    const auto codes = codec_test_codes<Sample>(count);
    const auto path = codec_test_file(name + "-" + std::to_string(channels) + ".png");
    write_png(path, width, height, channels, bits, codes.data(), srgb);
    const DecodedImage read = read_image_file(path);
    expect_shape(read, width, height, channels, bits == 8 ? SampleType::uint8 : SampleType::uint16, bits);
    EXPECT_EQ(read.values, codes_over_max(codes));
    EXPECT_EQ(reference_samples<Sample>(path, bits == 8 ? OIIO::TypeDesc::UINT8 : OIIO::TypeDesc::UINT16, spec), codes);
}

TEST(ImageFiles, PngRoundTripsEightAndSixteenBitCodesThatOpenImageIoReadsAlike) {
    for (const int channels : {1, 3}) {
        OIIO::ImageSpec spec;
        expect_png_round_trip<std::uint8_t>("eight", 7, 5, channels, true, spec);
        EXPECT_EQ(spec.get_string_attribute("Software"), "petroscope");
        EXPECT_EQ(spec.get_string_attribute("oiio:ColorSpace"), "sRGB");
        expect_png_round_trip<std::uint16_t>("sixteen", 7, 5, channels, false, spec);
    }
}

using FloatWriter = void (*)(const std::filesystem::path&, int, int, int, const float*);

// Writes `values` with `write` to `name`, reads it back with ours and with OpenImageIO (spec left in
// `spec`), and checks both give the floats bit for bit.
void expect_float_round_trip(FloatWriter write, const std::string& name, int width, int height, int channels, const std::vector<float>& values,
                             OIIO::ImageSpec& spec) {
    const auto path = codec_test_file(name);
    write(path, width, height, channels, values.data());
    const DecodedImage read = read_image_file(path);
    expect_shape(read, width, height, channels, SampleType::float32, 32);
    EXPECT_EQ(read.values, values);
    EXPECT_EQ(reference_samples<float>(path, OIIO::TypeDesc::FLOAT, spec), values);
    EXPECT_EQ(spec.get_string_attribute("compression"), "zip");
}

TEST(ImageFiles, FloatTiffAndExrRoundTripExactlyAndOpenImageIoReadsTheSameFloats) {
    const int width = 7, height = 5;
    for (const int channels : {1, 3}) {
        const std::vector<float> values = codec_test_floats(static_cast<std::size_t>(width * height * channels));
        OIIO::ImageSpec spec;
        expect_float_round_trip(write_tiff_float32, "float-" + std::to_string(channels) + ".tif", width, height, channels, values, spec);
        EXPECT_EQ(spec.format, OIIO::TypeDesc::FLOAT);
        EXPECT_EQ(spec.get_string_attribute("Software"), "petroscope");
        expect_float_round_trip(write_exr_float32, "float-" + std::to_string(channels) + ".exr", width, height, channels, values, spec);
        const std::vector<std::string> names = channels == 1 ? std::vector<std::string>{"Y"} : std::vector<std::string>{"R", "G", "B"};
        EXPECT_EQ(spec.channelnames, names);
    }
}

TEST(ImageFiles, ReadsSixteenBitPngAndTiffsInStripsTilesAndPlanesAsOpenImageIoWroteThem) {
    const int width = 37, height = 21;  // partial tiles at the right and bottom
    const auto codes = codec_test_codes<std::uint16_t>(static_cast<std::size_t>(width * height * 3));
    OIIO::ImageSpec plain(width, height, 3, OIIO::TypeDesc::UINT16);
    OIIO::ImageSpec tiled = plain;
    tiled.tile_width = 16;
    tiled.tile_height = 16;
    OIIO::ImageSpec planes = plain;
    planes.attribute("tiff:planarconfig", "separate");
    OIIO::ImageSpec tiled_planes = tiled;
    tiled_planes.attribute("tiff:planarconfig", "separate");
    const std::vector<std::pair<std::string, OIIO::ImageSpec>> cases{{"sixteen.png", plain},
                                                                     {"sixteen-strips.tif", plain},
                                                                     {"sixteen-tiles.tif", tiled},
                                                                     {"sixteen-planes.tif", planes},
                                                                     {"sixteen-tiled-planes.tif", tiled_planes}};
    for (const auto& [name, spec] : cases) {
        const auto path = codec_test_file(name);
        write_with_reference(path, spec, codes);
        OIIO::ImageSpec written;
        EXPECT_EQ(reference_samples<std::uint16_t>(path, OIIO::TypeDesc::UINT16, written), codes) << name;
        if (name.ends_with(".tif")) {
            EXPECT_EQ(written.tile_width, spec.tile_width) << name;
            EXPECT_EQ(written.get_int_attribute("tiff:PlanarConfiguration"), name.find("planes") != std::string::npos ? 2 : 1) << name;
        }
        const DecodedImage image = read_image_file(path);
        expect_shape(image, width, height, 3, SampleType::uint16, 16);
        EXPECT_EQ(image.values, codes_over_max(codes)) << name;
    }
}

// A one-strip, uncompressed TIFF written with libtiff's own API, for layouts OpenImageIO does not write.
void write_with_libtiff(const std::filesystem::path& path, int width, int height, int bits, int sample_format, int photometric,
                        const void* samples) {
    TIFF* tiff = TIFFOpen(path.c_str(), "w");
    ASSERT_NE(tiff, nullptr);
    TIFFSetField(tiff, TIFFTAG_IMAGEWIDTH, static_cast<std::uint32_t>(width));
    TIFFSetField(tiff, TIFFTAG_IMAGELENGTH, static_cast<std::uint32_t>(height));
    TIFFSetField(tiff, TIFFTAG_SAMPLESPERPIXEL, 1);
    TIFFSetField(tiff, TIFFTAG_BITSPERSAMPLE, bits);
    TIFFSetField(tiff, TIFFTAG_SAMPLEFORMAT, sample_format);
    TIFFSetField(tiff, TIFFTAG_PHOTOMETRIC, photometric);
    TIFFSetField(tiff, TIFFTAG_ROWSPERSTRIP, static_cast<std::uint32_t>(height));
    const tmsize_t bytes = static_cast<tmsize_t>(width) * height * bits / 8;
    EXPECT_EQ(TIFFWriteEncodedStrip(tiff, 0, const_cast<void*>(samples), bytes), bytes);
    TIFFClose(tiff);
}

TEST(ImageFiles, ReadsHalfAndDoubleFloats) {
    const int width = 7, height = 5;
    const std::size_t count = static_cast<std::size_t>(width * height);
    std::vector<float> expected(count);
    for (std::size_t i = 0; i < count; ++i) expected[i] = static_cast<float>(i) * 0.375f - 4.0f;  // exact in half
    const std::vector<Imath::half> halves(expected.begin(), expected.end());
    const auto exr_path = codec_test_file("half.exr");
    write_with_reference(exr_path, OIIO::ImageSpec(width, height, 1, OIIO::TypeDesc::HALF), halves);
    const auto tiff_path = codec_test_file("half.tif");  // OpenImageIO writes half TIFFs as 32-bit floats
    write_with_libtiff(tiff_path, width, height, 16, SAMPLEFORMAT_IEEEFP, PHOTOMETRIC_MINISBLACK, halves.data());
    for (const auto& path : {exr_path, tiff_path}) {
        const DecodedImage image = read_image_file(path);
        expect_shape(image, width, height, 1, SampleType::half, 16);
        EXPECT_EQ(image.values, expected) << path;
    }
    const auto double_path = codec_test_file("double.tif");
    const std::vector<double> doubles(expected.begin(), expected.end());
    write_with_reference(double_path, OIIO::ImageSpec(width, height, 1, OIIO::TypeDesc::DOUBLE), doubles);
    const DecodedImage image = read_image_file(double_path);
    expect_shape(image, width, height, 1, SampleType::float64, 64);
    EXPECT_EQ(image.values, expected);
}

TEST(ImageFiles, ReadsJpegsAsOpenImageIoDecodesThem) {
    const int width = 23, height = 17;
    for (const int channels : {1, 3}) {
        std::vector<std::uint8_t> codes(static_cast<std::size_t>(width * height * channels));
        for (std::size_t i = 0; i < codes.size(); ++i) codes[i] = static_cast<std::uint8_t>((i * 5) % 256);  // smooth ramps
        const auto path = codec_test_file("eight-" + std::to_string(channels) + ".jpg");
        write_with_reference(path, OIIO::ImageSpec(width, height, channels, OIIO::TypeDesc::UINT8), codes);
        OIIO::ImageSpec spec;
        const auto decoded = reference_samples<std::uint8_t>(path, OIIO::TypeDesc::UINT8, spec);
        const DecodedImage image = read_image_file(path);
        expect_shape(image, width, height, channels, SampleType::uint8, 8);
        EXPECT_EQ(image.values, codes_over_max(decoded));
    }
}

// Rows packed as PNG stores them (§7.2): samples below 8 bits fill each byte from its high bits.
std::vector<png_byte> packed_rows(const std::vector<int>& samples, int width, int height, int bit_depth) {
    const std::size_t row_bytes = (static_cast<std::size_t>(width * bit_depth) + 7) / 8;
    std::vector<png_byte> bytes(row_bytes * static_cast<std::size_t>(height));
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            const int bit = x * bit_depth;
            bytes[static_cast<std::size_t>(y) * row_bytes + static_cast<std::size_t>(bit / 8)] |=
                static_cast<png_byte>(samples[static_cast<std::size_t>(y * width + x)] << (8 - bit_depth - bit % 8));
        }
    }
    return bytes;
}

// A PNG written with libpng's own API (its default error handling: a test failure aborts), for layouts our
// writer does not produce.
void write_with_libpng(const std::filesystem::path& path, int width, int height, int bit_depth, int colour_type, bool interlaced,
                       const std::vector<png_byte>& rows_bytes, const std::vector<png_color>& palette = {}) {
    std::FILE* file = std::fopen(path.c_str(), "wb");
    ASSERT_NE(file, nullptr);
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
    png_infop info = png_create_info_struct(png);
    png_init_io(png, file);
    png_set_IHDR(png, info, static_cast<png_uint_32>(width), static_cast<png_uint_32>(height), bit_depth, colour_type,
                 interlaced ? PNG_INTERLACE_ADAM7 : PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    if (!palette.empty()) png_set_PLTE(png, info, palette.data(), static_cast<int>(palette.size()));
    png_write_info(png, info);
    std::vector<png_bytep> rows;
    const std::size_t row_bytes = rows_bytes.size() / static_cast<std::size_t>(height);
    for (int y = 0; y < height; ++y) rows.push_back(const_cast<png_bytep>(rows_bytes.data()) + static_cast<std::size_t>(y) * row_bytes);
    png_write_image(png, rows.data());
    png_write_end(png, nullptr);
    png_destroy_write_struct(&png, &info);
    std::fclose(file);
}

TEST(ImageFiles, ExpandsPaletteAndLowBitGreyPngsAndDeinterlaces) {
    const int width = 7, height = 5, pixels = width * height;
    // A 4-bit palette image: each index to its colour.
    const std::vector<png_color> palette{{0, 0, 0}, {255, 0, 0}, {10, 200, 30}, {1, 2, 3}, {250, 251, 252}};
    std::vector<int> indices;
    std::vector<float> colours;
    for (int i = 0; i < pixels; ++i) {
        indices.push_back(i % 5);
        const png_color& colour = palette[static_cast<std::size_t>(i % 5)];
        for (const int code : {colour.red, colour.green, colour.blue}) colours.push_back(static_cast<float>(code / 255.0));
    }
    const auto palette_path = codec_test_file("palette.png");
    write_with_libpng(palette_path, width, height, 4, PNG_COLOR_TYPE_PALETTE, false, packed_rows(indices, width, height, 4), palette);
    const DecodedImage palette_image = read_image_file(palette_path);
    expect_shape(palette_image, width, height, 3, SampleType::uint8, 4);
    EXPECT_EQ(palette_image.values, colours);

    // 2-bit grey: codes 0 … 3 expand to 0, 85, 170, 255; the stored depth is still reported.
    std::vector<int> greys;
    std::vector<float> grey_values;
    for (int i = 0; i < pixels; ++i) {
        greys.push_back(i % 4);
        grey_values.push_back(static_cast<float>((i % 4) * 85 / 255.0));
    }
    const auto grey_path = codec_test_file("grey-2bit.png");
    write_with_libpng(grey_path, width, height, 2, PNG_COLOR_TYPE_GRAY, false, packed_rows(greys, width, height, 2));
    const DecodedImage grey = read_image_file(grey_path);
    expect_shape(grey, width, height, 1, SampleType::uint8, 2);
    EXPECT_EQ(grey.values, grey_values);
    EXPECT_TRUE(fails_with([&] { read_label_png(grey_path); }, "has 2 bits per pixel; expected 8 or 16"));

    // Interlaced (Adam7) 16-bit RGB: rows as PNG stores them, big-endian.
    const auto codes = codec_test_codes<std::uint16_t>(static_cast<std::size_t>(pixels * 3));
    std::vector<png_byte> big_endian;
    for (const std::uint16_t code : codes) {
        big_endian.push_back(static_cast<png_byte>(code >> 8));
        big_endian.push_back(static_cast<png_byte>(code & 0xFF));
    }
    const auto interlaced_path = codec_test_file("interlaced.png");
    write_with_libpng(interlaced_path, width, height, 16, PNG_COLOR_TYPE_RGB, true, big_endian);
    const DecodedImage interlaced = read_image_file(interlaced_path);
    expect_shape(interlaced, width, height, 3, SampleType::uint16, 16);
    EXPECT_EQ(interlaced.values, codes_over_max(codes));
    OIIO::ImageSpec spec;
    EXPECT_EQ(reference_samples<std::uint16_t>(interlaced_path, OIIO::TypeDesc::UINT16, spec), codes);
}

TEST(ImageFileErrors, FilesCutShortAreRefusedNamingTheFile) {
    const int width = 64, height = 48;
    std::mt19937 random(3);
    std::vector<std::uint8_t> noise(static_cast<std::size_t>(width * height * 3));
    for (std::uint8_t& code : noise) code = static_cast<std::uint8_t>(random() & 0xFF);
    const std::vector<float> values(noise.begin(), noise.end());
    const OIIO::ImageSpec jpeg_spec(width, height, 3, OIIO::TypeDesc::UINT8);
    const std::vector<std::pair<std::string, std::function<void(const std::filesystem::path&)>>> writers{
        {"cut.png", [&](const std::filesystem::path& path) { write_png(path, width, height, 3, 8, noise.data(), false); }},
        {"cut.tif", [&](const std::filesystem::path& path) { write_tiff_float32(path, width, height, 3, values.data()); }},
        {"cut.exr", [&](const std::filesystem::path& path) { write_exr_float32(path, width, height, 3, values.data()); }},
        {"cut.jpg", [&](const std::filesystem::path& path) { write_with_reference(path, jpeg_spec, noise); }},
    };
    for (const auto& [name, write] : writers) {
        const auto path = codec_test_file(name);
        write(path);
        EXPECT_EQ(read_image_file(path).width, width) << name;
        std::filesystem::resize_file(path, std::filesystem::file_size(path) / 2);
        EXPECT_TRUE(fails_with([&] { read_image_file(path); }, "cannot read image " + path.string() + ": "));
        if (name == "cut.png") {
            EXPECT_TRUE(fails_with([&] { read_image_file(path); }, "the file ends early"));
        }
    }
}

TEST(ImageFileErrors, RefusesWhatIsNoImageOrMissingAndNamesTheTypesItReads) {
    const auto noise_path = codec_test_file("noise.bin");
    {
        std::ofstream file(noise_path, std::ios::binary);
        std::mt19937 random(5);
        for (int i = 0; i < 1000; ++i) file.put(static_cast<char>(random() & 0x7F));
    }
    EXPECT_TRUE(fails_with([&] { read_image_file(noise_path); },
                           "cannot read image " + noise_path.string() + ": it is not a PNG, TIFF, OpenEXR or JPEG image"));

    const auto missing = codec_test_file("missing.png");
    std::filesystem::remove(missing);
    EXPECT_EQ(codec_error([&] { read_image_file(missing, "photo"); }),
              "cannot read photo " + missing.string() + ": No such file or directory");

    const auto empty = codec_test_file("empty.png");
    std::ofstream(empty).close();
    EXPECT_TRUE(fails_with([&] { image_file_type_of(empty); }, "the file is empty"));
}

TEST(ImageFileErrors, WritingIntoAMissingFolderNamesTheFile) {
    const auto folder = codec_test_file("no-such-folder");
    std::filesystem::remove_all(folder);
    const std::vector<float> values(12, 0.5f);
    const std::vector<std::uint8_t> codes(12, 7);
    for (const std::string name : {"a.png", "a.tif", "a.exr"}) {
        const auto path = folder / name;
        const std::string error = codec_error([&] {
            if (name == "a.png") write_png(path, 2, 2, 3, 8, codes.data(), true);
            if (name == "a.tif") write_tiff_float32(path, 2, 2, 3, values.data());
            if (name == "a.exr") write_exr_float32(path, 2, 2, 3, values.data());
        });
        EXPECT_EQ(error.rfind("cannot write " + path.string() + ": ", 0), 0u) << error;
    }
}

// A TIFF header (TIFF 6.0 §2, little-endian) of a width x length image of `samples` 8-bit samples a pixel,
// with no pixel data: min-is-black grey, no compression, one strip of all rows at offset 8.
std::filesystem::path tiff_header_only(const std::string& name, std::uint32_t width, std::uint32_t length, std::uint32_t samples) {
    std::vector<char> bytes{'I', 'I', 42, 0, 8, 0, 0, 0};
    const auto put = [&](std::uint32_t value, int count) {
        for (int k = 0; k < count; ++k) bytes.push_back(static_cast<char>((value >> (8 * k)) & 0xFF));
    };
    // Tag, field type (3 SHORT, 4 LONG), value: width, length, bits, compression, photometric, strip offset,
    // samples per pixel, rows per strip, strip byte count (truncated to 32 bits: never read).
    const std::vector<std::array<std::uint32_t, 3>> entries{{256, 4, width}, {257, 4, length}, {258, 3, 8},
                                                            {259, 3, 1},     {262, 3, samples == 3 ? 2u : 1u}, {273, 4, 8},
                                                            {277, 3, samples}, {278, 4, length}, {279, 4, width * length * samples}};
    put(static_cast<std::uint32_t>(entries.size()), 2);
    for (const auto& [tag, type, value] : entries) {
        put(tag, 2);
        put(type, 2);
        put(1, 4);
        put(value, 4);  // a SHORT (type 3) sits in the first two bytes, little-endian
    }
    put(0, 4);
    const auto path = codec_test_file(name);
    std::ofstream(path, std::ios::binary).write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    return path;
}

TEST(ImageFileErrors, RefusesAbsurdSizesAndLayoutsItDoesNotRead) {
    EXPECT_TRUE(fails_with([] { read_image_file(tiff_header_only("huge.tif", 65536, 40000, 1)); }, "the image is too large (65536 x 40000 x 1 values"));
    // Each side below 2^31, their product with the channels beyond 2^63: refused with a message (libtiff's own,
    // before the size check), not an overflow.
    EXPECT_TRUE(fails_with([] { read_image_file(tiff_header_only("vast.tif", 2147483647, 2147483647, 3)); }, "vast.tif: libtiff: 'Integer overflow'"));

    // One channel is read whatever its name (a thickness map's "Z"); two unknown ones are refused.
    OIIO::ImageSpec depth_spec(3, 2, 1, OIIO::TypeDesc::FLOAT);
    depth_spec.channelnames = {"Z"};
    const auto depth = codec_test_file("depth.exr");
    write_with_reference(depth, depth_spec, std::vector<float>(6, 1.5f));
    const DecodedImage read_depth = read_image_file(depth);
    expect_shape(read_depth, 3, 2, 1, SampleType::float32, 32);
    EXPECT_EQ(read_depth.values, std::vector<float>(6, 1.5f));
    OIIO::ImageSpec pair_spec(3, 2, 2, OIIO::TypeDesc::FLOAT);
    pair_spec.channelnames = {"Z", "W"};
    const auto pair = codec_test_file("pair.exr");
    write_with_reference(pair, pair_spec, std::vector<float>(12, 1.0f));
    EXPECT_TRUE(fails_with([&] { read_image_file(pair); }, "its channels are 'W, Z'; expected R, G, B (and A), Y (and A) or a single channel"));

    const auto signed_path = codec_test_file("signed.tif");
    write_with_reference(signed_path, OIIO::ImageSpec(3, 2, 1, OIIO::TypeDesc::INT16), std::vector<std::int16_t>(6, -3));
    EXPECT_TRUE(fails_with([&] { read_image_file(signed_path); }, "its samples are 16-bit signed integers"));

    const auto inverted = codec_test_file("min-is-white.tif");
    write_with_libtiff(inverted, 3, 2, 8, SAMPLEFORMAT_UINT, PHOTOMETRIC_MINISWHITE, std::vector<std::uint8_t>(6, 9).data());
    EXPECT_TRUE(fails_with([&] { read_image_file(inverted); }, "its pixels are min-is-white grey, SamplesPerPixel 1; expected"));
}

TEST(ImageFiles, ThicknessMapsAreFloatsAndNameWhatTheyHoldOtherwise) {
    const auto path = codec_test_file("thickness.png");
    const std::vector<std::uint16_t> labels(6, 300);
    write_label_png(labels, 3, 2, path);
    EXPECT_TRUE(fails_with([&] { read_float_image(path); }, "holds 16-bit unsigned integer values; expected floating-point"));
    EXPECT_EQ(read_label_png(path).labels, labels);
    const auto half_path = codec_test_file("thickness.exr");
    write_with_reference(half_path, OIIO::ImageSpec(3, 2, 1, OIIO::TypeDesc::HALF), std::vector<Imath::half>(6, Imath::half(30.5f)));
    EXPECT_EQ(read_float_image(half_path).values, std::vector<float>(6, 30.5f));
}

}  // namespace
}  // namespace petroscope
