// petroscope section, run as a user would: a random section is written whole and reproducibly, `show`
// summarises it, and bad options exit non-zero with a message and no folder or file left behind.
#include "support/cli_fixture.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <atomic>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <unistd.h>
#include <vector>

namespace petroscope {
namespace {

namespace fs = std::filesystem;

using testing::CommandResult;
using testing::listing;
using testing::quoted;
using testing::read_text;

class CliSection : public testing::CliFixture {};

TEST_F(CliSection, RandomWritesAReproducibleSection) {
    const std::string arguments = " --minerals quartz,orthoclase,biotite --weights 5,3,1 --grains 60 --size 128 --pixel-size 3um --thickness 25um --seed 4";
    const CommandResult run = petroscope("section random" + arguments + " -o " + quoted(out() / "first"));
    ASSERT_EQ(run.exit_code, 0) << run.err;
    EXPECT_EQ(listing(out() / "first"), (std::set<std::string>{"section.txt", "grains.png"}));
    const std::string description = read_text(out() / "first" / "section.txt");
    EXPECT_NE(description.find("name: first\n"), std::string::npos) << description;
    EXPECT_NE(description.find("size_px: 128 128\n"), std::string::npos);
    EXPECT_NE(description.find("pixel_size_um: 3\n"), std::string::npos);
    EXPECT_NE(description.find("thickness_um: 25\n"), std::string::npos);

    ASSERT_EQ(petroscope("section random" + arguments + " --name first -o " + quoted(out() / "second")).exit_code, 0);
    EXPECT_EQ(read_text(out() / "second" / "section.txt"), description);
    EXPECT_EQ(read_text(out() / "second" / "grains.png"), read_text(out() / "first" / "grains.png"));

    const CommandResult show = petroscope("section show " + quoted(out() / "first") + " --json");
    ASSERT_EQ(show.exit_code, 0) << show.err;
    const nlohmann::json summary = nlohmann::json::parse(show.out);
    EXPECT_EQ(summary["name"], "first");
    EXPECT_EQ(summary["size_px"], nlohmann::json({128, 128}));
    EXPECT_EQ(summary["thickness"]["kind"], "uniform");
    EXPECT_EQ(summary["thickness"]["thickness_um"].get<double>(), 25.0);
    int grains = 0;
    double area = 0.0;
    for (const auto& [mineral, entry] : summary["minerals"].items()) {
        EXPECT_TRUE(mineral == "quartz" || mineral == "orthoclase" || mineral == "biotite") << mineral;
        grains += entry["grains"].get<int>();
        area += entry["area_fraction"].get<double>();
    }
    EXPECT_EQ(grains, summary["grains"].get<int>());
    EXPECT_GE(grains, 55);
    EXPECT_NEAR(area, 1.0, 1e-12);

    const CommandResult text = petroscope("section show " + quoted(out() / "first" / "section.txt"));
    ASSERT_EQ(text.exit_code, 0) << text.err;
    EXPECT_NE(text.out.find("128 x 128 px, pixel 3 um"), std::string::npos) << text.out;
    EXPECT_NE(text.out.find("uniform 25 um"), std::string::npos) << text.out;
}

TEST_F(CliSection, RandomMakesWedges) {
    const CommandResult run = petroscope("section random --minerals quartz --grains 20 --size 64 --wedge 0um,60um -o " + quoted(out() / "wedge"));
    ASSERT_EQ(run.exit_code, 0) << run.err;
    EXPECT_NE(read_text(out() / "wedge" / "section.txt").find("thickness_wedge_um: 0 60 x\n"), std::string::npos);
    const nlohmann::json summary = nlohmann::json::parse(petroscope("section show --json " + quoted(out() / "wedge")).out);
    EXPECT_EQ(summary["thickness"]["kind"], "wedge");
    EXPECT_EQ(summary["thickness"]["end_um"].get<double>(), 60.0);
}

TEST_F(CliSection, RandomRejectsBadOptionsAndWritesNothing) {
    const std::string to = " -o " + quoted(out() / "section");
    expect_rejected("section random --minerals quarz,biotite" + to, {"--minerals", "quarz", "quartz", "petroscope minerals"});
    expect_rejected("section random --minerals quartz,,biotite" + to, {"--minerals"});
    expect_rejected("section random --minerals quartz --grains 0" + to, {"--grains 0"});
    expect_rejected("section random --minerals quartz --size 16 --grains 257" + to, {"--grains 257", "1 to 256"});
    expect_rejected("section random --minerals quartz --size 8" + to, {"--size 8", "16 to 8192"});
    expect_rejected("section random --minerals quartz --size 9000" + to, {"--size 9000"});
    expect_rejected("section random --minerals quartz,biotite --weights 1" + to, {"--weights: 1 values for 2 minerals"});
    expect_rejected("section random --minerals quartz,biotite --weights 1,x" + to, {"--weights '1,x'"});
    expect_rejected("section random --minerals quartz,biotite --sizes 1,0" + to, {"grain sizes must be finite and > 0"});
    expect_rejected("section random --minerals quartz --pixel-size 0um" + to, {"--pixel-size"});
    expect_rejected("section random --minerals quartz --thickness 30" + to, {"--thickness", "unit"});
    expect_rejected("section random --minerals quartz --wedge 0um" + to, {"--wedge '0um'"});
    expect_rejected("section random --minerals quartz --wedge 0um,0um" + to, {"--wedge"});
    expect_rejected("section random --minerals quartz -o " + quoted(out() / "no" / "such"), {"does not exist"});
    expect_rejected("section show " + quoted(out() / "missing"), {"missing", "no such folder or description file"});
}

}  // namespace
}  // namespace petroscope
