#include "petroscope/minerals/mineral.hpp"

#include "petroscope/core/error.hpp"
#include "petroscope/core/text.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>

namespace petroscope {
namespace {

// The three X, Y, Z values from per-axis values listed in file order.
Eigen::Vector3d along_xyz(const Mineral& mineral, const Eigen::Vector3d& listed) {
    switch (mineral.optical_class) {
        case OpticalClass::isotropic: return Eigen::Vector3d::Constant(listed[0]);
        case OpticalClass::uniaxial: return {listed[0], listed[0], listed[1]};
        case OpticalClass::biaxial: return listed;
    }
    return listed;
}

}  // namespace

std::string_view optical_class_name(OpticalClass optical_class) {
    switch (optical_class) {
        case OpticalClass::isotropic: return "isotropic";
        case OpticalClass::uniaxial: return "uniaxial";
        case OpticalClass::biaxial: return "biaxial";
    }
    return "unknown";
}

Eigen::Vector3d Mineral::principal_n(double wavelength_nm) const {
    Eigen::Vector3d listed = Eigen::Vector3d::Zero();
    for (std::size_t i = 0; i < axes.size() && i < 3; ++i) listed[static_cast<Eigen::Index>(i)] = axes[i].n(wavelength_nm);
    return along_xyz(*this, listed);
}

Eigen::Vector3d Mineral::principal_kappa(double wavelength_nm) const {
    Eigen::Vector3d listed = Eigen::Vector3d::Zero();
    for (std::size_t i = 0; i < axes.size() && i < 3; ++i) {
        if (axes[i].kappa) listed[static_cast<Eigen::Index>(i)] = (*axes[i].kappa)(wavelength_nm);
    }
    return along_xyz(*this, listed);
}

Eigen::Vector3d Mineral::principal_rotatory_power(double wavelength_nm) const {
    Eigen::Vector3d listed = Eigen::Vector3d::Zero();
    for (std::size_t i = 0; i < rotatory_powers.size() && i < 3; ++i) {
        listed[static_cast<Eigen::Index>(i)] = rotatory_powers[i].deg_per_mm(wavelength_nm) * std::numbers::pi / 180.0 * 1e-3;
    }
    return along_xyz(*this, listed);
}

Eigen::Matrix3d Mineral::gyration(double wavelength_nm, Handedness handedness) const {
    return gyration_tensor(principal_rotatory_power(wavelength_nm), Eigen::Matrix3d::Identity(), wavelength_nm, handedness);
}

bool Mineral::absorbing() const {
    return std::any_of(axes.begin(), axes.end(), [](const PrincipalAxis& axis) { return axis.kappa.has_value(); });
}

std::vector<std::string> Mineral::range_warnings(const std::vector<double>& wavelengths_nm) const {
    std::vector<std::string> warnings;
    if (wavelengths_nm.empty()) return warnings;
    const auto [shortest, longest] = std::minmax_element(wavelengths_nm.begin(), wavelengths_nm.end());
    for (const PrincipalAxis& axis : axes) {
        if (!axis.range_um) continue;
        const double low_nm = (*axis.range_um)[0] * 1e3;
        const double high_nm = (*axis.range_um)[1] * 1e3;
        if (*shortest < low_nm || *longest > high_nm) {
            std::ostringstream text;
            text << name << ": " << axis.key << " formula is valid over " << low_nm << "-" << high_nm
                 << " nm; it is extrapolated to " << *shortest << "-" << *longest << " nm";
            warnings.push_back(text.str());
        }
    }
    return warnings;
}

OpticalSummary optical_summary(const Mineral& mineral, double wavelength_nm) {
    OpticalSummary summary;
    summary.wavelength_nm = wavelength_nm;
    for (const PrincipalAxis& axis : mineral.axes) {
        const double value = axis.n(wavelength_nm);
        if (!std::isfinite(value) || value < 1.0) {
            std::string range;
            if (axis.range_um) range = " (its formula is valid over " + format_number((*axis.range_um)[0] * 1e3) + "-" +
                                       format_number((*axis.range_um)[1] * 1e3) + " nm)";
            throw InputError(mineral.name + ": " + axis.key + " has no physical value at " + format_number(wavelength_nm) +
                             " nm" + range);
        }
    }
    Eigen::Vector3d n = mineral.principal_n(wavelength_nm);
    std::sort(n.data(), n.data() + 3);
    summary.n_alpha = n[0];
    summary.n_beta = n[1];
    summary.n_gamma = n[2];
    summary.birefringence = n[2] - n[0];
    if (mineral.optical_class == OpticalClass::isotropic) return summary;
    if (mineral.optical_class == OpticalClass::uniaxial) {
        const Eigen::Vector3d xyz = mineral.principal_n(wavelength_nm);
        summary.two_v_deg = 0.0;
        summary.sign = xyz[2] > xyz[0] ? "+" : "-";
        return summary;
    }
    // Sorted indices: V_z from the nγ axis (docs/theory.md §1, "Binormals and biradials"); positive when V_z < 45°.
    const double v_z = binormal_angle_from_z(n);
    const double v_acute = std::min(v_z, std::numbers::pi / 2.0 - v_z);
    summary.two_v_deg = 2.0 * v_acute * 180.0 / std::numbers::pi;
    summary.sign = v_z < std::numbers::pi / 4.0 ? "+" : "-";
    return summary;
}

}  // namespace petroscope
