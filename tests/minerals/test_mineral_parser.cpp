// The mineral record format of minerals/README.md (include/petroscope/minerals/mineral_parser.hpp): a valid
// record with every key, and errors located as "file:line: what" at the line that is wrong.
#include "petroscope/minerals/mineral_parser.hpp"

#include "petroscope/core/error.hpp"

#include <gtest/gtest.h>

#include <numbers>
#include <string>
#include <vector>

namespace petroscope {
namespace {

// Joins lines with '\n' and no final newline, so that line k of the vector is line k + 1 of the text and the
// last line of the text is lines.size().
std::string join(const std::vector<std::string>& lines) {
    std::string text;
    for (std::size_t i = 0; i < lines.size(); ++i) text += (i ? "\n" : "") + lines[i];
    return text;
}

// The InputError message of parsing `text` as "t.txt"; "" if it parses.
std::string parse_error(const std::string& text) {
    try {
        parse_mineral(text, "t.txt");
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

// A minimal valid biaxial record, 9 lines.
std::vector<std::string> biaxial_lines() {
    return {
        "name: testite",                 // 1
        "system: monoclinic",            // 2
        "class: biaxial",                // 3
        "n_alpha: constant 1.50",        // 4
        "n_alpha.source: a",             // 5
        "n_beta: constant 1.52",         // 6
        "n_beta.source: b",              // 7
        "n_gamma: constant 1.56",        // 8
        "n_gamma.source: c",             // 9
    };
}

std::vector<std::string> with(std::vector<std::string> lines, std::size_t line_number, const std::string& replacement) {
    lines.at(line_number - 1) = replacement;
    return lines;
}
std::vector<std::string> without(std::vector<std::string> lines, std::size_t line_number) {
    lines.erase(lines.begin() + static_cast<std::ptrdiff_t>(line_number - 1));
    return lines;
}
std::vector<std::string> plus(std::vector<std::string> lines, const std::string& extra) {
    lines.push_back(extra);
    return lines;
}

#define EXPECT_CONTAINS(haystack, needle) \
    EXPECT_NE(std::string(haystack).find(needle), std::string::npos) << "'" << (needle) << "' not in: " << (haystack)

TEST(MineralParser, ValidRecordWithEveryKey) {
    const std::string text =
        "# Test record: every key of minerals/README.md\n"
        "name: testite\n"
        "aliases: tt, test mineral\n"
        "formula: Ab2Cd#3\n"
        "system: monoclinic\n"
        "class: biaxial\n"
        "indicatrix: X = b, Z ^ c = 20 deg\n"
        "reference_wavelength_nm: 550\n"
        "source: invented for the test  # a trailing comment\n"
        "note: a note\n"
        "\n"
        "n_alpha: cauchy 1.50 0.004\n"
        "n_alpha.source: s-alpha\n"
        "n_alpha.range_um: 0.4 0.8\n"
        "kappa_alpha: constant 0.001\n"
        "kappa_alpha.source: k-alpha\n"
        "n_beta: constant 1.52\n"
        "n_beta.source: s-beta\n"
        "n_gamma: table-nm 400:1.56 700:1.54\n"
        "n_gamma.source: s-gamma\n";
    const Mineral m = parse_mineral(text, "t.txt");
    EXPECT_EQ(m.name, "testite");
    EXPECT_EQ(m.aliases, (std::vector<std::string>{"tt", "test mineral"}));
    EXPECT_EQ(m.formula, "Ab2Cd#3");
    EXPECT_EQ(m.system, "monoclinic");
    EXPECT_EQ(m.optical_class, OpticalClass::biaxial);
    EXPECT_EQ(m.indicatrix, "X = b, Z ^ c = 20 deg");
    EXPECT_EQ(m.reference_wavelength_nm, 550.0);
    EXPECT_EQ(m.source, "invented for the test");
    EXPECT_EQ(m.note, "a note");
    EXPECT_EQ(m.file, "t.txt");
    ASSERT_EQ(m.axes.size(), 3u);
    EXPECT_EQ(m.axes[0].key, "n_alpha");
    EXPECT_EQ(m.axes[1].key, "n_beta");
    EXPECT_EQ(m.axes[2].key, "n_gamma");
    EXPECT_EQ(m.axes[0].n.kind(), DispersionModel::Kind::cauchy);
    EXPECT_EQ(m.axes[0].n_source, "s-alpha");
    EXPECT_EQ(m.axes[1].n_source, "s-beta");
    EXPECT_EQ(m.axes[2].n_source, "s-gamma");
    ASSERT_TRUE(m.axes[0].range_um.has_value());
    EXPECT_EQ((*m.axes[0].range_um)[0], 0.4);
    EXPECT_EQ((*m.axes[0].range_um)[1], 0.8);
    EXPECT_FALSE(m.axes[1].range_um.has_value());
    ASSERT_TRUE(m.axes[0].kappa.has_value());
    EXPECT_EQ(m.axes[0].kappa_source, "k-alpha");
    EXPECT_FALSE(m.axes[1].kappa.has_value());
    EXPECT_FALSE(m.axes[2].kappa.has_value());
    EXPECT_TRUE(m.absorbing());

    // 550 nm: cauchy 1.5 + 0.004/0.55², constant 1.52, table 1.56 − 0.02·150/300 = 1.55.
    const Eigen::Vector3d n = m.principal_n(550.0);
    EXPECT_NEAR(n[0], 1.5 + 0.004 / (0.55 * 0.55), 1e-15);
    EXPECT_EQ(n[1], 1.52);
    EXPECT_NEAR(n[2], 1.55, 1e-15);
    EXPECT_EQ(m.principal_kappa(550.0), Eigen::Vector3d(0.001, 0.0, 0.0));

    // n_alpha is stated valid over 0.4–0.8 µm.
    EXPECT_TRUE(m.range_warnings({400.0, 589.3, 800.0}).empty());
    const auto warnings = m.range_warnings({380.0, 780.0});
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_CONTAINS(warnings[0], "n_alpha");
}

TEST(MineralParser, IsotropicAndUniaxialAxes) {
    const Mineral glass = parse_mineral("name: g\nsystem: amorphous\nclass: isotropic\nn: constant 1.5\nn.source: x", "g.txt");
    ASSERT_EQ(glass.axes.size(), 1u);
    EXPECT_EQ(glass.axes[0].key, "n");
    EXPECT_EQ(glass.principal_n(500.0), Eigen::Vector3d(1.5, 1.5, 1.5));
    EXPECT_FALSE(glass.absorbing());

    const Mineral spar = parse_mineral(
        "name: u\nsystem: trigonal\nclass: uniaxial\nn_o: constant 1.658\nn_o.source: x\nn_e: constant 1.486\nn_e.source: y",
        "u.txt");
    ASSERT_EQ(spar.axes.size(), 2u);
    EXPECT_EQ(spar.axes[0].key, "n_o");
    EXPECT_EQ(spar.axes[1].key, "n_e");
    EXPECT_EQ(spar.principal_n(500.0), Eigen::Vector3d(1.658, 1.658, 1.486));  // X, Y = ω; Z (optic axis) = ε
    EXPECT_EQ(spar.reference_wavelength_nm, 589.3);                            // the default
}

TEST(MineralParser, CommentsBlankLinesAndLineEndings) {
    const std::string plain = join(biaxial_lines());
    const std::string decorated =
        "# a whole-line comment\n"
        "\n"
        "   # an indented comment\n"
        "name: testite   # after spaces\n"
        "system: monoclinic\t# after a tab\n"
        "\t\n"
        "class: biaxial\r\n"  // CRLF line end
        "n_alpha: constant 1.50 # comment\n"
        "n_alpha.source: a\n"
        "# n_alpha.range_um: 9 1   (commented out, so not checked)\n"
        "n_beta: constant 1.52\n"
        "n_beta.source: b\n"
        "n_gamma: constant 1.56\n"
        "n_gamma.source: c\n"
        "\n\n";
    const Mineral a = parse_mineral(plain, "t.txt");
    const Mineral b = parse_mineral(decorated, "t.txt");
    EXPECT_EQ(b.name, a.name);
    EXPECT_EQ(b.system, a.system);
    EXPECT_EQ(b.optical_class, a.optical_class);
    EXPECT_EQ(b.principal_n(589.3), a.principal_n(589.3));
    EXPECT_FALSE(b.axes[0].range_um.has_value());
}

TEST(MineralParser, HashInsideAWordIsNotAComment) {
    // strip_comment: '#' starts a comment only at the start of a line or after a space or tab.
    auto lines = biaxial_lines();
    lines.push_back("formula: Fe#2+Mg#1 # comment");
    lines.push_back("note: a#b\t#c");
    lines.push_back("source:#hash right after the colon");
    const Mineral m = parse_mineral(join(lines), "t.txt");
    EXPECT_EQ(m.formula, "Fe#2+Mg#1");
    EXPECT_EQ(m.note, "a#b");
    EXPECT_EQ(m.source, "#hash right after the colon");
}

TEST(MineralParser, LineWithoutColon) {
    const std::string message = parse_error(join(with(biaxial_lines(), 3, "class biaxial")));
    EXPECT_CONTAINS(message, "t.txt:3:");
    EXPECT_CONTAINS(message, "'key: value'");
    EXPECT_CONTAINS(message, "class biaxial");
}

TEST(MineralParser, EmptyKeyOrValue) {
    EXPECT_CONTAINS(parse_error(join(plus(biaxial_lines(), "formula:"))), "t.txt:10:");
    EXPECT_CONTAINS(parse_error(join(plus(biaxial_lines(), "formula:"))), "'formula' has no value");
    EXPECT_CONTAINS(parse_error(join(plus(biaxial_lines(), "formula:   # only a comment"))), "t.txt:10:");
    EXPECT_CONTAINS(parse_error(join(with(biaxial_lines(), 2, ": monoclinic"))), "t.txt:2: missing key");
}

TEST(MineralParser, DuplicateKeyNamesBothLines) {
    const std::string message = parse_error(join(plus(biaxial_lines(), "name: other")));
    EXPECT_CONTAINS(message, "t.txt:10:");
    EXPECT_CONTAINS(message, "'name'");
    EXPECT_CONTAINS(message, "first on line 1");

    // Also for an index key, with the first occurrence later in the file.
    const std::string index = parse_error(join(plus(biaxial_lines(), "n_beta: constant 1.53")));
    EXPECT_CONTAINS(index, "t.txt:10:");
    EXPECT_CONTAINS(index, "first on line 6");
}

TEST(MineralParser, UnknownKeyListsTheValidKeys) {
    const std::string message = parse_error(join(plus(biaxial_lines(), "colour: red")));
    EXPECT_CONTAINS(message, "t.txt:10:");
    EXPECT_CONTAINS(message, "unknown key 'colour'");
    for (const char* key : {"name", "aliases", "formula", "system", "class", "indicatrix", "reference_wavelength_nm",
                            "source", "note", "n_alpha", "n_alpha.source", "n_alpha.range_um", "kappa_alpha",
                            "kappa_alpha.source", "n_beta", "n_gamma.range_um"}) {
        EXPECT_CONTAINS(message, key);
    }
    // The valid keys depend on the optical class: a biaxial file has no n_o.
    const std::string uniaxial_key = parse_error(join(with(biaxial_lines(), 9, "n_gamma.source: c\nn_o: constant 1.5")));
    EXPECT_CONTAINS(uniaxial_key, "t.txt:10:");
    EXPECT_CONTAINS(uniaxial_key, "unknown key 'n_o'");
    // Keys are case-sensitive.
    EXPECT_CONTAINS(parse_error(join(plus(biaxial_lines(), "Note: x"))), "unknown key 'Note'");
}

TEST(MineralParser, MissingRequiredKeysAreReportedAtTheLastLine) {
    // No line holds a missing key; the error points at the end of the file (here line 8 of 8).
    for (const auto& [line, key] : std::vector<std::pair<std::size_t, std::string>>{{1, "name"}, {2, "system"}, {3, "class"}}) {
        const std::string message = parse_error(join(without(biaxial_lines(), line)));
        EXPECT_CONTAINS(message, "t.txt:8:");
        EXPECT_CONTAINS(message, "missing key '" + key + "'");
    }
}

TEST(MineralParser, MissingKeyLineIsALineOfTheFileWhenItEndsWithANewline) {
    // Was a bug: RecordReader counts the empty text after the final '\n' as a line, so an 8-line file that ends
    // with a newline (as every editor writes it) reports a missing key at line 9, which does not exist.
    // Expected: the last line of the file, 8 (as for the same file without the final newline).
    const std::string message = parse_error(join(without(biaxial_lines(), 1)) + "\n");
    EXPECT_CONTAINS(message, "t.txt:8:");
    EXPECT_CONTAINS(message, "missing key 'name'");
}

TEST(MineralParser, UnknownClassOrSystem) {
    const std::string optical_class = parse_error(join(with(biaxial_lines(), 3, "class: biaxal")));
    EXPECT_CONTAINS(optical_class, "t.txt:3:");
    EXPECT_CONTAINS(optical_class, "'biaxal'");
    EXPECT_CONTAINS(optical_class, "isotropic, uniaxial or biaxial");

    const std::string system = parse_error(join(with(biaxial_lines(), 2, "system: cubik")));
    EXPECT_CONTAINS(system, "t.txt:2:");
    EXPECT_CONTAINS(system, "'cubik'");
    EXPECT_CONTAINS(system, "orthorhombic");
}

TEST(MineralParser, MissingIndexOrItsSource) {
    // n_beta and n_beta.source removed: 7 lines left.
    const std::string beta = parse_error(join(without(without(biaxial_lines(), 7), 6)));
    EXPECT_CONTAINS(beta, "t.txt:7:");
    EXPECT_CONTAINS(beta, "missing key 'n_beta'");

    const std::string source = parse_error(join(without(biaxial_lines(), 5)));
    EXPECT_CONTAINS(source, "t.txt:8:");
    EXPECT_CONTAINS(source, "missing key 'n_alpha.source'");
}

TEST(MineralParser, BadDispersionModelNamesTheKeyAndLine) {
    const std::string numbers = parse_error(join(with(biaxial_lines(), 4, "n_alpha: cauchy 1.5 x")));
    EXPECT_CONTAINS(numbers, "t.txt:4: n_alpha:");
    EXPECT_CONTAINS(numbers, "'x'");

    const std::string model = parse_error(join(with(biaxial_lines(), 6, "n_beta: sellmeier 1 2 3")));
    EXPECT_CONTAINS(model, "t.txt:6: n_beta:");
    EXPECT_CONTAINS(model, "'sellmeier'");

    const std::string kappa = parse_error(join(plus(plus(biaxial_lines(), "kappa_gamma: cauchy 0.1"), "kappa_gamma.source: k")));
    EXPECT_CONTAINS(kappa, "t.txt:10: kappa_gamma:");
}

TEST(MineralParser, IndicesMustBePhysicalAndOrdered) {
    const std::string order = parse_error(join(with(biaxial_lines(), 6, "n_beta: constant 1.49")));
    EXPECT_CONTAINS(order, "t.txt:6:");
    EXPECT_CONTAINS(order, "n_alpha < n_beta < n_gamma");
    EXPECT_CONTAINS(parse_error(join(with(biaxial_lines(), 6, "n_beta: constant 1.50"))), "n_alpha < n_beta < n_gamma");
    EXPECT_CONTAINS(parse_error(join(with(biaxial_lines(), 6, "n_beta: constant 1.57"))), "t.txt:6:");

    // Order at the reference wavelength, not elsewhere: n_alpha falls through n_beta = 1.52 at 500 nm.
    auto crossing = biaxial_lines();
    crossing[3] = "n_alpha: table-nm 400:1.53 800:1.49";
    crossing.push_back("reference_wavelength_nm: 700");
    EXPECT_EQ(parse_error(join(crossing)), "");
    crossing.back() = "reference_wavelength_nm: 450";
    EXPECT_CONTAINS(parse_error(join(crossing)), "t.txt:6:");

    const std::string below_one = parse_error(join(with(biaxial_lines(), 4, "n_alpha: constant 0.9")));
    EXPECT_CONTAINS(below_one, "t.txt:4:");
    EXPECT_CONTAINS(below_one, "n_alpha");

    const std::string equal = parse_error(
        "name: u\nsystem: trigonal\nclass: uniaxial\nn_o: constant 1.5\nn_o.source: x\nn_e: constant 1.5\nn_e.source: y");
    EXPECT_CONTAINS(equal, "t.txt:6:");
    EXPECT_CONTAINS(equal, "isotropic");
}

TEST(MineralParser, RangeMustBeTwoIncreasingPositiveNumbers) {
    for (const std::string range : {"0.8 0.4", "0.4", "a b", "0 0.8", "-0.4 0.8", "0.4 0.8 1.2", "0.4 0.4", "0.4-0.8"}) {
        SCOPED_TRACE(range);
        const std::string message = parse_error(join(plus(biaxial_lines(), "n_alpha.range_um: " + range)));
        EXPECT_CONTAINS(message, "t.txt:10:");
        EXPECT_CONTAINS(message, "n_alpha.range_um");
    }
}

TEST(MineralParser, KappaAndItsSourceGoTogether) {
    const std::string orphan = parse_error(join(plus(biaxial_lines(), "kappa_beta.source: x")));
    EXPECT_CONTAINS(orphan, "t.txt:10:");
    EXPECT_CONTAINS(orphan, "kappa_beta.source given without kappa_beta");

    const std::string no_source = parse_error(join(plus(biaxial_lines(), "kappa_beta: constant 0.01")));
    EXPECT_CONTAINS(no_source, "missing key 'kappa_beta.source'");
}

TEST(MineralParser, OtherValueErrors) {
    const std::string aliases = parse_error(join(plus(biaxial_lines(), "aliases: a,,b")));
    EXPECT_CONTAINS(aliases, "t.txt:10:");
    EXPECT_CONTAINS(aliases, "aliases");
    for (const std::string bad : {"abc", "-5", "0", "nan"}) {
        const std::string reference = parse_error(join(plus(biaxial_lines(), "reference_wavelength_nm: " + bad)));
        EXPECT_CONTAINS(reference, "t.txt:10:");
        EXPECT_CONTAINS(reference, "reference_wavelength_nm");
    }
}

// A minimal uniaxial record, 7 lines, optionally active.
std::vector<std::string> uniaxial_lines() {
    return {"name: quartzite", "system: trigonal", "class: uniaxial", "n_o: constant 1.544", "n_o.source: o",
            "n_e: constant 1.553", "n_e.source: e"};
}

std::vector<std::string> active_uniaxial_lines() {
    auto lines = uniaxial_lines();
    for (const char* line : {"rotatory_power_axis: drude 7.16 0.13",   // 8
                             "rotatory_power_axis.source: along",      // 9
                             "rotatory_power_normal: constant -10.9",  // 10
                             "rotatory_power_normal.source: across"})  // 11
        lines.push_back(line);
    return lines;
}

TEST(MineralParser, RotatoryPowersOfAUniaxialCrystal) {
    const Mineral active = parse_mineral(join(active_uniaxial_lines()), "t.txt");
    ASSERT_TRUE(active.optically_active());
    const Eigen::Vector3d rho = active.principal_rotatory_power(589.3);
    const double deg_per_mm = std::numbers::pi / 180.0 * 1e-3;
    EXPECT_NEAR(rho[2], 7.16 / (0.5893 * 0.5893 - 0.0169) * deg_per_mm, 1e-15);
    EXPECT_NEAR(rho[0], -10.9 * deg_per_mm, 1e-18);
    EXPECT_EQ(rho[0], rho[1]);
    EXPECT_EQ(active.rotatory_powers[1].source, "along");
    EXPECT_FALSE(parse_mineral(join(uniaxial_lines()), "t.txt").optically_active());
    EXPECT_TRUE(parse_mineral(join(uniaxial_lines()), "t.txt").principal_rotatory_power(589.3).isZero(0.0));
}

TEST(MineralParser, BadRotatoryPowersAreRefusedWithTheLineAndReason) {
    // One component alone, a missing source, a bad model, out of range, negative along the axis (the record gives
    // the right-handed form), a pole among the wavelengths, uniaxial keys on biaxial and isotropic records.
    EXPECT_CONTAINS(parse_error(join(without(without(active_uniaxial_lines(), 11), 10))), "rotatory_power_normal is missing");
    EXPECT_CONTAINS(parse_error(join(without(active_uniaxial_lines(), 9))), "missing key 'rotatory_power_axis.source'");
    const std::string model = parse_error(join(with(active_uniaxial_lines(), 10, "rotatory_power_normal: drude 1")));
    EXPECT_CONTAINS(model, "t.txt:10: rotatory_power_normal:");
    // Quartz's 21.7 °/mm written in °/m.
    const std::string range = parse_error(join(with(active_uniaxial_lines(), 10, "rotatory_power_normal: constant -21700")));
    EXPECT_CONTAINS(range, "t.txt:10:");
    EXPECT_CONTAINS(range, "within");
    const std::string sign = parse_error(join(with(active_uniaxial_lines(), 8, "rotatory_power_axis: constant -21.7")));
    EXPECT_CONTAINS(sign, "t.txt:8:");
    EXPECT_CONTAINS(sign, "right-handed");
    // A Drude pole among the visible wavelengths (0.45 µm) is refused although the value at 589.3 nm is fine.
    const std::string pole = parse_error(join(with(active_uniaxial_lines(), 8, "rotatory_power_axis: drude 7 0.45")));
    EXPECT_CONTAINS(pole, "t.txt:8:");
    EXPECT_CONTAINS(pole, "from 360 to 830 nm");
    // The uniaxial keys on biaxial and isotropic records are unknown there.
    EXPECT_CONTAINS(parse_error(join(plus(plus(biaxial_lines(), "rotatory_power_axis: constant 1"), "rotatory_power_axis.source: s"))),
                    "unknown key 'rotatory_power_axis'");
    EXPECT_CONTAINS(parse_error("name: g\nsystem: cubic\nclass: isotropic\nn: constant 1.5\nn.source: x\nrotatory_power_axis: constant 3\n"
                                "rotatory_power_axis.source: s"),
                    "unknown key 'rotatory_power_axis'");
}

// testite (nα 1.50, nβ 1.52, nγ 1.56) with rotatory powers along X, Y, Z.
std::vector<std::string> active_biaxial_lines(const std::string& x, const std::string& y, const std::string& z) {
    auto lines = biaxial_lines();
    for (const std::string& line : {"rotatory_power_x: constant " + x, std::string("rotatory_power_x.source: X"),  // 10, 11
                                    "rotatory_power_y: constant " + y, std::string("rotatory_power_y.source: Y"),  // 12, 13
                                    "rotatory_power_z: constant " + z, std::string("rotatory_power_z.source: Z")})  // 14, 15
        lines.push_back(line);
    return lines;
}

TEST(MineralParser, RotatoryPowersOfABiaxialCrystalAlongItsIndicatrixAxes) {
    const Mineral active = parse_mineral(join(active_biaxial_lines("5", "-3", "2")), "t.txt");
    ASSERT_TRUE(active.optically_active());
    const double deg_per_mm = std::numbers::pi / 180.0 * 1e-3;
    EXPECT_TRUE(active.principal_rotatory_power(500.0).isApprox(Eigen::Vector3d(5.0, -3.0, 2.0) * deg_per_mm, 1e-15));
    EXPECT_EQ(active.rotatory_powers[2].source, "Z");
    // Landau's g = λρ/π along each axis (docs/theory.md §9), and the mirror form's opposite.
    const Eigen::Matrix3d g = active.gyration(500.0, Handedness::right);
    EXPECT_NEAR(g(0, 0), 0.5 * 5.0 * deg_per_mm / std::numbers::pi, 1e-18);
    EXPECT_NEAR(g(1, 1), 0.5 * -3.0 * deg_per_mm / std::numbers::pi, 1e-18);
    EXPECT_EQ(g(0, 1), 0.0);
    EXPECT_TRUE(active.gyration(500.0, Handedness::left).isApprox(-g, 1e-15));
}

TEST(MineralParser, BadBiaxialRotatoryPowersAreRefusedWithTheLineAndReason) {
    // A missing component names the others.
    const std::string missing = parse_error(join(without(without(active_biaxial_lines("5", "-3", "2"), 13), 12)));
    EXPECT_CONTAINS(missing, "t.txt:10:");
    EXPECT_CONTAINS(missing, "rotatory_power_y is missing");
    // Along the optic axes, at V = 36.1° from Z (sin²V = 0.3463), ρ_x sin²V + ρ_z cos²V = −5·0.3463 + 2·0.6537 < 0:
    // the left-handed form, refused; with ρ_x = −3 the same sum is +0.27 and the record is accepted.
    const std::string sign = parse_error(join(active_biaxial_lines("-5", "1", "2")));
    EXPECT_CONTAINS(sign, "t.txt:14:");
    EXPECT_CONTAINS(sign, "optic axes is -0.42");
    EXPECT_CONTAINS(sign, "right-handed");
    EXPECT_TRUE(parse_mineral(join(active_biaxial_lines("-3", "1", "2")), "t.txt").optically_active());
}

TEST(MineralParser, RotatoryPowerOfAnIsotropicCrystalIsTheSameAlongEveryAxis) {
    const Mineral cubic = parse_mineral("name: chlorate\nsystem: cubic\nclass: isotropic\nn: constant 1.515\nn.source: x\n"
                                        "rotatory_power: constant 3.1\nrotatory_power.source: s",
                                        "c.txt");
    ASSERT_TRUE(cubic.optically_active());
    const Eigen::Vector3d rho = cubic.principal_rotatory_power(500.0);
    EXPECT_NEAR(rho[0], 3.1 * std::numbers::pi / 180.0 * 1e-3, 1e-18);
    EXPECT_EQ(rho[0], rho[1]);
    EXPECT_EQ(rho[1], rho[2]);
    EXPECT_CONTAINS(parse_error("name: chlorate\nsystem: cubic\nclass: isotropic\nn: constant 1.515\nn.source: x\nrotatory_power: constant -3.1\n"
                                "rotatory_power.source: s"),
                    "right-handed");
}

}  // namespace
}  // namespace petroscope
