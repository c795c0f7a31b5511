// Thin-section files (thin_sections/README.md, include/petroscope/io/thin_section_file.hpp): write → read
// round trips, every kind of bad input located by file and line (or label), all-or-nothing writing, and
// the shipped examples.
#include "petroscope/io/thin_section_file.hpp"

#include "petroscope/core/error.hpp"
#include "petroscope/core/image.hpp"
#include "petroscope/io/data_files.hpp"
#include "petroscope/io/image_writer.hpp"
#include "petroscope/io/label_image.hpp"
#include "petroscope/optics/orientation.hpp"

#include "support/test_files.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <set>
#include <sstream>
#include <string>
#include <unistd.h>
#include <vector>

namespace petroscope {
namespace {

namespace fs = std::filesystem;

using testing::listing;
using testing::read_text;
using testing::write_text;

class ThinSectionFile : public ::testing::Test {
protected:
    static void SetUpTestSuite() {
        catalog_ = std::make_unique<MineralCatalog>(load_mineral_catalog(PETROSCOPE_SOURCE_DIR "/minerals"));
    }
    static void TearDownTestSuite() { catalog_.reset(); }
    static const MineralCatalog& catalog() { return *catalog_; }

    void SetUp() override {
        static std::atomic<int> counter{0};
        folder_ = fs::temp_directory_path() / ("petroscope-section-" + std::to_string(::getpid()) + "-" + std::to_string(counter++) + "-" +
                                               ::testing::UnitTest::GetInstance()->current_test_info()->name());
        fs::remove_all(folder_);
        fs::create_directories(folder_);
    }
    void TearDown() override {
        std::error_code ignored;
        fs::remove_all(folder_, ignored);
    }
    const fs::path& folder() const { return folder_; }

    // A 4x3 map with labels 1, 2 and 7, and its description lines (numbered from 1 as in the file).
    fs::path write_small(const std::vector<std::string>& lines) const {
        write_label_png({1, 1, 2, 2, 1, 7, 7, 2, 1, 7, 7, 2}, 4, 3, folder_ / "grains.png");
        std::string text;
        for (const std::string& line : lines) text += line + "\n";
        write_text(folder_ / "section.txt", text);
        return folder_ / "section.txt";
    }
    static std::vector<std::string> small_lines() {
        return {
            "name: small",                                      // 1
            "grain_map: grains.png",                             // 2
            "size_px: 4 3",                                      // 3
            "pixel_size_um: 2.5",                                // 4
            "thickness_um: 30",                                  // 5
            "grain 1: quartz, euler 10 20 30",                   // 6
            "grain 2: Muscovite, cut acute-bisectrix azimuth 45 tilt 5, thickness 28um",  // 7
            "grain 7: garnet",                                   // 8
        };
    }

