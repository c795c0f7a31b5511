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

/// What the Biot–Fresnel construction needs (docs/theory.md §1; Born & Wolf §15.3.3): the sorted principal impermeabilities
/// a ≥ b ≥ c (a = 1/n_min², c = 1/n_max²) and the two binormals (optic axes of the wave normals),
/// b₁,₂ = cos V·e_c ± sin V·e_a, both with a non-negative component along e_c, tan²V = (a − b)/(b − c).
/// A uniaxial crystal has b₁ = ±b₂ (V = 0 or 90°), an isotropic one a = c. `Real` is double, or long double
/// where an interface must balance its fluxes far below double precision (optics/interface.hpp).
template <typename Real>
struct BasicBinormalFrame {
    using Vector = Eigen::Matrix<Real, 3, 1>;
    using Matrix = Eigen::Matrix<Real, 3, 3>;
    Real a = 1, b = 1, c = 1;
    Vector e_a = Vector::UnitX();  // axis of the smallest index
    Vector e_c = Vector::UnitZ();  // axis of the largest index
    Vector binormal_1 = Vector::UnitZ();
    Vector binormal_2 = Vector::UnitZ();
    Real v_rad = 0;  // angle of each binormal from e_c
    Matrix impermeability = Matrix::Identity();  // η in the lab frame, exactly symmetric

    /// Computed in `Real` from the indicatrix's (double) indices and axes.
    explicit BasicBinormalFrame(const Indicatrix& indicatrix);
    BasicBinormalFrame() = default;
    /// b₁ = ±b₂ exactly: a uniaxial or isotropic crystal.
    bool uniaxial() const { return a == b || b == c; }
};

using BinormalFrame = BasicBinormalFrame<double>;
extern template struct BasicBinormalFrame<double>;
extern template struct BasicBinormalFrame<long double>;

}  // namespace petroscope
