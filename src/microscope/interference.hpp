#pragma once
// The intensity of two interfering modes, shared by the conoscope's kernel and its reference path.

namespace petroscope::detail {

/// |c₀e^{iφ₀} + c₁e^{iφ₁}|² for real amplitudes cₘ, with sin2 = sin²((φ₀ − φ₁)/2):
/// (c₀ − c₁)² + 4c₀c₁cos²(δ/2) = (c₀ + c₁)² − 4c₀c₁sin²(δ/2). The form whose terms are both
/// non-negative is used, so rounding never makes an intensity negative.
inline double pair_intensity(double c0, double c1, double sin2) {
    const double product = c0 * c1;
    return product >= 0.0 ? (c0 - c1) * (c0 - c1) + 4.0 * product * (1.0 - sin2)
                          : (c0 + c1) * (c0 + c1) - 4.0 * product * sin2;
}

/// The same intensity as a function of the phase difference δ: mean + modulation·cos δ with
/// mean = c₀² + c₁² and modulation = 2c₀c₁ (the thickness dependence that fitting uses).
struct PairTerms {
    double mean = 0.0;
    double modulation = 0.0;
};
inline PairTerms pair_terms(double c0, double c1) { return {c0 * c0 + c1 * c1, 2.0 * c0 * c1}; }

/// |bᵀ(E₀e^{iφ₀} + E₁e^{iφ₁})|² for real mode fields Eₘ = (uₘ, vₘ) and a complex analyzer b = b_re + i·b_im
/// (after a plate), both in one orthonormal basis (u, v): with αₘ = b_re·Eₘ, βₘ = b_im·Eₘ and δ = φ₀ − φ₁
/// it is Σₘ(αₘ² + βₘ²) + 2(α₀α₁ + β₀β₁)cos δ + 2(α₀β₁ − β₀α₁)sin δ: |Σₘ (αₘ + iβₘ)e^{iφₘ}|² written out
/// (the Jones calculus of Yariv & Yeh, Optical Waves in Crystals, 1984, §5.1).
inline double complex_analyzer_intensity(double re_u, double re_v, double im_u, double im_v, double u0, double v0, double u1,
                                         double v1, double cos_delta, double sin_delta) {
    const double alpha0 = re_u * u0 + re_v * v0, alpha1 = re_u * u1 + re_v * v1;
    const double beta0 = im_u * u0 + im_v * v0, beta1 = im_u * u1 + im_v * v1;
    return alpha0 * alpha0 + alpha1 * alpha1 + beta0 * beta0 + beta1 * beta1 + 2.0 * (alpha0 * alpha1 + beta0 * beta1) * cos_delta +
           2.0 * (alpha0 * beta1 - beta0 * alpha1) * sin_delta;
}

}  // namespace petroscope::detail
