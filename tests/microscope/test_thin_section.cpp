// Thin sections in memory (include/petroscope/microscope/thin_section.hpp): the random Voronoi and power
// tessellations against a brute-force nearest-seed search, uniformity of the random orientations (Haar
// measure), mineral frequencies, and the thickness of every kind.
#include "petroscope/microscope/thin_section.hpp"

#include "petroscope/core/error.hpp"
#include "petroscope/optics/orientation.hpp"

#include <Eigen/LU>
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <set>

namespace petroscope {
namespace {

ThinSection small_section() {
    ThinSection section;
    section.name = "test";
    section.width_px = 4;
    section.height_px = 2;
    section.labels = {1, 1, 2, 2, 1, 1, 2, 2};
    ThinSectionGrain quartz{1, "quartz", Eigen::Matrix3d::Identity(), std::nullopt, 0};
    ThinSectionGrain calcite{2, "calcite", euler_zyz_deg(10, 20, 30), std::nullopt, 0};
    section.grains = {quartz, calcite};
    section.validate();
    return section;
}

// The section random_voronoi_section must produce, found the slow way: the same draws (x, y, mineral,
// u1, u2, u3 per seed), every pixel against every seed, ties to the lower index, empty cells dropped.
std::vector<std::uint16_t> brute_force_labels(const VoronoiSectionSettings& settings) {
    std::mt19937_64 rng(settings.seed);
    const std::size_t n = static_cast<std::size_t>(settings.grain_count);
    std::vector<double> x(n), y(n), w(n, 0.0);
    double total = 0.0;
    for (std::size_t m = 0; m < settings.minerals.size(); ++m) total += settings.weights.empty() ? 1.0 : settings.weights[m];
    double mean_size = 0.0, smallest = std::numeric_limits<double>::infinity();
    for (std::size_t m = 0; m < settings.grain_sizes.size(); ++m) {
        mean_size += settings.grain_sizes[m] * (settings.weights.empty() ? 1.0 : settings.weights[m]) / total;
        smallest = std::min(smallest, settings.grain_sizes[m]);
    }
    const double spacing = settings.size_px / std::sqrt(static_cast<double>(n));
    for (std::size_t i = 0; i < n; ++i) {
        x[i] = uniform_unit_interval(rng) * settings.size_px;
        y[i] = uniform_unit_interval(rng) * settings.size_px;
        const double pick = uniform_unit_interval(rng) * total;
        std::size_t m = 0;
        double cumulative = settings.weights.empty() ? 1.0 : settings.weights[0];
        while (m + 1 < settings.minerals.size() && !(pick < cumulative)) {
            ++m;
            cumulative += settings.weights.empty() ? 1.0 : settings.weights[m];
        }
        if (!settings.grain_sizes.empty()) w[i] = spacing * spacing * (settings.grain_sizes[m] - smallest) / mean_size;
        for (int k = 0; k < 3; ++k) uniform_unit_interval(rng);
    }
    const std::size_t size = static_cast<std::size_t>(settings.size_px);
    std::vector<std::size_t> owner(size * size);
    std::vector<int> used(n, 0);
    for (std::size_t row = 0; row < size; ++row) {
        for (std::size_t column = 0; column < size; ++column) {
            const double px = static_cast<double>(column) + 0.5, py = static_cast<double>(row) + 0.5;
            double best = std::numeric_limits<double>::infinity();
            for (std::size_t i = 0; i < n; ++i) {
                const double power = (px - x[i]) * (px - x[i]) + (py - y[i]) * (py - y[i]) - w[i];
                if (power < best) {
                    best = power;
                    owner[row * size + column] = i;
                }
            }
            used[owner[row * size + column]] = 1;
        }
    }
    std::vector<std::uint16_t> label_of(n, 0);
    std::uint16_t next = 1;
    for (std::size_t i = 0; i < n; ++i) {
        if (used[i]) label_of[i] = next++;
    }
    std::vector<std::uint16_t> labels(owner.size());
    for (std::size_t p = 0; p < owner.size(); ++p) labels[p] = label_of[owner[p]];
    return labels;
}

TEST(ThinSection, ThicknessUniformWedgeMapAndOwn) {
    ThinSection section = small_section();
    const ThinSectionGrain& quartz = section.grains[0];
    section.thickness_um = 25.0;
    EXPECT_EQ(section.thickness_at(3, 1, quartz), 25.0);

    // Wedge along x, 0 at the left edge and 40 µm at the right: pixel i has 40 (i + ½)/4.
    section.thickness_kind = ThicknessKind::wedge;
    section.wedge_start_um = 0.0;
    section.wedge_end_um = 40.0;
    for (int x = 0; x < 4; ++x) EXPECT_DOUBLE_EQ(section.thickness_at(x, 1, quartz), 40.0 * (x + 0.5) / 4.0) << x;
    // Along y, from the top edge (row 0) down, and decreasing wedges are allowed.
    section.wedge_along_x = false;
    section.wedge_start_um = 50.0;
    section.wedge_end_um = 10.0;
    EXPECT_DOUBLE_EQ(section.thickness_at(3, 0, quartz), 40.0);
    EXPECT_DOUBLE_EQ(section.thickness_at(0, 1, quartz), 20.0);

    section.thickness_kind = ThicknessKind::map;
    section.thickness_map_um = {1, 2, 3, 4, 5, 6, 7, 8};
    EXPECT_EQ(section.thickness_at(2, 1, quartz), 7.0);
    EXPECT_EQ(section.thickness_at(0, 0, quartz), 1.0);

    // A grain's own thickness wins over every kind.
    ThinSectionGrain thin = quartz;
    thin.thickness_um = 12.5;
    EXPECT_EQ(section.thickness_at(2, 1, thin), 12.5);
    section.thickness_kind = ThicknessKind::wedge;
    EXPECT_EQ(section.thickness_at(2, 1, thin), 12.5);
    EXPECT_EQ(section.section_thickness_at(0, 1), 20.0);
}

TEST(ThinSection, GrainIndexAndValidation) {
    ThinSection section = small_section();
    EXPECT_EQ(section.grain_at(0, 0).mineral, "quartz");
    EXPECT_EQ(section.grain_at(3, 1).mineral, "calcite");
    EXPECT_EQ(section.grain_index_of_label.size(), 65536u);
    EXPECT_EQ(section.grain_index_of_label[0], -1);

    // Extra grains (labels the map does not use) are allowed.
    section.grains.push_back({9, "quartz", Eigen::Matrix3d::Identity(), std::nullopt, 0});
    EXPECT_NO_THROW(section.validate());

    ThinSection duplicate = small_section();
    duplicate.grains.push_back({2, "quartz", Eigen::Matrix3d::Identity(), std::nullopt, 7});
    duplicate.grains[1].line = 5;
    try {
        duplicate.index_grains();
        FAIL() << "a duplicate label was accepted";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("label 2 is defined twice (lines 5 and 7)"), std::string::npos) << e.what();
    }

