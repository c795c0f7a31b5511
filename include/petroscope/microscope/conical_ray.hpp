#pragma once
// Internal conical refraction in ray optics: the paper's scene. A filter of thickness h with a pinhole
// of radius R lies on a biaxial slab (thickness d) cut perpendicular to a binormal; rays through the
// pinhole are traced through both faces with the exact plane-wave modes (optics/berreman.hpp; checked against
// the interface model of optics/interface.hpp) and collected on a screen at distance D behind the slab (docs/theory.md §8).
#include "petroscope/core/image.hpp"
#include "petroscope/core/progress.hpp"

#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <functional>
#include <vector>

namespace petroscope {

struct ConicalRaySettings {
    Eigen::Vector3d principal_n = Eigen::Vector3d(2.0135, 2.0458, 2.0860);  // along X, Y, Z at the wavelength
    double slab_um = 20000.0;          // d: slab thickness along its normal
    double rotate_deg = 0.0;           // turn of the crystal about the binormal (the slab normal)
    double tilt_deg = 0.0;             // tilt of the binormal away from the slab normal (toward the rotation azimuth)
    enum class Source { pinhole, point } source = Source::pinhole;
    double pinhole_radius_um = 25.0;   // R
    double filter_um = 1000.0;         // h: rays through both openings, tilted by at most about 2R/h
    double angular_width_rad = 0.0;    // point source: per-axis standard deviation of the ray angles in air
    double screen_distance_um = 50000.0;  // D, from the exit face
    /// Incident polarization as a Stokes vector in the lab frame with (x, y) in the roles of (s, p) of
    /// optics/polarization.hpp: S1 = +S0 for light polarized along x. Default unpolarized.
    Eigen::Vector4d stokes = Eigen::Vector4d(1, 0, 0, 0);
    std::int64_t rays = 200000;
    std::uint64_t seed = 1;
    int size_px = 512;                 // square screen image
    double half_width_um = 0.0;        // of the image, around the predicted ring centre (0: 2 R₀)
};

/// Rings measured on the landing points: the power centroid is the ring centre (the pattern is symmetric
/// about it), and the radial power density about it, smoothed, gives the dark (Poggendorff) ring as its
/// minimum near R₀ and the bright rings as the maxima on either side (each refined by a parabola).
struct ConicalRayRings {
    Eigen::Vector2d centre_um = Eigen::Vector2d::Zero();
    double inner_bright_um = 0.0, dark_um = 0.0, outer_bright_um = 0.0;
};

struct ConicalRayResult {
    Image screen;                      // 1 channel: collected power per pixel (incident power 1 per ray)
    double ring_radius_um = 0.0;       // R₀ = A·d with A = ½ tan χ (Berry, J. Opt. A 6, 289 (2004); docs/theory.md §8)
    double cone_angle_deg = 0.0;       // χ
    Eigen::Vector2d pinhole_point_um = Eigen::Vector2d::Zero();   // the point below the pinhole on the screen
    Eigen::Vector2d ring_centre_um = Eigen::Vector2d::Zero();     // predicted: R₀ from the pinhole point toward the
                                                                  // second binormal's projection (the image is centred on it)
    ConicalRayRings rings;             // measured
    double max_interface_power_sum = 0.0;  // over every interface met: never above 1
    std::int64_t rays_traced = 0, non_finite = 0;
};

/// tan χ = √((nβ² − nα²)(nγ² − nβ²))/(nα nγ) (Born & Wolf §15.3.4; docs/theory.md §8) for indices in any order.
double conical_cone_angle_rad(const Eigen::Vector3d& principal_n);

/// One ray through the slab: its two waves inside, each with its ray (Poynting) direction and the fraction of
/// the incident power that it carries out of the exit face. Every wave of the ray shares the tangential
/// wavevector ξ of the incident one (Snell's law): Berreman's modes of air and crystal for that ξ
/// (optics/berreman.hpp) and the boundary conditions at each face (forward_boundary: the forward waves
/// matched with the reflected ones) give it all; the wave leaving the exit face travels along the incident
/// direction. `coherency_sp`: the incident light in the ray's (s, p) basis (docs/interface.md).
struct SlabWave {
    Eigen::Vector3d ray_direction = Eigen::Vector3d::UnitZ();
    double weight = 0.0;
};
struct SlabCrossing {
    std::array<SlabWave, 2> waves;   // weight 0: evanescent, or carrying no power
    double largest_power_sum = 0.0;  // reflected + transmitted at the entry face, and at the exit face per wave
};
SlabCrossing cross_slab(const Eigen::Matrix3cd& crystal_epsilon, const Eigen::Vector3d& direction, const Eigen::Matrix2cd& coherency_sp);

/// Traces the rays (in parallel); throws InputError for a non-biaxial crystal or non-positive lengths.
ConicalRayResult trace_conical_rays(const ConicalRaySettings& settings, const ProgressCallback& progress = {});

}  // namespace petroscope
