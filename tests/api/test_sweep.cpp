// Sweeps in the library's terms: the grid's frame order, typed fields put in place, frames rendered in
// parallel equal to the same frames rendered alone, errors and cancelling.
#include "api_testing.hpp"

#include "petroscope/api/sweep.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <mutex>
#include <set>

namespace petroscope {
namespace {

SweepGrid tilt_by_azimuth() {
    return SweepGrid{{{"tilt_deg", {0.0, 10.0}}, {"azimuth_deg", {0.0, 45.0, 90.0}}}};
}

TEST(Sweep, FramesRunThroughTheGridLastAxisFastest) {
    const SweepGrid grid = tilt_by_azimuth();
    grid.validate();
    ASSERT_EQ(grid.frame_count(), 6u);
    EXPECT_EQ(grid.values_of(0), (std::vector<double>{0.0, 0.0}));
    EXPECT_EQ(grid.values_of(2), (std::vector<double>{0.0, 90.0}));
    EXPECT_EQ(grid.values_of(4), (std::vector<double>{10.0, 45.0}));
    EXPECT_EQ(grid.label(5), "tilt_deg 10, azimuth_deg 90");
}

TEST(Sweep, ABadGridFailsNamingWhatIsWrong) {
    expect_input_error([] { SweepGrid{}.validate(); }, "no field to sweep");
    expect_input_error([] { SweepGrid{{{"tilt_deg", {}}}}.validate(); }, "'tilt_deg' has no values");
    expect_input_error([] { SweepGrid{{{"tilt_deg", {1.0}}, {"tilt_deg", {2.0}}}}.validate(); }, "swept twice");
    expect_input_error([] { SweepGrid{{{"tilt_deg", {std::nan("")}}}}.validate(); }, "not a finite number");
    const SweepGrid large{{{"a", std::vector<double>(2000, 1.0)}, {"b", std::vector<double>(2000, 1.0)}}};
    expect_input_error([&] { large.validate(1000000); }, "4000000 frames; at most 1000000");
}

TEST(Sweep, AFrameRequestIsTheBaseWithTheFramesValuesInPlace) {
    ConoscopeRequest base;
    base.mineral = "calcite";
    const SweepGrid grid{{{"thickness_um", {10.0, 20.0}}, {"wavelength_nm", {500.0, 600.0}}}};
    const ConoscopeRequest request = frame_request(base, "conoscope", grid, 2);
    EXPECT_EQ(request.mineral, "calcite");
    EXPECT_EQ(request.thickness_um, 20.0);
    EXPECT_EQ(request.light.wavelength_nm, 500.0);
    EXPECT_FALSE(base.light.wavelength_nm.has_value());

    OrthoscopeRequest section_base;
    const OrthoscopeRequest thinner = frame_request(section_base, "orthoscope", SweepGrid{{{"thickness_um", {25.0}}}}, 0);
    EXPECT_EQ(thinner.thickness_um, 25.0);
    const ConicalRequest longer = frame_request(ConicalRequest{}, "conical", SweepGrid{{{"length_um", {5000.0}}}}, 0);
    EXPECT_EQ(longer.length_um, 5000.0);
}

TEST(Sweep, AnUnknownFieldOrAPlateFieldWithoutAPlateFails) {
    expect_input_error([] { frame_request(ConoscopeRequest{}, "conoscope", SweepGrid{{{"thickness", {1.0}}}}, 0); },
                       "'thickness' is not a numeric field of conoscope; these can be swept: thickness_um, azimuth_deg");
    expect_input_error([] { frame_request(ConoscopeRequest{}, "conoscope", SweepGrid{{{"plate_slow_deg", {1.0}}}}, 0); },
                       "plate_slow_deg is swept, but there is no plate");
    ConoscopeRequest with_wedge;
    with_wedge.plate = PlateRequest{PlateKind::wedge, 45.0, 0.5};
    EXPECT_EQ(frame_request(with_wedge, "conoscope", SweepGrid{{{"wedge_position", {0.25}}}}, 0).plate->wedge_position, 0.25);
}

TEST(Sweep, EveryFieldOfEveryRequestHasADistinctName) {
    const auto distinct = [](auto fields) {
        std::set<std::string_view> names;
        for (const auto& field : fields) names.insert(field.name);
        return names.size() == fields.size() && !fields.empty();
    };
    EXPECT_TRUE(distinct(sweep_fields<ConoscopeRequest>()));
    EXPECT_TRUE(distinct(sweep_fields<OrthoscopeRequest>()));
    EXPECT_TRUE(distinct(sweep_fields<ConicalRequest>()));
}

ConoscopeFigure small_figure(const ConoscopeRequest& request, const ProgressCallback& progress = {}) {
    return render_conoscope_figure(plan_conoscope(request, minerals()), progress);
}

TEST(Sweep, FramesRenderedInParallelEqualEachFrameRenderedAlone) {
    ConoscopeRequest base;
    base.size_px = 64;
    base.light.wavelength_nm = 589.3;
    const SweepGrid grid = tilt_by_azimuth();
    std::vector<Image> swept(grid.frame_count());
    std::vector<std::size_t> frames{0, 1, 2, 3, 4, 5};
    std::vector<double> reported;
    run_sweep_frames(frames, 2, [&](std::size_t frame, const ProgressCallback& progress) {
        swept[frame] = small_figure(frame_request(base, "conoscope", grid, frame), progress).image.linear_rgb;
    }, [&](double fraction) {
        reported.push_back(fraction);
        return true;
    });
    for (std::size_t frame = 0; frame < frames.size(); ++frame) {
        const Image alone = small_figure(frame_request(base, "conoscope", grid, frame)).image.linear_rgb;
        ASSERT_EQ(alone.pixels.size(), swept[frame].pixels.size());
        EXPECT_TRUE(alone.pixels == swept[frame].pixels) << "frame " << frame;
    }
    ASSERT_FALSE(reported.empty());
    EXPECT_EQ(reported.back(), 1.0);
    // The frames differ: a tilted figure is not the centred one.
    EXPECT_FALSE(swept[0].pixels == swept[3].pixels);
}

TEST(Sweep, AFramesErrorStopsTheSweepAndComesBack) {
    std::atomic<int> started{0};
    expect_input_error([&] {
        run_sweep_frames({0, 1, 2, 3}, 1, [&](std::size_t frame, const ProgressCallback&) {
            ++started;
            if (frame == 1) throw InputError("frame 1 is bad");
        });
    }, "frame 1 is bad");
    EXPECT_EQ(started.load(), 2);  // one job: frames in order, none after the failing one
}

TEST(Sweep, TheCallbackCancelsBetweenAndWithinFrames) {
    std::atomic<int> rendered{0};
    EXPECT_THROW(run_sweep_frames({0, 1, 2, 3}, 1, [&](std::size_t, const ProgressCallback&) { ++rendered; },
                                  [](double fraction) { return fraction < 0.5; }),
                 Cancelled);
    EXPECT_EQ(rendered.load(), 2);
    ConoscopeRequest base;
    base.size_px = 64;
    EXPECT_THROW(run_sweep_frames({0}, 1, [&](std::size_t, const ProgressCallback& progress) { small_figure(base, progress); },
                                  [](double) { return false; }),
                 Cancelled);
}

}  // namespace
}  // namespace petroscope
