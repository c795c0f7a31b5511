#pragma once
// Fitting the thickness (and the optic orientation) of one grain to its colours in orthoscopic photos:
// one or several photos between crossed polars at known stage angles, with or without an accessory plate.
// The model is the orthoscope's own (microscope/polarizing_microscope.hpp, GrainResponse) in white light;
// the method and its limits: docs/fitting.md.
#include "petroscope/core/image.hpp"
#include "petroscope/core/progress.hpp"
#include "petroscope/fit/conoscope_fit.hpp"
#include "petroscope/microscope/polarizing_microscope.hpp"
#include "petroscope/minerals/mineral.hpp"
#include "petroscope/spectral/colorimetry.hpp"

#include <Eigen/Core>

#include <array>
#include <optional>
#include <string>
#include <vector>

namespace petroscope {

/// The grain's colour in one photo: the mean sRGB code value (0 … 1) of its unsaturated pixels.
struct GrainColour {
    Eigen::Vector3d mean_code = Eigen::Vector3d::Zero();
    std::size_t pixels = 0;     // pixels averaged
    std::size_t saturated = 0;  // pixels left out: a channel at or above the saturation level
    bool grey = false;          // R = G = B in every pixel of the photo, and not all dark
};

/// Mean colour of the pixels of `photo` (3 channels, sRGB codes 0 … 1) where the first channel of `mask`
/// (same size) is non-zero. Throws InputError when the photo has fewer than 3 channels, the sizes differ, the mask
/// selects nothing or every selected pixel is saturated (`saturated_level`, on any channel). A photo with
/// R = G = B everywhere is marked `grey` (a first-order grey grain may look so; an extinct one is dark).
GrainColour grain_colour(const Image& photo, const Image& mask, double saturated_level = 0.995);
/// A mask selecting the rectangle x0 … x0 + width − 1, y0 … y0 + height − 1 (pixels, top row 0) of an image
/// of width_px × height_px; throws InputError when the rectangle leaves the image or is empty.
Image rectangle_mask(int width_px, int height_px, int x0, int y0, int width, int height);

/// One photo of the grain: its measured colour and how it was taken.
struct GrainPhoto {
    GrainColour colour;
    double stage_deg = 0.0;
    std::optional<AccessoryPlate> plate;
    std::string label;  // for reports, e.g. the file name
    /// The colour of a reference region in this photo, if one is given: a region that shows no birefringence
    /// (a hole filled with the mountant, an isotropic grain, a grain at extinction), which the camera shows
    /// as black without a plate and as the plate's own colour with one. It calibrates the camera.
    std::optional<GrainColour> reference;
};

/// Birefringence of the waves travelling along the microscope axis in a crystal of `mineral` with
/// indicatrix axes `axes` (columns, lab frame), at `wavelength_nm`: the difference of 1/√ of the eigenvalues
/// of the (x, y) block of the impermeability (Born & Wolf §15.3.3, the index ellipse of the section).
double normal_incidence_birefringence(const Mineral& mineral, const Eigen::Matrix3d& axes, double wavelength_nm);

/// What is known of the grain's optic orientation.
enum class GrainOrientation {
    known,              // the indicatrix axes are given: only the thickness (and exposure) is fitted
    max_birefringence,  // the section contains the fastest and slowest directions (X and Z): the grain shows
                        // its highest interference colour; its angle about the microscope axis is fitted
    free,               // any orientation (three Euler angles): only the retardation is determined
};
std::string_view grain_orientation_name(GrainOrientation orientation);  // "known", "max-birefringence", "free"
GrainOrientation parse_grain_orientation(std::string_view name);      // throws InputError listing the names

struct OrthoscopeFitOptions {
    MicroscopeSettings microscope;  // polars, condenser, wavelengths (white light); stage and plate per photo
    SectionMounting mounting;
    GrainOrientation orientation = GrainOrientation::max_birefringence;
    Eigen::Matrix3d known_axes = Eigen::Matrix3d::Identity();  // indicatrix X, Y, Z (columns) at stage 0, for `known`
    double thickness_min_um = 1.0, thickness_max_um = 200.0;  // the global search range
    double exposure = 1.0;  // linear display value of the empty field between parallel polars
    bool white_balance = true;  // as the renderer's default: the light's white shown as display white
    bool exposure_free = false;
    int candidates = 4;  // grid minima refined by Ceres
    Handedness handedness = Handedness::right;  // the form of an optically active mineral (quartz); others ignore it
};

/// One refined minimum of the global search.
struct GrainCandidate {
    double thickness_um = 0.0;
    std::array<double, 3> angles_deg{};  // the orientation parameters at the minimum
    double rms_code = 0.0;              // rms of the colour residuals, sRGB code units (0 … 1)
};

/// The camera's colour rendering found from the reference region (docs/fitting.md, "Calibrating the camera").
struct CameraCalibration {
    Eigen::Vector3d channel_gains = Eigen::Vector3d::Ones();  // on the linear display channels, at the reference's light
    /// Channels no reference lights (the gypsum plate's red has no green in sRGB: its linear green is below 0):
    /// their gain is fitted with the grain.
    std::array<bool, 3> fitted_with_grain{};
    FittedValue contrast;  // the tone curve's contrast a (1: the sRGB curve), fitted with the grain
    std::vector<std::optional<Eigen::Vector3d>> model_code;   // per photo, the reference's calibrated model colour
    double rms_code = 0.0;  // rms of the reference's colour residuals after calibration (code units 0 … 1)
};

struct OrthoscopeFitResult {
    FittedValue thickness_um;
    FittedValue retardation_nm;       // t·Δn at 550 nm for the fitted orientation, normal incidence
    FittedValue birefringence;        // Δn at 550 nm, normal incidence, of the fitted orientation
    std::array<FittedValue, 3> angles_deg;  // max-birefringence: [0] the X axis from E toward N; free: ZYZ Euler
    FittedValue exposure;
    Eigen::Matrix3d axes = Eigen::Matrix3d::Identity();  // fitted indicatrix axes at stage 0
    std::optional<double> thickness_lower_bound_um;  // free orientation: retardation / maximum birefringence
    std::vector<Eigen::Vector3d> model_code;  // per photo, the model's colour
    std::vector<GrainCandidate> candidates;    // best first
    double rms_code = 0.0;
    std::optional<CameraCalibration> calibration;  // when the photos carry a reference region
    bool acceptable = false;
    std::string verdict;
    std::vector<std::string> warnings;
};

/// Fits the grain; `integrator` defines the white light, on the wavelengths of options.microscope. When any
/// photo carries a reference colour, the camera's gains are those that carry the references' model colours to
/// their measured ones, and its contrast, the gains no reference lights and the exposure (the light may differ
/// between the reference and the grain) are fitted with the grain. Throws InputError for
/// unusable input (no photos, every photo grey, a thickness range that is not 0 < min < max, a wavelength
/// grid unlike the integrator's, references that are dark in every photo), Cancelled when `progress` says stop.
OrthoscopeFitResult fit_orthoscope_grain(const std::vector<GrainPhoto>& photos, const Mineral& mineral, const OrthoscopeFitOptions& options,
                                         const SpectralIntegrator& integrator, const ProgressCallback& progress = {});

}  // namespace petroscope
