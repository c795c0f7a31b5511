// Scene files: a valid scene reads back as written; bad ones fail with the file, the JSON path and what
// was expected.
#include "render_scenes.hpp"

#include "petroscope/core/error.hpp"
#include "petroscope/io/scene_file.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <string>

namespace petroscope {
namespace {

const std::string kCamera = R"("camera": {"position_mm": [0, -300, 200], "target_mm": [0, 0, 0], "sensor_width_mm": 24,
    "sensor_height_mm": 18, "sensor_distance_mm": 35, "width_px": 32, "height_px": 24})";
const std::string kBox = R"("box": {"lower_mm": [-100, -100, 0], "upper_mm": [100, 100, 100]})";
const std::string kCube = R"("vertices_mm": [[0,0,10],[10,0,10],[0,10,10],[10,10,10],[0,0,20],[10,0,20],[0,10,20],[10,10,20]])";

std::filesystem::path write_scene(const std::string& name, const std::string& text) {
    const std::filesystem::path path = std::filesystem::path(PETROSCOPE_TEST_OUTPUT_DIR) / "scenes" / name;
    std::filesystem::create_directories(path.parent_path());
    std::ofstream(path) << text;
    return path;
}

Scene read(const std::string& name, const std::string& text) {
    return read_scene(write_scene(name, text), testing::render_minerals(), testing::d65_spectrum());
}

void expect_error(const std::string& name, const std::string& text, const std::vector<std::string>& fragments) {
    try {
        read(name, text);
        ADD_FAILURE() << name << ": no error";
    } catch (const InputError& e) {
        const std::string message = e.what();
        for (const std::string& fragment : fragments) EXPECT_NE(message.find(fragment), std::string::npos) << message << "\n(expected: " << fragment << ")";
    }
}

TEST(SceneFile, ThePapersSceneReads) {
    const Scene scene = read_scene(std::filesystem::path(PETROSCOPE_SOURCE_DIR) / "scenes" / "calcite-box.json", testing::render_minerals(),
                                   testing::d65_spectrum());
    EXPECT_EQ(scene.camera.width_px, 480);
    EXPECT_EQ(scene.camera.height_px, 435);
    ASSERT_EQ(scene.crystals.size(), 1u);
    // Lying on a face, just above the bottom wall, its optic axis along the obtuse corners' diagonal.
    EXPECT_GT(scene.crystals[0].shape.lower().z(), 0.0);
    EXPECT_LT(scene.crystals[0].shape.lower().z(), 1e-5);
    const WallEmission& bottom = scene.box.walls[static_cast<std::size_t>(Wall::bottom)];
    EXPECT_EQ(bottom.kind, WallEmission::Kind::texture);
    EXPECT_EQ(bottom.texture_width, 16 * 16);
    EXPECT_EQ(scene.box.walls[static_cast<std::size_t>(Wall::top)].kind, WallEmission::Kind::off);
}

TEST(SceneFile, AGenericPolyhedronWithItsOrientation) {
    const Scene scene = read("cube.json", "{" + kBox + ", " + kCamera + R"(, "crystals": [{"mineral": "sapphire", )" + kCube +
                                              R"(, "faces": [[0,1,3,2],[4,5,7,6],[0,1,5,4],[2,3,7,6],[0,2,6,4],[1,3,7,5]], "euler_zyz_deg": [0, 90, 0]}]})");
    ASSERT_EQ(scene.crystals.size(), 1u);
    EXPECT_EQ(scene.crystals[0].shape.faces.size(), 6u);
    EXPECT_NEAR(scene.crystals[0].axes.col(2).x(), 1.0, 1e-12);  // Ry(90°) turns Z onto x
}

TEST(SceneFile, BadScenesNameTheJsonPath) {
    const std::string faces5 = R"(, "faces": [[0,1,3,2],[4,5,7,6],[0,1,5,4],[2,3,7,6],[0,2,6,4]]})";
    expect_error("unknown_key.json", "{" + kBox + ", " + kCamera + R"(, "crystal": []})", {"unknown_key.json", "unknown key 'crystal'", "valid keys"});
    expect_error("open.json", "{" + kBox + ", " + kCamera + R"(, "crystals": [{"mineral": "sapphire", )" + kCube + faces5 + "]}",
                 {"crystals[0]", "not closed"});
    expect_error("concave.json",
                 "{" + kBox + ", " + kCamera +
                     R"(, "crystals": [{"mineral": "sapphire", "vertices_mm": [[0,0,10],[10,0,10],[0,10,10],[10,10,10],[0,0,20],[10,0,20],[0,10,20],[4,4,12]], "faces": [[0,1,3,2],[4,5,7,6],[0,1,5,4],[2,3,7,6],[0,2,6,4],[1,3,7,5]]}]})",
                 {"crystals[0]"});
    expect_error("active.json", "{" + kBox + ", " + kCamera + R"(, "crystals": [{"mineral": "quartz", )" + kCube +
                                     R"(, "faces": [[0,1,3,2],[4,5,7,6],[0,1,5,4],[2,3,7,6],[0,2,6,4],[1,3,7,5]]}]})",
                 {"crystals[0].mineral", "optically active"});
    expect_error("through_wall.json",
                 "{" + kBox + ", " + kCamera + R"(, "crystals": [{"mineral": "calcite", "calcite_rhomb": {"edges_mm": [40, 30, 30]}, "on_bottom": {"center_mm": [95, 0]}}]})",
                 {"crystals[0]", "crosses a wall"});
    expect_error("texture.json",
                 R"({"box": {"lower_mm": [-100, -100, 0], "upper_mm": [100, 100, 100], "walls": {"bottom": {"texture": "missing.png"}}}, )" + kCamera + "}",
                 {"box.walls.bottom.texture", "missing.png"});
    expect_error("mineral.json", "{" + kBox + ", " + kCamera + R"(, "crystals": [{"mineral": "calcyte", "calcite_rhomb": {"edges_mm": [4, 3, 3]}, "on_bottom": {"center_mm": [0, 0]}}]})",
                 {"crystals[0].mineral", "calcyte"});
    expect_error("wall.json", R"({"box": {"lower_mm": [-100, -100, 0], "upper_mm": [100, 100, 100], "walls": {"floor": "off"}}, )" + kCamera + "}",
                 {"box.walls", "unknown key 'floor'"});
    expect_error("colour.json", R"({"box": {"lower_mm": [-100, -100, 0], "upper_mm": [100, 100, 100], "walls": {"top": {"rgb": [1.2, 0, 0]}}}, )" + kCamera + "}",
                 {"box.walls.top.rgb", "0 … 1"});
    expect_error("camera.json", "{" + kBox + R"(, "camera": {"position_mm": [0, 0, 50], "target_mm": [0, 0, 0], "sensor_width_mm": 0,
        "sensor_height_mm": 18, "sensor_distance_mm": 35, "width_px": 32, "height_px": 24}})",
                 {"camera.sensor_width_mm", "> 0"});
    expect_error("syntax.json", "{" + kBox + ",", {"syntax.json", "invalid JSON"});
}

}  // namespace
}  // namespace petroscope
