// Acceptance of `fit orthoscope` (issue 6) on synthetic photos: a one-grain section rendered by the
// orthoscope renderer at several stage angles, with and without the gypsum plate, through an sRGB camera
// with noise σ = 2/255 and JPEG quality 85; the thickness and orientation hidden from the fit.
#include "grain_photo.hpp"

#include "petroscope/core/error.hpp"
#include "petroscope/fit/orthoscope_fit.hpp"
#include "petroscope/microscope/orthoscope.hpp"
#include "petroscope/optics/orientation.hpp"

#include <gtest/gtest.h>

namespace petroscope {
namespace {

constexpr int kSize = 32;  // the photo, px; the grain fills it, the region is its central 12 px

struct GrainShot {
    double stage_deg = 0.0;
    bool gypsum = false;
};

class GrainPhotos {
public:
    GrainPhotos()
        : light_(testing::white_light()), options_() {
        options_.microscope.wavelengths_nm = light_.wavelengths_nm;
        options_.mounting = standard_mounting(testing::fit_minerals());
    }

    const OrthoscopeFitOptions& options() const { return options_; }
    OrthoscopeFitOptions& options() { return options_; }
    const SpectralIntegrator& integrator() const { return *light_.integrator; }

    /// Photos of a grain of `mineral`, `thickness_um` thick, with indicatrix axes `axes` at stage 0.
    std::vector<GrainPhoto> take(const std::string& mineral, double thickness_um, const Eigen::Matrix3d& axes,
                                 const std::vector<GrainShot>& shots, unsigned seed) const {
        ThinSection section;
        section.name = "grain";
        section.width_px = section.height_px = kSize;
        section.pixel_size_um = 10.0;
        section.labels.assign(kSize * kSize, 1);
        section.grains.push_back({1, mineral, axes, std::nullopt, 0});
        section.thickness_um = thickness_um;
        section.validate();
        std::vector<GrainPhoto> photos;
        for (const GrainShot& shot : shots) {
            const cv::Mat linear = testing::section_linear(section, options_, light_, shot.stage_deg, shot.gypsum);
            const Image photo = testing::camera_image(
                linear, [](int, double value) { return encode_srgb(std::clamp(value, 0.0, 1.0)); }, 2.0 / 255.0, 85, seed++);
            GrainPhoto grain;
            grain.colour = grain_colour(photo, rectangle_mask(kSize, kSize, 10, 10, 12, 12));
            grain.stage_deg = shot.stage_deg;
            if (shot.gypsum) grain.plate = testing::gypsum_plate();
            photos.push_back(grain);
        }
        return photos;
    }

private:
    testing::PhotoLight light_;
    OrthoscopeFitOptions options_;
};

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

TEST(OrthoscopeFit, KnownOrientationThicknessWithinHalfAMicrometre) {
    GrainPhotos camera;
    std::mt19937_64 rng(6);
    for (const std::string& name : kMinerals) {
        const Mineral& mineral = testing::fit_minerals().find(name);
        for (const double thickness : kThicknesses) {
            const Eigen::Matrix3d axes = random_birefringent_orientation(mineral, rng);
            const std::vector<GrainPhoto> photos = camera.take(name, thickness, axes, {{30.0, false}, {30.0, true}}, 11);
            camera.options().orientation = GrainOrientation::known;
            camera.options().known_axes = axes;
            const OrthoscopeFitResult fit = fit_orthoscope_grain(photos, mineral, camera.options(), camera.integrator());
            SCOPED_TRACE(name + " " + std::to_string(thickness) + " um");
            EXPECT_TRUE(fit.acceptable) << fit.verdict;
            ASSERT_TRUE(fit.thickness_um.identifiable);
            EXPECT_NEAR(fit.thickness_um.value, thickness, 0.5);
            ASSERT_TRUE(fit.thickness_um.sigma.has_value());
            EXPECT_LE(std::abs(fit.thickness_um.value - thickness), 2.0 * *fit.thickness_um.sigma + 0.05) << "sigma " << *fit.thickness_um.sigma;
            std::printf("known orientation, %s %.0f um: %.3f +- %.3f um (rms %.2f codes)\n", name.c_str(), thickness, fit.thickness_um.value,
                        *fit.thickness_um.sigma, 255.0 * fit.rms_code);
        }
    }
}

TEST(OrthoscopeFit, UnknownInPlaneOrientationThicknessWithinOneAndAHalfMicrometres) {
    GrainPhotos camera;
    std::mt19937_64 rng(9);
    for (const std::string& name : kMinerals) {
        const Mineral& mineral = testing::fit_minerals().find(name);
        for (const double thickness : kThicknesses) {
            // A grain of maximum birefringence (X and Z in the section) at a random angle on the stage.
            const double angle_deg = 180.0 * uniform_unit_interval(rng);
            const Eigen::Matrix3d axes = testing::max_birefringence_axes(angle_deg);
            const std::vector<GrainPhoto> photos = camera.take(name, thickness, axes, {{0.0, false}, {30.0, false}, {0.0, true}}, 21);
            camera.options().orientation = GrainOrientation::max_birefringence;
            const OrthoscopeFitResult fit = fit_orthoscope_grain(photos, mineral, camera.options(), camera.integrator());
            SCOPED_TRACE(name + " " + std::to_string(thickness) + " um, X at " + std::to_string(angle_deg) + " deg");
            EXPECT_TRUE(fit.acceptable) << fit.verdict;
            ASSERT_TRUE(fit.thickness_um.identifiable);
            EXPECT_NEAR(fit.thickness_um.value, thickness, 1.5);
            // The plate tells the slow direction from the fast: the angle is found modulo 180°, not 90°.
            const double angle_error = std::remainder(fit.angles_deg[0].value - angle_deg, 180.0);
            EXPECT_LT(std::abs(angle_error), 2.0);
            std::printf("max birefringence, %s %.0f um: %.3f +- %.3f um, angle error %.2f deg (rms %.2f codes)\n", name.c_str(), thickness,
                        fit.thickness_um.value, fit.thickness_um.sigma.value_or(-1.0), angle_error, 255.0 * fit.rms_code);
        }
    }
}

TEST(OrthoscopeFit, FreeOrientationReportsRetardationAndNoThickness) {
    GrainPhotos camera;
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
    GrainPhotos camera;
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
        fit_orthoscope_grain({grey_photo, grey_photo}, testing::fit_minerals().find("quartz"), GrainPhotos().options(), GrainPhotos().integrator());
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
    GrainPhotos camera;
    camera.options().thickness_min_um = 50.0;
    camera.options().thickness_max_um = 10.0;
    GrainPhoto photo;
    photo.colour.pixels = 1;
    EXPECT_THROW(fit_orthoscope_grain({photo}, testing::fit_minerals().find("quartz"), camera.options(), camera.integrator()), InputError);
    EXPECT_THROW(fit_orthoscope_grain({}, testing::fit_minerals().find("quartz"), GrainPhotos().options(), camera.integrator()), InputError);
}

}  // namespace
}  // namespace petroscope
