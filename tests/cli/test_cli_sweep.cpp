// petroscope sweep, as a user runs it: the acceptance (melatope azimuth, extinction every 90°,
// resuming, shards merged byte for byte) and its bad inputs.
#include "support/cli_fixture.hpp"

#include "petroscope/io/data_files.hpp"
#include "petroscope/io/json_sidecar.hpp"
#include "petroscope/io/thin_section_file.hpp"
#include "petroscope/optics/orientation.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <map>

namespace petroscope::testing {
namespace {

using CsvRow = std::map<std::string, std::string>;

std::vector<CsvRow> read_csv(const std::filesystem::path& path) {
    std::vector<CsvRow> rows;
    std::vector<std::string> header;
    std::istringstream text(read_text(path));
    for (std::string line; std::getline(text, line);) {
        std::vector<std::string> fields;
        std::istringstream cells(line);
        for (std::string cell; std::getline(cells, cell, ',');) fields.push_back(cell);
        if (line.ends_with(",")) fields.emplace_back();
        if (header.empty()) {
            header = fields;
            continue;
        }
        EXPECT_EQ(fields.size(), header.size()) << line;
        CsvRow row;
        for (std::size_t k = 0; k < std::min(fields.size(), header.size()); ++k) row[header[k]] = fields[k];
        rows.push_back(row);
    }
    return rows;
}

double number(const CsvRow& row, const std::string& column) {
    const auto found = row.find(column);
    EXPECT_NE(found, row.end()) << column;
    EXPECT_FALSE(found == row.end() || found->second.empty()) << column << " is empty";
    return found == row.end() || found->second.empty() ? NAN : std::stod(found->second);
}

// Every file under `folder` (relative path → bytes).
std::map<std::string, std::string> tree(const std::filesystem::path& folder) {
    std::map<std::string, std::string> files;
    for (const auto& entry : std::filesystem::recursive_directory_iterator(folder)) {
        if (entry.is_regular_file()) files[std::filesystem::relative(entry.path(), folder).string()] = read_text(entry.path());
    }
    return files;
}

double angle_difference_deg(double a, double b) { return std::abs(std::remainder(a - b, 360.0)); }

class SweepCli : public CliFixture {
protected:
    // The acceptance sweep: an off-centre calcite figure (optic axis tilted 20°) turned from 0° to 330°.
    std::string off_centre_sweep(const std::filesystem::path& folder, const std::string& extra = "") const {
        return "sweep conoscope --mineral calcite --thickness 30um --cut optic-axis --tilt-deg 20 --size 256 "
               "--vary azimuth-deg=0:330:30 -o " + quoted(folder) + (extra.empty() ? "" : " " + extra);
    }
};

TEST_F(SweepCli, MelatopeOfAnOffCentreUniaxialFigureFollowsTheSweptAzimuth) {
    const CommandResult run = petroscope(off_centre_sweep(out() / "sweep"));
    ASSERT_EQ(run.exit_code, 0) << run.err;
    const std::vector<CsvRow> rows = read_csv(out() / "sweep" / "measurements.csv");
    ASSERT_EQ(rows.size(), 12u);
    double worst_deg = 0.0;
    for (const CsvRow& row : rows) {
        const double swept = number(row, "azimuth-deg");
        const double measured = number(row, "melatope_1_azimuth_deg");
        worst_deg = std::max(worst_deg, angle_difference_deg(measured, swept));
        EXPECT_LT(angle_difference_deg(measured, swept), 0.3) << row.at("file");
        // Where the model puts the axis: ω sin 20° / NA from the centre (ω of calcite at 555 nm), exactly at the azimuth.
        EXPECT_LT(angle_difference_deg(number(row, "optic_axis_1_azimuth_deg"), swept), 1e-9);
        EXPECT_NEAR(number(row, "melatope_1_radius"), number(row, "optic_axis_1_radius"), 2.0 / 128);  // 2 px at 256²
        EXPECT_EQ(row.at("melatope_2_x"), "");  // uniaxial: one axis
    }
    std::printf("off-centre calcite, 256^2 white: melatope azimuth within %.3f deg of the swept azimuth\n", worst_deg);
    for (const char* name : {"sweep.json", "sheet.png", "sheet.png.json", "animation.gif", "frames/frame_0011.png", "frames/frame_0011.png.json"}) {
        EXPECT_TRUE(std::filesystem::is_regular_file(out() / "sweep" / name)) << name;
    }
}

TEST_F(SweepCli, StageSweepOfAGrainShowsExtinctionEvery90Degrees) {
    // One quartz grain, its optic axis in the plane of the section at 20° from E: extinct where the axis
    // lies along a polar, at stage 70°, 160°, 250°, 340°. Quartz is optically active, so its waves are
    // ellipses of sin²2χ ≈ 1.6e-5 (docs/theory.md §9): at extinction it keeps about that much of the light.
    ThinSection section;
    section.name = "one-grain";
    section.width_px = section.height_px = 64;
    section.labels.assign(64 * 64, 1);
    section.grains.push_back({1, "quartz", euler_zyz_deg(20.0, 90.0, 0.0), std::nullopt, 0});
    section.thickness_um = 30.0;
    write_thin_section(section, scratch() / "one-grain");
    const CommandResult run = petroscope("sweep orthoscope --section " + quoted(scratch() / "one-grain") +
                                         " --wavelengths 400:700:20 --vary stage-deg=0:355:5 --animation none -o " + quoted(out() / "stage"));
    ASSERT_EQ(run.exit_code, 0) << run.err;
    const std::vector<CsvRow> rows = read_csv(out() / "stage" / "measurements.csv");
    ASSERT_EQ(rows.size(), 72u);
    double brightest = 0.0;
    for (const CsvRow& row : rows) brightest = std::max(brightest, number(row, "mean_luminance"));
    std::vector<double> extinct_at;
    for (const CsvRow& row : rows) {
        const double fraction = number(row, "mean_luminance") / brightest;
        if (fraction < 1e-4) {
            extinct_at.push_back(number(row, "stage-deg"));
            EXPECT_GT(fraction, 5e-6) << "the activity's light at stage " << row.at("stage-deg");
            std::printf("stage %s: %.3g of the brightest\n", row.at("stage-deg").c_str(), fraction);
        }
    }
    EXPECT_EQ(extinct_at, (std::vector<double>{70, 160, 250, 340}));
    // And bright at 45° from extinction.
    EXPECT_GT(number(rows[(70 + 45) / 5], "mean_luminance"), 0.9 * brightest);
}

TEST_F(SweepCli, AnInterruptedSweepRendersOnlyTheMissingFramesAndEndsTheSame) {
    ASSERT_EQ(petroscope(off_centre_sweep(out() / "whole")).exit_code, 0);
    const auto complete = tree(out() / "whole");
    // Interrupt: three frames lost (one without its sidecar, as if stopped between the two renames), and
    // the merged outputs not made yet.
    const std::filesystem::path frames = out() / "whole" / "frames";
    std::filesystem::remove(frames / "frame_0002.png");
    std::filesystem::remove(frames / "frame_0002.png.json");
    std::filesystem::remove(frames / "frame_0007.png.json");
    std::filesystem::remove(frames / "frame_0011.png");
    for (const char* name : {"measurements.csv", "sheet.png", "sheet.png.json", "animation.gif"}) std::filesystem::remove(out() / "whole" / name);
    const auto kept_time = std::filesystem::last_write_time(frames / "frame_0005.png");

    const CommandResult resumed = petroscope(off_centre_sweep(out() / "whole"));
    ASSERT_EQ(resumed.exit_code, 0) << resumed.err;
    EXPECT_NE(resumed.err.find("3 to render, 9 already there"), std::string::npos) << resumed.err;
    EXPECT_EQ(std::filesystem::last_write_time(frames / "frame_0005.png"), kept_time);
    EXPECT_EQ(tree(out() / "whole"), complete);
}

TEST_F(SweepCli, ShardsMergedEqualTheUnshardedSweepByteForByte) {
    ASSERT_EQ(petroscope(off_centre_sweep(out() / "whole")).exit_code, 0);
    const CommandResult first = petroscope(off_centre_sweep(out() / "sharded", "--shard 1/2"));
    ASSERT_EQ(first.exit_code, 0) << first.err;
    EXPECT_NE(first.err.find("--merge"), std::string::npos);
    EXPECT_FALSE(std::filesystem::exists(out() / "sharded" / "measurements.csv"));
    // Merging before every shard is done names what is missing and writes nothing.
    const CommandResult early = petroscope("sweep --merge " + quoted(out() / "sharded"));
    EXPECT_EQ(early.exit_code, 2);
    EXPECT_NE(early.err.find("6 of 12 frames are missing (frame_0006.png"), std::string::npos) << early.err;
    EXPECT_FALSE(std::filesystem::exists(out() / "sharded" / "measurements.csv"));

    ASSERT_EQ(petroscope(off_centre_sweep(out() / "sharded", "--shard 2/2 --jobs 1")).exit_code, 0);
    const CommandResult merged = petroscope("sweep --merge " + quoted(out() / "sharded"));
    ASSERT_EQ(merged.exit_code, 0) << merged.err;
    const auto whole = tree(out() / "whole"), sharded = tree(out() / "sharded");
    EXPECT_EQ(whole.size(), 4u + 12u * 2u + 1u);  // plan, csv, sheet + sidecar, animation; frames with sidecars
    ASSERT_EQ(whole.size(), sharded.size());
    for (const auto& [name, bytes] : whole) EXPECT_TRUE(sharded.count(name) && sharded.at(name) == bytes) << name;
}

TEST_F(SweepCli, AFrameSidecarsCommandLineRendersThatFrameAgain) {
    ASSERT_EQ(petroscope(off_centre_sweep(out() / "sweep", "--animation mp4")).exit_code, 0);
    EXPECT_GT(std::filesystem::file_size(out() / "sweep" / "animation.mp4"), 1000u);
    const std::filesystem::path frame = out() / "sweep" / "frames" / "frame_0004.png";
    const nlohmann::json sidecar = nlohmann::json::parse(read_text(sidecar_path(frame)));
    EXPECT_EQ(sidecar["sweep"]["values"]["azimuth-deg"], "120");
    std::string command = sidecar["command_line"];
    ASSERT_TRUE(command.starts_with("petroscope conoscope ")) << command;
    command = command.substr(std::string("petroscope ").size());
    command.replace(command.rfind(" -o "), std::string::npos, " -o " + quoted(out() / "again.png"));
    const CommandResult again = petroscope(command);
    ASSERT_EQ(again.exit_code, 0) << again.err;
    EXPECT_EQ(read_text(out() / "again.png"), read_text(frame));
}

TEST_F(SweepCli, TwoOptionsMakeAGridAndConicalRingsScaleWithLengthAndWaist) {
    const CommandResult run = petroscope("sweep conical --size 128 --vary length=10mm:20mm:10mm --vary waist=30um,60um --animation none -o " +
                                         quoted(out() / "grid"));
    ASSERT_EQ(run.exit_code, 0) << run.err;
    const std::vector<CsvRow> rows = read_csv(out() / "grid" / "measurements.csv");
    ASSERT_EQ(rows.size(), 4u);
    EXPECT_EQ(rows[1].at("length"), "10mm");
    EXPECT_EQ(rows[1].at("waist"), "60um");
    EXPECT_EQ(rows[2].at("length"), "20mm");
    // The paraxial rings depend on ρ0 = A·l/w alone, in units of w (docs/theory.md §8): (10 mm, 30 µm) and
    // (20 mm, 60 µm) share ρ0, so every ring radius doubles.
    for (const char* ring : {"ring_outer_bright_um", "ring_dark_um", "ring_inner_bright_um"}) {
        EXPECT_NEAR(number(rows[3], ring) / number(rows[0], ring), 2.0, 1e-9) << ring;
    }
    EXPECT_GT(number(rows[2], "ring_dark_um"), number(rows[0], "ring_dark_um"));
    const nlohmann::json sheet = nlohmann::json::parse(read_text(out() / "grid" / "sheet.png.json"));
    EXPECT_EQ(sheet["sheet_layout"]["columns"], 2);
}

TEST_F(SweepCli, BadInputIsRejectedAndNothingIsWritten) {
    const std::string base = "sweep conoscope --mineral calcite --size 64 -o " + quoted(out() / "s");
    expect_rejected(base + " --vary azimut-deg=0:90:10", {"'azimut-deg' is not a numeric option of conoscope", "azimuth-deg", "tilt-deg", "thickness"});
    expect_rejected(base + " --vary mineral=0:90:10", {"not a numeric option"});
    expect_rejected(base + " --vary size=64:128:64", {"not a numeric option"});
    expect_rejected(base + " --vary azimuth-deg=0:90", {"azimuth-deg=0:90", "START:END:STEP"});
    expect_rejected(base + " --vary azimuth-deg=0-90-10", {"expected NAME=START:END:STEP"});
    expect_rejected(base + " --vary azimuth-deg=0:90:x", {"'x' is not a number"});
    expect_rejected(base + " --vary azimuth-deg=0:90:0", {"the step is zero"});
    expect_rejected(base + " --vary azimuth-deg=90:0:10", {"leads away from the end", "negative step"});
    expect_rejected(base + " --vary thickness=10:60:10", {"give the unit of the length", "thickness=10um:60um:10um"});
    expect_rejected(base + " --vary azimuth-deg=0:10:1deg", {"plain number, without a unit"});
    expect_rejected(base + " --vary azimuth-deg=0:359:1 --vary tilt-deg=0:29:1", {"10800 frames", "more than 10000", "--yes"});
    expect_rejected(base + " --azimuth-deg 5 --vary azimuth-deg=0:90:10", {"given a value and swept"});
    expect_rejected(base + " --vary na=0.5:1.2:0.35", {"frame 2 (na 1.20)", "numerical aperture"});
    expect_rejected(base + " --vary azimuth-deg=0:90:10 --shard 3/2", {"--shard '3/2'", "K/N"});
    expect_rejected(base + " --vary azimuth-deg=0:90:10 --animation avi", {"--animation 'avi'"});
    expect_rejected("sweep conoscope --vary azimuth-deg=0:90:10", {"--output"});
    expect_rejected("sweep", {"name what to sweep"});
    expect_rejected("sweep --merge " + quoted(out()), {"no sweep.json"});
    // A folder holding something else, or another sweep, is left alone.
    std::filesystem::create_directories(out() / "busy");
    write_text(out() / "busy" / "notes.txt", "mine");
    expect_rejected("sweep conoscope --size 64 --vary azimuth-deg=0:90:45 -o " + quoted(out() / "busy"), {"not empty"});
    ASSERT_EQ(petroscope("sweep conoscope --size 64 --vary azimuth-deg=0:90:45 --animation none -o " + quoted(out() / "done")).exit_code, 0);
    const auto before = tree(out() / "done");
    expect_rejected("sweep conoscope --size 64 --vary azimuth-deg=0:90:30 -o " + quoted(out() / "done"), {"holds another sweep"});
    EXPECT_EQ(tree(out() / "done"), before);
}

}  // namespace
}  // namespace petroscope::testing
