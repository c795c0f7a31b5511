#pragma once
// Backward spectral polarized path tracing of a Scene (docs/render.md): one wavelength per path (strata
// over the grid per pixel), polarization as Stokes vectors and Mueller matrices built from the exact
// interface model's waves at every crystal face, every branch followed at a path's first faces and one
// chosen by power after them, Russian roulette for weak split branches, a depth limit. The result is the
// Stokes vector of the light reaching each pixel, in XYZ.
#include "petroscope/core/image.hpp"
#include "petroscope/core/progress.hpp"
#include "petroscope/render/scene.hpp"
#include "petroscope/spectral/colorimetry.hpp"

#include <Eigen/Core>

#include <cstdint>
#include <vector>

namespace petroscope {

struct RenderSettings {
    int samples_per_pixel = 64;
    int max_depth = 15;  // interactions with crystal faces along a path
    /// Russian roulette from `roulette_depth` on, for paths that carry less than `roulette_power` of their
    /// camera ray's power (split branches): they survive with probability power / roulette_power. A path
    /// followed by power alone keeps all its power (lossless crystals) and ends at a wall or max_depth.
    /// From the 2nd interaction on: weak internal reflections stop being followed at full cost at the last
    /// split face (the paper's scene: 9% faster than from the 3rd on, at the same flat-region noise).
    int roulette_depth = 2;
    double roulette_power = 0.01;
    /// At the first `split_depth` interactions of a path every branch is followed (splitting: no noise
    /// from choosing between the doubled images or between reflection and refraction there); later ones
    /// choose one branch by power.
    int split_depth = 3;
    /// A pixel's samples stratify their wavelengths (antithetic pairs of strata) and the first random
    /// decisions of their paths (Latin hypercube), so the pixel converges faster than 1/√spp; false draws
    /// every number independently (plain Monte Carlo, noise exactly ∝ 1/√spp).
    bool stratified = true;
    std::uint64_t seed = 1;
};

/// The colour-matching weights of the renderer's wavelength grid (380 … 780 nm by 1 nm) under the
/// scene's light, normalised so that the light itself has Y = 1 (as SpectralIntegrator's).
struct RenderSpectrum {
    std::vector<double> wavelengths_nm;
    std::vector<Eigen::Vector3d> weights;
    Eigen::Matrix3d xyz_to_linear_srgb;  // with Bradford adaptation of the light's white to the sRGB white
};
RenderSpectrum render_spectrum(const ColorMatchingFunctions& cmf, const LightSource& light);

struct RenderStatistics {
    std::uint64_t paths = 0;              // camera samples
    std::uint64_t crystal_interactions = 0;
    std::uint64_t depth_limited = 0;      // paths stopped by max_depth
    std::uint64_t roulette_killed = 0;
    /// Paths stopped because a ray inside a crystal found no face to leave through (rounding at an edge).
    std::uint64_t inconsistent = 0;
    /// Paths ended where a crystal wave's ray and wave normal lie on opposite sides of a face (walk-off
    /// near grazing incidence), which the interface model cannot take as incident (docs/render.md).
    std::uint64_t walked_off = 0;
    double seconds = 0.0;
};

struct RenderResult {
    /// 12 channels: the XYZ of S0, S1, S2, S3 (the Stokes vector in the image's frame: S1 > 0 for light
    /// polarized along the image's horizontal, S2 > 0 at +45° from right toward up). Y = 1 for the white.
    Image stokes_xyz;
    /// Per pixel, 4 channels: the standard errors of the estimates of Y(S0), Y(S1), Y(S2), Y(S3).
    Image standard_error_y;
    RenderStatistics statistics;

    /// XYZ of what the camera records through an ideal linear polarizer at `polarizer_deg` (from right
    /// toward up): ½(S0 + cos 2θ S1 + sin 2θ S2); `polarizer` false: S0.
    Image camera_xyz(bool polarizer, double polarizer_deg) const;
};

/// Renders `scene` with its spectra relative to `spectrum`'s light. `progress` gets the fraction of rows.
RenderResult render_scene(const Scene& scene, const RenderSpectrum& spectrum, const RenderSettings& settings,
                          const ProgressCallback& progress = {});

}  // namespace petroscope
