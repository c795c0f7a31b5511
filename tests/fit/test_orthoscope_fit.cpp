// Acceptance of `fit orthoscope` (issue 6) on synthetic photos: a one-grain section rendered by the
// orthoscope renderer at several stage angles, with and without the gypsum plate, through an sRGB camera
// with noise σ = 2/255 and JPEG quality 85; the thickness and orientation hidden from the fit.
#include "grain_photo.hpp"

#include "petroscope/core/error.hpp"
#include "petroscope/fit/orthoscope_fit.hpp"
#include "petroscope/optics/orientation.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

namespace petroscope {
namespace {

/// Orientations of grains with at least half the mineral's maximum birefringence (a grain near an optic
/// axis section shows grey whatever its thickness: no method finds its thickness from colours).
Eigen::Matrix3d random_birefringent_orientation(const Mineral& mineral, std::mt19937_64& rng) {
    const Eigen::Vector3d n = mineral.principal_n(550.0);
    for (;;) {
        const Eigen::Matrix3d axes = shoemake_rotation(uniform_unit_interval(rng), uniform_unit_interval(rng), uniform_unit_interval(rng));
        if (normal_incidence_birefringence(mineral, axes, 550.0) >= 0.5 * (n.maxCoeff() - n.minCoeff())) return axes;
    }
}

const std::vector<std::string> kMinerals{"quartz", "labradorite", "forsterite"};
const std::vector<double> kThicknesses{20.0, 35.0, 60.0};

/// One grain of the two tests below: a mineral of kMinerals at each of kThicknesses, drawn from one random
/// sequence over all minerals in order, so that each mineral's cases are the same whichever runs alone (the
/// sanitizer build runs forsterite's only, docs/testing.md).
struct GrainCase {
    double thickness_um = 0.0;
    Eigen::Matrix3d axes;
    double angle_deg = 0.0;  // X's angle on the stage, for a grain of maximum birefringence
};

/// Grains of a known random orientation, or (GrainOrientation::max_birefringence) of maximum birefringence at a random angle.
std::vector<GrainCase> grain_cases(const std::string& mineral_name, unsigned seed, GrainOrientation orientation) {
    std::mt19937_64 rng(seed);
    for (const std::string& name : kMinerals) {
        std::vector<GrainCase> cases;
        for (const double thickness : kThicknesses) {
            GrainCase grain{thickness, Eigen::Matrix3d::Identity(), 0.0};
            if (orientation == GrainOrientation::max_birefringence) {
                grain.angle_deg = 180.0 * uniform_unit_interval(rng);  // X and Z in the section, X at a random angle
                grain.axes = testing::max_birefringence_axes(grain.angle_deg);
            } else {
                grain.axes = random_birefringent_orientation(testing::fit_minerals().find(name), rng);
            }
            cases.push_back(grain);
        }
        if (name == mineral_name) return cases;
    }
    throw std::invalid_argument("no grain cases for " + mineral_name);
}

class OrthoscopeFitOfMineral : public ::testing::TestWithParam<std::string> {};

TEST_P(OrthoscopeFitOfMineral, KnownOrientationThicknessWithinHalfAMicrometre) {
    testing::GrainPhotos camera;
    const std::string& name = GetParam();
    const Mineral& mineral = testing::fit_minerals().find(name);
    for (const GrainCase& grain : grain_cases(name, 6, GrainOrientation::known)) {
        const std::vector<GrainPhoto> photos = camera.take(name, grain.thickness_um, grain.axes, {{30.0, false}, {30.0, true}}, 11);
        camera.options().orientation = GrainOrientation::known;
        camera.options().known_axes = grain.axes;
        const OrthoscopeFitResult fit = fit_orthoscope_grain(photos, mineral, camera.options(), camera.integrator());
        SCOPED_TRACE(name + " " + std::to_string(grain.thickness_um) + " um");
        EXPECT_TRUE(fit.acceptable) << fit.verdict;
        ASSERT_TRUE(fit.thickness_um.identifiable);
        EXPECT_NEAR(fit.thickness_um.value, grain.thickness_um, 0.5);
        ASSERT_TRUE(fit.thickness_um.sigma.has_value());
        EXPECT_LE(std::abs(fit.thickness_um.value - grain.thickness_um), 2.0 * *fit.thickness_um.sigma + 0.05) << "sigma " << *fit.thickness_um.sigma;
        std::printf("known orientation, %s %.0f um: %.3f +- %.3f um (rms %.2f codes)\n", name.c_str(), grain.thickness_um, fit.thickness_um.value,
                    *fit.thickness_um.sigma, 255.0 * fit.rms_code);
    }
}

TEST_P(OrthoscopeFitOfMineral, UnknownInPlaneOrientationThicknessWithinOneAndAHalfMicrometres) {
    testing::GrainPhotos camera;
    const std::string& name = GetParam();
    const Mineral& mineral = testing::fit_minerals().find(name);
    for (const GrainCase& grain : grain_cases(name, 9, GrainOrientation::max_birefringence)) {
        const std::vector<GrainPhoto> photos = camera.take(name, grain.thickness_um, grain.axes, {{0.0, false}, {30.0, false}, {0.0, true}}, 21);
        camera.options().orientation = GrainOrientation::max_birefringence;
        const OrthoscopeFitResult fit = fit_orthoscope_grain(photos, mineral, camera.options(), camera.integrator());
        SCOPED_TRACE(name + " " + std::to_string(grain.thickness_um) + " um, X at " + std::to_string(grain.angle_deg) + " deg");
        EXPECT_TRUE(fit.acceptable) << fit.verdict;
        ASSERT_TRUE(fit.thickness_um.identifiable);
        EXPECT_NEAR(fit.thickness_um.value, grain.thickness_um, 1.5);
        // The plate tells the slow direction from the fast: the angle is found modulo 180°, not 90°.
        const double angle_error = std::remainder(fit.angles_deg[0].value - grain.angle_deg, 180.0);
        EXPECT_LT(std::abs(angle_error), 2.0);
        std::printf("max birefringence, %s %.0f um: %.3f +- %.3f um, angle error %.2f deg (rms %.2f codes)\n", name.c_str(), grain.thickness_um,
                    fit.thickness_um.value, fit.thickness_um.sigma.value_or(-1.0), angle_error, 255.0 * fit.rms_code);
    }
}

INSTANTIATE_TEST_SUITE_P(Minerals, OrthoscopeFitOfMineral, ::testing::ValuesIn(kMinerals),
                         [](const ::testing::TestParamInfo<std::string>& info) { return info.param; });

TEST(OrthoscopeFit, FreeOrientationReportsRetardationAndNoThickness) {
    testing::GrainPhotos camera;
    std::mt19937_64 rng(3);
    const Mineral& quartz = testing::fit_minerals().find("quartz");
    const Eigen::Matrix3d axes = random_birefringent_orientation(quartz, rng);
    const double thickness = 30.0;
    const std::vector<GrainPhoto> photos = camera.take("quartz", thickness, axes, {{0.0, false}, {30.0, false}, {0.0, true}}, 31);
    camera.options().orientation = GrainOrientation::free;
    const OrthoscopeFitResult fit = fit_orthoscope_grain(photos, quartz, camera.options(), camera.integrator());
    EXPECT_TRUE(fit.acceptable) << fit.verdict;
    // Thickness and birefringence enter only as their product: neither is a measurement, the product is.
    EXPECT_FALSE(fit.thickness_um.identifiable);
    EXPECT_FALSE(fit.thickness_um.sigma.has_value());
    const double retardation_nm = thickness * 1e3 * normal_incidence_birefringence(quartz, axes, 550.0);
    ASSERT_TRUE(fit.retardation_nm.identifiable);
    EXPECT_NEAR(fit.retardation_nm.value, retardation_nm, 0.03 * retardation_nm);
    ASSERT_TRUE(fit.thickness_lower_bound_um.has_value());
    EXPECT_LE(*fit.thickness_lower_bound_um, thickness * 1.03);
    std::printf("free orientation: retardation %.1f nm (true %.1f), thickness >= %.2f um\n", fit.retardation_nm.value, retardation_nm,
                *fit.thickness_lower_bound_um);
}

TEST(OrthoscopeFit, PhotoOfSomethingElseIsNoAcceptableFit) {
    testing::GrainPhotos camera;
    // A saturated green no grain of quartz shows between crossed polars.
    GrainPhoto photo;
    photo.colour.mean_code = Eigen::Vector3d(0.05, 0.9, 0.05);
    photo.colour.pixels = 100;
    camera.options().orientation = GrainOrientation::max_birefringence;
    const OrthoscopeFitResult fit = fit_orthoscope_grain({photo}, testing::fit_minerals().find("quartz"), camera.options(), camera.integrator());
    EXPECT_FALSE(fit.acceptable);
    EXPECT_NE(fit.verdict.find("no acceptable fit"), std::string::npos) << fit.verdict;
    EXPECT_TRUE(std::isfinite(fit.thickness_um.value));
    EXPECT_TRUE(std::isfinite(fit.rms_code));
}

TEST(OrthoscopeFit, BadPhotosAreRefusedWithAClearMessage) {
    const Image grey(8, 8, 1);
    EXPECT_THROW(grain_colour(grey, rectangle_mask(8, 8, 0, 0, 8, 8)), InputError);
    const auto expect_refused = [](const Image& photo, const std::string& expected) {
        try {
            grain_colour(photo, rectangle_mask(8, 8, 2, 2, 4, 4));
            ADD_FAILURE() << "accepted; expected an error with '" << expected << "'";
        } catch (const InputError& error) {
            EXPECT_NE(std::string(error.what()).find(expected), std::string::npos) << error.what();
        }
    };
    Image grey_rgb(8, 8, 3);
    std::fill(grey_rgb.pixels.begin(), grey_rgb.pixels.end(), 0.5f);
    GrainPhoto grey_photo;
    grey_photo.colour = grain_colour(grey_rgb, rectangle_mask(8, 8, 2, 2, 4, 4));
    EXPECT_TRUE(grey_photo.colour.grey);
    try {
        fit_orthoscope_grain({grey_photo, grey_photo}, testing::fit_minerals().find("quartz"), testing::GrainPhotos().options(), testing::GrainPhotos().integrator());
        ADD_FAILURE() << "grey photos were fitted";
    } catch (const InputError& error) {
        EXPECT_NE(std::string(error.what()).find("grayscale"), std::string::npos) << error.what();
    }
    std::fill(grey_rgb.pixels.begin(), grey_rgb.pixels.end(), 0.0f);  // an extinct grain: black, not "grey"
    EXPECT_FALSE(grain_colour(grey_rgb, rectangle_mask(8, 8, 2, 2, 4, 4)).grey);
    Image white(8, 8, 3);
    std::fill(white.pixels.begin(), white.pixels.end(), 1.0f);
    expect_refused(white, "saturated");
    EXPECT_THROW(rectangle_mask(8, 8, 4, 4, 8, 2), InputError);  // leaves the photo
    EXPECT_THROW(rectangle_mask(8, 8, 0, 0, 0, 2), InputError);  // empty
    EXPECT_THROW(grain_colour(white, Image(4, 4, 1)), InputError);  // mask of another size
    EXPECT_THROW(grain_colour(white, Image(8, 8, 1)), InputError);  // mask selects nothing
    testing::GrainPhotos camera;
    camera.options().thickness_min_um = 50.0;
    camera.options().thickness_max_um = 10.0;
    GrainPhoto photo;
    photo.colour.pixels = 1;
    EXPECT_THROW(fit_orthoscope_grain({photo}, testing::fit_minerals().find("quartz"), camera.options(), camera.integrator()), InputError);
    EXPECT_THROW(fit_orthoscope_grain({}, testing::fit_minerals().find("quartz"), testing::GrainPhotos().options(), camera.integrator()), InputError);
}

}  // namespace
}  // namespace petroscope
