#include "petroscope/optics/medium.hpp"

#include "petroscope/optics/gyration.hpp"

namespace petroscope {

OpticalMedium OpticalMedium::isotropic(std::complex<double> n) {
    return OpticalMedium{Eigen::Vector3cd::Constant(n), Eigen::Matrix3d::Identity()};
}

OpticalMedium OpticalMedium::from_n_kappa(const Eigen::Vector3d& n, const Eigen::Vector3d& kappa, const Eigen::Matrix3d& axes) {
    return OpticalMedium{n.cast<std::complex<double>>() + std::complex<double>(0.0, 1.0) * kappa.cast<std::complex<double>>(), axes};
}

bool OpticalMedium::is_isotropic() const {
    return principal_n[0] == principal_n[1] && principal_n[1] == principal_n[2];
}

bool OpticalMedium::is_lossless() const { return principal_n.imag().isZero(0.0); }

bool OpticalMedium::is_uniaxial() const {
    const int equal_pairs = (principal_n[0] == principal_n[1]) + (principal_n[1] == principal_n[2]) + (principal_n[0] == principal_n[2]);
    return equal_pairs == 1;
}

Eigen::Matrix3cd OpticalMedium::permittivity() const {
    const Eigen::Matrix3cd rotation = axes.cast<std::complex<double>>();
    const Eigen::Matrix3cd product = rotation * principal_n.array().square().matrix().asDiagonal() * rotation.transpose();
    // Exactly symmetric (a reciprocal medium): rounding in the product leaves ε_ij ≠ ε_ji by ~1e-16, which
    // breaks the power orthogonality of nearly degenerate modes by 1e-16/(their splitting).
    Eigen::Matrix3cd symmetric = product;
    for (int i = 0; i < 3; ++i) {
        for (int j = i + 1; j < 3; ++j) symmetric(i, j) = symmetric(j, i) = 0.5 * (product(i, j) + product(j, i));
    }
    return symmetric;
}

Eigen::Matrix3d OpticalMedium::lab_gyration() const { return turned_gyration(gyration, axes); }

}  // namespace petroscope
