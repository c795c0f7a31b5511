#pragma once
// The optical indicatrix of a crystal at one wavelength, placed in the microscope (lab) frame.
#include <Eigen/Core>

namespace petroscope {

/// Principal refractive indices along the indicatrix axes X, Y, Z, and those axes in the lab frame.
/// For uniaxial crystals Z is the optic axis (n_z = ε, n_x = n_y = ω); for biaxial X, Y, Z carry
/// nα, nβ, nγ at the mineral's reference wavelength (their order may change with dispersion).
struct Indicatrix {
    Eigen::Vector3d principal_n = Eigen::Vector3d::Ones();  // (n_X, n_Y, n_Z)
    Eigen::Matrix3d axes = Eigen::Matrix3d::Identity();     // columns: X, Y, Z as unit lab vectors

    /// The relative impermeability tensor η = ε⁻¹ = R·diag(1/n²)·Rᵀ in the lab frame.
    Eigen::Matrix3d impermeability() const;
};

/// What the Biot–Fresnel construction needs (physics notes §2): the sorted principal impermeabilities
/// a ≥ b ≥ c (a = 1/n_min², c = 1/n_max²) and the two binormals (optic axes of the wave normals),
/// b₁,₂ = cos V·e_c ± sin V·e_a, both with a non-negative component along e_c, tan²V = (a − b)/(b − c).
/// A uniaxial crystal has b₁ = ±b₂ (V = 0 or 90°), an isotropic one a = c.
struct BinormalFrame {
    double a = 1.0, b = 1.0, c = 1.0;
    Eigen::Vector3d e_a = Eigen::Vector3d::UnitX();  // axis of the smallest index
    Eigen::Vector3d e_c = Eigen::Vector3d::UnitZ();  // axis of the largest index
    Eigen::Vector3d binormal_1 = Eigen::Vector3d::UnitZ();
    Eigen::Vector3d binormal_2 = Eigen::Vector3d::UnitZ();
    double v_rad = 0.0;  // angle of each binormal from e_c
    Eigen::Matrix3d impermeability = Eigen::Matrix3d::Identity();

    explicit BinormalFrame(const Indicatrix& indicatrix);
    /// b₁ = ±b₂ exactly: a uniaxial or isotropic crystal.
    bool uniaxial() const { return a == b || b == c; }
    BinormalFrame() = default;
};

}  // namespace petroscope
