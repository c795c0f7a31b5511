#pragma once
// A homogeneous optical medium at one wavelength: isotropic or anisotropic, lossless or absorbing, optically
// active or not.
#include <Eigen/Core>

#include <complex>

namespace petroscope {

struct OpticalMedium {
    Eigen::Vector3cd principal_n = Eigen::Vector3cd::Ones();  // n + iκ along the indicatrix axes X, Y, Z
    Eigen::Matrix3d axes = Eigen::Matrix3d::Identity();       // columns: X, Y, Z in the lab frame
    /// Natural optical activity: Landau's gyration tensor g (optics/gyration.hpp), real symmetric, in the frame
    /// of `axes` as principal_n is (quartz: diag(g₁₁, g₁₁, g₃₃)). Zero: an inactive medium.
    Eigen::Matrix3d gyration = Eigen::Matrix3d::Zero();

    static OpticalMedium isotropic(std::complex<double> n);
    /// Principal indices n + iκ from the real parts n and the extinction coefficients κ.
    static OpticalMedium from_n_kappa(const Eigen::Vector3d& n, const Eigen::Vector3d& kappa, const Eigen::Matrix3d& axes);

    /// Equal principal indices (an optically active isotropic medium is still isotropic here).
    bool is_isotropic() const;
    bool is_active() const { return !gyration.isZero(0.0); }
    /// Its plane waves are the s and p waves of one index: isotropic and inactive.
    bool has_s_and_p_waves() const { return is_isotropic() && !is_active(); }
    bool is_lossless() const;
    /// Uniaxial: exactly two equal principal indices (the optic axis is the odd one's axis).
    bool is_uniaxial() const;
    /// Relative permittivity ε = R·diag(n²)·Rᵀ in the lab frame (non-magnetic medium).
    Eigen::Matrix3cd permittivity() const;
    /// The gyration tensor in the lab frame, A·g·Aᵀ with A = axes.
    Eigen::Matrix3d lab_gyration() const;
    /// The real indices (for a lossless medium).
    Eigen::Vector3d real_n() const { return principal_n.real(); }
};

}  // namespace petroscope
