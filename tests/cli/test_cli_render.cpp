// petroscope render as a user runs it: the paper's scene at a small size, its sidecar; bad options and
// scenes rejected with nothing written.
#include "petroscope/io/image_writer.hpp"

#include "support/cli_fixture.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

namespace petroscope {
namespace {

class RenderCli : public testing::CliFixture {
protected:
    /// The paper's scene with the camera's image size reduced to `width` × `height`.
    std::filesystem::path small_scene(int width, int height, const std::string& name = "scene.json") {
        nlohmann::json scene = nlohmann::json::parse(testing::read_text(std::filesystem::path(PETROSCOPE_SOURCE_DIR) / "scenes" / "calcite-box.json"));
        scene["camera"]["width_px"] = width;
        scene["camera"]["height_px"] = height;
        const std::filesystem::path path = scratch() / name;
        testing::write_text(path, scene.dump(2));
        return path;
    }
};

TEST_F(RenderCli, RendersTheScene) {
    const auto image = out() / "box.png";
    const testing::CommandResult run = petroscope("render --scene " + testing::quoted(small_scene(48, 44)) + " --spp 2 --polarizer-deg 30 -o " +
                                                  testing::quoted(image));
    ASSERT_EQ(run.exit_code, 0) << run.err;
    const Image png = read_image(image);
    EXPECT_EQ(png.width, 48);
    EXPECT_EQ(png.height, 44);
    const nlohmann::json sidecar = nlohmann::json::parse(testing::read_text(image.string() + ".json"));
    EXPECT_EQ(sidecar["samples_per_pixel"], 2);
    EXPECT_EQ(sidecar["max_depth"], 15);
    EXPECT_EQ(sidecar["polarizer_deg"], 30.0);
    EXPECT_EQ(sidecar["scene"]["fnv1a64"].get<std::string>().size(), 16u);
    EXPECT_EQ(sidecar["statistics"]["paths"], 48 * 44 * 2);
    EXPECT_GT(sidecar["statistics"]["crystal_interactions"], 0);
    EXPECT_EQ(sidecar["statistics"]["inconsistent"], 0);
    EXPECT_TRUE(sidecar.contains("estimated_noise"));
}

TEST_F(RenderCli, RejectsBadInput) {
    const std::string scene = testing::quoted(small_scene(8, 8));
    const std::string output = " -o " + testing::quoted(out() / "x.png");
    expect_rejected("render --scene " + scene + " --spp 0" + output, {"--spp 0", "1 to 1000000"});
    expect_rejected("render --scene " + scene + " --depth 0" + output, {"--depth 0"});
    expect_rejected("render --scene " + scene + " --polarizer-deg 10 --no-polarizer" + output, {"exclude each other"});
    expect_rejected("render --scene " + testing::quoted(scratch() / "none.json") + output, {"none.json"});
    expect_rejected("render --scene " + testing::quoted(small_scene(5000, 4000, "large.json")) + output, {"5000 x 4000", "above 4096 x 4096", "--allow-large"});
    expect_rejected("render --scene " + scene + " --spp 100000" + output, {"--spp 100000", "--allow-large"});
    testing::write_text(scratch() / "bad.json", R"({"box": {"lower_mm": [0, 0, 0], "upper_mm": [1, 1, 1]}, "camera": {}})");
    expect_rejected("render --scene " + testing::quoted(scratch() / "bad.json") + output, {"bad.json", "camera.position_mm", "missing"});
}

}  // namespace
}  // namespace petroscope