    // The InputError message of reading `path`; "" if it reads.
    std::string read_error(const fs::path& path) const {
        try {
            read_thin_section(path, catalog());
        } catch (const InputError& e) {
            return e.what();
        }
        return "";
    }
    // Replaces line `number` (from 1) of the small description, or removes it when `text` is empty.
    std::string error_with_line(int number, const std::string& text) const {
        std::vector<std::string> lines = small_lines();
        if (text.empty()) lines.erase(lines.begin() + (number - 1));
        else lines[static_cast<std::size_t>(number - 1)] = text;
        return read_error(write_small(lines));
    }
    std::string shown() const { return (folder_ / "section.txt").string(); }

private:
    static std::unique_ptr<MineralCatalog> catalog_;
    fs::path folder_;
};
std::unique_ptr<MineralCatalog> ThinSectionFile::catalog_;

#define EXPECT_CONTAINS(text, part) EXPECT_NE(std::string(text).find(part), std::string::npos) << "'" << (part) << "' not in: " << (text)

TEST_F(ThinSectionFile, ReadsAHandWrittenDescription) {
    const ThinSection section = read_thin_section(write_small(small_lines()), catalog());
    EXPECT_EQ(section.name, "small");
    EXPECT_EQ(section.width_px, 4);
    EXPECT_EQ(section.height_px, 3);
    EXPECT_EQ(section.pixel_size_um, 2.5);
    EXPECT_EQ(section.thickness_kind, ThicknessKind::uniform);
    EXPECT_EQ(section.thickness_um, 30.0);
    EXPECT_EQ(section.labels, (std::vector<std::uint16_t>{1, 1, 2, 2, 1, 7, 7, 2, 1, 7, 7, 2}));
    ASSERT_EQ(section.grains.size(), 3u);
    EXPECT_EQ(section.grains[0].mineral, "quartz");
    EXPECT_EQ(section.grains[0].line, 6);
    EXPECT_LT((section.grains[0].crystal_axes - euler_zyz_deg(10, 20, 30)).cwiseAbs().maxCoeff(), 1e-15);
    const Mineral& muscovite = catalog().find("muscovite");
    EXPECT_EQ(section.grains[1].mineral, "muscovite");  // canonical name
    EXPECT_LT((section.grains[1].crystal_axes - cut_orientation(Cut::acute_bisectrix, OpticalClass::biaxial,
                                                                muscovite.principal_n(muscovite.reference_wavelength_nm), 45, 5))
                  .cwiseAbs().maxCoeff(), 1e-15);
    EXPECT_EQ(section.grains[1].thickness_um, 28.0);
    EXPECT_EQ(section.grains[2].mineral, "almandine");  // alias 'garnet', isotropic: no orientation needed
    EXPECT_EQ(section.grains[2].crystal_axes, Eigen::Matrix3d::Identity());
    EXPECT_EQ(section.grain_at(3, 1).label, 2);
    EXPECT_EQ(section.thickness_at(3, 1, section.grain_at(3, 1)), 28.0);
    EXPECT_EQ(section.thickness_at(0, 0, section.grain_at(0, 0)), 30.0);
    // The folder means folder/section.txt.
    EXPECT_EQ(read_thin_section(folder(), catalog()).labels, section.labels);
}

TEST_F(ThinSectionFile, RoundTripsEveryThicknessKind) {
    VoronoiSectionSettings settings;
    settings.minerals = {"quartz", "muscovite", "almandine"};
    settings.grain_count = 40;
    settings.size_px = 64;
    settings.pixel_size_um = 3.25;
    settings.name = "round trip";
    ThinSection original = random_voronoi_section(settings);
    draw_handedness(original, catalog(), 3);
    original.note = "made for a test: 'quotes', colons: and C#, no comment";
    original.grains[3].thickness_um = 17.125;
    original.grains.push_back({500, "calcite", euler_zyz_deg(1, 2, 3), std::nullopt, 0});  // not in the map: kept
    for (const ThicknessKind kind : {ThicknessKind::uniform, ThicknessKind::wedge, ThicknessKind::map}) {
        SCOPED_TRACE(static_cast<int>(kind));
        original.thickness_kind = kind;
        original.wedge_start_um = 60.0;
        original.wedge_end_um = 0.5;
        original.wedge_along_x = false;
        original.thickness_map_um.assign(original.labels.size(), 0.0f);
        for (std::size_t i = 0; i < original.thickness_map_um.size(); ++i) original.thickness_map_um[i] = 20.0f + 0.001f * static_cast<float>(i);
        const fs::path dir = folder() / ("kind-" + std::to_string(static_cast<int>(kind)));
        write_thin_section(original, dir);
        const std::set<std::string> expected_files = kind == ThicknessKind::map ? std::set<std::string>{"section.txt", "grains.png", "thickness.tif"}
                                                                                  : std::set<std::string>{"section.txt", "grains.png"};
        EXPECT_EQ(listing(dir), expected_files);
        EXPECT_EQ(read_label_png(dir / "grains.png").bits, 8);

        const ThinSection copy = read_thin_section(dir, catalog());
        EXPECT_EQ(copy.name, original.name);
        EXPECT_EQ(copy.note, original.note);
        EXPECT_EQ(copy.width_px, original.width_px);
        EXPECT_EQ(copy.height_px, original.height_px);
        EXPECT_EQ(copy.pixel_size_um, original.pixel_size_um);
        EXPECT_EQ(copy.labels, original.labels);
        EXPECT_EQ(copy.thickness_kind, kind);
        for (int y = 0; y < copy.height_px; y += 7) {
            for (int x = 0; x < copy.width_px; x += 5) {
                EXPECT_EQ(copy.thickness_at(x, y, copy.grain_at(x, y)), original.thickness_at(x, y, original.grain_at(x, y)));
            }
        }
        ASSERT_EQ(copy.grains.size(), original.grains.size());
        for (std::size_t i = 0; i < copy.grains.size(); ++i) {
            EXPECT_EQ(copy.grains[i].label, original.grains[i].label);
            EXPECT_EQ(copy.grains[i].mineral, original.grains[i].mineral);
            EXPECT_EQ(copy.grains[i].handedness, original.grains[i].handedness);
            EXPECT_EQ(copy.grains[i].thickness_um, original.grains[i].thickness_um);
            EXPECT_LT((copy.grains[i].crystal_axes - original.grains[i].crystal_axes).cwiseAbs().maxCoeff(), 1e-13);
        }
        // Writing what was read gives the same header again (the Euler angles of the grains may differ in
        // their last digit: angles → axes → angles is exact only to rounding).
        const std::string again = thin_section_description(copy), written = read_text(dir / "section.txt");
        EXPECT_EQ(again.substr(0, again.find("grain 1:")), written.substr(0, written.find("grain 1:")));
    }
}

TEST_F(ThinSectionFile, ManyGrainsGiveASixteenBitMap) {
    const ThinSection original = random_voronoi_section({"quartz"}, {}, 400, 64, 1.0, 30.0, 9);
    ASSERT_GT(original.grains.size(), 255u);
    write_thin_section(original, folder() / "wide");
    const LabelImage map = read_label_png(folder() / "wide" / "grains.png");
    EXPECT_EQ(map.bits, 16);
    EXPECT_EQ(read_thin_section(folder() / "wide", catalog()).labels, original.labels);
}

TEST_F(ThinSectionFile, LabelWithoutAGrainNamesTheLabel) {
    const std::string error = error_with_line(8, "");  // no 'grain 7'
    EXPECT_CONTAINS(error, shown() + ": grain map grains.png has label 7 (4 pixels, first at x 1, y 1)");
    EXPECT_CONTAINS(error, "no 'grain 7: MINERAL, ORIENTATION' line");
}

TEST_F(ThinSectionFile, UnknownMineralSuggestsNames) {
    const std::string error = error_with_line(6, "grain 1: quarz, euler 0 0 0");
    EXPECT_CONTAINS(error, shown() + ":6: grain 1: unknown mineral 'quarz'; did you mean quartz?");
    EXPECT_CONTAINS(error, "'petroscope minerals' lists all");
}

TEST_F(ThinSectionFile, MapSizeMustMatchSizePx) {
    const std::string error = error_with_line(3, "size_px: 4 4");
    EXPECT_CONTAINS(error, shown() + ":3: size_px is 4x4 but grain map grains.png is 4x3 pixels");
}

TEST_F(ThinSectionFile, MapMustBeASingleChannelPng) {
    write_small(small_lines());
    write_text(folder() / "grains.png", "P2\n4 3\n255\n1 1 2 2 1 7 7 2 1 7 7 2\n");  // a PGM under a PNG name
    std::string error = read_error(folder());
    EXPECT_CONTAINS(error, shown() + ":2: grain_map: grain map " + (folder() / "grains.png").string() + " is not a PNG file");

    write_image(Image(4, 3, 3), folder() / "grains.png", ImageFormat::tiff);  // a TIFF under a PNG name
    EXPECT_CONTAINS(read_error(folder()), "is not a PNG file");

    write_image(Image(4, 3, 3), folder() / "grains.png", ImageFormat::png);  // colour
    error = read_error(folder());
    EXPECT_CONTAINS(error, shown() + ":2: grain_map: grain map");
    EXPECT_CONTAINS(error, "has 3 channels (colour, or a palette image); expected a single grey channel");

    fs::remove(folder() / "grains.png");
    EXPECT_CONTAINS(read_error(folder()), shown() + ":2: grain_map: grain map " + (folder() / "grains.png").string() + " does not exist");
}

TEST_F(ThinSectionFile, MissingKeysAreNamed) {
    EXPECT_CONTAINS(error_with_line(4, ""), shown() + ":7: missing key 'pixel_size_um'");
    EXPECT_CONTAINS(error_with_line(1, ""), "missing key 'name'");
    EXPECT_CONTAINS(error_with_line(2, ""), "missing key 'grain_map'");
    EXPECT_CONTAINS(error_with_line(3, ""), "missing key 'size_px'");
    EXPECT_CONTAINS(error_with_line(5, ""), shown() + ":7: missing the section's thickness: expected one of 'thickness_um: 30'");
    EXPECT_CONTAINS(read_error(write_small({"name: x", "grain_map: grains.png", "size_px: 4 3", "pixel_size_um: 1", "thickness_um: 30"})),
                    shown() + ":5: no grains");
}

TEST_F(ThinSectionFile, DuplicatesAreRefused) {
    EXPECT_CONTAINS(error_with_line(8, "grain 1: garnet"), shown() + ":8: grain 1 is defined twice (first on line 6)");
    EXPECT_CONTAINS(error_with_line(8, "grain 01: garnet"), shown() + ":8: grain 1 is defined twice (first on line 6)");
    EXPECT_CONTAINS(error_with_line(8, "name: again"), shown() + ":8: key 'name' appears twice (first on line 1)");
    EXPECT_CONTAINS(error_with_line(8, "thickness_wedge_um: 0 30"), shown() + ":8: the thickness is given more than once");
    EXPECT_CONTAINS(error_with_line(6, "grain 1: quartz, euler 0 0 0, cut optic-axis"), shown() + ":6: grain 1: a second orientation");
    EXPECT_CONTAINS(error_with_line(7, "grain 2: muscovite, euler 0 0 0, thickness 3um, thickness 4um"), shown() + ":7: grain 2: 'thickness' given twice");
}

TEST_F(ThinSectionFile, BadNumbersAreLocated) {
    EXPECT_CONTAINS(error_with_line(4, "pixel_size_um: abc"), shown() + ":4: pixel_size_um: expected the edge of a pixel in micrometres > 0");
    EXPECT_CONTAINS(error_with_line(4, "pixel_size_um: 0"), shown() + ":4: pixel_size_um");
    EXPECT_CONTAINS(error_with_line(3, "size_px: 4 three"), shown() + ":3: size_px: expected the width and height in pixels");
    EXPECT_CONTAINS(error_with_line(3, "size_px: 4.5 3"), shown() + ":3: size_px");
    EXPECT_CONTAINS(error_with_line(3, "size_px: 4"), shown() + ":3: size_px");
    EXPECT_CONTAINS(error_with_line(5, "thickness_um: -30"), shown() + ":5: thickness_um: expected a thickness in micrometres > 0");
    EXPECT_CONTAINS(error_with_line(5, "thickness_wedge_um: 0 sixty"), shown() + ":5: thickness_wedge_um: expected 'START END [x|y]'");
    EXPECT_CONTAINS(error_with_line(5, "thickness_wedge_um: 0 60 z"), shown() + ":5: thickness_wedge_um");
    EXPECT_CONTAINS(error_with_line(5, "thickness_wedge_um: 0 0"), shown() + ":5: thickness_wedge_um");
    EXPECT_CONTAINS(error_with_line(6, "grain 1: quartz, euler 10 20 x"), shown() + ":6: grain 1 euler: expected an angle in degrees (a bare number), found 'x'");
    EXPECT_CONTAINS(error_with_line(6, "grain 1: quartz, euler 10 20"), shown() + ":6: grain 1: expected 'euler A B C'");
    EXPECT_CONTAINS(error_with_line(6, "grain 1: quartz, cut optic-axis tilt ten"), shown() + ":6: grain 1 tilt: expected an angle");
    EXPECT_CONTAINS(error_with_line(6, "grain 1: quartz, cut optic-axis spin 10"), shown() + ":6: grain 1: after the cut name expected 'azimuth DEG'");
    EXPECT_CONTAINS(error_with_line(7, "grain 2: muscovite, euler 0 0 0, thickness 28"), shown() + ":7: grain 2: invalid length '28'");
    EXPECT_CONTAINS(error_with_line(7, "grain 2: muscovite, euler 0 0 0, thickness 0um"), shown() + ":7: grain 2: the grain's thickness must be > 0");
    EXPECT_CONTAINS(error_with_line(6, "grain x: quartz, euler 0 0 0"), shown() + ":6: expected 'grain LABEL: MINERAL, …'");
    EXPECT_CONTAINS(error_with_line(6, "grain 65536: quartz, euler 0 0 0"), shown() + ":6: expected 'grain LABEL");
}

TEST_F(ThinSectionFile, OrientationsMustSuitTheMineral) {
    EXPECT_CONTAINS(error_with_line(6, "grain 1: quartz"), shown() + ":6: grain 1: quartz is uniaxial; expected an orientation");
    EXPECT_CONTAINS(error_with_line(6, "grain 1: quartz, cut acute-bisectrix"), shown() + ":6: grain 1 (quartz): cut 'acute-bisectrix' exists only for biaxial minerals");
    EXPECT_CONTAINS(error_with_line(6, "grain 1: quartz, cut sideways"), shown() + ":6: grain 1 (quartz): unknown cut 'sideways'");
    EXPECT_CONTAINS(error_with_line(6, "grain 1: quartz, spin 10"),
                    shown() + ":6: grain 1: expected 'euler A B C', 'cut NAME [azimuth DEG] [tilt DEG]', 'thickness LENGTH' or 'handedness right|left'");
    EXPECT_CONTAINS(error_with_line(6, "grain 1: , euler 0 0 0"), shown() + ":6: grain 1: expected a mineral name first");
    // Any orientation will do for an isotropic mineral.
    EXPECT_EQ(error_with_line(8, "grain 7: garnet, cut optic-axis tilt 20"), "");
}

// Quartz is optically active: a grain may name its form; other minerals have none.
TEST_F(ThinSectionFile, OnlyAnOpticallyActiveGrainHasAHandedness) {
    std::vector<std::string> lines = small_lines();
    lines[5] = "grain 1: quartz, euler 10 20 30, handedness left";
    const ThinSection section = read_thin_section(write_small(lines), catalog());
    EXPECT_EQ(section.grains[0].handedness, Handedness::left);
    EXPECT_EQ(section.grains[1].handedness, std::nullopt);  // muscovite
    const std::string written = thin_section_description(section);
    const std::size_t line = written.find("grain 1: quartz, euler ");
    ASSERT_NE(line, std::string::npos);
    EXPECT_EQ(written.substr(written.find(',', line + 23), written.find('\n', line) - written.find(',', line + 23)), ", handedness left");
    EXPECT_EQ(read_thin_section(write_small(small_lines()), catalog()).grains[0].handedness, std::nullopt);  // unnamed: right when rendered
    EXPECT_CONTAINS(error_with_line(7, "grain 2: muscovite, euler 0 0 0, handedness right"), shown() + ":7: grain 2: muscovite is not optically active: it has no handedness");
    EXPECT_CONTAINS(error_with_line(6, "grain 1: quartz, euler 0 0 0, handedness sideways"), shown() + ":6: grain 1: unknown handedness 'sideways' (expected right or left)");
    EXPECT_CONTAINS(error_with_line(6, "grain 1: quartz, euler 0 0 0, handedness"), shown() + ":6: grain 1: expected 'handedness right' or 'handedness left'");
    EXPECT_CONTAINS(error_with_line(6, "grain 1: quartz, euler 0 0 0, handedness left, handedness right"), shown() + ":6: grain 1: 'handedness' given twice");
}

// A random section draws each quartz grain's form, half right and half left, without changing its grains.
TEST_F(ThinSectionFile, RandomSectionsDrawTheFormOfEveryOpticallyActiveGrain) {
    VoronoiSectionSettings settings;
    settings.minerals = {"quartz", "muscovite"};
    settings.grain_count = 400;
    settings.size_px = 128;
    ThinSection section = random_voronoi_section(settings);
    const ThinSection before = section;
    draw_handedness(section, catalog(), settings.seed);
    int right = 0, left = 0;
    for (std::size_t g = 0; g < section.grains.size(); ++g) {
        const ThinSectionGrain& grain = section.grains[g];
        EXPECT_EQ(grain.crystal_axes, before.grains[g].crystal_axes);
        if (grain.mineral != "quartz") {
            EXPECT_EQ(grain.handedness, std::nullopt);
            continue;
        }
        ASSERT_TRUE(grain.handedness.has_value());
        (*grain.handedness == Handedness::right ? right : left) += 1;
    }
    EXPECT_EQ(section.labels, before.labels);
    // Binomial with p = ½ over ~200 grains: within 4σ of half.
    const double n = right + left;
    EXPECT_LT(std::abs(right - n / 2), 4.0 * std::sqrt(n) / 2) << right << " right, " << left << " left";
}

TEST_F(ThinSectionFile, OtherSyntaxErrors) {
    EXPECT_CONTAINS(error_with_line(5, "thickness 30"), shown() + ":5: expected 'key: value', found 'thickness 30'");
    EXPECT_CONTAINS(error_with_line(5, "thickness: 30"), shown() + ":5: unknown key 'thickness' (valid keys: name, note, grain_map");
    EXPECT_CONTAINS(error_with_line(5, "thickness_um:"), shown() + ":5: key 'thickness_um' has no value");
    // Comments and blank lines are fine.
    EXPECT_EQ(error_with_line(5, "thickness_um: 30   # standard"), "");
    EXPECT_EQ(error_with_line(5, "# thickness_um: 30\n\nthickness_um: 25"), "");
    EXPECT_CONTAINS(read_error(folder() / "nothing-here.txt"), "nothing-here.txt");
}

TEST_F(ThinSectionFile, ThicknessMapsAreCheckedToo) {
    std::vector<std::string> lines = small_lines();
    lines[4] = "thickness_map: t.tif";
    write_small(lines);
    EXPECT_CONTAINS(read_error(folder()), shown() + ":5: thickness_map: thickness map " + (folder() / "t.tif").string() + " does not exist");
    write_float_tiff(std::vector<float>(12, 25.0f), 4, 3, folder() / "t.tif");
    const ThinSection section = read_thin_section(folder(), catalog());
    EXPECT_EQ(section.thickness_kind, ThicknessKind::map);
    EXPECT_EQ(section.thickness_at(0, 0, section.grain_at(0, 0)), 25.0);
    write_float_tiff(std::vector<float>(16, 25.0f), 4, 4, folder() / "t.tif");
    EXPECT_CONTAINS(read_error(folder()), shown() + ":5: thickness_map t.tif is 4x4 pixels; expected size_px 4x3");
    std::vector<float> negative(12, 25.0f);
    negative[5] = -1.0f;
    write_float_tiff(negative, 4, 3, folder() / "t.tif");
    EXPECT_CONTAINS(read_error(folder()), shown() + ":5: thickness_map t.tif holds -1.000000 at (x 1, y 1)");
    write_label_png(std::vector<std::uint16_t>(12, 30), 4, 3, folder() / "t.tif");
    EXPECT_CONTAINS(read_error(folder()), "expected floating-point micrometres");
}

TEST_F(ThinSectionFile, WritingIsAllOrNothing) {
    ThinSection section = random_voronoi_section({"quartz"}, {}, 10, 32, 1.0, 30.0, 1);
    // A folder whose parent does not exist: nothing is created.
    EXPECT_THROW(write_thin_section(section, folder() / "no" / "such"), InputError);
    EXPECT_FALSE(fs::exists(folder() / "no"));
    // An invalid section (a label without a grain): the new folder is not left behind.
    ThinSection broken = section;
    broken.grains.pop_back();
    EXPECT_THROW(write_thin_section(broken, folder() / "broken"), InputError);
    EXPECT_FALSE(fs::exists(folder() / "broken"));
    // A name that would not read back.
    ThinSection multiline = section;
    multiline.name = "two\nlines";
    EXPECT_THROW(write_thin_section(multiline, folder() / "multiline"), InputError);
    EXPECT_FALSE(fs::exists(folder() / "multiline"));
    // A path that is a file.
    write_text(folder() / "file", "x");
    EXPECT_THROW(write_thin_section(section, folder() / "file"), InputError);
    // Into an existing folder: its other files stay, no temporary file remains.
    fs::create_directories(folder() / "existing");
    write_text(folder() / "existing" / "keep.txt", "x");
    write_thin_section(section, folder() / "existing");
    EXPECT_EQ(listing(folder() / "existing"), (std::set<std::string>{"keep.txt", "section.txt", "grains.png"}));
}

TEST_F(ThinSectionFile, TheReadmeExampleReads) {
    const std::string readme = read_text(PETROSCOPE_SOURCE_DIR "/thin_sections/README.md");
    const std::size_t start = readme.find("```\n# A hand-written example");
    ASSERT_NE(start, std::string::npos);
    const std::size_t end = readme.find("```", start + 3);
    write_text(folder() / "section.txt", readme.substr(start + 4, end - start - 4));
    std::vector<std::uint16_t> labels(256 * 128, 1);
    for (std::size_t i = 0; i < labels.size(); ++i) labels[i] = (i % 256 < 100) ? 1 : (i % 256 < 200 ? 2 : 7);
    write_label_png(labels, 256, 128, folder() / "grains.png");
    const ThinSection section = read_thin_section(folder(), catalog());
    EXPECT_EQ(section.name, "two grains");
    ASSERT_EQ(section.grains.size(), 3u);
    EXPECT_EQ(section.grains[1].thickness_um, 28.0);
    EXPECT_EQ(section.grains[2].mineral, "almandine");
}

TEST_F(ThinSectionFile, TheExamplesLoad) {
    const fs::path examples = PETROSCOPE_SOURCE_DIR "/thin_sections";
    const std::map<std::string, std::set<std::string>> expected{
        {"granite", {"quartz", "orthoclase", "albite", "biotite", "muscovite"}},
        {"basalt", {"forsterite", "augite", "labradorite", "basaltic glass"}},
        {"quartzite-wedge", {"quartz"}},
    };
    for (const auto& [name, minerals] : expected) {
        SCOPED_TRACE(name);
        const ThinSection section = read_thin_section(examples / name, catalog());
        EXPECT_EQ(section.name, name);
        EXPECT_LE(section.width_px, 512);
        EXPECT_LE(section.height_px, 512);
        std::set<std::string> found;
        for (const auto& [label, count] : section.label_counts()) {
            found.insert(section.grains[static_cast<std::size_t>(section.grain_index_of_label[label])].mineral);
        }
        EXPECT_EQ(found, minerals);
        // The recorded command made these files.
        EXPECT_NE(section.note.find("petroscope section random"), std::string::npos);
    }
    const ThinSection wedge = read_thin_section(examples / "quartzite-wedge", catalog());
    EXPECT_EQ(wedge.thickness_kind, ThicknessKind::wedge);
    EXPECT_EQ(wedge.wedge_start_um, 0.0);
    EXPECT_EQ(wedge.wedge_end_um, 60.0);
    EXPECT_TRUE(wedge.wedge_along_x);
}

}  // namespace
}  // namespace petroscope
