#pragma once
// Spectra to CIE XYZ: colour-matching functions, light sources, and the per-wavelength weights that
// turn a transmission spectrum into XYZ.
#include "petroscope/spectral/tabulated.hpp"

#include <Eigen/Core>

#include <array>
#include <functional>
#include <string>
#include <vector>

namespace petroscope {

/// CIE 1931 2° standard observer x̄, ȳ, z̄ (loaded from data/cie, see its README).
struct ColorMatchingFunctions {
    TabulatedSpectrum x_bar, y_bar, z_bar;
};

/// A light source's relative spectral power as a function of wavelength in nm.
struct LightSource {
    std::string name;  // "D65", "A", "blackbody:3200K"
    std::function<double(double wavelength_nm)> relative_power;
};

/// Planck's law: spectral radiance of a blackbody at `temperature_k`, relative (λ in nm; the constant
/// factor 2hc² is dropped). B(λ,T) ∝ λ⁻⁵ / (exp(hc/λkT) − 1).
double planck_relative_radiance(double wavelength_nm, double temperature_k);
LightSource blackbody_source(double temperature_k);

/// XYZ = Σᵢ Tᵢ wᵢ for a transmission spectrum Tᵢ sampled on the grid, with
/// wᵢ = S(λᵢ)·(x̄, ȳ, z̄)(λᵢ)·Δλ / Σⱼ S(λⱼ)ȳ(λⱼ)Δλ (CIE 15:2004, §7), so that a perfect transmitter
/// (T ≡ 1) has Y = 1. The wavelengths must be uniformly spaced (a WavelengthGrid).
class SpectralIntegrator {
public:
    SpectralIntegrator(const std::vector<double>& wavelengths_nm, const ColorMatchingFunctions& cmf,
                       const LightSource& source);

    const std::vector<Eigen::Vector3d>& weights() const { return weights_; }
    /// XYZ of the source itself (T ≡ 1): the white of this light, with Y = 1.
    const Eigen::Vector3d& white_xyz() const { return white_xyz_; }
    Eigen::Vector3d integrate(const std::vector<double>& transmission) const;

private:
    std::vector<Eigen::Vector3d> weights_;
    std::array<std::vector<double>, 3> channel_weights_;  // the same per channel, for a vectorised sum
    Eigen::Vector3d white_xyz_ = Eigen::Vector3d::Zero();
};

}  // namespace petroscope
