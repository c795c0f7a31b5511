// The petroscope command-line tool, run as a user would: exit codes, messages, JSON output, and the promise
// that a failed command leaves no output and no temporary file behind.
#include "petroscope/core/image.hpp"
#include "petroscope/io/data_files.hpp"
#include "petroscope/io/image_writer.hpp"
#include "petroscope/minerals/mineral.hpp"

#include "support/cli_fixture.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <atomic>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
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

class Cli : public testing::CliFixture {};

const std::set<std::string> kMineralNames{
    "quartz", "calcite", "muscovite", "biotite", "forsterite", "fayalite", "augite", "hornblende", "albite",
    "anorthite", "orthoclase", "almandine", "aragonite", "gypsum", "topaz", "zircon", "tourmaline", "apatite",
    "kyanite", "sillimanite", "sapphire", "rutile", "KTP", "LBO", "KGd(WO4)2", "BBO", "LiNbO3", "YVO4", "KY(WO4)2",
    "labradorite", "basaltic glass", "canada balsam", "crown glass", "paratellurite"};

TEST_F(Cli, MineralsListsEveryShippedMineral) {
    const CommandResult run = petroscope("minerals");
    ASSERT_EQ(run.exit_code, 0) << run.err;
    std::istringstream lines(run.out);
    std::string line;
    std::getline(lines, line);  // header
    EXPECT_EQ(line.rfind("name", 0), 0u) << line;
    std::set<std::string> listed;
    int rows = 0;
    while (std::getline(lines, line)) {
        if (line.empty()) continue;
        ++rows;
        std::string name = line.substr(0, 14);  // the name column is 14 wide ("%-14s "); names may hold spaces
        name.erase(name.find_last_not_of(' ') + 1);
        listed.insert(name);
    }
    EXPECT_EQ(rows, 34);
    EXPECT_EQ(listed, kMineralNames);
}

TEST_F(Cli, MineralsShowJson) {
    const CommandResult run = petroscope("minerals show quartz --json");
    ASSERT_EQ(run.exit_code, 0) << run.err;
    const nlohmann::json quartz = nlohmann::json::parse(run.out);  // throws (fails the test) if not JSON
    for (const char* key : {"n_alpha", "n_beta", "n_gamma", "two_v_deg", "sign", "birefringence"}) {
        EXPECT_TRUE(quartz.contains(key)) << key;
    }
    EXPECT_EQ(quartz["name"], "quartz");
    ASSERT_EQ(quartz["optical_activity"].size(), 2u);
    EXPECT_EQ(quartz["optical_activity"][1]["key"], "rotatory_power_axis");
    EXPECT_NEAR(quartz["optical_activity"][1]["deg_per_mm_right_handed"].get<double>(), 21.72, 0.005);
    EXPECT_EQ(quartz["sign"], "+");
    EXPECT_EQ(quartz["two_v_deg"].get<double>(), 0.0);
    EXPECT_EQ(quartz["wavelength_nm"].get<double>(), 589.3);
    // The same numbers as the library (nlohmann writes doubles that read back exactly).
    const MineralCatalog catalog = load_mineral_catalog(PETROSCOPE_SOURCE_DIR "/minerals");
    const OpticalSummary summary = optical_summary(catalog.find("quartz"), 589.3);
    EXPECT_EQ(quartz["n_alpha"].get<double>(), summary.n_alpha);
    EXPECT_EQ(quartz["n_beta"].get<double>(), summary.n_beta);
    EXPECT_EQ(quartz["n_gamma"].get<double>(), summary.n_gamma);
    EXPECT_EQ(quartz["birefringence"].get<double>(), summary.birefringence);

    const CommandResult muscovite_run = petroscope("minerals show muscovite --json");
    ASSERT_EQ(muscovite_run.exit_code, 0) << muscovite_run.err;
    const nlohmann::json muscovite = nlohmann::json::parse(muscovite_run.out);
    EXPECT_NEAR(muscovite["two_v_deg"].get<double>(), 40.0, 1.0);
    EXPECT_EQ(muscovite["sign"], "-");

    const CommandResult at_500 = petroscope("minerals show quartz --wavelength 0.5um --json");
    ASSERT_EQ(at_500.exit_code, 0) << at_500.err;
    EXPECT_EQ(nlohmann::json::parse(at_500.out)["wavelength_nm"].get<double>(), 500.0);
}

