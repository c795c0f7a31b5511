#include "petroscope/spectral/colorimetry.hpp"

#include "petroscope/core/error.hpp"

#include <cmath>
#include <stdexcept>

namespace petroscope {

double planck_relative_radiance(double wavelength_nm, double temperature_k) {
    // Second radiation constant c₂ = hc/k = 1.438776877e-2 m·K (CODATA 2018).
    constexpr double c2_nm_k = 1.438776877e7;
    const double wavelength_um = wavelength_nm * 1e-3;
    return 1.0 / (std::pow(wavelength_um, 5) * std::expm1(c2_nm_k / (wavelength_nm * temperature_k)));
}

LightSource blackbody_source(double temperature_k) {
    if (!(temperature_k > 0.0) || !std::isfinite(temperature_k)) {
        throw InputError("blackbody temperature must be a positive number of kelvin");
    }
    return LightSource{"blackbody:" + std::to_string(static_cast<long>(std::lround(temperature_k))) + "K",
                       [temperature_k](double nm) { return planck_relative_radiance(nm, temperature_k); }};
}

SpectralIntegrator::SpectralIntegrator(const std::vector<double>& wavelengths_nm,
                                       const ColorMatchingFunctions& cmf, const LightSource& source) {
    if (wavelengths_nm.empty()) throw std::invalid_argument("SpectralIntegrator needs wavelengths");
    // On a uniform grid the band width Δλ is common to numerator and normalisation and cancels.
    weights_.resize(wavelengths_nm.size());
    double normalisation = 0.0;
    for (std::size_t i = 0; i < wavelengths_nm.size(); ++i) {
        const double lambda = wavelengths_nm[i];
        const double power = source.relative_power(lambda);
        if (!(power >= 0.0) || !std::isfinite(power)) {
            throw InputError("light source " + source.name + " has no valid power at " + std::to_string(lambda) + " nm");
        }
        weights_[i] = power * Eigen::Vector3d(cmf.x_bar(lambda), cmf.y_bar(lambda), cmf.z_bar(lambda));
        normalisation += weights_[i].y();
    }
    if (!(normalisation > 0.0)) {
        throw InputError("the wavelength grid sees no light: the source times ȳ is zero on every sample");
    }
    for (auto& weight : weights_) {
        weight /= normalisation;
        white_xyz_ += weight;
        for (int c = 0; c < 3; ++c) channel_weights_[static_cast<std::size_t>(c)].push_back(weight[c]);
    }
}

Eigen::Vector3d SpectralIntegrator::integrate(const std::vector<double>& transmission) const {
    if (transmission.size() != weights_.size()) throw std::invalid_argument("transmission size differs from the grid");
    const double *t = transmission.data(), *wx = channel_weights_[0].data(), *wy = channel_weights_[1].data();
    const double* wz = channel_weights_[2].data();
    double x = 0.0, y = 0.0, z = 0.0;
    const int count = static_cast<int>(transmission.size());
#pragma omp simd reduction(+ : x, y, z)
    for (int i = 0; i < count; ++i) {
        x += t[i] * wx[i];
        y += t[i] * wy[i];
        z += t[i] * wz[i];
    }
    return {x, y, z};
}

}  // namespace petroscope
