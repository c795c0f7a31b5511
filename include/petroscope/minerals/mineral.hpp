#pragma once
// A mineral's optical data: principal indices with their dispersion, absorption, and their sources.
#include "petroscope/optics/dispersion.hpp"
#include "petroscope/optics/gyration.hpp"
#include "petroscope/optics/orientation.hpp"

#include <Eigen/Core>

#include <array>
#include <optional>
#include <string>
#include <vector>

namespace petroscope {

/// One principal axis of the indicatrix: n(λ), optionally κ(λ), and where the numbers come from.
struct PrincipalAxis {
    std::string key;                        // "n_alpha", "n_o", "n", … as in the file
    DispersionModel n;
    std::string n_source;
    std::optional<std::array<double, 2>> range_um;  // validity of the formula
    std::optional<DispersionModel> kappa;
    std::string kappa_source;
};

/// One principal component of natural optical activity: the rotatory power (°/mm, positive dextrorotatory) of
/// the right-handed form for waves along a principal direction, and where the numbers come from.
struct RotatoryPower {
    std::string key;  // "rotatory_power", "rotatory_power_axis", "rotatory_power_normal" as in the file
    DispersionModel deg_per_mm;
    std::string source;
};

struct Mineral {
    std::string name;
    std::vector<std::string> aliases;
    std::string formula, system, indicatrix, source, note;
    OpticalClass optical_class = OpticalClass::isotropic;
    double reference_wavelength_nm = 589.3;
    std::vector<PrincipalAxis> axes;  // isotropic: {n}; uniaxial: {o, e}; biaxial: {alpha, beta, gamma}
    std::vector<RotatoryPower> rotatory_powers;  // empty: inactive; isotropic: {all directions}; uniaxial: {normal, axis}
    std::string file;                 // where the record was read from

    /// Indices along the indicatrix axes X, Y, Z (uniaxial: ω, ω, ε; isotropic: n, n, n).
    Eigen::Vector3d principal_n(double wavelength_nm) const;
    /// Extinction coefficients κ along X, Y, Z (zero where the file gives none).
    Eigen::Vector3d principal_kappa(double wavelength_nm) const;
    bool absorbing() const;
    bool optically_active() const { return !rotatory_powers.empty(); }
    /// Rotatory power (rad/µm) of the right-handed form for waves along X, Y, Z; zero for an inactive mineral.
    Eigen::Vector3d principal_rotatory_power(double wavelength_nm) const;
    /// Landau's gyration tensor of its `handedness` form in its indicatrix frame (optics/gyration.hpp); zero for
    /// an inactive mineral.
    Eigen::Matrix3d gyration(double wavelength_nm, Handedness handedness) const;
    /// The axes whose formula is used outside its stated validity range at some of `wavelengths_nm`,
    /// as readable warnings.
    std::vector<std::string> range_warnings(const std::vector<double>& wavelengths_nm) const;
};

/// What optical mineralogy tables list, at one wavelength.
struct OpticalSummary {
    double wavelength_nm = 0.0;
    double n_alpha = 0.0, n_beta = 0.0, n_gamma = 0.0;
    double birefringence = 0.0;                 // nγ − nα
    std::optional<double> two_v_deg;            // acute 2V (0 for uniaxial; none for isotropic)
    std::string sign;                           // "+", "-", or "" for isotropic
};
OpticalSummary optical_summary(const Mineral& mineral, double wavelength_nm);

std::string_view optical_class_name(OpticalClass optical_class);

}  // namespace petroscope
