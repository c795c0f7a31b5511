// The live microscope's answers (serve/live_microscope.hpp) without a socket: the page's files and nothing
// else, the catalog, the views' binary format against the library's harmonics, and bad input refused with
// a message that names the parameter.
#include "petroscope/core/error.hpp"
#include "petroscope/io/data_files.hpp"
#include "petroscope/io/thin_section_file.hpp"
#include "petroscope/serve/live_microscope.hpp"
#include "petroscope/serve/view_requests.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstdint>
#include <cstring>
#include <filesystem>

namespace petroscope::serve {
namespace {

const MineralCatalog& catalog() {
    static const MineralCatalog minerals = load_mineral_catalog(std::filesystem::path(PETROSCOPE_SOURCE_DIR) / "minerals");
    return minerals;
}

const LiveMicroscope& microscope() {
    static const LiveMicroscope live(catalog(), std::filesystem::path(PETROSCOPE_SOURCE_DIR) / "web",
                                     std::filesystem::path(PETROSCOPE_SOURCE_DIR) / "thin_sections");
    return live;
}

Reply get(const std::string& path, const std::vector<std::pair<std::string, std::string>>& query = {}) {
    return microscope().get(path, QueryParameters(query));
}

std::string error_of(const Reply& reply) {
    EXPECT_EQ(reply.status, 400) << reply.body;
    return nlohmann::json::parse(reply.body).value("error", "");
}

std::uint32_t header_word(const std::string& body, int index) {
    std::uint32_t word = 0;
    std::memcpy(&word, body.data() + 4 * index, 4);
    return word;
}

TEST(LiveMicroscope, ServesThePageAndNoOtherFile) {
    EXPECT_EQ(get("/").status, 200);
    EXPECT_EQ(get("/").content_type, "text/html; charset=utf-8");
    EXPECT_EQ(get("/microscope.js").content_type, "text/javascript; charset=utf-8");
    for (const std::string path : {"/../CMakeLists.txt", "/web/index.html", "/api/nothing", "/etc/passwd", "/index.html/"}) {
        EXPECT_EQ(get(path).status, 404) << path;
    }
}

TEST(LiveMicroscope, TheCatalogListsMineralsAndTheShippedSections) {
    const nlohmann::json catalog_json = nlohmann::json::parse(get("/api/catalog").body);
    EXPECT_EQ(catalog_json["minerals"].size(), catalog().minerals().size());
    for (const auto& mineral : catalog_json["minerals"]) {
        const bool active = mineral["name"] == "quartz" || mineral["name"] == "paratellurite";
        EXPECT_EQ(mineral["optically_active"].get<bool>(), active) << mineral["name"];
    }
    const std::vector<std::string> sections = catalog_json["sections"];
    EXPECT_NE(std::find(sections.begin(), sections.end(), "granite"), sections.end());
    EXPECT_EQ(sections.back(), "random");
}

// The bytes the page decodes are the library's harmonics: header, outside, then 15 floats per pixel.
TEST(LiveMicroscope, AViewIsTheLibrarysHarmonicsInTheDocumentedFormat) {
    const std::vector<std::pair<std::string, std::string>> query{{"mineral", "quartz"}, {"cut", "optic-axis"}, {"tilt_deg", "40"}, {"plate", "gypsum"}};
    const Reply reply = get("/api/view", query);
    ASSERT_EQ(reply.status, 200) << reply.body;
    EXPECT_EQ(reply.content_type, "application/octet-stream");
    EXPECT_EQ(header_word(reply.body, 0), 0x31485350u);
    EXPECT_EQ(header_word(reply.body, 1), static_cast<std::uint32_t>(kCrystalFieldPx));
    EXPECT_EQ(header_word(reply.body, 3), 0u);  // containing pixel
    const StageHarmonics expected =
        orthoscope_stage_harmonics(orthoscope_view_request(QueryParameters(query), catalog(), {}), catalog());
    ASSERT_EQ(reply.body, encode_stage_harmonics(expected));
    EXPECT_EQ(reply.body.size(), 16 + 4 * (kStageHarmonicChannels + expected.coefficients.pixels.size()));
}

TEST(LiveMicroscope, TheBertrandViewOfAPickedGrainIsThatGrainsFigure) {
    const Reply reply = get("/api/view", {{"optics", "conoscope"}, {"section", "granite"}, {"x", "100"}, {"y", "300"}, {"size_px", "64"}});
    ASSERT_EQ(reply.status, 200) << reply.body;
    EXPECT_EQ(header_word(reply.body, 1), 64u);
    EXPECT_EQ(header_word(reply.body, 3), 1u);  // bilinear
    const nlohmann::json grain = nlohmann::json::parse(get("/api/grain", {{"section", "granite"}, {"x", "100"}, {"y", "300"}}).body);
    EXPECT_TRUE(grain.contains("label"));
    EXPECT_GT(grain["retardation_nm"].get<double>(), 0.0);
    EXPECT_EQ(grain["thickness_um"].get<double>(), 30.0);
}

// The numbers name an optically active grain's form: a section grain's own, a single crystal's as chosen.
TEST(LiveMicroscope, TheNumbersNameTheFormOfAQuartzGrain) {
    const ThinSection granite = read_thin_section(std::filesystem::path(PETROSCOPE_SOURCE_DIR) / "thin_sections" / "granite", catalog());
    int quartz_grains = 0;
    for (int y = 8; y < granite.height_px && quartz_grains < 3; y += 64) {
        for (int x = 8; x < granite.width_px && quartz_grains < 3; x += 64) {
            const ThinSectionGrain& grain = granite.grain_at(x, y);
            const nlohmann::json numbers = nlohmann::json::parse(
                get("/api/grain", {{"section", "granite"}, {"x", std::to_string(x)}, {"y", std::to_string(y)}, {"handedness", "right"}}).body);
            if (grain.mineral != "quartz") {
                EXPECT_TRUE(numbers["handedness"].is_null()) << grain.mineral;
                continue;
            }
            ASSERT_TRUE(grain.handedness.has_value());
            EXPECT_EQ(numbers["handedness"], handedness_name(*grain.handedness));  // the section's, whatever the page chose
            ++quartz_grains;
        }
    }
    EXPECT_GE(quartz_grains, 1);
    for (const std::string hand : {"right", "left"}) {
        const nlohmann::json crystal = nlohmann::json::parse(get("/api/grain", {{"mineral", "quartz"}, {"cut", "optic-axis"}, {"handedness", hand}}).body);
        EXPECT_EQ(crystal["handedness"], hand);
    }
    EXPECT_TRUE(nlohmann::json::parse(get("/api/grain", {{"mineral", "calcite"}, {"handedness", "left"}}).body)["handedness"].is_null());
}

std::vector<UploadedFile> granite_files() {
    const std::filesystem::path folder = std::filesystem::path(PETROSCOPE_SOURCE_DIR) / "thin_sections" / "granite";
    return {{"description", "section.txt", read_text_file(folder / "section.txt")}, {"map", "grains.png", read_text_file(folder / "grains.png")}};
}

// A section sent to the server is the section read from its folder, viewed by the name it gets.
TEST(LiveMicroscope, ASectionSentIsTheSameSectionUnderANewName) {
    const Reply reply = microscope().post_section(granite_files());
    ASSERT_EQ(reply.status, 200) << reply.body;
    const std::string name = nlohmann::json::parse(reply.body)["section"];
    EXPECT_EQ(name.rfind("upload-", 0), 0u);
    const auto numbers = [&](const std::string& section) { return nlohmann::json::parse(get("/api/grain", {{"section", section}, {"x", "77"}, {"y", "301"}}).body); };
    EXPECT_EQ(numbers(name), numbers("granite"));
}

TEST(LiveMicroscope, ASectionSentMayNameOnlyTheFilesSentWithIt) {
    std::vector<UploadedFile> files = granite_files();
    const std::string original = files[0].content;
    files[0].content.replace(original.find("grain_map: grains.png"), 21, "grain_map: ../granite/grains.png");
    const Reply reply = microscope().post_section(files);
    EXPECT_NE(error_of(reply).find("'../granite/grains.png' was not sent with the description"), std::string::npos);
    EXPECT_EQ(error_of(get("/api/view", {{"section", "upload-999"}})).find("parameter 'section': no section 'upload-999'"), 0u);
}

TEST(LiveMicroscope, BadInputIsRefusedNamingTheParameter) {
    EXPECT_EQ(error_of(get("/api/view", {{"thickness_um", "-1"}})), "parameter 'thickness_um': expected a number from 0.01 to 1e+05, got '-1'");
    EXPECT_NE(error_of(get("/api/view", {{"section", "../../etc"}})).find("parameter 'section': expected one of"), std::string::npos);
    EXPECT_NE(error_of(get("/api/view", {{"mineral", "kryptonite\x1b[2J"}})).find("kryptonite\\x1b[2J"), std::string::npos);
    EXPECT_NE(error_of(get("/api/view", {{"size_px", "5000"}, {"optics", "conoscope"}})).find("parameter 'size_px'"), std::string::npos);
    EXPECT_NE(error_of(get("/api/view", {{"euler", "1,2"}})).find("parameter 'euler'"), std::string::npos);
    EXPECT_NE(error_of(get("/api/view", {{"handedness", "sideways"}, {"optics", "conoscope"}})).find("parameter 'handedness': expected one of right, left"),
              std::string::npos);
    EXPECT_NE(error_of(get("/api/view", {{"cut", "sideways"}})).find("parameter 'cut'"), std::string::npos);
    EXPECT_NE(error_of(get("/api/grain", {{"section", "granite"}, {"x", "512"}})).find("parameter 'x'"), std::string::npos);
    EXPECT_NE(error_of(get("/api/view", {{"analyzer", "maybe"}})).find("expected one of in, out"), std::string::npos);
    EXPECT_NE(error_of(get("/api/view", {{"zoom", "2"}})).find("unknown parameter 'zoom'"), std::string::npos);
    EXPECT_THROW(QueryParameters({{"plate", "mica"}, {"plate", "gypsum"}}), InputError);
}

}  // namespace
}  // namespace petroscope::serve
