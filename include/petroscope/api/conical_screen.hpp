#pragma once
// The screen behind a biaxial slab cut perpendicular to an optic axis (internal conical refraction), as
// every front end asks for it: in wave optics (microscope/conical_wave.hpp) or ray optics
// (microscope/conical_ray.hpp).
#include "petroscope/api/measurements.hpp"
#include "petroscope/core/image.hpp"
#include "petroscope/core/progress.hpp"
#include "petroscope/microscope/conical_ray.hpp"
#include "petroscope/microscope/conical_wave.hpp"
#include "petroscope/minerals/mineral_catalog.hpp"

#include <Eigen/Core>

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace petroscope {

enum class ConicalOptics { wave, ray };
ConicalOptics parse_conical_optics(std::string_view name);  // "wave", "ray"; throws InputError listing them
ConicalBeam parse_conical_beam(std::string_view name);      // "gaussian", "pinhole"

/// "unpolarized", "circular" (right; also "circular:right"), "circular:left", "linear:ANGLE" (degrees from +x)
/// as a Stokes vector with (x, y) in the roles of (s, p) (optics/polarization.hpp); throws InputError.
Eigen::Vector4d parse_polarization(std::string_view text);

struct ConicalRequest {
    std::string crystal = "KGd(WO4)2";       // a biaxial mineral
    double length_um = 20000.0;              // slab thickness l along the optic axis
    double wavelength_nm = 633.0;
    ConicalOptics optics = ConicalOptics::wave;
    ConicalBeam beam = ConicalBeam::gaussian;  // wave optics
    double waist_um = 40.0;                  // wave optics, Gaussian beam: w, E(r) = exp(−r²/2w²)
    double pinhole_um = 25.0;                // pinhole radius (wave optics with a pinhole beam; ray optics)
    double filter_um = 50000.0;              // ray optics: thickness of the filter holding the pinhole
    /// Incident polarization, Stokes (S0, S1, S2, S3) with (x, y) in the roles of (s, p): (1, 1, 0, 0) is
    /// linear along x, (1, 0, 0, 1) right circular.
    Eigen::Vector4d stokes = Eigen::Vector4d(1, 0, 0, 0);
    double z = 0.0;                          // wave optics: observation plane Z (0: the focal image plane)
    double rotate_deg = 0.0;                 // ray optics: the slab turned about its optic axis
    double tilt_deg = 0.0;                   // ray optics: the optic axis tilted from the slab normal
    double screen_distance_um = 50000.0;     // ray optics
    std::int64_t rays = 200000;              // ray optics, 1 … 1e8 (48 bytes of memory a ray)
    int size_px = 1024;                      // square image, 64 … 4096
};

/// A request checked against the catalog; the catalog must outlive it.
struct ConicalPlan {
    ConicalRequest request;
    const Mineral* crystal = nullptr;
    Eigen::Vector3d principal_n = Eigen::Vector3d::Zero();  // at the wavelength
    double cone_angle_rad = 0.0;     // χ
    double ring_radius_um = 0.0;     // R₀ = A·l, A = ½ tan χ
    ConicalWaveParameters wave;      // wave optics
    double scale_um = 0.0;           // wave optics: the beam scale w (waist or pinhole radius)
    double half_width_um = 0.0;      // of the image, around the (predicted) ring centre
    ConicalRaySettings ray;          // ray optics
    std::vector<std::string> notes;  // each beginning "warning: "
};

/// Throws InputError naming the bad value (no computation is done).
ConicalPlan plan_conical(const ConicalRequest& request, const MineralCatalog& catalog);

struct ConicalScreen {
    Image linear_rgb;  // 3 equal channels, normalised so that the brightest pixel is 1
    /// ring_outer_bright_um, ring_dark_um, ring_inner_bright_um (from the ring centre), mean_luminance; in
    /// ray optics also the measured centre ring_centre_x_um, ring_centre_y_um.
    Measurements measurements;
    std::optional<double> power;                    // wave optics: the beam's power in the screen (π for a whole Gaussian)
    std::optional<double> max_interface_power_sum;  // ray optics: over every interface met, never above 1
    /// The point the image is centred on, from the point below the pinhole: the predicted ring centre
    /// (ray optics; 0 in wave optics, whose frame is the ring centre's).
    Eigen::Vector2d image_centre_um = Eigen::Vector2d::Zero();
};

/// Computes the screen; throws Cancelled when `progress` says stop.
ConicalScreen render_conical_screen(const ConicalPlan& plan, const ProgressCallback& progress = {});

}  // namespace petroscope
