#pragma once
// Smooth reflectance spectra for RGB colours (textures, wall colours): the sigmoid-polynomial model of
// Jakob & Hanika, "A low-dimensional function space for efficient spectral upsampling", Computer Graphics
// Forum 38(2), 2019: ρ(λ) = S(c₀x² + c₁x + c₂), S(z) = ½ + z / (2√(1 + z²)), with x = (λ − 380 nm)/400 nm
// here (the paper uses λ in nm; the rescaling only conditions the fit). Smooth, bounded in (0, 1), and
// fitted so that the spectrum's colour under the grid's light equals the target exactly.
#include <Eigen/Core>

#include <array>
#include <vector>

namespace petroscope {

class SigmoidSpectrum {
public:
    /// ρ ≡ value: neutral colours (black and white are limits the sigmoid reaches only at infinity).
    static SigmoidSpectrum constant(double value);
    static SigmoidSpectrum polynomial(const std::array<double, 3>& coefficients);

    double operator()(double wavelength_nm) const;
    const std::array<double, 3>& coefficients() const { return coefficients_; }

private:
    std::array<double, 3> coefficients_{0.0, 0.0, 0.0};
    double constant_ = -1.0;  // < 0: the polynomial
};

/// The sigmoid spectrum whose XYZ = Σᵢ ρ(λᵢ)·wᵢ equals `target_xyz` (weights as SpectralIntegrator's:
/// light × colour-matching functions, white Y = 1), by Levenberg–Marquardt from ρ ≡ ½. Targets equal to
/// 0 or to the white XYZ (within 1e-9) give the constant spectra. Throws InputError when no sigmoid
/// spectrum reaches the colour (outside the gamut of reflectances, e.g. negative RGB).
SigmoidSpectrum fit_sigmoid_spectrum(const Eigen::Vector3d& target_xyz, const std::vector<double>& wavelengths_nm,
                                     const std::vector<Eigen::Vector3d>& weights);

}  // namespace petroscope
