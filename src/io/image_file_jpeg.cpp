// JPEG files (ITU-T T.81) through libjpeg: reading (read_jpeg, for read_image_file).
#include "image_file_formats.hpp"
#include "image_files.hpp"

#include <cstdio>  // before jpeglib.h, which uses FILE and size_t without declaring them
#include <jpeglib.h>
#include <jerror.h>  // the message codes (JWRN_…) that jpeg_message tests

#include <array>
#include <csetjmp>
#include <cstddef>
#include <string>
#include <vector>

namespace petroscope::detail {
namespace {

// ---- JPEG (ITU-T T.81), through libjpeg. Its errors longjmp back to JpegReader::jump: the functions that
// call setjmp hold no object with a destructor.

struct JpegReader {
    jpeg_error_mgr errors{};  // first member: libjpeg's cinfo->err points here, and to the reader
    std::jmp_buf jump{};
    std::array<char, JMSG_LENGTH_MAX> message{};
    jpeg_decompress_struct info{};

    JpegReader();
    ~JpegReader() { jpeg_destroy_decompress(&info); }  // also on a struct never created (its mem is null)
    JpegReader(const JpegReader&) = delete;
    JpegReader& operator=(const JpegReader&) = delete;
};

void jump_on_jpeg_error(j_common_ptr info) {
    auto* reader = reinterpret_cast<JpegReader*>(info->err);
    (*info->err->format_message)(info, reader->message.data());
    std::longjmp(reader->jump, 1);
}

// Damaged image data (a file cut short, broken entropy-coded segments) is an error here, not the warning
// libjpeg makes it: it would go on with made-up grey pixels. Warnings about the markers around intact data
// (extraneous bytes before a marker, which phone cameras write; an unknown JFIF version; a bad ICC profile)
// and trace messages (levels ≥ 0) are dropped.
void jpeg_message(j_common_ptr info, int level) {
    const int code = info->err->msg_code;
    const bool damaged_pixels = code == JWRN_JPEG_EOF || code == JWRN_HIT_MARKER || code == JWRN_HUFF_BAD_CODE ||
                                code == JWRN_MUST_RESYNC || code == JWRN_NOT_SEQUENTIAL || code == JWRN_BOGUS_PROGRESSION;
    if (level < 0 && damaged_pixels) jump_on_jpeg_error(info);
}

void print_no_jpeg_message(j_common_ptr) {}

JpegReader::JpegReader() {
    info.err = jpeg_std_error(&errors);
    errors.error_exit = jump_on_jpeg_error;
    errors.emit_message = jpeg_message;
    errors.output_message = print_no_jpeg_message;
}

// Reads the markers up to the first scan (T.81 B.2) and the output size. False on a libjpeg error.
bool start_jpeg(JpegReader& reader, std::FILE* file) {
    if (setjmp(reader.jump)) return false;
    jpeg_create_decompress(&reader.info);
    jpeg_stdio_src(&reader.info, file);
    jpeg_read_header(&reader.info, TRUE);
    jpeg_calc_output_dimensions(&reader.info);
    return true;
}

// Decodes every row into `bytes` (output_width × output_components bytes a row). False on a libjpeg error.
bool decode_jpeg(JpegReader& reader, std::vector<unsigned char>& bytes) {
    if (setjmp(reader.jump)) return false;
    jpeg_start_decompress(&reader.info);
    const std::size_t row_bytes = std::size_t{reader.info.output_width} * static_cast<std::size_t>(reader.info.output_components);
    while (reader.info.output_scanline < reader.info.output_height) {
        JSAMPROW row = bytes.data() + reader.info.output_scanline * row_bytes;
        jpeg_read_scanlines(&reader.info, &row, 1);
    }
    jpeg_finish_decompress(&reader.info);
    return true;
}

}  // namespace

// 8-bit grey or colour (YCbCr or RGB, decoded to RGB); CMYK and YCCK are refused.
DecodedImage read_jpeg(const ReadSource& source) {
    const FileHandle file = open_for_reading(source);
    JpegReader reader;
    if (!start_jpeg(reader, file.get())) source.fail(library_message("libjpeg", reader.message.data()));
    const J_COLOR_SPACE space = reader.info.jpeg_color_space;
    if (space != JCS_GRAYSCALE && space != JCS_YCbCr && space != JCS_RGB) {
        const std::string name = space == JCS_CMYK ? "CMYK" : space == JCS_YCCK ? "YCCK (CMYK)" : "unknown";
        source.fail("its colour space is " + name + "; expected grey or colour (YCbCr or RGB)");
    }
    const jpeg_decompress_struct& info = reader.info;
    DecodedImage image = allocated_image(source, info.output_width, info.output_height, info.output_components, SampleType::uint8);
    std::vector<unsigned char> bytes(image.values.size());
    if (!decode_jpeg(reader, bytes)) source.fail(library_message("libjpeg", reader.message.data()));
    convert_samples(SampleType::uint8, bytes.data(), bytes.size(), image.values.data(), 1);
    return image;
}

}  // namespace petroscope::detail
