// petroscope fit conoscope as a user runs it: a rendered figure fitted back, and bad photos refused.
#include "support/cli_fixture.hpp"

#include <nlohmann/json.hpp>

namespace petroscope {
namespace {

class FitCli : public testing::CliFixture {
protected:
    /// A white-light figure of quartz, 400 µm, 128 px (the fit's photo), in the scratch folder.
    std::filesystem::path quartz_photo(const std::string& extra = "", const std::string& name = "photo.png") {
        const std::filesystem::path photo = scratch() / name;
        const testing::CommandResult run =
            petroscope("conoscope --mineral quartz --thickness 400um --size 128 " + extra + " -o " + testing::quoted(photo));
        EXPECT_EQ(run.exit_code, 0) << run.err;
        return photo;
    }
};

TEST_F(FitCli, RenderedFigureFitsBackWithReportAndImages) {
    const auto photo = quartz_photo();
    const testing::CommandResult run =
        petroscope("fit conoscope --photo " + testing::quoted(photo) + " --mineral quartz --thickness 250um --fix field_radius_px=64 -o " +
                   testing::quoted(out()));
    ASSERT_EQ(run.exit_code, 0) << run.out << run.err;
    for (const char* file : {"model.png", "side_by_side.png", "residual.tiff", "report.json"}) EXPECT_TRUE(std::filesystem::exists(out() / file)) << file;
    const nlohmann::json report = nlohmann::json::parse(testing::read_text(out() / "report.json"));
    const nlohmann::json& thickness = report["parameters"]["thickness_um"];
    EXPECT_TRUE(report["acceptable"].get<bool>());
    EXPECT_TRUE(thickness["identifiable"].get<bool>());
    EXPECT_NEAR(thickness["value"].get<double>(), 400.0, 4.0);
    EXPECT_GT(thickness["sigma"].get<double>(), 0.0);
    EXPECT_FALSE(report["candidates"].empty());
    EXPECT_NE(run.out.find("thickness_um = "), std::string::npos);
}

TEST_F(FitCli, BadPhotosAndOptionsAreRefused) {
    const std::string tail = " --mineral quartz --thickness 250um -o " + testing::quoted(out());
    expect_rejected("fit conoscope --photo " + testing::quoted(scratch() / "missing.png") + tail, {"--photo", "missing.png"});
    testing::write_text(scratch() / "empty.png", "");
    expect_rejected("fit conoscope --photo " + testing::quoted(scratch() / "empty.png") + tail, {"--photo", "empty.png"});
    const auto grey = quartz_photo("--wavelength 589nm", "grey.png");
    expect_rejected("fit conoscope --photo " + testing::quoted(grey) + tail, {"grayscale", "white light"});
    const auto saturated = quartz_photo("--exposure 1000", "saturated.png");
    expect_rejected("fit conoscope --photo " + testing::quoted(saturated) + tail, {"saturated"});
    const auto photo = quartz_photo();
    expect_rejected("fit conoscope --photo " + testing::quoted(photo) + tail + " --free thickness,colour", {"--free", "colour", "white-balance"});
    expect_rejected("fit conoscope --photo " + testing::quoted(photo) + tail + " --fix scale=3", {"--fix", "scale", "field_radius_px"});
    expect_rejected("fit conoscope --photo " + testing::quoted(photo) + tail + " --fix gamma", {"--fix", "NAME=VALUE"});
    expect_rejected("fit conoscope --photo " + testing::quoted(photo) + " --mineral quartz --thickness-range 5mm:1mm -o " + testing::quoted(out()),
                    {"--thickness-range", "maximum"});
}

// A photo of something else (the Michel-Lévy chart) ends with "no acceptable fit", its cost, exit 1.
TEST_F(FitCli, PhotoOfSomethingElseHasNoAcceptableFit) {
    const std::filesystem::path chart = scratch() / "chart.png";
    ASSERT_EQ(petroscope("chart -o " + testing::quoted(chart)).exit_code, 0);
    const testing::CommandResult run =
        petroscope("fit conoscope --photo " + testing::quoted(chart) + " --mineral calcite --thickness 30um -o " + testing::quoted(out()));
    EXPECT_EQ(run.exit_code, 1) << run.out << run.err;
    EXPECT_NE(run.err.find("no acceptable fit"), std::string::npos) << run.err;
    EXPECT_NE(run.err.find("cost"), std::string::npos) << run.err;
}

}  // namespace
}  // namespace petroscope