// `petroscope serve` with an address it cannot listen on, or a port out of range: exit 2 with a message,
// instead of serving (203.0.113.7 is a documentation address, RFC 5737, never this machine's).
TEST_F(Cli, ServeRejectsAnAddressOrPortItCannotUse) {
    expect_rejected("serve --port 70000", {"--port"});
    expect_rejected("serve --host 203.0.113.7 --port 0", {"cannot listen on '203.0.113.7'"});
}

TEST_F(Cli, MineralsShowUnknownNameSuggests) {
    const CommandResult run = petroscope("minerals show quarz");
    EXPECT_NE(run.exit_code, 0);
    EXPECT_NE(run.err.find("quartz"), std::string::npos) << run.err;
}

TEST_F(Cli, MineralsShowRejectsWavelengthsWithoutFiniteIndices) {
    // Was a bug: `minerals show` had no check that the indices are finite (the conoscope has one): at 9 um, between
    // the poles of Ghosh's quartz formula (n^2 < 0), and at 1e306 um (the unit conversion overflows to inf, see
    // tests/core/test_units), it exits 0 and prints n_alpha = n_beta = n_gamma = null (NaN) with sign "-" for
    // quartz, which is optically positive. Expected: a non-zero exit with a message naming the wavelength.
    for (const std::string wavelength : {"9um", "1e306um"}) {
        SCOPED_TRACE(wavelength);
        const CommandResult run = petroscope("minerals show quartz --json --wavelength " + wavelength);
        EXPECT_NE(run.exit_code, 0) << run.out;
        EXPECT_EQ(run.out.find("null"), std::string::npos) << run.out;
    }
}

TEST_F(Cli, ConoscopeRejectsBadInputAndLeavesNoFiles) {
    const std::string png = " -o " + quoted(out() / "figure.png");
    const std::string quick = " --size 64 --wavelength 589nm";
    expect_rejected("conoscope --mineral quarz" + quick + png, {"quarz", "quartz"});
    expect_rejected("conoscope --thickness 0um" + quick + png, {"--thickness", "0um"});
    expect_rejected("conoscope --thickness -5um" + quick + png, {"-5um"});
    expect_rejected("conoscope --thickness=-5um" + quick + png, {"-5um"});
    expect_rejected("conoscope --thickness 30" + quick + png, {"'30'", "unit"});
    expect_rejected("conoscope --na 0" + quick + png, {"numerical aperture"});
    expect_rejected("conoscope --na 1.2" + quick + png, {"numerical aperture"});
    expect_rejected("conoscope --size 32 --wavelength 589nm" + png, {"size", "32"});
    expect_rejected("conoscope --size 5000 --wavelength 589nm" + png, {"size", "5000"});
    expect_rejected("conoscope" + quick + " -o " + quoted(out() / "figure.jpg"), {"'.jpg'"});
    expect_rejected("conoscope --mineral calcite --cut acute-bisectrix" + quick + png, {"acute-bisectrix", "biaxial"});
    // Failures found only after the output files were reserved: the temporaries must be removed.
    expect_rejected("conoscope --cut sideways" + quick + png, {"sideways"});
    expect_rejected("conoscope --size 64 --illuminant D50" + png, {"D50"});
    expect_rejected("conoscope --wavelength green --size 64" + png, {"green"});
}

TEST_F(Cli, ConoscopeRejectsAMalformedMineralFile) {
    const fs::path minerals = scratch() / "minerals";
    fs::create_directories(minerals);
    std::ofstream(minerals / "broken.txt") << "name: broken\nsystem cubic\nclass: isotropic\n";
    expect_rejected("--minerals-dir " + quoted(minerals) + " conoscope --size 64 --wavelength 589nm -o " +
                        quoted(out() / "figure.png"),
                    {"broken.txt:2:"});
}

TEST_F(Cli, ConoscopeRejectsUnwritableOutputs) {
    const fs::path missing = scratch() / "no-such-folder";
    expect_rejected("conoscope --size 64 --wavelength 589nm -o " + quoted(missing / "figure.png"), {"does not exist"});
    EXPECT_FALSE(fs::exists(missing));
    // An output name that is a folder.
    fs::create_directories(out() / "taken.png");
    expect_rejected("conoscope --size 64 --wavelength 589nm -o " + quoted(out() / "taken.png"), {"folder"});
    EXPECT_TRUE(fs::is_directory(out() / "taken.png"));
}

