// The shipped mineral catalog (minerals/*.txt, read by load_mineral_catalog) and MineralCatalog lookup.
#include "petroscope/minerals/mineral_catalog.hpp"

#include "petroscope/core/error.hpp"
#include "petroscope/io/data_files.hpp"
#include "petroscope/minerals/mineral.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>
#include <numbers>
#include <set>
#include <string>
#include <unistd.h>

namespace petroscope {
namespace {

namespace fs = std::filesystem;

// A fresh folder under the system temporary directory, removed with everything in it at scope exit.
class TemporaryFolder {
public:
    TemporaryFolder() {
        static std::atomic<int> counter{0};
        const auto* test = ::testing::UnitTest::GetInstance()->current_test_info();
        path_ = fs::temp_directory_path() /
                ("petroscope-test-" + std::to_string(::getpid()) + "-" + std::to_string(counter++) + "-" +
                 (test ? std::string(test->name()) : std::string("suite")));
        fs::create_directories(path_);
    }
    ~TemporaryFolder() {
        std::error_code ignored;
        fs::remove_all(path_, ignored);
    }
    TemporaryFolder(const TemporaryFolder&) = delete;
    TemporaryFolder& operator=(const TemporaryFolder&) = delete;

    const fs::path& path() const { return path_; }
    fs::path write(const std::string& name, const std::string& text) const {
        const fs::path file = path_ / name;
        std::ofstream(file, std::ios::binary) << text;
        return file;
    }

private:
    fs::path path_;
};

std::string record(const std::string& name, const std::string& extra = "") {
    return "name: " + name + "\n" + extra + "system: cubic\nclass: isotropic\nn: constant 1.5\nn.source: test\n";
}

class ShippedCatalog : public ::testing::Test {
protected:
    static void SetUpTestSuite() {
        catalog_ = std::make_unique<MineralCatalog>(load_mineral_catalog(PETROSCOPE_SOURCE_DIR "/minerals"));
    }
    static void TearDownTestSuite() { catalog_.reset(); }
    static const MineralCatalog& catalog() { return *catalog_; }

private:
    static std::unique_ptr<MineralCatalog> catalog_;
};
std::unique_ptr<MineralCatalog> ShippedCatalog::catalog_;

TEST_F(ShippedCatalog, HoldsTheShippedMinerals) {
    // The 28 of issue 2, KY(WO4)2 for conical refraction (issue 5), for thin sections (issue 4) labradorite,
    // basaltic glass, and the mounting media canada balsam and crown glass, and the second optically active crystal,
    // paratellurite (issue 19).
    const std::set<std::string> expected{
        "quartz", "calcite", "muscovite", "biotite", "forsterite", "fayalite", "augite", "hornblende", "albite",
        "anorthite", "orthoclase", "almandine", "aragonite", "gypsum", "topaz", "zircon", "tourmaline", "apatite",
        "kyanite", "sillimanite", "sapphire", "rutile", "KTP", "LBO", "KGd(WO4)2", "BBO", "LiNbO3", "YVO4", "KY(WO4)2",
        "labradorite", "basaltic glass", "canada balsam", "crown glass", "paratellurite"};
    ASSERT_EQ(expected.size(), 34u);
    std::set<std::string> names;
    for (const Mineral& mineral : catalog().minerals()) names.insert(mineral.name);
    EXPECT_EQ(names, expected);
    EXPECT_EQ(catalog().minerals().size(), 34u);
    // Sorted by name, case-insensitively (the order `petroscope minerals` prints).
    EXPECT_TRUE(std::is_sorted(catalog().minerals().begin(), catalog().minerals().end(), [](const Mineral& a, const Mineral& b) {
        std::string x = a.name, y = b.name;
        std::transform(x.begin(), x.end(), x.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
        std::transform(y.begin(), y.end(), y.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
        return x < y;
    }));
}

TEST_F(ShippedCatalog, FindIsCaseInsensitiveAndKnowsAliases) {
    EXPECT_EQ(catalog().find("quartz").name, "quartz");
    EXPECT_EQ(catalog().find("QUARTZ").name, "quartz");
    EXPECT_EQ(catalog().find("Quartz").name, "quartz");
    EXPECT_EQ(catalog().find("  quartz ").name, "quartz");
    EXPECT_EQ(catalog().find("garnet").name, "almandine");
    EXPECT_EQ(catalog().find("KGW").name, "KGd(WO4)2");
    EXPECT_EQ(catalog().find("kgw").name, "KGd(WO4)2");
    EXPECT_EQ(catalog().find("kgd(wo4)2").name, "KGd(WO4)2");
    EXPECT_EQ(catalog().find("corundum").name, "sapphire");
    EXPECT_EQ(catalog().find("iceland spar").name, "calcite");
    EXPECT_EQ(catalog().find("Iceland Spar").name, "calcite");
    EXPECT_EQ(catalog().find("bbo").name, "BBO");
}

TEST_F(ShippedCatalog, UnknownNameSuggestsTheCloseOne) {
    try {
        catalog().find("quarz");
        FAIL() << "no error for 'quarz'";
    } catch (const InputError& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find("'quarz'"), std::string::npos) << message;
        EXPECT_NE(message.find("did you mean quartz"), std::string::npos) << message;
    }
    try {
        catalog().find("unobtainium");
        FAIL() << "no error for 'unobtainium'";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("'unobtainium'"), std::string::npos) << e.what();
    }
}

TEST_F(ShippedCatalog, OpticalSummariesMatchTheHandbooks) {
    // Muscovite: optically negative, 2Vx = 40° (Deer, Howie & Zussman; the record's n_beta is chosen for it).
    const OpticalSummary muscovite = optical_summary(catalog().find("muscovite"), 589.3);
    ASSERT_TRUE(muscovite.two_v_deg.has_value());
    EXPECT_NEAR(*muscovite.two_v_deg, 40.0, 1.0);
    EXPECT_EQ(muscovite.sign, "-");
    EXPECT_NEAR(muscovite.birefringence, muscovite.n_gamma - muscovite.n_alpha, 1e-15);

    // Quartz: uniaxial positive.
    const OpticalSummary quartz = optical_summary(catalog().find("quartz"), 589.3);
    EXPECT_EQ(quartz.sign, "+");
    ASSERT_TRUE(quartz.two_v_deg.has_value());
    EXPECT_EQ(*quartz.two_v_deg, 0.0);
    // Ghosh (1999) via refractiveindex.info: ω = 1.54421, ε = 1.55331 at 589.3 nm (tests/optics/test_dispersion).
    EXPECT_NEAR(quartz.n_alpha, 1.5442057387841213, 1e-12);
    EXPECT_NEAR(quartz.n_gamma, 1.5533057742676768, 1e-12);

    // Calcite: uniaxial negative.
    EXPECT_EQ(optical_summary(catalog().find("calcite"), 589.3).sign, "-");

    // Almandine: isotropic, no 2V and no sign.
    const OpticalSummary almandine = optical_summary(catalog().find("almandine"), 589.3);
    EXPECT_FALSE(almandine.two_v_deg.has_value());
    EXPECT_EQ(almandine.sign, "");
    EXPECT_EQ(almandine.birefringence, 0.0);
}

TEST_F(ShippedCatalog, KgwIndicesAt633nm) {
    // Loiko et al., Appl. Opt. 51, 2951 (2012): np, nm, ng = 2.0135, 2.0458, 2.0860 at 632.8 nm. The record's
    // Cauchy A is set so that n(632.8 nm) equals these to 1e-8; at 633 nm the assumed dispersion
    // (B = 0.0143 µm²) shifts n by 2B·Δλ/λ³ = 2.3e-5, so 5e-5 bounds the difference.
    const Mineral& kgw = catalog().find("KGW");
    for (const auto& [wavelength, tolerance] : std::vector<std::pair<double, double>>{{632.8, 1e-8}, {633.0, 5e-5}}) {
        SCOPED_TRACE(wavelength);
        Eigen::Vector3d n = kgw.principal_n(wavelength);
        std::sort(n.data(), n.data() + 3);
        EXPECT_NEAR(n[0], 2.0135, tolerance);
        EXPECT_NEAR(n[1], 2.0458, tolerance);
        EXPECT_NEAR(n[2], 2.0860, tolerance);
    }
}

TEST_F(ShippedCatalog, QuartzRotatoryPowerReproducesLowrysTableWithinTheStatedResidual) {
    // Lowry, Phil. Trans. R. Soc. A 212, 261 (1912), °/mm along c at 20 °C; the record's Drude formula states a
    // largest residual of 0.025 °/mm. Across c the record assumes −0.5 times the value along it.
    const Mineral& quartz = catalog().find("quartz");
    ASSERT_TRUE(quartz.optically_active());
    const double to_deg_per_mm = 180.0 / std::numbers::pi * 1e3;
    const std::vector<std::pair<double, double>> lowry{{404.7, 48.95}, {435.8, 41.55}, {486.1, 32.76},
                                                       {546.1, 25.54}, {589.3, 21.72}, {656.3, 17.32}};
    double worst = 0.0;
    for (const auto& [wavelength_nm, deg_per_mm] : lowry) {
        const Eigen::Vector3d rho = quartz.principal_rotatory_power(wavelength_nm) * to_deg_per_mm;
        worst = std::max(worst, std::abs(rho[2] - deg_per_mm));
        EXPECT_NEAR(rho[0], -0.5 * rho[2], 1e-12);
        EXPECT_EQ(rho[0], rho[1]);
    }
    EXPECT_LE(worst, 0.025);
    // Every shipped mineral but quartz and paratellurite is inactive.
    for (const Mineral& mineral : catalog().minerals()) {
        if (mineral.name != "quartz" && mineral.name != "paratellurite") EXPECT_FALSE(mineral.optically_active()) << mineral.name;
    }
}

TEST_F(ShippedCatalog, ParatelluriteRotatoryPowerReproducesItsTableWithinTheStatedResidual) {
    // The table of rotatory power along [001] that the record cites (°/mm); its one-term Drude formula states a
    // largest relative residual of 1.6 % (at 369.8 nm) and 0.2 % at 632.8 nm. Across c: −2 times the value along it.
    const Mineral& paratellurite = catalog().find("TeO2");
    ASSERT_EQ(paratellurite.name, "paratellurite");
    ASSERT_TRUE(paratellurite.optically_active());
    const double to_deg_per_mm = 180.0 / std::numbers::pi * 1e3;
    const std::vector<std::pair<double, double>> table{{369.8, 587.1}, {378.3, 520.6}, {391.7, 437.4}, {415.2, 337.6}, {438.2, 271.0},
                                                       {463.0, 221.1}, {499.5, 171.2}, {530.0, 143.4}, {589.3, 104.9}, {632.8, 86.9},
                                                       {700.0, 67.4},  {800.0, 48.5},  {900.0, 37.4},  {1000.0, 29.5}, {1100.0, 23.8}};
    double worst = 0.0;
    for (const auto& [wavelength_nm, deg_per_mm] : table) {
        const Eigen::Vector3d rho = paratellurite.principal_rotatory_power(wavelength_nm) * to_deg_per_mm;
        worst = std::max(worst, std::abs(rho[2] / deg_per_mm - 1.0));
        EXPECT_NEAR(rho[0], -2.0 * rho[2], 1e-12 * std::abs(rho[2]));
        EXPECT_EQ(rho[0], rho[1]);
    }
    EXPECT_LE(worst, 0.0161);
    EXPECT_NEAR(paratellurite.principal_rotatory_power(632.8)[2] * to_deg_per_mm / 86.9, 1.0, 0.002);
}

TEST_F(ShippedCatalog, EveryMineralIsPhysicalAcrossTheVisible) {
    for (const Mineral& mineral : catalog().minerals()) {
        SCOPED_TRACE(mineral.name);
        EXPECT_FALSE(mineral.file.empty());
        double worst_n = 10.0;
        bool all_finite = true;
        bool kappa_ok = true;
        for (int nm = 380; nm <= 780; ++nm) {
            const Eigen::Vector3d n = mineral.principal_n(nm);
            const Eigen::Vector3d kappa = mineral.principal_kappa(nm);
            all_finite = all_finite && n.allFinite();
            worst_n = std::min(worst_n, n.minCoeff());
            kappa_ok = kappa_ok && kappa.allFinite() && kappa.minCoeff() >= 0.0;
        }
        EXPECT_TRUE(all_finite);
        EXPECT_GT(worst_n, 1.0);
        EXPECT_TRUE(kappa_ok);
        // The labels hold at the reference wavelength: sorted summary equals the X, Y, Z indices.
        const Eigen::Vector3d xyz = mineral.principal_n(mineral.reference_wavelength_nm);
        const OpticalSummary summary = optical_summary(mineral, mineral.reference_wavelength_nm);
        if (mineral.optical_class == OpticalClass::biaxial) {
            EXPECT_EQ(summary.n_alpha, xyz[0]);
            EXPECT_EQ(summary.n_beta, xyz[1]);
            EXPECT_EQ(summary.n_gamma, xyz[2]);
            ASSERT_TRUE(summary.two_v_deg.has_value());
            EXPECT_GT(*summary.two_v_deg, 0.0);
            EXPECT_LE(*summary.two_v_deg, 90.0);
        } else if (mineral.optical_class == OpticalClass::uniaxial) {
            ASSERT_TRUE(summary.two_v_deg.has_value());
            EXPECT_EQ(*summary.two_v_deg, 0.0);
            EXPECT_EQ(summary.sign, xyz[2] > xyz[0] ? "+" : "-");
        } else {
            EXPECT_FALSE(summary.two_v_deg.has_value());
        }
    }
}

TEST(MineralCatalogFiles, DuplicateNamesAcrossFilesNameBothFiles) {
    TemporaryFolder folder;
    const fs::path first = folder.write("a.txt", record("stone"));
    const fs::path second = folder.write("b.txt", record("Stone"));  // same name, other case
    try {
        load_mineral_catalog(folder.path());
        FAIL() << "no error for a duplicate name";
    } catch (const InputError& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find(first.string()), std::string::npos) << message;
        EXPECT_NE(message.find(second.string()), std::string::npos) << message;
    }
}

TEST(MineralCatalogFiles, AliasCollidingWithAnotherNameNamesBothFiles) {
    TemporaryFolder folder;
    const fs::path first = folder.write("one.txt", record("rock"));
    const fs::path second = folder.write("two.txt", record("pebble", "aliases: cobble, rock\n"));
    try {
        load_mineral_catalog(folder.path());
        FAIL() << "no error for an alias equal to another mineral's name";
    } catch (const InputError& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find("'rock'"), std::string::npos) << message;
        EXPECT_NE(message.find(first.string()), std::string::npos) << message;
        EXPECT_NE(message.find(second.string()), std::string::npos) << message;
    }
}

TEST(MineralCatalogFiles, ReadsOnlyTxtFilesAndLocatesErrors) {
    TemporaryFolder folder;
    folder.write("good.txt", record("stone"));
    folder.write("README.md", "not a record");
    folder.write("backup.txt~", "not a record either");
    EXPECT_EQ(load_mineral_catalog(folder.path()).minerals().size(), 1u);

    const fs::path broken = folder.write("broken.txt", "name: broken\nsystem cubic\n");
    try {
        load_mineral_catalog(folder.path());
        FAIL() << "no error for a broken record";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find(broken.string() + ":2:"), std::string::npos) << e.what();
    }
}

TEST(MineralCatalogFiles, MissingOrEmptyFolders) {
    TemporaryFolder folder;
    EXPECT_THROW(load_mineral_catalog(folder.path()), InputError);  // no *.txt records
    try {
        load_mineral_catalog(folder.path() / "nonexistent");
        FAIL() << "no error for a missing folder";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("nonexistent"), std::string::npos) << e.what();
    }
}

}  // namespace
}  // namespace petroscope
