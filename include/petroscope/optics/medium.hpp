#pragma once
// A homogeneous optical medium at one wavelength: isotropic or anisotropic, lossless or absorbing.
#include <Eigen/Core>

#include <complex>

namespace petroscope {

struct OpticalMedium {
    Eigen::Vector3cd principal_n = Eigen::Vector3cd::Ones();  // n + iκ along the indicatrix axes X, Y, Z
    Eigen::Matrix3d axes = Eigen::Matrix3d::Identity();       // columns: X, Y, Z in the lab frame

    static OpticalMedium isotropic(std::complex<double> n);
    /// Principal indices n + iκ from the real parts n and the extinction coefficients κ.
    static OpticalMedium from_n_kappa(const Eigen::Vector3d& n, const Eigen::Vector3d& kappa, const Eigen::Matrix3d& axes);

    bool is_isotropic() const;
    bool is_lossless() const;
    /// Uniaxial: exactly two equal principal indices (the optic axis is the odd one's axis).
    bool is_uniaxial() const;
    /// Relative permittivity ε = R·diag(n²)·Rᵀ in the lab frame (non-magnetic medium).
    Eigen::Matrix3cd permittivity() const;
    /// The real indices (for a lossless medium).
    Eigen::Vector3d real_n() const { return principal_n.real(); }
};

}  // namespace petroscope