TEST_F(Cli, ConoscopeWritesPngAndSidecar) {
    const fs::path png = out() / "calcite.png";
    const CommandResult run = petroscope("conoscope --mineral calcite --size 64 --wavelength 589nm -o " + quoted(png));
    ASSERT_EQ(run.exit_code, 0) << run.err;
    EXPECT_EQ(listing(out()), (std::set<std::string>{"calcite.png", "calcite.png.json"}));

    const nlohmann::json sidecar = nlohmann::json::parse(read_text(out() / "calcite.png.json"));
    EXPECT_EQ(sidecar["thickness_um"].get<double>(), 30.0);
    EXPECT_EQ(sidecar["mineral"]["name"], "calcite");
    EXPECT_EQ(sidecar["size_px"].get<int>(), 64);
    EXPECT_EQ(sidecar["light"]["mode"], "monochromatic");
    EXPECT_EQ(sidecar["light"]["wavelength_nm"].get<double>(), 589.0);
    EXPECT_EQ(sidecar["orientation"]["cut"], "optic-axis");  // the default for a uniaxial mineral

    const Image image = read_image(png);
    EXPECT_EQ(image.width, 64);
    EXPECT_EQ(image.height, 64);
    ASSERT_EQ(image.channels, 3);
    bool grey = true, in_range = true, any_light = false;
    for (int y = 0; y < image.height; ++y) {
        for (int x = 0; x < image.width; ++x) {
            const float r = image.at(x, y, 0);
            grey = grey && r == image.at(x, y, 1) && r == image.at(x, y, 2);  // monochromatic: equal channels
            in_range = in_range && r >= 0.0f && r <= 1.0f;
            any_light = any_light || r > 0.1f;
        }
    }
    EXPECT_TRUE(grey);
    EXPECT_TRUE(in_range);
    EXPECT_TRUE(any_light);
    EXPECT_EQ(image.at(0, 0, 0), 0.0f);  // outside the aperture circle
}

TEST_F(Cli, ConoscopeWritesFloatExr) {
    const fs::path exr = out() / "figure.exr";
    const CommandResult run = petroscope("conoscope --size 64 -o " + quoted(exr));
    ASSERT_EQ(run.exit_code, 0) << run.err;
    EXPECT_EQ(listing(out()), (std::set<std::string>{"figure.exr", "figure.exr.json"}));
    const Image image = read_image(exr);
    EXPECT_EQ(image.width, 64);
    EXPECT_EQ(image.height, 64);
    ASSERT_EQ(image.channels, 3);
    // Luminance: Y = 0.2126 R + 0.7152 G + 0.0722 B (IEC 61966-2-1) recovers the Y of the transmitted light,
    // which cannot exceed that of the white (T <= 1 at every wavelength between crossed polars) nor be negative.
    // 1e-3 covers the 4-digit sRGB matrices (inverse to ~1e-4) and float storage.
    double lowest_y = 1.0, highest_y = 0.0;
    for (int y = 0; y < image.height; ++y) {
        for (int x = 0; x < image.width; ++x) {
            const double luminance = 0.2126 * image.at(x, y, 0) + 0.7152 * image.at(x, y, 1) + 0.0722 * image.at(x, y, 2);
            lowest_y = std::min(lowest_y, luminance);
            highest_y = std::max(highest_y, luminance);
        }
    }
    EXPECT_GE(lowest_y, -1e-3);
    EXPECT_LE(highest_y, 1.0 + 1e-3);
    EXPECT_GT(highest_y, 0.1);  // not a black image
    EXPECT_EQ(image.at(0, 0, 0), 0.0f);  // outside the aperture circle
    const nlohmann::json sidecar = nlohmann::json::parse(read_text(out() / "figure.exr.json"));
    EXPECT_EQ(sidecar["light"]["mode"], "white");
    EXPECT_EQ(sidecar["mineral"]["name"], "muscovite");
}

