#pragma once
// Random crystals and directions for property tests (fixed seeds: every run checks the same cases).
#include "petroscope/optics/indicatrix.hpp"
#include "petroscope/optics/medium.hpp"

#include <Eigen/Geometry>

#include <random>

namespace petroscope::testing {

inline Eigen::Vector3d random_unit_vector(std::mt19937_64& rng) {
    std::normal_distribution<double> normal;
    Eigen::Vector3d v(normal(rng), normal(rng), normal(rng));
    return v.normalized();
}

inline Eigen::Matrix3d random_rotation(std::mt19937_64& rng) {
    std::normal_distribution<double> normal;
    Eigen::Quaterniond q(normal(rng), normal(rng), normal(rng), normal(rng));
    return q.normalized().toRotationMatrix();
}

/// A biaxial crystal with indices between 1.3 and 2.8 and birefringence up to 0.3, randomly oriented.
inline Indicatrix random_biaxial(std::mt19937_64& rng) {
    std::uniform_real_distribution<double> base(1.3, 2.5), spread(0.001, 0.3), fraction(0.02, 0.98);
    const double n_alpha = base(rng);
    const double n_gamma = n_alpha + spread(rng);
    const double n_beta = n_alpha + fraction(rng) * (n_gamma - n_alpha);
    return Indicatrix{{n_alpha, n_beta, n_gamma}, random_rotation(rng)};
}

/// A uniaxial crystal (positive or negative at random), randomly oriented; Z is the optic axis.
inline Indicatrix random_uniaxial(std::mt19937_64& rng) {
    std::uniform_real_distribution<double> base(1.3, 2.5), birefringence(-0.3, 0.3);
    const double n_o = base(rng);
    const double n_e = n_o + birefringence(rng);
    return Indicatrix{{n_o, n_o, n_e}, random_rotation(rng)};
}

/// A lossless medium of each kind (0 isotropic, 1 uniaxial, 2 biaxial), or an absorbing uniaxial one (3).
inline OpticalMedium random_medium_of_kind(std::mt19937_64& rng, int kind) {
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    if (kind == 0) return OpticalMedium::isotropic(1.0 + 1.6 * unit(rng));
    if (kind == 3) {
        const std::complex<double> n_o(1.5 + unit(rng), 0.5 * unit(rng)), n_e(1.5 + unit(rng), 0.5 * unit(rng));
        return OpticalMedium{Eigen::Vector3cd(n_o, n_o, n_e), random_rotation(rng)};
    }
    const Indicatrix crystal = kind == 1 ? random_uniaxial(rng) : random_biaxial(rng);
    return OpticalMedium{crystal.principal_n.cast<std::complex<double>>(), crystal.axes};
}

}  // namespace petroscope::testing