    ThinSection missing = small_section();
    missing.grains.pop_back();
    try {
        missing.validate();
        FAIL() << "a label without a grain was accepted";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("label 2 (first at (x 2, y 0)) has no grain"), std::string::npos) << e.what();
    }

    ThinSection skewed = small_section();
    skewed.grains[0].crystal_axes(0, 1) = 0.1;
    EXPECT_THROW(skewed.validate(), InputError);
    ThinSection mirrored = small_section();
    mirrored.grains[0].crystal_axes = -Eigen::Matrix3d::Identity();
    EXPECT_THROW(mirrored.validate(), InputError);
    ThinSection flat = small_section();
    flat.thickness_kind = ThicknessKind::wedge;  // 0 → 0
    EXPECT_THROW(flat.validate(), InputError);
    ThinSection holes = small_section();
    holes.thickness_kind = ThicknessKind::map;
    holes.thickness_map_um = {1, 2, 3};
    EXPECT_THROW(holes.validate(), InputError);
}

TEST(ThinSection, EulerAnglesOfARotationReproduceIt) {
    std::mt19937_64 rng(11);
    std::vector<Eigen::Matrix3d> rotations{Eigen::Matrix3d::Identity(), euler_zyz_deg(30, 0, 0), euler_zyz_deg(0, 180, 0),
                                           euler_zyz_deg(40, 180, -70), euler_zyz_deg(10, 1e-9, 20), euler_zyz_deg(-120, 90, 45)};
    for (int i = 0; i < 1000; ++i) {
        const double u1 = uniform_unit_interval(rng), u2 = uniform_unit_interval(rng), u3 = uniform_unit_interval(rng);
        rotations.push_back(shoemake_rotation(u1, u2, u3));
    }
    for (const Eigen::Matrix3d& rotation : rotations) {
        const Eigen::Vector3d angles = euler_zyz_deg_of(rotation);
        EXPECT_GE(angles[1], 0.0);
        EXPECT_LE(angles[1], 180.0);
        EXPECT_LT((euler_zyz_deg(angles[0], angles[1], angles[2]) - rotation).cwiseAbs().maxCoeff(), 1e-13) << rotation;
    }
    const Eigen::Vector3d plain = euler_zyz_deg_of(euler_zyz_deg(25, 60, -100));
    EXPECT_NEAR(plain[0], 25, 1e-12);
    EXPECT_NEAR(plain[1], 60, 1e-12);
    EXPECT_NEAR(plain[2], -100, 1e-12);
}