TEST_F(Cli, ConoscopeExactSpectrumSolvesEveryWavelengthAndSaysSo) {
    const fs::path interpolated = out() / "interpolated.exr", exact = out() / "exact.exr";
    const CommandResult first = petroscope("conoscope --mineral calcite --thickness 300um --size 64 -o " + quoted(interpolated));
    const CommandResult second = petroscope("conoscope --mineral calcite --thickness 300um --size 64 --exact-spectrum -o " + quoted(exact));
    ASSERT_EQ(first.exit_code, 0) << first.err;
    ASSERT_EQ(second.exit_code, 0) << second.err;
    const Image a = read_image(interpolated), b = read_image(exact);
    ASSERT_EQ(a.pixels.size(), b.pixels.size());
    double largest = 0.0;
    for (std::size_t i = 0; i < a.pixels.size(); ++i) largest = std::max(largest, static_cast<double>(std::abs(a.pixels[i] - b.pixels[i])));
    // The library's tests measure at most ΔE₀₀ = 6e-3 between the two (tests/microscope/test_conoscope_spectrum.cpp).
    EXPECT_LT(largest, 1e-4);
    const auto spectrum = [this](const char* name) {
        return nlohmann::json::parse(read_text(out() / (std::string(name) + ".exr.json")))["spectrum"].get<std::string>();
    };
    EXPECT_NE(spectrum("interpolated").find("interpolated"), std::string::npos);
    EXPECT_EQ(spectrum("exact"), "every wavelength solved (--exact-spectrum)");
}

TEST_F(Cli, ConoscopeOfQuartzUsesItsOpticalActivityAndHandedness) {
    // The sidecar names the form and its rotatory power along Z (c) at 589.3 nm, 21.72 deg/mm, positive for the
    // right-handed form; an unknown handedness is refused.
    const auto sidecar = [this](const std::string& extra, const char* name) {
        const fs::path image = out() / (std::string(name) + ".exr");
        const CommandResult run = petroscope("conoscope --size 64 --wavelength 589.3nm " + extra + " -o " + quoted(image));
        EXPECT_EQ(run.exit_code, 0) << run.err;
        return std::pair{nlohmann::json::parse(read_text(out() / (std::string(name) + ".exr.json"))), run};
    };
    const auto [right, right_run] = sidecar("--mineral quartz --thickness 1mm", "right");
    EXPECT_EQ(right["optical_activity"]["handedness"], "right");
    EXPECT_NEAR(right["optical_activity"]["rotatory_power_deg_per_mm_xyz_at_reference"][2].get<double>(), 21.72, 0.005);
    EXPECT_EQ(right["spectrum"], "every wavelength solved");
    const auto [left, left_run] = sidecar("--mineral quartz --thickness 1mm --handedness left", "left");
    EXPECT_EQ(left["optical_activity"]["handedness"], "left");
    EXPECT_NEAR(left["optical_activity"]["rotatory_power_deg_per_mm_xyz_at_reference"][2].get<double>(), -21.72, 0.005);
    const auto [calcite, calcite_run] = sidecar("--mineral calcite --handedness left", "calcite");
    EXPECT_TRUE(calcite["optical_activity"].is_null());
    EXPECT_NE(calcite_run.err.find("not optically active"), std::string::npos) << calcite_run.err;
    const std::string png = " -o " + quoted(out() / "x.png");
    expect_rejected("conoscope --mineral quartz --size 64 --handedness sideways" + png, {"--handedness", "'sideways'", "expected right or left"});
    // The mounted section carries the activity too: its centre is lit between crossed polars.
    const fs::path stack = out() / "stack.exr";
    const CommandResult mounted = petroscope("conoscope --mineral quartz --thickness 1mm --size 64 --wavelength 589.3nm --stack -o " + quoted(stack));
    ASSERT_EQ(mounted.exit_code, 0) << mounted.err;
    EXPECT_GT(read_image(stack).at(32, 32, 0), 0.1);
}

// ---- petroscope interface and verify (issue 3) ----

TEST_F(Cli, InterfacePrintsEveryWaveAsJson) {
    const CommandResult run = petroscope("interface --case " + quoted(fs::path(PETROSCOPE_SOURCE_DIR) / "verification/cases/brewster-s.json") + " --json");
    ASSERT_EQ(run.exit_code, 0) << run.err;
    const nlohmann::json result = nlohmann::json::parse(run.out);
    ASSERT_EQ(result["waves"].size(), 2u);
    double total = 0.0;
    for (const auto& wave : result["waves"]) {
        for (const char* key : {"kind", "mode", "direction", "ray_direction", "n", "power", "stokes", "evanescent"}) EXPECT_TRUE(wave.contains(key)) << key;
        total += wave["power"].get<double>();
    }
    EXPECT_NEAR(total, 1.0, 1e-12);
    // Brewster, s light: partly reflected (0.1479), the rest refracted.
    EXPECT_NEAR(result["waves"][0]["power"].get<double>(), 0.14792899408284, 1e-12);
    const CommandResult table = petroscope("interface --case " + quoted(fs::path(PETROSCOPE_SOURCE_DIR) / "verification/cases/brewster-s.json"));
    EXPECT_EQ(table.exit_code, 0);
    EXPECT_NE(table.out.find("sum of powers"), std::string::npos);
}

