#pragma once
// What a petrologist reads off one grain at the microscope (orthoscopy, parallel light along the axis):
// the two waves the grain lets through, its retardation and where it goes extinct, and the mineral's own
// birefringence, 2V and optic sign. Frames and angle senses: docs/conventions.md.
#include "petroscope/minerals/mineral.hpp"

#include <Eigen/Core>

#include <optional>

namespace petroscope {

struct GrainOptics {
    double wavelength_nm = 0.0;
    double n_fast = 1.0, n_slow = 1.0;        // the two waves along the microscope axis
    double birefringence_in_section = 0.0;    // n_slow − n_fast
    double retardation_nm = 0.0;              // (n_slow − n_fast)·thickness
    /// The slow wave's vibration direction at stage 0, degrees from E toward N in [0°, 180°); none where the
    /// grain shows no birefringence along the axis (isotropic, or cut ⟂ an optic axis).
    std::optional<double> slow_azimuth_deg;
    /// The first stage angle in [0°, 90°) that puts the grain at extinction between crossed polars (polarizer
    /// E–W): its vibration directions then lie E–W and N–S, and so on every 90°. None when slow_azimuth_deg is.
    std::optional<double> extinction_stage_deg;
    OpticalSummary mineral;                   // nα, nβ, nγ, the largest birefringence, 2V, sign
};

/// At `wavelength_nm`, for the grain's indicatrix axes (columns, lab frame, stage 0) and thickness. The
/// waves along the axis are the eigenmodes of the wave normal z (Born & Wolf, Principles of Optics, §15.3).
/// Throws InputError where the mineral's data give no physical index at that wavelength.
GrainOptics grain_optics(const Mineral& mineral, const Eigen::Matrix3d& crystal_axes, double thickness_um, double wavelength_nm);

}  // namespace petroscope
