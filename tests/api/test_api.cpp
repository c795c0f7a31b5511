// The library layer: requests in the user's terms give what the physics gives for the same settings,
// bad requests fail before any work with a message naming the value, and progress can cancel.
#include "api_testing.hpp"

#include "petroscope/api/conical_screen.hpp"
#include "petroscope/api/conoscope_figure.hpp"
#include "petroscope/api/conoscope_photo_model.hpp"
#include "petroscope/api/orthoscope_image.hpp"
#include "petroscope/core/error.hpp"
#include "petroscope/io/data_files.hpp"
#include "petroscope/spectral/color.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace petroscope {
namespace {

TEST(LibraryLayer, TheDefaultCutFollowsTheOpticalClass) {
    EXPECT_EQ(default_cut(OpticalClass::biaxial), Cut::acute_bisectrix);
    EXPECT_EQ(default_cut(OpticalClass::uniaxial), Cut::optic_axis);
    const Mineral& muscovite = minerals().find("muscovite");
    EXPECT_EQ(cut_used(muscovite, {}), Cut::acute_bisectrix);
    CrystalOrientation euler;
    euler.euler_zyz_deg = Eigen::Vector3d(10, 20, 30);
    EXPECT_FALSE(cut_used(muscovite, euler).has_value());
    EXPECT_LT((indicatrix_axes(muscovite, euler) - euler_zyz_deg(10, 20, 30)).cwiseAbs().maxCoeff(), 1e-15);
}

TEST(LibraryLayer, AConoscopeRequestGivesThePhysicsFigureInDisplayColours) {
    ConoscopeRequest request;
    request.mineral = "calcite";
    request.thickness_um = 100.0;
    request.size_px = 64;
    request.light.wavelength_nm = 589.3;
    request.light.exposure = 2.0;
    const ConoscopePlan plan = plan_conoscope(request, minerals());
    ASSERT_EQ(plan.cut, Cut::optic_axis);
    const ConoscopeFigure figure = render_conoscope_figure(plan);

    // The same figure straight from the physics core: crossed polars, balsam, the optic axis vertical.
    ConoscopeSettings settings;
    settings.size_px = 64;
    settings.thickness_um = 100.0;
    settings.wavelengths_nm = {589.3};
    const Mineral& calcite = minerals().find("calcite");
    settings.crystal_axes = cut_orientation(Cut::optic_axis, OpticalClass::uniaxial, calcite.principal_n(calcite.reference_wavelength_nm), 0, 0);
    const Image expected = gray_image_to_rgb(render_conoscope(settings, [&](double nm) { return calcite.principal_n(nm); }, nullptr), 2.0);
    ASSERT_EQ(figure.image.linear_rgb.pixels.size(), expected.pixels.size());
    for (std::size_t i = 0; i < expected.pixels.size(); ++i) ASSERT_EQ(figure.image.linear_rgb.pixels[i], expected.pixels[i]) << i;
    EXPECT_TRUE(figure.image.illuminant.empty());

    // The centred optic axis is imaged at the centre, where the melatope is found.
    EXPECT_NEAR(*measured(figure.measurements, "optic_axis_1_radius"), 0.0, 1e-12);
    EXPECT_LT(*measured(figure.measurements, "melatope_1_radius"), 2.0 / 32.0);
    EXPECT_FALSE(measured(figure.measurements, "optic_axis_2_x").has_value());  // uniaxial: one axis
}

TEST(LibraryLayer, BadRequestsNameTheValueAndDoNoWork) {
    ConoscopeRequest negative;
    negative.thickness_um = -5.0;
    expect_input_error([&] { plan_conoscope(negative, minerals()); }, "thickness");
    ConoscopeRequest unknown;
    unknown.mineral = "unobtainium";
    expect_input_error([&] { plan_conoscope(unknown, minerals()); }, "unobtainium");
    ConoscopeRequest dark;
    dark.light.exposure = std::nan("");
    expect_input_error([&] { plan_conoscope(dark, minerals()); }, "exposure");
    ConoscopeRequest wrong_cut;
    wrong_cut.mineral = "calcite";
    wrong_cut.orientation.cut = Cut::acute_bisectrix;
    expect_input_error([&] { plan_conoscope(wrong_cut, minerals()); }, "acute-bisectrix");
    ConicalRequest uniaxial;
    uniaxial.crystal = "calcite";
    expect_input_error([&] { plan_conical(uniaxial, minerals()); }, "biaxial");
    ConicalRequest no_rays;
    no_rays.optics = ConicalOptics::ray;
    no_rays.rays = 0;
    expect_input_error([&] { plan_conical(no_rays, minerals()); }, "rays");
}

TEST(LibraryLayer, WhiteLightUsesTheIlluminantAndTheFitModelItsColours) {
    ConoscopeRequest request;
    request.size_px = 64;
    request.light.grid = {400.0, 700.0, 20.0};
    const ConoscopeFigure figure = render_conoscope_figure(plan_conoscope(request, minerals()));
    EXPECT_EQ(figure.image.illuminant, "D65");
    EXPECT_EQ(figure.image.linear_rgb.channels, 3);
    // The fit's colour per unit transmission: a transmission of 1 at every wavelength is white (1, 1, 1)
    // once white balanced, to the 4 digits of the sRGB matrix (IEC 61966-2-1 maps D65 to white within 2e-4).
    ConoscopePhotoSetup setup;
    setup.light = request.light;
    const ConoscopePhotoModel model = conoscope_photo_model(minerals().find("muscovite"), setup);
    Eigen::Vector3d white = Eigen::Vector3d::Zero();
    for (const Eigen::Vector3d& weight : model.rgb_per_transmission) white += weight;
    EXPECT_LT((white - Eigen::Vector3d::Ones()).cwiseAbs().maxCoeff(), 3e-4) << white.transpose();
    const Mineral& muscovite = minerals().find("muscovite");
    EXPECT_LT((model.orientation(0.0, 0.0) - indicatrix_axes(muscovite, {})).cwiseAbs().maxCoeff(), 1e-15);
}

TEST(LibraryLayer, AnOrthoscopeRequestOverridesTheThicknessAndMeasuresTheField) {
    ThinSection section;
    section.width_px = section.height_px = 8;
    section.labels.assign(64, 1);
    section.grains = {{1, "quartz", euler_zyz_deg(0, 90, 30), std::nullopt, 0}};
    OrthoscopeRequest thin;
    thin.section = section;
    thin.light.wavelength_nm = 550.0;
    thin.thickness_um = 1e-3;  // next to nothing: dark between crossed polars
    const OrthoscopeImage dark = render_orthoscope_image(plan_orthoscope(thin, minerals()));
    EXPECT_LT(*measured(dark.measurements, "mean_luminance"), 1e-4);
    OrthoscopeRequest plane = thin;
    plane.analyzer_in = false;  // plane-polarized light: nearly everything passes (reflections aside)
    const OrthoscopeImage bright = render_orthoscope_image(plan_orthoscope(plane, minerals()));
    EXPECT_GT(*measured(bright.measurements, "mean_luminance"), 0.8);
    OrthoscopeRequest negative = thin;
    negative.thickness_um = -1.0;
    expect_input_error([&] { plan_orthoscope(negative, minerals()); }, "thickness");
}

TEST(LibraryLayer, ProgressCancelsTheLongCalls) {
    const ProgressCallback stop = [](double) { return false; };
    ConoscopeRequest figure;
    figure.size_px = 64;
    figure.light.wavelength_nm = 589.3;
    EXPECT_THROW(render_conoscope_figure(plan_conoscope(figure, minerals()), stop), Cancelled);
    ConicalRequest rays;
    rays.optics = ConicalOptics::ray;
    rays.size_px = 64;
    EXPECT_THROW(render_conical_screen(plan_conical(rays, minerals()), stop), Cancelled);
    ConoscopePhotoSetup setup;
    setup.light.wavelength_nm = 589.3;
    const ConoscopePhotoModel model = conoscope_photo_model(minerals().find("muscovite"), setup);
    const Image photo = render_conoscope_photo(model, default_photo_parameters(64, 64), 64, 64);
    ConoscopeFitOptions options;
    options.initial = default_photo_parameters(64, 64);
    options.free.fill(true);
    EXPECT_THROW(fit_conoscope_photo(photo, model, options, stop), Cancelled);
}

}  // namespace
}  // namespace petroscope