TEST_F(Cli, InterfaceRejectsBadCasesNamingTheKey) {
    const std::string good_incident = R"("incident": {"direction": [0, 0, 1], "polarization": "s"})";
    const auto run_case = [&](const std::string& name, const std::string& text) {
        const fs::path file = out() / name;
        std::ofstream(file) << text;
        return petroscope("interface --case " + quoted(file));
    };
    const std::vector<std::tuple<std::string, std::string, std::vector<std::string>>> cases{
        {"syntax.json", "{\"wavelength_nm\": 589.3,", {"syntax.json", "invalid JSON"}},
        {"missing.json", R"({"wavelength_nm": 589.3, "normal": [0,0,1], "incident": {"polarization": "s"}, "medium1": {"n": 1}, "medium2": {"n": 1.5}})",
         {"missing.json", "incident.direction", "missing"}},
        {"zero.json", R"({"wavelength_nm": 589.3, "normal": [0,0,0], )" + good_incident + R"(, "medium1": {"n": 1}, "medium2": {"n": 1.5}})",
         {"zero.json", "normal", "non-zero"}},
        {"side.json", R"({"wavelength_nm": 589.3, "normal": [0,0,1], "incident": {"direction": [0,0,-1], "polarization": "s"}, "medium1": {"n": 1}, "medium2": {"n": 1.5}})",
         {"side.json", "incident.direction", "medium 1 into medium 2"}},
        {"index.json", R"({"wavelength_nm": 589.3, "normal": [0,0,1], )" + good_incident + R"(, "medium1": {"n": 1}, "medium2": {"n": -1.5}})",
         {"index.json", "medium2.n", "n > 0"}},
        {"polarization.json", R"({"wavelength_nm": 589.3, "normal": [0,0,1], "incident": {"direction": [0,0,1], "polarization": "sideways"}, "medium1": {"n": 1}, "medium2": {"n": 1.5}})",
         {"polarization.json", "incident.polarization"}},
        {"mineral.json", R"({"wavelength_nm": 589.3, "normal": [0,0,1], )" + good_incident + R"(, "medium1": {"n": 1}, "medium2": {"mineral": "calcyte"}})",
         {"mineral.json", "medium2.mineral", "calcite"}},
        {"nan.json", R"({"wavelength_nm": 589.3, "normal": [0,0,"x"], )" + good_incident + R"(, "medium1": {"n": 1}, "medium2": {"n": 1.5}})",
         {"nan.json", "normal[2]", "expected a number"}},
        {"hand-inactive.json", R"({"wavelength_nm": 589.3, "normal": [0,0,1], )" + good_incident + R"(, "medium1": {"n": 1}, "medium2": {"mineral": "calcite", "handedness": "left"}})",
         {"hand-inactive.json", "medium2.handedness", "not optically active"}},
        {"hand-value.json", R"({"wavelength_nm": 589.3, "normal": [0,0,1], )" + good_incident + R"(, "medium1": {"n": 1}, "medium2": {"mineral": "quartz", "handedness": "sideways"}})",
         {"hand-value.json", "medium2.handedness", "expected right or left"}},
        {"hand-index.json", R"({"wavelength_nm": 589.3, "normal": [0,0,1], )" + good_incident + R"(, "medium1": {"n": 1}, "medium2": {"n": 1.5, "handedness": "right"}})",
         {"hand-index.json", "medium2.handedness", "rotatory_power_deg_per_mm"}},
        {"rho-mineral.json", R"({"wavelength_nm": 589.3, "normal": [0,0,1], )" + good_incident + R"(, "medium1": {"n": 1}, "medium2": {"mineral": "quartz", "rotatory_power_deg_per_mm": [1, 1, 1]}})",
         {"rho-mineral.json", "medium2.rotatory_power_deg_per_mm", "record"}},
        {"rho-range.json", R"({"wavelength_nm": 589.3, "normal": [0,0,1], )" + good_incident + R"(, "medium1": {"n": 1}, "medium2": {"n": 1.5, "rotatory_power_deg_per_mm": [2e4, 0, 0]}})",
         {"rho-range.json", "medium2.rotatory_power_deg_per_mm", "10000"}},
        {"active-mode.json", R"({"wavelength_nm": 589.3, "normal": [0,0,1], "incident": {"direction": [0,0,1], "polarization": "ordinary"}, "medium1": {"mineral": "quartz"}, "medium2": {"n": 1}})",
         {"active-mode.json", "incident.polarization", "optically active", "\"fast\" or \"slow\""}},
    };
    for (const auto& [name, text, expected] : cases) {
        SCOPED_TRACE(name);
        const CommandResult run = run_case(name, text);
        EXPECT_NE(run.exit_code, 0);
        EXPECT_NE(run.exit_code, -1);
        for (const std::string& fragment : expected) EXPECT_NE(run.err.find(fragment), std::string::npos) << fragment << " not in: " << run.err;
    }
}

