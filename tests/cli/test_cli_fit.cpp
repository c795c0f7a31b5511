// petroscope fit conoscope and fit orthoscope as a user runs them: rendered photos fitted back, bad photos
// and options refused.
#include "support/cli_fixture.hpp"

#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include <algorithm>
#include <cmath>

namespace petroscope {
namespace {

class FitCli : public testing::CliFixture {
protected:
    /// A white-light figure of quartz, 400 µm, 64 px (the fit's photo, small for speed), in the scratch folder.
    std::filesystem::path quartz_photo(const std::string& extra = "", const std::string& name = "photo.png") {
        const std::filesystem::path photo = scratch() / name;
        const testing::CommandResult run =
            petroscope("conoscope --mineral quartz --thickness 400um --size 64 " + extra + " -o " + testing::quoted(photo));
        EXPECT_EQ(run.exit_code, 0) << run.err;
        return photo;
    }
};

TEST_F(FitCli, RenderedFigureFitsBackWithReportAndImages) {
    const auto photo = quartz_photo();
    const testing::CommandResult run =
        petroscope("fit conoscope --photo " + testing::quoted(photo) + " --mineral quartz --thickness 250um --fix field_radius_px=32 -o " +
                   testing::quoted(out()));
    ASSERT_EQ(run.exit_code, 0) << run.out << run.err;
    for (const char* file : {"model.png", "side_by_side.png", "residual.tiff", "report.json"}) EXPECT_TRUE(std::filesystem::exists(out() / file)) << file;
    const nlohmann::json report = nlohmann::json::parse(testing::read_text(out() / "report.json"));
    const nlohmann::json& thickness = report["parameters"]["thickness_um"];
    EXPECT_TRUE(report["acceptable"].get<bool>());
    EXPECT_TRUE(thickness["identifiable"].get<bool>());
    EXPECT_NEAR(thickness["value"].get<double>(), 400.0, 4.0);
    EXPECT_GT(thickness["sigma"].get<double>(), 0.0);
    EXPECT_FALSE(report["candidates"].empty());
    EXPECT_EQ(report["photo_encoding"], "none (lossless)");
    EXPECT_FALSE(thickness.contains("encoding_shift"));
    EXPECT_EQ(report["sensor"], "full-colour");  // --sensor auto: a PNG may be rendered
    EXPECT_FALSE(thickness.contains("mosaic_shift"));
    EXPECT_NE(run.out.find("thickness_um = "), std::string::npos);
}

// A JPEG photo: the report names its encoding, and the fit checks the encoding's systematic error and, the photo
// being a camera's (--sensor auto), its Bayer sensor's (docs/fitting.md); the 1σ includes both shifts in quadrature,
// unless the checks are switched off.
TEST_F(FitCli, JpegPhotoReportsItsEncodingAndItsShift) {
    const auto png = quartz_photo();
    const std::filesystem::path jpeg = scratch() / "photo.jpg";
    ASSERT_TRUE(cv::imwrite(jpeg.string(), cv::imread(png.string(), cv::IMREAD_COLOR), {cv::IMWRITE_JPEG_QUALITY, 90}));
    const testing::CommandResult run =
        petroscope("fit conoscope --photo " + testing::quoted(jpeg) + " --mineral quartz --thickness 250um --fix field_radius_px=32 -o " +
                   testing::quoted(out()));
    ASSERT_EQ(run.exit_code, 0) << run.out << run.err;
    const nlohmann::json report = nlohmann::json::parse(testing::read_text(out() / "report.json"));
    EXPECT_EQ(report["photo_encoding"]["description"], "quality 90, 4:2:0");
    EXPECT_TRUE(report["photo_encoding"]["checked"].get<bool>());
    EXPECT_TRUE(report["photo_encoding"]["repeated_exactly"].get<bool>());
    const nlohmann::json& thickness = report["parameters"]["thickness_um"];
    ASSERT_TRUE(thickness.contains("encoding_shift"));
    EXPECT_EQ(report["sensor"], "bayer");
    ASSERT_TRUE(thickness.contains("mosaic_shift"));
    const double shift = thickness["encoding_shift"].get<double>(), mosaic_shift = thickness["mosaic_shift"].get<double>();
    EXPECT_GE(thickness["sigma"].get<double>(), std::hypot(shift, mosaic_shift) * (1.0 - 1e-12));
    EXPECT_NE(mosaic_shift, 0.0);
    EXPECT_NEAR(thickness["value"].get<double>(), 400.0, 4.0);
    EXPECT_NE(run.out.find("JPEG photo (quality 90, 4:2:0): checked"), std::string::npos) << run.out;
    EXPECT_NE(run.out.find("Bayer sensor (--sensor bayer): its demosaicing, checked, shifts the thickness by"), std::string::npos) << run.out;

    const testing::CommandResult unchecked =
        petroscope("fit conoscope --photo " + testing::quoted(jpeg) + " --mineral quartz --thickness 250um --fix field_radius_px=32 "
                   "--no-encoding-check --sensor full-colour -o " + testing::quoted(out()));
    ASSERT_EQ(unchecked.exit_code, 0) << unchecked.out << unchecked.err;
    const nlohmann::json plain = nlohmann::json::parse(testing::read_text(out() / "report.json"));
    EXPECT_FALSE(plain["photo_encoding"]["checked"].get<bool>());
    EXPECT_FALSE(plain["parameters"]["thickness_um"].contains("encoding_shift"));
    EXPECT_EQ(plain["sensor"], "full-colour");
    EXPECT_FALSE(plain["parameters"]["thickness_um"].contains("mosaic_shift"));
    EXPECT_NE(unchecked.out.find("not checked"), std::string::npos) << unchecked.out;

}

// A grey JPEG (a monochrome camera, monochromatic light) is not taken for a Bayer sensor's photo: --sensor auto
// checks its encoding only.
TEST_F(FitCli, GreyJpegPhotoIsNotTakenForABayerSensors) {
    const auto png = quartz_photo("--wavelength 589nm", "grey.png");
    const std::filesystem::path jpeg = scratch() / "grey.jpg";
    ASSERT_TRUE(cv::imwrite(jpeg.string(), cv::imread(png.string(), cv::IMREAD_GRAYSCALE), {cv::IMWRITE_JPEG_QUALITY, 90}));
    const testing::CommandResult run = petroscope("fit conoscope --photo " + testing::quoted(jpeg) +
                                                  " --mineral quartz --wavelength 589nm --thickness 250um --fix field_radius_px=32 -o " +
                                                  testing::quoted(out()));
    ASSERT_EQ(run.exit_code, 0) << run.out << run.err;
    const nlohmann::json report = nlohmann::json::parse(testing::read_text(out() / "report.json"));
    EXPECT_EQ(report["sensor"], "full-colour");
    EXPECT_FALSE(report["parameters"]["thickness_um"].contains("mosaic_shift"));
    EXPECT_TRUE(report["parameters"]["thickness_um"].contains("encoding_shift"));
}

TEST_F(FitCli, BadPhotosAndOptionsAreRefused) {
    const std::string tail = " --mineral quartz --thickness 250um -o " + testing::quoted(out());
    expect_rejected("fit conoscope --photo " + testing::quoted(scratch() / "missing.png") + tail, {"--photo", "missing.png"});
    testing::write_text(scratch() / "empty.png", "");
    expect_rejected("fit conoscope --photo " + testing::quoted(scratch() / "empty.png") + tail, {"--photo", "empty.png"});
    const auto grey = quartz_photo("--wavelength 589nm", "grey.png");
    expect_rejected("fit conoscope --photo " + testing::quoted(grey) + tail, {"grayscale", "white light"});
    const auto saturated = quartz_photo("--exposure 1000", "saturated.png");
    expect_rejected("fit conoscope --photo " + testing::quoted(saturated) + tail, {"saturated"});
    const auto photo = quartz_photo();
    expect_rejected("fit conoscope --photo " + testing::quoted(photo) + tail + " --free thickness,colour", {"--free", "colour", "white-balance"});
    expect_rejected("fit conoscope --photo " + testing::quoted(photo) + tail + " --fix scale=3", {"--fix", "scale", "field_radius_px"});
    expect_rejected("fit conoscope --photo " + testing::quoted(photo) + tail + " --fix gamma", {"--fix", "NAME=VALUE"});
    expect_rejected("fit conoscope --photo " + testing::quoted(photo) + tail + " --handedness sideways", {"--handedness", "'sideways'", "expected right or left"});
    expect_rejected("fit conoscope --photo " + testing::quoted(photo) + tail + " --projection fisheye",
                    {"--projection", "'fisheye'", "sine, tangent, equidistant"});
    expect_rejected("fit conoscope --photo " + testing::quoted(photo) + tail + " --field-stop soft", {"--field-stop", "'soft'", "sharp, none"});
    expect_rejected("fit conoscope --photo " + testing::quoted(photo) + tail + " --illumination dim", {"--illumination", "'dim'", "even, falloff"});
    expect_rejected("fit conoscope --photo " + testing::quoted(photo) + tail + " --sensor rgb", {"--sensor", "rgb", "auto", "bayer", "full-colour"});
    expect_rejected("fit conoscope --photo " + testing::quoted(photo) + tail + " --illumination falloff --fix envelope_radius_px=0",
                    {"envelope_radius_px = 0", "outside"});
    expect_rejected("fit conoscope --photo " + testing::quoted(photo) + tail + " --fix extinction_ratio=1.5", {"extinction_ratio = 1.5", "0 ... 0.2"});
    expect_rejected("fit conoscope --photo " + testing::quoted(photo) + tail + " --fix crosstalk_bg=0.9", {"crosstalk_bg = 0.9", "-0.5 ... 0.5"});
    expect_rejected("fit conoscope --photo " + testing::quoted(photo) + tail + " --free thickness,colour-matrx",
                    {"--free", "'colour-matrx'", "colour-matrix"});
    expect_rejected("fit conoscope --photo " + testing::quoted(photo) + tail + " --free thickness,envelope",
                    {"--free", "envelope_center_x_px", "illumination is even", "falloff"});
    expect_rejected("fit conoscope --photo " + testing::quoted(photo) + " --mineral quartz --thickness-range 5mm:1mm -o " + testing::quoted(out()),
                    {"--thickness-range", "maximum"});
}

// A photo of something else (a thin section between crossed polars) ends with "no acceptable fit", its
// cost, exit 1.
TEST_F(FitCli, PhotoOfSomethingElseHasNoAcceptableFit) {
    const std::filesystem::path section = scratch() / "section", photo = scratch() / "section.png";
    ASSERT_EQ(petroscope("section random --minerals quartz,orthoclase,biotite --grains 12 --size 64 --pixel-size 10um --seed 3 -o " +
                         testing::quoted(section)).exit_code, 0);
    ASSERT_EQ(petroscope("orthoscope --section " + testing::quoted(section) + " -o " + testing::quoted(photo)).exit_code, 0);
    const testing::CommandResult run =
        petroscope("fit conoscope --photo " + testing::quoted(photo) + " --mineral calcite --thickness 30um -o " + testing::quoted(out()));
    EXPECT_EQ(run.exit_code, 1) << run.out << run.err;
    EXPECT_NE(run.err.find("no acceptable fit"), std::string::npos) << run.err;
    EXPECT_NE(run.err.find("cost"), std::string::npos) << run.err;
    EXPECT_LT(std::count(run.err.begin(), run.err.end(), '\n'), 50) << run.err;  // the solver stays silent
}

// A photo of noise: nothing to fit, and the solver (Ceres, glog) must not print on the terminal.
TEST_F(FitCli, PhotoOfNoiseEndsWithAVerdictAndFewLines) {
    cv::Mat noise(64, 64, CV_8UC3);
    cv::randu(noise, cv::Scalar::all(0), cv::Scalar::all(256));
    const std::filesystem::path photo = scratch() / "noise.png";
    ASSERT_TRUE(cv::imwrite(photo.string(), noise));
    const testing::CommandResult run =
        petroscope("fit conoscope --photo " + testing::quoted(photo) + " --mineral calcite --thickness 100um --candidates 1 -o " +
                   testing::quoted(out()));
    EXPECT_EQ(run.exit_code, 1) << run.out << run.err;
    EXPECT_NE(run.err.find("no acceptable fit"), std::string::npos) << run.err;
    EXPECT_LT(std::count(run.err.begin(), run.err.end(), '\n'), 50) << run.err;
    EXPECT_EQ(run.err.find("ResidualBlock"), std::string::npos) << run.err;
    EXPECT_TRUE(std::filesystem::exists(out() / "report.json"));  // the diagnostics are written all the same
}

// fit orthoscope: photos of a one-grain quartz section (random orientation, 30 µm) between crossed polars
// at two stage angles and with the gypsum plate.
class FitOrthoscopeCli : public testing::CliFixture {
protected:
    void SetUp() override {
        testing::CliFixture::SetUp();
        const testing::CommandResult made = petroscope("section random --minerals quartz --grains 1 --size 64 --pixel-size 10um --thickness 30um "
                                                       "--seed 4 -o " + testing::quoted(scratch() / "grain"));
        ASSERT_EQ(made.exit_code, 0) << made.err;
        const std::string description = testing::read_text(scratch() / "grain" / "section.txt");
        // "grain 1: quartz, euler A B C, handedness H": the grain's orientation and form, as the fit is told them.
        const auto euler = description.find("euler ", description.find("\ngrain 1:"));
        ASSERT_NE(euler, std::string::npos);
        euler_ = description.substr(euler + 6, description.find(',', euler) - euler - 6);
        std::replace(euler_.begin(), euler_.end(), ' ', ',');
        const auto hand = description.find("handedness ", euler);
        ASSERT_NE(hand, std::string::npos);
        handedness_ = description.substr(hand + 11, description.find('\n', hand) - hand - 11);
        for (const auto& [name, options] : std::vector<std::pair<std::string, std::string>>{
                 {"xpl0.png", "--stage-deg 0"}, {"xpl30.png", "--stage-deg 30"}, {"gypsum0.png", "--stage-deg 0 --plate gypsum"}}) {
            const testing::CommandResult run = petroscope("orthoscope --section " + testing::quoted(scratch() / "grain") + " " + options + " -o " +
                                                          testing::quoted(scratch() / name));
            ASSERT_EQ(run.exit_code, 0) << run.err;
        }
    }
    std::string photos() const {
        return "--photo " + testing::quoted(scratch() / "xpl0.png") + " --photo " + testing::quoted(scratch() / "xpl30.png") + " --photo " +
               testing::quoted(scratch() / "gypsum0.png") + " --stage-deg 0,30,0 --plate none,none,gypsum";
    }
    std::string euler_, handedness_;
};

TEST_F(FitOrthoscopeCli, KnownOrientationGivesTheThicknessWithReportAndSwatches) {
    const testing::CommandResult run = petroscope("fit orthoscope " + photos() + " --mineral quartz --region 16,16,32,32 --euler-deg=" + euler_ + " --handedness " + handedness_ + " -o " + testing::quoted(out()));
    ASSERT_EQ(run.exit_code, 0) << run.out << run.err;
    const nlohmann::json report = nlohmann::json::parse(testing::read_text(out() / "report.json"));
    EXPECT_TRUE(report["acceptable"].get<bool>());
    EXPECT_NEAR(report["thickness_um"]["value"].get<double>(), 30.0, 0.5);
    EXPECT_GT(report["thickness_um"]["sigma"].get<double>(), 0.0);
    EXPECT_EQ(report["photos"].size(), 3u);
    EXPECT_TRUE(std::filesystem::exists(out() / "colours.png"));
    EXPECT_NE(run.out.find("thickness_um = "), std::string::npos);
}

// The grain map marks the grain in the photos at stage 0 (at 30° the section's corners leave the field).
TEST_F(FitOrthoscopeCli, MaskSelectsTheGrain) {
    const testing::CommandResult run = petroscope(
        "fit orthoscope --photo " + testing::quoted(scratch() / "xpl0.png") + " --photo " + testing::quoted(scratch() / "gypsum0.png") +
        " --plate none,gypsum --mask " + testing::quoted(scratch() / "grain" / "grains.png") + " --mineral quartz --euler-deg=" + euler_ +
        " --handedness " + handedness_ + " --json -o " + testing::quoted(out()));
    ASSERT_EQ(run.exit_code, 0) << run.out << run.err;
    const nlohmann::json report = nlohmann::json::parse(run.out);
    EXPECT_EQ(report["photos"][0]["pixels"].get<int>(), 64 * 64);
    EXPECT_NEAR(report["thickness_um"]["value"].get<double>(), 30.0, 0.5);
    EXPECT_EQ(report["handedness"], handedness_);
}

TEST_F(FitOrthoscopeCli, FreeOrientationReportsTheRetardationNotTheThickness) {
    const testing::CommandResult run = petroscope("fit orthoscope " + photos() + " --mineral quartz --region 16,16,32,32 --orientation free --json -o " + testing::quoted(out()));
    ASSERT_EQ(run.exit_code, 0) << run.out << run.err;
    const nlohmann::json report = nlohmann::json::parse(run.out);
    EXPECT_TRUE(report["thickness_um"]["value"].is_null());
    EXPECT_FALSE(report["thickness_um"]["identifiable"].get<bool>());
    EXPECT_TRUE(report["retardation_550nm"]["identifiable"].get<bool>());
    EXPECT_LE(report["thickness_lower_bound_um"].get<double>(), 30.0 * 1.03);
}

TEST_F(FitOrthoscopeCli, BadPhotosAndOptionsAreRefused) {
    const std::string tail = " --mineral quartz -o " + testing::quoted(out());
    expect_rejected("fit orthoscope --photo " + testing::quoted(scratch() / "missing.png") + tail, {"--photo", "missing.png"});
    expect_rejected("fit orthoscope " + photos() + " --stage-deg 0,30" + tail, {"--stage-deg", "one per photo"});
    expect_rejected("fit orthoscope " + photos() + " --region 60,60,10,10" + tail, {"--region", "leaves"});
    expect_rejected("fit orthoscope " + photos() + " --region 1,2,3" + tail, {"--region", "X,Y,WIDTH,HEIGHT"});
    expect_rejected("fit orthoscope " + photos() + " --region 1,1,4,4 --mask " + testing::quoted(scratch() / "xpl0.png") + tail, {"--mask", "--region"});
    expect_rejected("fit orthoscope " + photos() + " --wavelength 589nm" + tail, {"--wavelength", "white light"});
    expect_rejected("fit orthoscope " + photos() + " --orientation sideways" + tail, {"--orientation", "max-birefringence"});
    expect_rejected("fit orthoscope " + photos() + " --orientation known" + tail, {"--euler-deg"});
    expect_rejected("fit orthoscope " + photos() + " --euler-deg 1,2" + tail, {"--euler-deg", "ALPHA,BETA,GAMMA"});
    expect_rejected("fit orthoscope " + photos() + " --handedness sideways" + tail, {"--handedness", "'sideways'", "expected right or left"});
    expect_rejected("fit orthoscope " + photos() + " --thickness-range 50um:10um" + tail, {"--thickness-range", "maximum"});
    expect_rejected("fit orthoscope " + photos() + " --mineral quartz -o " + testing::quoted(scratch() / "xpl0.png"), {"-o", "not a folder"});
    const testing::CommandResult grey = petroscope("orthoscope --section " + testing::quoted(scratch() / "grain") + " --wavelength 589nm -o " +
                                                   testing::quoted(scratch() / "grey.png"));
    ASSERT_EQ(grey.exit_code, 0) << grey.err;
    expect_rejected("fit orthoscope --photo " + testing::quoted(scratch() / "grey.png") + tail, {"grey.png", "grayscale"});
}

// fit orthoscope with a reference region: a quartz grain (optic axis in the section, at 20°) around a hole
// filled with balsam, photographed at stage 0° and 30° and with the gypsum plate at the grain's 45° position.
class FitOrthoscopeReferenceCli : public testing::CliFixture {
protected:
    void SetUp() override {
        testing::CliFixture::SetUp();
        const std::filesystem::path folder = scratch() / "hole";
        std::filesystem::create_directories(folder);
        cv::Mat labels(64, 64, CV_8UC1);
        for (int y = 0; y < 64; ++y) {
            for (int x = 0; x < 64; ++x) labels.at<unsigned char>(y, x) = std::hypot(x - 31.5, y - 31.5) < 12.0 ? 2 : 1;
        }
        ASSERT_TRUE(cv::imwrite((folder / "grains.png").string(), labels));
        testing::write_text(folder / "section.txt", "name: hole\ngrain_map: grains.png\nsize_px: 64 64\npixel_size_um: 10\nthickness_um: 30\n"
                                                    "grain 1: quartz, euler 20 90 0\ngrain 2: canada balsam, euler 0 0 0\n");
        for (const auto& [name, options] : std::vector<std::pair<std::string, std::string>>{
                 {"xpl0.png", "--stage-deg 0"}, {"xpl30.png", "--stage-deg 30"}, {"gypsum25.png", "--stage-deg 25 --plate gypsum"}}) {
            const testing::CommandResult run = petroscope("orthoscope --section " + testing::quoted(folder) + " " + options + " -o " + testing::quoted(scratch() / name));
            ASSERT_EQ(run.exit_code, 0) << run.err;
        }
    }
    std::string photos() const {
        return "--photo " + testing::quoted(scratch() / "xpl0.png") + " --photo " + testing::quoted(scratch() / "xpl30.png") + " --photo " +
               testing::quoted(scratch() / "gypsum25.png") + " --stage-deg 0,30,25 --plate none,none,gypsum --region 46,26,12,12 --mineral quartz";
    }
};

TEST_F(FitOrthoscopeReferenceCli, TheHoleCalibratesTheCameraAndTheReportSaysHow) {
    const testing::CommandResult run = petroscope("fit orthoscope " + photos() + " --reference-region 26,26,12,12 -o " + testing::quoted(out()));
    ASSERT_EQ(run.exit_code, 0) << run.out << run.err;
    const nlohmann::json report = nlohmann::json::parse(testing::read_text(out() / "report.json"));
    EXPECT_NEAR(report["thickness_um"]["value"].get<double>(), 30.0, 0.3);
    const nlohmann::json& camera = report["camera_calibration"];
    // The renderer's own camera: the sRGB curve, white balanced on the light.
    EXPECT_NEAR(camera["channel_gains"][0].get<double>(), 1.0, 0.02) << camera;
    EXPECT_NEAR(camera["channel_gains"][2].get<double>(), 1.0, 0.02) << camera;
    EXPECT_EQ(camera["gains_fitted_with_the_grain"], nlohmann::json::array({"G"}));
    EXPECT_LT(camera["reference_rms_code"].get<double>(), 1.0 / 255.0);
    EXPECT_EQ(report["photos"][2]["reference"]["pixels"].get<int>(), 144);
    EXPECT_NE(run.out.find("camera: gains"), std::string::npos) << run.out;
    const cv::Mat swatches = cv::imread((out() / "colours.png").string());
    EXPECT_EQ(swatches.cols, 4 * 64);  // grain measured | model, reference measured | model
}

TEST_F(FitOrthoscopeReferenceCli, BadReferencesAreRefused) {
    const std::string tail = " -o " + testing::quoted(out());
    expect_rejected("fit orthoscope " + photos() + " --reference-region 1,2,3" + tail, {"--reference-region", "X,Y,WIDTH,HEIGHT"});
    expect_rejected("fit orthoscope " + photos() + " --reference-region 60,60,10,10" + tail, {"--reference-region", "leaves"});
    expect_rejected("fit orthoscope " + photos() + " --reference-region 26,26,12,12 --reference-mask " + testing::quoted(scratch() / "xpl0.png") + tail,
                    {"--reference-mask", "--reference-region"});
    expect_rejected("fit orthoscope " + photos() + " --reference-region 26,26,12,12 --reference-region none" + tail, {"--reference-region", "one per photo"});
    expect_rejected("fit orthoscope " + photos() + " --reference-region 26,26,12,12 --reference-region 26,26,12,12 --reference-region none" + tail,
                    {"dark in every photo"});
    EXPECT_FALSE(std::filesystem::exists(out() / "report.json"));
}

// Photos of quartz fitted as calcite: no calcite grain shows these colours at any thickness in range.
TEST_F(FitOrthoscopeCli, WrongMineralHasNoAcceptableFit) {
    const testing::CommandResult run =
        petroscope("fit orthoscope " + photos() + " --mineral calcite --thickness-range 20um:60um -o " + testing::quoted(out()));
    EXPECT_EQ(run.exit_code, 1) << run.out << run.err;
    EXPECT_NE(run.err.find("no acceptable fit"), std::string::npos) << run.err;
}

}  // namespace
}  // namespace petroscope
