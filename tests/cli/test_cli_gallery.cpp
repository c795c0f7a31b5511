// The gallery's conoscopic figures against stored float references (issue 22: output stays the same where
// the physics did not change). Every `figure NAME … conoscope ARGS` of docs/gallery.sh is rendered at
// 64 × 64 px to OpenEXR and compared with tests/references/gallery/NAME.exr. After a change that is meant
// to change the figures, PETROSCOPE_UPDATE_REFERENCES=1 writes the references anew (say why in the commit).
#include "petroscope/core/image.hpp"
#include "petroscope/io/image_writer.hpp"

#include "support/cli_fixture.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace petroscope {
namespace {

namespace fs = std::filesystem;

struct GalleryFigure {
    std::string name, arguments;
};

/// The conoscope figures of docs/gallery.sh: a line `figure NAME "caption" \` followed by `    conoscope ARGS`,
/// with $size replaced by 64.
std::vector<GalleryFigure> gallery_conoscope_figures() {
    std::ifstream script(fs::path(PETROSCOPE_SOURCE_DIR) / "docs" / "gallery.sh");
    std::vector<GalleryFigure> figures;
    std::string line, pending_name;
    while (std::getline(script, line)) {
        if (!pending_name.empty()) {
            const std::size_t start = line.find_first_not_of(' ');
            if (start != std::string::npos && line.compare(start, 10, "conoscope ") == 0) {
                std::string arguments = line.substr(start);
                const std::size_t size = arguments.find("$size");
                if (size != std::string::npos) arguments.replace(size, 5, "64");
                figures.push_back({pending_name, arguments});
            }
            pending_name.clear();
        }
        if (line.rfind("figure ", 0) == 0) {
            std::istringstream words(line.substr(7));
            words >> pending_name;
        }
    }
    return figures;
}

class CliGallery : public testing::CliFixture {};

// Linear sRGB within 1e-4 of the reference in every channel and pixel: far below what shows (ΔE₀₀ ≈ 0.1 at
// the darkest tones), far above the rounding that differs between builds (portable or native, FMA or not)
// and the interpolation error of the white light's spectral nodes (docs/conoscope.md).
TEST_F(CliGallery, ConoscopeFiguresMatchTheStoredReferences) {
    const std::vector<GalleryFigure> figures = gallery_conoscope_figures();
    ASSERT_GE(figures.size(), 10u) << "docs/gallery.sh changed its form";
    const fs::path references = fs::path(PETROSCOPE_SOURCE_DIR) / "tests" / "references" / "gallery";
    const bool update = std::getenv("PETROSCOPE_UPDATE_REFERENCES") != nullptr;
    for (const GalleryFigure& figure : figures) {
        const fs::path rendered = out() / (figure.name + ".exr");
        const testing::CommandResult run = petroscope(figure.arguments + " -o " + testing::quoted(rendered));
        ASSERT_EQ(run.exit_code, 0) << figure.name << ": " << run.err;
        const fs::path reference = references / (figure.name + ".exr");
        if (update) {
            fs::copy_file(rendered, reference, fs::copy_options::overwrite_existing);
            continue;
        }
        ASSERT_TRUE(fs::exists(reference)) << reference << " is missing: PETROSCOPE_UPDATE_REFERENCES=1 writes it";
        const Image expected = read_image(reference), actual = read_image(rendered);
        ASSERT_EQ(expected.pixels.size(), actual.pixels.size()) << figure.name;
        double largest = 0.0;
        for (std::size_t i = 0; i < expected.pixels.size(); ++i) {
            largest = std::max(largest, static_cast<double>(std::abs(expected.pixels[i] - actual.pixels[i])));
        }
        std::printf("%s: largest difference %.2g\n", figure.name.c_str(), largest);
        EXPECT_LE(largest, 1e-4) << figure.name << " (" << figure.arguments << ")";
    }
}

}  // namespace
}  // namespace petroscope