TEST_F(Cli, VerifyPassesEveryTestAndReportsJson) {
    const CommandResult run = petroscope("verify --json");
    ASSERT_EQ(run.exit_code, 0) << run.out.substr(0, 2000) << run.err;
    const nlohmann::json report = nlohmann::json::parse(run.out);
    EXPECT_GE(report["tests"].size(), 50u);
    EXPECT_EQ(report["failed"].get<int>(), 0);
    for (const auto& test : report["tests"]) {
        for (const char* key : {"name", "statement", "passed", "checks"}) EXPECT_TRUE(test.contains(key)) << key;
        EXPECT_TRUE(test["passed"].get<bool>()) << test["name"];
    }
    const CommandResult text = petroscope("verify");
    EXPECT_EQ(text.exit_code, 0);
    EXPECT_NE(text.out.find(", 0 failed"), std::string::npos);
}

TEST_F(Cli, VerifyExitsNonZeroWhenACaseFails) {
    // A case whose expected reflectance is wrong (normal incidence 1 → 1.5 reflects 0.04, not 0.05).
    const fs::path cases = scratch() / "cases";
    fs::create_directories(cases);
    std::ofstream(cases / "wrong.json") << R"({"name": "wrong", "wavelength_nm": 589.3, "normal": [0,0,1],
        "incident": {"direction": [0,0,1], "polarization": "s"}, "medium1": {"n": 1}, "medium2": {"n": 1.5},
        "expected": {"waves": [{"kind": "reflected", "mode": "s+p", "power": 0.05, "tolerance": {"power": 1e-12}}]}})";
    const CommandResult run = petroscope("verify --cases " + quoted(cases));
    EXPECT_EQ(run.exit_code, 1);
    EXPECT_NE(run.out.find("FAIL  wrong"), std::string::npos) << run.out.substr(0, 500);
}

// ---- petroscope conical (issue 5) ----

TEST_F(Cli, ConicalWritesTheRingAndItsNumbers) {
    for (const std::string mode : {"wave", "ray"}) {
        const fs::path image = out() / (mode + ".png");
        const CommandResult run = petroscope("conical --crystal KGW --length 20mm --wavelength 633nm --mode " + mode +
                                             " --filter 50mm --rays 20000 --size 128 -o " + quoted(image));
        ASSERT_EQ(run.exit_code, 0) << run.err;
        const nlohmann::json sidecar = nlohmann::json::parse(read_text(fs::path(image.string() + ".json")));
        EXPECT_NEAR(sidecar["cone_angle_chi_deg"].get<double>(), 2.012, 1e-3);
        EXPECT_NEAR(sidecar["A_rad"].get<double>() * 1000.0, 17.57, 5e-3);
        EXPECT_NEAR(sidecar["R0_um"].get<double>(), 351.35, 0.05);
        for (const char* key : {"outer_bright", "dark", "inner_bright"}) EXPECT_TRUE(sidecar["rings"].contains(key)) << key;
        EXPECT_TRUE(fs::exists(image));
    }
}

