#include "petroscope/optics/orientation.hpp"

#include "petroscope/core/error.hpp"
#include "petroscope/core/text.hpp"

#include <Eigen/Geometry>

#include <array>
#include <cmath>
#include <numbers>

namespace petroscope {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

constexpr std::array<std::pair<Cut, std::string_view>, 4> kCutNames{{
    {Cut::optic_axis, "optic-axis"},
    {Cut::acute_bisectrix, "acute-bisectrix"},
    {Cut::obtuse_bisectrix, "obtuse-bisectrix"},
    {Cut::optic_normal, "optic-normal"},
}};

// Rotation that takes the indicatrix-frame direction `along_microscope` to lab z and `east` (⟂ to it) to
// lab x; its inverse's columns are the indicatrix axes. Returned as the indicatrix-to-lab matrix.
Eigen::Matrix3d frame_with(const Eigen::Vector3d& along_microscope, const Eigen::Vector3d& east) {
    const Eigen::Vector3d u = along_microscope.normalized();
    const Eigen::Vector3d w = (east - east.dot(u) * u).normalized();
    const Eigen::Vector3d v = u.cross(w);
    Eigen::Matrix3d lab_from_indicatrix;
    lab_from_indicatrix.row(0) = w.transpose();
    lab_from_indicatrix.row(1) = v.transpose();
    lab_from_indicatrix.row(2) = u.transpose();
    return lab_from_indicatrix;
}

}  // namespace

Eigen::Matrix3d rotation_z_deg(double angle_deg) {
    return Eigen::AngleAxisd(angle_deg * kDegree, Eigen::Vector3d::UnitZ()).toRotationMatrix();
}

Eigen::Matrix3d euler_zyz_deg(double alpha_deg, double beta_deg, double gamma_deg) {
    return rotation_z_deg(alpha_deg) *
           Eigen::AngleAxisd(beta_deg * kDegree, Eigen::Vector3d::UnitY()).toRotationMatrix() *
           rotation_z_deg(gamma_deg);
}

Cut parse_cut(std::string_view name) {
    for (const auto& [cut, cut_text] : kCutNames) {
        if (name == cut_text) return cut;
    }
    throw InputError("unknown cut " + quote_input(name) +
                     " (expected optic-axis, acute-bisectrix, obtuse-bisectrix or optic-normal)");
}

std::string_view cut_name(Cut cut) {
    for (const auto& [c, text] : kCutNames) {
        if (c == cut) return text;
    }
    return "unknown";
}

double binormal_angle_from_z(const Eigen::Vector3d& principal_n) {
    const Eigen::Vector3d impermeability = principal_n.array().square().inverse();
    return std::atan2(std::sqrt(std::max(impermeability[0] - impermeability[1], 0.0)),
                      std::sqrt(std::max(impermeability[1] - impermeability[2], 0.0)));
}

Eigen::Matrix3d cut_orientation(Cut cut, OpticalClass optical_class, const Eigen::Vector3d& principal_n,
                                double azimuth_deg, double tilt_deg) {
    const Eigen::Vector3d x = Eigen::Vector3d::UnitX();
    const Eigen::Vector3d y = Eigen::Vector3d::UnitY();
    const Eigen::Vector3d z = Eigen::Vector3d::UnitZ();
    Eigen::Matrix3d lab_from_indicatrix = Eigen::Matrix3d::Identity();
    if (optical_class == OpticalClass::uniaxial) {
        // The optic axis is the indicatrix Z axis.
        switch (cut) {
            case Cut::optic_axis: lab_from_indicatrix = frame_with(z, x); break;
            case Cut::optic_normal: lab_from_indicatrix = frame_with(x, z); break;
            case Cut::acute_bisectrix:
            case Cut::obtuse_bisectrix:
                throw InputError("cut '" + std::string(cut_name(cut)) +
                                 "' exists only for biaxial minerals (use optic-axis or optic-normal, or --euler)");
        }
    } else if (optical_class == OpticalClass::biaxial) {
        const double v_z = binormal_angle_from_z(principal_n);
        const bool positive = v_z < std::numbers::pi / 4.0;  // Z is the acute bisectrix
        const Eigen::Vector3d acute = positive ? z : x;
        const Eigen::Vector3d obtuse = positive ? x : z;
        // Binormal 1 in the X–Z plane along the microscope axis; the second binormal, taken with its end
        // pointing up the microscope, leans toward +x (East). b₂ = (−sin V, 0, cos V) has components
        // sin 2V along `toward_second` and cos 2V along binormal 1, hence the sign of cos 2V.
        const Eigen::Vector3d binormal(std::sin(v_z), 0.0, std::cos(v_z));
        const double upward = std::cos(2.0 * v_z) < 0.0 ? -1.0 : 1.0;
        const Eigen::Vector3d toward_second = upward * Eigen::Vector3d(-std::cos(v_z), 0.0, std::sin(v_z));
        switch (cut) {
            case Cut::optic_axis: lab_from_indicatrix = frame_with(binormal, toward_second); break;
            case Cut::acute_bisectrix: lab_from_indicatrix = frame_with(acute, obtuse); break;
            case Cut::obtuse_bisectrix: lab_from_indicatrix = frame_with(obtuse, acute); break;
            case Cut::optic_normal: lab_from_indicatrix = frame_with(y, acute); break;
        }
    }
    const Eigen::Matrix3d tilt = Eigen::AngleAxisd(tilt_deg * kDegree, y).toRotationMatrix();
    return rotation_z_deg(azimuth_deg) * tilt * lab_from_indicatrix;
}

}  // namespace petroscope
