#include "petroscope/render/sigmoid_spectrum.hpp"

#include "petroscope/core/error.hpp"

#include <Eigen/Dense>

#include <cmath>
#include <sstream>

namespace petroscope {
namespace {

double normalised_wavelength(double wavelength_nm) { return (wavelength_nm - 380.0) / 400.0; }

double sigmoid(double z) { return 0.5 + z / (2.0 * std::sqrt(1.0 + z * z)); }
double sigmoid_slope(double z) { return 0.5 / std::pow(1.0 + z * z, 1.5); }

}  // namespace

SigmoidSpectrum SigmoidSpectrum::constant(double value) {
    SigmoidSpectrum spectrum;
    spectrum.constant_ = value;
    return spectrum;
}

SigmoidSpectrum SigmoidSpectrum::polynomial(const std::array<double, 3>& coefficients) {
    SigmoidSpectrum spectrum;
    spectrum.coefficients_ = coefficients;
    return spectrum;
}

double SigmoidSpectrum::operator()(double wavelength_nm) const {
    if (constant_ >= 0.0) return constant_;
    const double x = normalised_wavelength(wavelength_nm);
    return sigmoid((coefficients_[0] * x + coefficients_[1]) * x + coefficients_[2]);
}

SigmoidSpectrum fit_sigmoid_spectrum(const Eigen::Vector3d& target_xyz, const std::vector<double>& wavelengths_nm,
                                     const std::vector<Eigen::Vector3d>& weights) {
    Eigen::Vector3d white = Eigen::Vector3d::Zero();
    for (const auto& w : weights) white += w;
    if (target_xyz.norm() < 1e-9) return SigmoidSpectrum::constant(0.0);
    if ((target_xyz - white).norm() < 1e-9) return SigmoidSpectrum::constant(1.0);
    const auto residual = [&](const Eigen::Vector3d& c, Eigen::Matrix3d* jacobian) {
        Eigen::Vector3d xyz = Eigen::Vector3d::Zero();
        if (jacobian) jacobian->setZero();
        for (std::size_t i = 0; i < weights.size(); ++i) {
            const double x = normalised_wavelength(wavelengths_nm[i]);
            const double z = (c[0] * x + c[1]) * x + c[2];
            xyz += sigmoid(z) * weights[i];
            if (jacobian) *jacobian += sigmoid_slope(z) * weights[i] * Eigen::RowVector3d(x * x, x, 1.0);
        }
        return Eigen::Vector3d(xyz - target_xyz);
    };
    // Levenberg–Marquardt (Nocedal & Wright, Numerical Optimization, §10.3) on the three coefficients.
    Eigen::Vector3d c = Eigen::Vector3d::Zero();
    Eigen::Matrix3d jacobian;
    Eigen::Vector3d r = residual(c, &jacobian);
    double damping = 1e-3;
    for (int iteration = 0; iteration < 500 && r.norm() > 1e-12; ++iteration) {
        const Eigen::Matrix3d normal = jacobian.transpose() * jacobian;
        const Eigen::Vector3d step = (normal + damping * Eigen::Matrix3d(normal.diagonal().asDiagonal()) + 1e-30 * Eigen::Matrix3d::Identity())
                                         .ldlt()
                                         .solve(-jacobian.transpose() * r);
        Eigen::Matrix3d trial_jacobian;
        const Eigen::Vector3d trial = residual(c + step, &trial_jacobian);
        if (trial.allFinite() && trial.norm() < r.norm()) {
            c += step;
            r = trial;
            jacobian = trial_jacobian;
            damping = std::max(damping * 0.3, 1e-12);
        } else {
            damping *= 10.0;
            if (damping > 1e12) break;
        }
    }
    if (!(r.norm() <= 1e-7 * std::max(1.0, target_xyz.norm()))) {
        std::ostringstream message;
        message << "no smooth reflectance spectrum has the colour XYZ (" << target_xyz.x() << ", " << target_xyz.y() << ", " << target_xyz.z()
                << "): it lies outside the colours a reflectance between 0 and 1 can have under the light";
        throw InputError(message.str());
    }
    return SigmoidSpectrum::polynomial({c[0], c[1], c[2]});
}

}  // namespace petroscope