TEST_F(Cli, ConicalRejectsBadInput) {
    const std::string output = " -o " + quoted(out() / "ring.png");
    expect_rejected("conical --crystal calcite" + output, {"calcite", "biaxial"});
    expect_rejected("conical --length 0mm" + output, {"--length"});
    expect_rejected("conical --length -5mm" + output, {"--length"});
    expect_rejected("conical --waist 0um" + output, {"--waist"});
    expect_rejected("conical --mode ray --screen-distance -1mm" + output, {"--screen-distance"});
    expect_rejected("conical --mode ray --rays 20000000" + output, {"--rays 20000000", "above 1e7", "--allow-large"});
    expect_rejected("conical --mode ray --pinhole 30mm --length 20mm" + output, {"pinhole", "larger than the slab"});
    expect_rejected("conical --polarization sideways" + output, {"--polarization"});
    expect_rejected("conical --mode particle" + output, {"--mode"});
    // An optically active biaxial crystal: the rings would ignore its activity.
    const fs::path minerals = scratch() / "active-minerals";
    fs::create_directories(minerals);
    std::ofstream(minerals / "active-kgw.txt") << read_text(fs::path(PETROSCOPE_SOURCE_DIR) / "minerals" / "kgd-wo4-2.txt")
                                               << "\nrotatory_power_x: constant 5\nrotatory_power_x.source: test\nrotatory_power_y: constant 5\n"
                                                  "rotatory_power_y.source: test\nrotatory_power_z: constant 5\nrotatory_power_z.source: test\n";
    expect_rejected("--minerals-dir " + quoted(minerals) + " conical --crystal KGW" + output, {"KGd(WO4)2", "optically active", "conical"});
}

}  // namespace
}  // namespace petroscope

