#pragma once
// The Michel-Lévy chart of interference colours, computed by the orthoscope's own pipeline: a crystal
// plate with its vibration directions at 45° to crossed polars, in a standard mounting, at retardations
// 0 … Γ_max (Michel-Lévy & Lacroix 1888; the modern layout after Sørensen, Eur. J. Mineral. 25, 5 (2013)).
#include "petroscope/microscope/polarizing_microscope.hpp"
#include "petroscope/spectral/colorimetry.hpp"

#include <optional>
#include <vector>

namespace petroscope {

struct MichelLevySettings {
    double max_retardation_nm = 2000.0;
    double step_nm = 1.0;
    /// Reference wavelength at which Γ = (n_slow − n_fast)·d is stated (the chart's axis).
    double reference_wavelength_nm = 550.0;
    /// With a mineral: its real dispersion of birefringence (a section containing its X and Z axes, the
    /// largest birefringence); without: a dispersion-free plate of birefringence 0.009 (the classic chart).
    const Mineral* mineral = nullptr;
    std::vector<double> wavelengths_nm;
    /// Checks the ranges; throws InputError naming the setting.
    void validate() const;
};

struct MichelLevyStep {
    double retardation_nm = 0.0;  // at the reference wavelength
    double thickness_um = 0.0;    // of the plate that gives it
    Eigen::Vector3d xyz = Eigen::Vector3d::Zero();  // Y = 1 for the source itself
};

/// The plate the chart is computed with (its indicatrix axes: the X–Z section at 45°, slow NE–SW), and its
/// birefringence at the reference wavelength.
DispersiveMedium michel_levy_plate(const MichelLevySettings& settings, double& birefringence_at_reference);

/// The chart's colours at Γ = 0, step, 2·step, … ≤ max_retardation_nm, between crossed polars in parallel
/// light, in `mounting`.
std::vector<MichelLevyStep> michel_levy_colours(const MichelLevySettings& settings, const SectionMounting& mounting,
                                                const SpectralIntegrator& integrator);

}  // namespace petroscope
