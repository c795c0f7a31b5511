#pragma once
// Fitting a photograph of a conoscopic figure: the slab thickness, and the unknowns of a real photo (the
// figure's centre and angular scale, the camera's rotation against the polarizers, the optic axis's
// tilt and azimuth, and the camera's response), by a global search over thickness followed by Ceres.
// The model and the method: docs/fitting.md.
#include "petroscope/core/image.hpp"
#include "petroscope/core/progress.hpp"
#include "petroscope/microscope/conoscope.hpp"

#include <Eigen/Core>

#include <array>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace petroscope {

/// The model's parameters, in the order of the parameter vector.
enum class PhotoParameter : int {
    thickness_um,     // slab thickness
    center_x_px,      // the figure's centre (the microscope axis) in the photo, pixel units, x to the right
    center_y_px,      //   … and y down (pixel centres at integer + 0.5)
    field_radius_px,  // the angular scale: the radius in pixels of the field edge, sin θ_air = NA
    rotation_deg,     // the image turned counter-clockwise against the lab (polarizers and stage)
    tilt_deg,         // the cut direction tilted away from the microscope axis (cut_orientation)
    azimuth_deg,      //   … toward this azimuth, from E toward N
    gain_r,           // camera: value = black + (gain·mixed)^(1/gamma), per channel, mixed = linear sRGB
                      //   through the colour matrix (crosstalk_* below)
    gain_g,
    gain_b,
    black_level,
    gamma,
    blur_variance_px2,  // Gaussian blur of the optics and camera: σ² in pixels² (σ² rather than σ: the
                        // model is smooth in σ² down to 0, where ∂/∂σ would vanish)
    envelope_center_x_px,  // IlluminationProfile::falloff: the centre of the light's envelope exp(−(r/R)^p) …
    envelope_center_y_px,
    envelope_radius_px,    //   … its radius R …
    envelope_power,        //   … and its power p (2: Gaussian; large: a soft-edged disc)
    distortion,            // radial distortion: the projection sees u·(1 + distortion·u²), u = r / field radius
    analyzer_offset_deg,   // the analyzer turned from its set direction (polars not exactly crossed)
    extinction_ratio,      // the fraction of the light vibrating across the analyzer that it lets through
    crosstalk_rg,          // camera colour matrix: each channel's linear value gains these fractions of the
    crosstalk_rb,          //   other two before its gain (crosstalk_rg: of green in red); a sensor's
    crosstalk_gr,          //   colours are not the observer's, and its colour matrix maps them only
    crosstalk_gb,          //   approximately
    crosstalk_br,
    crosstalk_bg,
};
constexpr int kPhotoParameterCount = 26;
using PhotoParameters = std::array<double, kPhotoParameterCount>;
using PhotoParameterFlags = std::array<bool, kPhotoParameterCount>;

inline double& at(PhotoParameters& values, PhotoParameter p) { return values[static_cast<std::size_t>(p)]; }
inline double at(const PhotoParameters& values, PhotoParameter p) { return values[static_cast<std::size_t>(p)]; }

/// "thickness_um", "center_x_px", …
std::string_view photo_parameter_name(PhotoParameter parameter);
/// The inverse; throws InputError listing the names.
PhotoParameter parse_photo_parameter(std::string_view name);

/// How directions map to the photo: the distance from the figure's centre is proportional to sin θ
/// (a microscope objective, Abbe's sine condition), tan θ (a camera or plain lens looking through the
/// crystal at a diffuse source, a figure on a screen) or θ (an equidistant, fish-eye-like lens); θ is
/// the direction in air, where the objective or lens is.
enum class Projection { sine, tangent, equidistant };

/// What bounds the lit field: the objective's aperture at sin θ_air = NA, a sharp circle (`sharp`), or
/// nothing the model draws (`none`: the frame and the illumination envelope bound it; a figure larger
/// than the frame, or a soft stop).
enum class FieldStop { sharp, none };

/// The light over the photo: even, or falling off about its own centre as exp(−(r/R)^p) (vignetting,
/// uneven Köhler illumination, a diffuse source of finite size).
enum class IlluminationProfile { even, falloff };

/// The camera's sensor: one that measures every colour at every pixel (`full-colour`: a three-sensor camera, a
/// rendered photo), or an RGGB Bayer mosaic demosaiced by the camera (`bayer`: nearly every colour camera,
/// phones included), whose interpolation the model does not follow.
enum class ColourSensor { full_colour, bayer };

/// Everything about the figure that is not fitted.
struct ConoscopePhotoModel {
    /// NA, polars, stage, surrounding medium, wavelengths (crystal_axes is not used), and whether white light is
    /// interpolated from spectral nodes (spectrum). thickness_um: at least the thickest slab the model is evaluated
    /// for (ConoscopeTerms; the model takes the larger of it and the thickness evaluated; the fit, its bound).
    ConoscopeSettings settings;
    PrincipalIndexFunction principal_n;
    /// The indicatrix axes for a tilt and azimuth (e.g. cut_orientation for the photo's cut).
    std::function<Eigen::Matrix3d(double tilt_deg, double azimuth_deg)> orientation;
    /// Linear sRGB per unit transmission at each wavelength of settings (white light: the colour
    /// integrator's weights through the display conversion; monochromatic light: (1, 1, 1)).
    std::vector<Eigen::Vector3d> rgb_per_transmission;
    Projection projection = Projection::sine;
    FieldStop field_stop = FieldStop::sharp;
    IlluminationProfile illumination = IlluminationProfile::even;
};

