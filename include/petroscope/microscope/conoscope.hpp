#pragma once
// Conoscopic interference figures: the image in the back focal plane of the objective, seen through the
// Bertrand lens, of a crystal slab between polarizer and analyzer.
#include "petroscope/core/image.hpp"
#include "petroscope/core/progress.hpp"
#include "petroscope/microscope/polarizing_microscope.hpp"
#include "petroscope/spectral/colorimetry.hpp"

#include <Eigen/Core>

#include <functional>
#include <optional>
#include <vector>

namespace petroscope {

struct ConoscopeSettings {
    int size_px = 512;                  // square image, 64 … 4096
    double numerical_aperture = 0.85;   // of the objective, in air: r/r_max = sin θ_air / NA (Abbe sine condition)
    double thickness_um = 30.0;         // slab thickness
    double surround_n = 1.54;           // isotropic medium on both faces (Canada balsam ≈ 1.54)
    double polarizer_deg = 0.0;         // transmission direction, from E toward N
    double analyzer_deg = 90.0;
    bool analyzer_in = true;
    double stage_deg = 0.0;             // stage rotation, counter-clockwise seen from the observer
    Eigen::Matrix3d crystal_axes = Eigen::Matrix3d::Identity();  // indicatrix X, Y, Z (columns) at stage 0
    std::vector<double> wavelengths_nm{589.3};
    /// An accessory plate in the tube, crossed at normal incidence by the light of every image point (the same
    /// retardation over the figure). With a plate every sample goes through the reference path (slower).
    std::optional<AccessoryPlate> plate;
    /// The whole thin-section stack instead of a slab in balsam half-spaces: air, slide glass, balsam, crystal,
    /// balsam, cover glass, air (microscope/polarizing_microscope.hpp), each image point on its own (slower).
    std::optional<SectionMounting> mounting;
    /// With `mounting`: the coherent 4×4 solution (every multiple reflection) instead of single pass.
    bool exact = false;

    /// Checks every field; throws InputError naming the setting and the accepted range.
    void validate() const;
};


/// The lab-frame direction of the wave that reaches image point (x, y) ∈ [−1, 1]² (x to the E, y to the
/// N): tangential wavevector ξ = NA·(x, y) in units of k₀ (sin θ_air = NA·r).
Eigen::Vector2d conoscope_tangential_wavevector(const ConoscopeSettings& settings, int column, int row);

/// Transmission spectrum of one image point: intensity after the analyzer relative to the incident
/// intensity after the polarizer, per wavelength of `settings`. Single pass (no multiple reflections).
std::vector<double> conoscope_point_transmission(const ConoscopeSettings& settings,
                                                 const PrincipalIndexFunction& principal_n,
                                                 const Eigen::Vector2d& xi);

/// Renders the figure. With `integrator` (white light): 3 channels, CIE XYZ with Y = 1 for a perfect
/// transmitter. Without it: 1 channel, the transmission at the single wavelength of `settings`. Pixels
/// outside the aperture circle are 0.
Image render_conoscope(const ConoscopeSettings& settings, const PrincipalIndexFunction& principal_n,
                       const SpectralIntegrator* integrator, const ProgressCallback& progress = {});

}  // namespace petroscope
