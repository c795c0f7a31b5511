// Sweep plans: the range syntax, the grid order, shards that partition the frames, the plan file.
#include "petroscope/core/error.hpp"
#include "petroscope/io/sweep_plan.hpp"

#include <gtest/gtest.h>

namespace petroscope {
namespace {

using Values = std::vector<std::string>;

TEST(SweepRange, IncludesTheEndWhenTheStepsReachIt) {
    EXPECT_EQ(parse_sweep_parameter("azimuth-deg=0:90:30").values, (Values{"0", "30", "60", "90"}));
    EXPECT_EQ(parse_sweep_parameter("azimuth-deg=0:100:30").values, (Values{"0", "30", "60", "90"}));
    EXPECT_EQ(parse_sweep_parameter("--stage-deg=90:0:-45").values, (Values{"90", "45", "0"}));
    EXPECT_EQ(parse_sweep_parameter("stage-deg=-10:10:10").values, (Values{"-10", "0", "10"}));
    EXPECT_EQ(parse_sweep_parameter("stage-deg=5:5:1").values, (Values{"5"}));
    EXPECT_EQ(parse_sweep_parameter("--stage-deg=5:5:1").name, "stage-deg");
}

TEST(SweepRange, PrintsValuesWithTheDecimalsTheRangeWasWrittenWith) {
    // 0.1·3 = 0.30000000000000004 in binary; the value must read back as the user wrote it.
    EXPECT_EQ(parse_sweep_parameter("na=0.1:0.5:0.1").values, (Values{"0.1", "0.2", "0.3", "0.4", "0.5"}));
    EXPECT_EQ(parse_sweep_parameter("z=-0.5:0.5:0.25").values, (Values{"-0.50", "-0.25", "0.00", "0.25", "0.50"}));
    EXPECT_EQ(parse_sweep_parameter("na=0.2:0.8:0.3").values, (Values{"0.2", "0.5", "0.8"}));
    // 1000 steps of 0.001 accumulate no error into the last value.
    EXPECT_EQ(parse_sweep_parameter("x=0:1:0.001").values.back(), "1.000");
}

TEST(SweepRange, CarriesOneUnitForEveryValue) {
    EXPECT_EQ(parse_sweep_parameter("thickness=10um:30um:10um").values, (Values{"10um", "20um", "30um"}));
    EXPECT_EQ(parse_sweep_parameter("thickness=10:30:10um").values, (Values{"10um", "20um", "30um"}));
    EXPECT_EQ(parse_sweep_parameter("wavelength=450nm,550nm,650").values, (Values{"450nm", "550nm", "650nm"}));
    EXPECT_EQ(parse_sweep_parameter("thickness=1.5mm,2mm").values, (Values{"1.5mm", "2mm"}));
    EXPECT_THROW(parse_sweep_parameter("thickness=10um:1mm:10um"), InputError);
}

TEST(SweepRange, RejectsWhatIsNotARange) {
    for (const char* text : {"azimuth-deg", "=0:90:10", "azimuth-deg=0:90", "azimuth-deg=0:90:10:5", "azimuth-deg=0:90:0",
                             "azimuth-deg=90:0:10", "azimuth-deg=a:90:10", "azimuth-deg=1e3:2e3:1", "azimuth-deg=0:90:",
                             "azimuth-deg=", "azimuth-deg=1,,2", "azimuth-deg=nan:1:1"}) {
        EXPECT_THROW(parse_sweep_parameter(text), InputError) << text;
    }
    try {
        parse_sweep_parameter("azimuth-deg=0:90:0");
        FAIL();
    } catch (const InputError& error) {
        EXPECT_NE(std::string(error.what()).find("--vary 'azimuth-deg=0:90:0': the step is zero"), std::string::npos) << error.what();
    }
    EXPECT_THROW(parse_sweep_parameter("x=0:1000000:1", 1000), InputError);
    EXPECT_EQ(parse_sweep_parameter("x=0:999:1", 1000).values.size(), 1000u);
}

SweepPlan grid_plan() {
    SweepPlan plan;
    plan.command = "conoscope";
    plan.arguments = {"--mineral", "calcite"};
    plan.parameters = {parse_sweep_parameter("tilt-deg=0:20:10"), parse_sweep_parameter("azimuth-deg=0,90")};
    return plan;
}

TEST(SweepPlan, RunsThroughTheGridWithTheLastOptionFastest) {
    const SweepPlan plan = grid_plan();
    ASSERT_EQ(plan.frame_count(), 6u);
    EXPECT_EQ(plan.values_of(0), (Values{"0", "0"}));
    EXPECT_EQ(plan.values_of(1), (Values{"0", "90"}));
    EXPECT_EQ(plan.values_of(4), (Values{"20", "0"}));
    EXPECT_EQ(plan.label(3), "tilt-deg 10, azimuth-deg 90");
    EXPECT_EQ(plan.frame_arguments(5), (Values{"--mineral", "calcite", "--tilt-deg", "20", "--azimuth-deg", "90"}));
    EXPECT_EQ(plan.sheet_columns(), 2);
    EXPECT_EQ(plan.frame_name(5), "frame_0005.png");
    SweepPlan big = plan;
    big.parameters = {parse_sweep_parameter("x=0:12345:1")};
    EXPECT_EQ(big.frame_name(7), "frame_00007.png");
    EXPECT_EQ(big.sheet_columns(), 112);  // ⌈√12346⌉
}

TEST(SweepPlan, ShardsPartitionTheFrames) {
    for (const std::size_t frames : {1u, 5u, 12u, 72u, 1001u}) {
        for (const int count : {1, 2, 3, 7, 16}) {
            std::size_t next = 0;
            for (int index = 1; index <= count; ++index) {
                const SweepShard shard{index, count};
                EXPECT_EQ(shard.begin(frames), next) << frames << " " << index << "/" << count;
                EXPECT_LE(shard.end(frames) - shard.begin(frames), frames / count + 1);
                next = shard.end(frames);
            }
            EXPECT_EQ(next, frames);
        }
    }
    EXPECT_EQ(parse_sweep_shard("2/8").index, 2);
    EXPECT_EQ(parse_sweep_shard("2/8").count, 8);
    for (const char* text : {"0/2", "3/2", "1/0", "1", "a/b", "1.5/2", "1/2/3", "-1/2"}) EXPECT_THROW(parse_sweep_shard(text), InputError) << text;
}

TEST(SweepPlan, ReadsBackWhatItWrites) {
    SweepPlan plan = grid_plan();
    plan.animation = "mp4";
    plan.fps = 12.5;
    plan.columns = 3;
    plan.thumbnail_px = 128;
    const SweepPlan read = SweepPlan::from_json(plan.to_json(), "sweep.json");
    EXPECT_EQ(read.to_json(), plan.to_json());
    nlohmann::json broken = plan.to_json();
    broken["frames"] = 7;
    EXPECT_THROW(SweepPlan::from_json(broken, "sweep.json"), InputError);
    broken = plan.to_json();
    broken.erase("vary");
    try {
        SweepPlan::from_json(broken, "sweep.json");
        FAIL();
    } catch (const InputError& error) {
        EXPECT_NE(std::string(error.what()).find("sweep.json"), std::string::npos) << error.what();
    }
}

}  // namespace
}  // namespace petroscope