/// "sine", "tangent", "equidistant"; "sharp", "none"; "even", "falloff"; and the inverses, which throw
/// InputError listing the names.
std::string_view projection_name(Projection projection);
Projection parse_projection(std::string_view name);
std::string_view field_stop_name(FieldStop stop);
FieldStop parse_field_stop(std::string_view name);
std::string_view illumination_name(IlluminationProfile illumination);
IlluminationProfile parse_illumination(std::string_view name);
std::string_view colour_sensor_name(ColourSensor sensor);  // "full-colour", "bayer"
ColourSensor parse_colour_sensor(std::string_view name);   // throws InputError listing the names

/// Starting values for a photo of this size: centre of the image, field radius half the shorter side,
/// thickness 30 µm, no tilt, unit gains, black 0, gamma 2.2, blur 1 px; the envelope centred, of radius
/// half the diagonal and power 2; no distortion, polars crossed, a perfect analyzer.
PhotoParameters default_photo_parameters(int width_px, int height_px);

struct ConoscopeFitOptions {
    PhotoParameters initial{};
    PhotoParameterFlags free{};       // fixed parameters keep their initial value
    double thickness_min_um = 5.0;    // the global search covers this range
    double thickness_max_um = 5000.0;
    int candidates = 3;               // thickness minima refined by Ceres
    /// With the centre free and the cut not tilted (tilt held at 0), or tilted a little (tilt free from 0) with no
    /// field stop, start the centre where the photo is most nearly symmetric under a half turn (docs/fitting.md,
    /// "Finding the figure"), not at initial's centre.
    bool locate_centre = true;
    double robust_scale = 0.05;       // Cauchy loss: residuals (in photo values, 0 … 1) beyond this count less
    double saturated_level = 0.995;   // pixels with a channel at or above this are not used
    /// The lossy encoding the photo went through (a JPEG's: io/jpeg_encoding.hpp), on camera values
    /// 0 … 1. When given, the fit measures the systematic error the encoding causes: the best-fit model's
    /// photo is encoded the same way and fitted again from the best fit; the shift of every parameter is
    /// reported and added to its 1σ in quadrature (docs/fitting.md, "The photo's encoding").
    std::function<Image(const Image&)> photo_encoding;
    /// With a Bayer sensor the fit measures the systematic error of its demosaicing the same way: the best-fit
    /// model's photo through an RGGB mosaic and bilinear demosaicing (before the camera's curve, as a camera does
    /// it), fitted again from the best fit; the shift is reported and added to each 1σ in quadrature, apart from
    /// the encoding's (docs/fitting.md, "The camera's sensor").
    ColourSensor sensor = ColourSensor::full_colour;
};

/// One minimum of the cost over thickness on the unblurred photo, at the geometry found on the blurred
/// (coarse) level, after refinement of thickness, blur and camera there (the best one: of every parameter
/// on the full photo).
struct ThicknessCandidate {
    double start_thickness_um = 0.0;  // where the thickness scan found it
    double thickness_um = 0.0;        // after refinement
    double cost = 0.0;                // mean robust cost per residual after the refinement with the geometry held
};

struct FittedValue {
    double value = 0.0;
    std::optional<double> sigma;  // 1σ; none when fixed or not identifiable
    bool free = false;
    bool identifiable = true;     // false: the photo does not determine it (value is meaningless)
};

struct ConoscopeFitResult {
    PhotoParameters values{};
    std::array<FittedValue, kPhotoParameterCount> parameters{};
    std::vector<ThicknessCandidate> candidates;  // best first
    std::vector<std::string> warnings;
    /// The shift of each parameter when the best-fit model's photo goes through options.photo_encoding and
    /// is fitted again: the encoding's systematic error, included in each 1σ. None without an encoding.
    std::optional<PhotoParameters> encoding_shift;
    /// The same for the Bayer mosaic's demosaicing (options.sensor): none for a full-colour sensor.
    std::optional<PhotoParameters> mosaic_shift;
    double rms_residual = 0.0;       // photo values, over the pixels used
    double explained_variance = 0.0; // R² of the photo's values over the pixels used
    int pixels_used = 0;
    int pixels_saturated = 0;
    int iterations = 0;
    bool acceptable = false;
    std::string verdict;             // why the fit is (not) acceptable
};

/// Fits `photo` (3 channels of camera values in 0 … 1; 1 channel accepted in monochromatic light).
/// Throws InputError for a photo that cannot be fitted (too small, grayscale in white light, saturated).
ConoscopeFitResult fit_conoscope_photo(const Image& photo, const ConoscopePhotoModel& model, const ConoscopeFitOptions& options,
                                       const ProgressCallback& progress = {});

/// The model's photo at `values`: camera values (3 channels), 0 outside the field.
Image render_conoscope_photo(const ConoscopePhotoModel& model, const PhotoParameters& values, int width_px, int height_px);

}  // namespace petroscope