namespace petroscope {
namespace {

const std::string kGranite = quoted(fs::path(PETROSCOPE_SOURCE_DIR) / "thin_sections" / "granite");

TEST_F(Cli, OrthoscopeWritesImageAndSidecar) {
    const fs::path png = out() / "granite.png";
    const CommandResult run = petroscope("orthoscope --section " + kGranite + " --stage-deg 30 --plate gypsum --wavelengths 400:700:10 -o " + quoted(png));
    ASSERT_EQ(run.exit_code, 0) << run.err;
    EXPECT_EQ(listing(out()), (std::set<std::string>{"granite.png", "granite.png.json"}));
    const nlohmann::json sidecar = nlohmann::json::parse(read_text(out() / "granite.png.json"));
    EXPECT_EQ(sidecar["command"], "orthoscope");
    EXPECT_EQ(sidecar["stage_deg"].get<double>(), 30.0);
    EXPECT_EQ(sidecar["plate"]["kind"], "gypsum");
    EXPECT_EQ(sidecar["plate"]["slow_deg"].get<double>(), 45.0);
    EXPECT_EQ(sidecar["view"], "crossed polars");
    EXPECT_EQ(sidecar["light"]["wavelengths_nm"]["count"].get<int>(), 31);
    const Image image = read_image(png);
    EXPECT_EQ(image.width, sidecar["section"]["size_px"][0].get<int>());
    EXPECT_EQ(image.height, sidecar["section"]["size_px"][1].get<int>());
}

TEST_F(Cli, OrthoscopeRejectsBadInputAndLeavesNoFiles) {
    const std::string png = quoted(out() / "x.png");
    expect_rejected("orthoscope --section " + quoted(scratch() / "missing") + " -o " + png, {"missing"});
    expect_rejected("orthoscope --section " + kGranite + " --plate lambda -o " + png, {"--plate", "gypsum, mica or wedge"});
    expect_rejected("orthoscope --section " + kGranite + " --plate wedge --wedge-position 1.5 -o " + png, {"wedge position", "0 to 1"});
    expect_rejected("orthoscope --section " + kGranite + " --condenser-na 1.2 -o " + png, {"condenser NA", "0 <= NA < 1"});
    expect_rejected("orthoscope --section " + kGranite + " --thickness 30 -o " + png, {"--thickness"});
    expect_rejected("orthoscope --section " + kGranite + " --ppl --xpl -o " + png, {"excludes"});
    expect_rejected("orthoscope --section " + kGranite + " --condenser-na 0.2 --condenser-rings 65 -o " + png, {"--condenser-rings", "0 (automatic) to 64"});
    expect_rejected("orthoscope --section " + kGranite + " --exposure 0 -o " + png, {"--exposure"});
    expect_rejected("orthoscope --section " + kGranite + " -o " + quoted(out() / "x.jpg"), {"x.jpg"});
}

// A section file of random bytes (a terminal escape, control characters, bytes that are not UTF-8, one
// line of 5000 bytes): the message names the file and quotes the line escaped and cut.
TEST_F(Cli, ASectionOfRandomBytesIsQuotedSafely) {
    std::string noise = "\x1b[2J\x1b]0;owned\x07";
    std::mt19937 random(7);
    for (int i = 0; i < 5000; ++i) {
        const auto byte = static_cast<char>(random() % 256);
        noise += byte == '\n' ? '\0' : byte;  // one line
    }
    const fs::path file = scratch() / "noise.txt";
    std::ofstream(file, std::ios::binary) << noise;
    const std::string png = quoted(out() / "x.png");
    expect_rejected("orthoscope --section " + quoted(file) + " -o " + png, {"noise.txt", "\\x1b[2J", "bytes)"});
    const CommandResult run = petroscope("orthoscope --section " + quoted(file) + " -o " + png);
    EXPECT_LT(run.err.size(), 600u) << run.err;
    for (const char c : run.err) {
        const auto byte = static_cast<unsigned char>(c);
        EXPECT_TRUE(byte == '\n' || (byte >= 0x20 && byte != 0x7F)) << "raw byte " << int(byte) << " in: " << run.err;
    }
}

TEST_F(Cli, ConoscopeThroughTheWholeStack) {
    const fs::path png = out() / "stack.png";
    const CommandResult run = petroscope("conoscope --mineral calcite --size 64 --wavelength 589nm --exact -o " + quoted(png));
    ASSERT_EQ(run.exit_code, 0) << run.err;
    const nlohmann::json sidecar = nlohmann::json::parse(read_text(out() / "stack.png.json"));
    EXPECT_EQ(sidecar["mounting"]["cover_um"].get<double>(), 170.0);
    EXPECT_TRUE(sidecar["surround_n"].is_null());
    EXPECT_NE(sidecar["model"].get<std::string>().find("exact coherent 4x4"), std::string::npos);
    expect_rejected("conoscope --stack --surround-n 1.6 -o " + quoted(out() / "x.png"), {"excludes"});
}

// The chart's CSV: one row per retardation step, black at Γ = 0, first-order red near 550 nm (the least
// luminous colour of the first order's end).
TEST_F(Cli, ChartWritesImageCsvAndSidecar) {
    const fs::path png = out() / "chart.png", csv = out() / "chart.csv";
    const CommandResult run = petroscope("chart --max-retardation 1000 --step 5 --csv " + quoted(csv) + " -o " + quoted(png));
    ASSERT_EQ(run.exit_code, 0) << run.err;
    EXPECT_EQ(listing(out()), (std::set<std::string>{"chart.png", "chart.png.json", "chart.csv"}));
    std::istringstream lines(read_text(csv));
    std::string line;
    std::getline(lines, line);
    EXPECT_EQ(line, "retardation_nm,thickness_um,X,Y,Z,x,y,sR,sG,sB,sR8,sG8,sB8");
    std::vector<std::pair<double, double>> luminance;  // (Γ, Y)
    while (std::getline(lines, line)) {
        std::istringstream fields(line);
        std::string gamma, thickness, x, y;
        std::getline(fields, gamma, ',');
        std::getline(fields, thickness, ',');
        std::getline(fields, x, ',');
        std::getline(fields, y, ',');
        luminance.emplace_back(std::stod(gamma), std::stod(y));
    }
    ASSERT_EQ(luminance.size(), 201u);
    EXPECT_LT(luminance[0].second, 1e-6);
    const auto darkest = std::min_element(luminance.begin() + 60, luminance.begin() + 140,
                                          [](const auto& a, const auto& b) { return a.second < b.second; });
    EXPECT_NEAR(darkest->first, 550.0, 40.0);
    expect_rejected("chart --step 0 -o " + quoted(out() / "bad.png"), {"retardation step"});
    expect_rejected("chart --mineral almandine -o " + quoted(out() / "bad.png"), {"isotropic"});
    expect_rejected("chart --max-thickness 0um -o " + quoted(out() / "bad.png"), {"--max-thickness", "must be > 0"});
    expect_rejected("chart --max-retardation 30000 -o " + quoted(out() / "bad.png"), {"maximum retardation", "0 < max <= 20000"});
    // An unwritable CSV fails before any work, and the image is not left behind either.
    expect_rejected("chart --csv " + quoted(out() / "no-such-folder" / "c.csv") + " -o " + quoted(out() / "bad.png"), {"no-such-folder"});
}

}  // namespace
}  // namespace petroscope