// Uniform rotations (Haar measure) carry any fixed crystal axis to a direction uniform on the sphere, whose
// z component c is uniform on [−1, 1]: E|c| = 1/2 (variance 1/12), E c² = 1/3 (variance 1/5 − 1/9 = 4/45).
TEST(ThinSection, ShoemakeRotationsAreUniform) {
    constexpr int kCount = 20000;
    std::mt19937_64 rng(2024);
    Eigen::Vector3d sum_abs = Eigen::Vector3d::Zero(), sum_square = Eigen::Vector3d::Zero();
    double sum_xx = 0.0;  // a component across: the x component of the crystal X axis, mean 0
    for (int i = 0; i < kCount; ++i) {
        const double u1 = uniform_unit_interval(rng), u2 = uniform_unit_interval(rng), u3 = uniform_unit_interval(rng);
        const Eigen::Matrix3d rotation = shoemake_rotation(u1, u2, u3);
        ASSERT_LT((rotation.transpose() * rotation - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff(), 1e-12);
        ASSERT_NEAR(rotation.determinant(), 1.0, 1e-12);
        for (int axis = 0; axis < 3; ++axis) {
            const double c = rotation(2, axis);  // (crystal axis)·z
            sum_abs[axis] += std::abs(c);
            sum_square[axis] += c * c;
        }
        sum_xx += rotation(0, 0);
    }
    const double sigma_abs = std::sqrt(1.0 / 12.0 / kCount), sigma_square = std::sqrt(4.0 / 45.0 / kCount);
    for (int axis = 0; axis < 3; ++axis) {
        EXPECT_NEAR(sum_abs[axis] / kCount, 0.5, 4.0 * sigma_abs) << "axis " << axis;
        EXPECT_NEAR(sum_square[axis] / kCount, 1.0 / 3.0, 4.0 * sigma_square) << "axis " << axis;
    }
    EXPECT_NEAR(sum_xx / kCount, 0.0, 4.0 * std::sqrt(1.0 / 3.0 / kCount));
}

TEST(ThinSection, UniformUnitIntervalIsInRangeAndFixed) {
    std::mt19937_64 rng(1);
    std::mt19937_64 raw(1);
    for (int i = 0; i < 1000; ++i) {
        const double u = uniform_unit_interval(rng);
        EXPECT_GE(u, 0.0);
        EXPECT_LT(u, 1.0);
        EXPECT_EQ(u, static_cast<double>(raw() >> 11) / 9007199254740992.0);  // 2^53
    }
}

TEST(RandomVoronoiSection, IsDeterministicForASeed) {
    const std::vector<std::string> minerals{"quartz", "orthoclase", "biotite"};
    const ThinSection a = random_voronoi_section(minerals, {5, 3, 1}, 150, 256, 2.0, 30.0, 42);
    const ThinSection b = random_voronoi_section(minerals, {5, 3, 1}, 150, 256, 2.0, 30.0, 42);
    EXPECT_EQ(a.labels, b.labels);
    ASSERT_EQ(a.grains.size(), b.grains.size());
    for (std::size_t i = 0; i < a.grains.size(); ++i) {
        EXPECT_EQ(a.grains[i].label, b.grains[i].label);
        EXPECT_EQ(a.grains[i].mineral, b.grains[i].mineral);
        EXPECT_EQ(a.grains[i].crystal_axes, b.grains[i].crystal_axes);
    }
    const ThinSection c = random_voronoi_section(minerals, {5, 3, 1}, 150, 256, 2.0, 30.0, 43);
    EXPECT_NE(a.labels, c.labels);
    // The weights choose the minerals only: the same seed with other weights gives the same cells.
    const ThinSection d = random_voronoi_section(minerals, {1, 1, 1}, 150, 256, 2.0, 30.0, 42);
    EXPECT_EQ(a.labels, d.labels);
}

TEST(RandomVoronoiSection, EveryLabelHasAGrainAndLabelsCountFromOne) {
    const ThinSection section = random_voronoi_section({"quartz", "calcite"}, {}, 300, 200, 1.5, 25.0, 7);
    EXPECT_EQ(section.width_px, 200);
    EXPECT_EQ(section.height_px, 200);
    EXPECT_EQ(section.labels.size(), 200u * 200u);
    EXPECT_EQ(section.pixel_size_um, 1.5);
    EXPECT_EQ(section.thickness_kind, ThicknessKind::uniform);
    EXPECT_EQ(section.thickness_um, 25.0);
    const auto used = section.label_counts();
    ASSERT_EQ(used.size(), section.grains.size());  // no extra grains either
    EXPECT_GE(used.size(), 295u);                    // an empty cell is rare at 133 pixels per seed
    for (std::size_t i = 0; i < used.size(); ++i) {
        EXPECT_EQ(used[i].first, i + 1);
        ASSERT_GE(section.grain_index_of_label[used[i].first], 0);
        const ThinSectionGrain& grain = section.grains[static_cast<std::size_t>(section.grain_index_of_label[used[i].first])];
        EXPECT_EQ(grain.label, used[i].first);
        EXPECT_TRUE(grain.mineral == "quartz" || grain.mineral == "calcite");
        EXPECT_FALSE(grain.thickness_um);
    }
    ThinSection copy = section;
    EXPECT_NO_THROW(copy.validate());
}

TEST(RandomVoronoiSection, CellsAreTheNearestSeedsFoundByBruteForce) {
    VoronoiSectionSettings settings;
    settings.minerals = {"quartz", "orthoclase", "biotite"};
    settings.size_px = 96;
    for (const int grains : {1, 2, 7, 60, 100, 900}) {  // 100: blocks of 5 px, the last one 1 px wide (h = 0)
        for (const std::uint64_t seed : {1u, 2u}) {
            settings.grain_count = grains;
            settings.seed = seed;
            settings.weights = seed == 1 ? std::vector<double>{4, 3, 2} : std::vector<double>{};
            settings.grain_sizes.clear();
            EXPECT_EQ(random_voronoi_section(settings).labels, brute_force_labels(settings)) << grains << " grains, seed " << seed;
            settings.grain_sizes = {1.0, 2.5, 0.4};  // power diagram
            EXPECT_EQ(random_voronoi_section(settings).labels, brute_force_labels(settings)) << grains << " grains, seed " << seed << ", sizes";
        }
    }
}

TEST(RandomVoronoiSection, MineralFrequenciesFollowTheWeights) {
    constexpr int kGrains = 4000;
    const ThinSection section = random_voronoi_section({"quartz", "calcite", "gypsum"}, {3, 1, 0}, kGrains, 512, 1.0, 30.0, 5);
    std::map<std::string, int> count;
    for (const ThinSectionGrain& grain : section.grains) ++count[grain.mineral];
    const double n = static_cast<double>(section.grains.size());
    EXPECT_GT(n, 0.99 * kGrains);
    EXPECT_NEAR(count["quartz"] / n, 0.75, 4.0 * std::sqrt(0.75 * 0.25 / n));
    EXPECT_EQ(count["gypsum"], 0);  // weight 0: never drawn
}

TEST(RandomVoronoiSection, LargerGrainSizesGiveLargerGrains) {
    VoronoiSectionSettings settings;
    settings.minerals = {"orthoclase", "biotite"};
    settings.grain_sizes = {2.0, 1.0};
    settings.grain_count = 800;
    settings.size_px = 512;
    const ThinSection section = random_voronoi_section(settings);
    std::map<std::string, std::pair<double, int>> area;  // pixels, grains
    for (const auto& [label, pixels] : section.label_counts()) {
        auto& entry = area[section.grains[static_cast<std::size_t>(section.grain_index_of_label[label])].mineral];
        entry.first += static_cast<double>(pixels);
        ++entry.second;
    }
    const double orthoclase = area["orthoclase"].first / area["orthoclase"].second;
    const double biotite = area["biotite"].first / area["biotite"].second;
    // Diameters roughly in proportion 2 : 1, so areas near 4 : 1; at least clearly larger.
    EXPECT_GT(orthoclase / biotite, 2.0);
    EXPECT_LT(orthoclase / biotite, 8.0);
}

TEST(RandomVoronoiSection, RejectsBadSettings) {
    const auto make = [](int grains, int size) { return random_voronoi_section({"quartz"}, {}, grains, size, 1.0, 30.0, 1); };
    EXPECT_THROW(make(0, 64), InputError);
    EXPECT_THROW(make(16 * 16 + 1, 16), InputError);
    EXPECT_THROW(make(65536, 8192), InputError);
    EXPECT_THROW(make(10, 15), InputError);
    EXPECT_THROW(make(10, 8193), InputError);
    EXPECT_NO_THROW(make(16 * 16, 16));
    EXPECT_THROW(random_voronoi_section({}, {}, 10, 64, 1.0, 30.0, 1), InputError);
    EXPECT_THROW(random_voronoi_section({"quartz", "calcite"}, {1}, 10, 64, 1.0, 30.0, 1), InputError);
    EXPECT_THROW(random_voronoi_section({"quartz", "calcite"}, {0, 0}, 10, 64, 1.0, 30.0, 1), InputError);
    EXPECT_THROW(random_voronoi_section({"quartz"}, {-1}, 10, 64, 1.0, 30.0, 1), InputError);
    EXPECT_THROW(random_voronoi_section({"quartz"}, {}, 10, 64, 0.0, 30.0, 1), InputError);
    EXPECT_THROW(random_voronoi_section({"quartz"}, {}, 10, 64, 1.0, -30.0, 1), InputError);
}

// Was a bug: in a block of a single pixel (h = 0) the bound of the best seed and U are the same number
// computed in two ways, and with fused multiply-adds the bound came out one rounding above U, leaving the
// pixel without a candidate and writing out of bounds (2048 = 89·23 + 1: the corner block is one pixel).
TEST(RandomVoronoiSection, EveryPixelGetsASeedInPowerDiagrams) {
    VoronoiSectionSettings settings;
    settings.minerals = {"quartz", "orthoclase", "albite"};
    settings.grain_sizes = {2.0, 1.0, 0.5};
    settings.grain_count = 2000;
    settings.size_px = 2048;
    ThinSection section = random_voronoi_section(settings);
    EXPECT_NO_THROW(section.validate());
    EXPECT_GT(section.grains.size(), 1000u);
}

// The speed promised in the header: a 2048² map of 2000 grains well under a second.
TEST(RandomVoronoiSection, LargeMapIsFast) {
    const auto started = std::chrono::steady_clock::now();
    const ThinSection section = random_voronoi_section({"quartz", "orthoclase", "albite"}, {}, 2000, 2048, 1.0, 30.0, 3);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    RecordProperty("seconds", std::to_string(seconds));
    std::printf("2048x2048, 2000 grains: %.3f s\n", seconds);
    EXPECT_EQ(section.grains.size(), 2000u);
    EXPECT_LT(seconds, 1.0);
}

}  // namespace
}  // namespace petroscope
