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

/// An optically active crystal's terms (conoscope.hpp, InterferenceTerms) for one analyzed component: the analyzer
/// reads u₀ = U₀·t₀ of the fast and u₁ = U₁·t₁ of the slow mode's entrance amplitude t, the modes are coupled by
/// (c₀, c₁) (optics/slab.hpp) and split by Δ = (q_fast − q_slow)/2, W = √(Δ² + c₀c₁). Across the slab
/// exp(i·k₀d·Q) (slab_propagation) makes the amplitude cos(k₀Wd)·A + sin(k₀Wd)·(B + iC) with A = U₀t₀ + U₁t₁,
/// B = (U₁c₁t₀ − U₀c₀t₁)/W and C = Δ(U₀t₀ − U₁t₁)/W, whose square is the mean (A² + B² + C²)/2, the modulation
/// (A² − B² − C²)/2 of cos 2k₀Wd and AB of sin 2k₀Wd. `inverse_w` is 1/W (0 where W = 0: no coupling, no splitting).
struct ActiveTerms {
    double mean = 0.0, modulation = 0.0, sine_modulation = 0.0;
};
inline ActiveTerms active_terms(double analyzer_fast, double analyzer_slow, double t0, double t1, double c0, double c1, double half_split,
                                double inverse_w) {
    const double a = analyzer_fast * t0 + analyzer_slow * t1;
    const double b = (analyzer_slow * c1 * t0 - analyzer_fast * c0 * t1) * inverse_w;
    const double c = half_split * (analyzer_fast * t0 - analyzer_slow * t1) * inverse_w;
    return {0.5 * (a * a + b * b + c * c), 0.5 * (a * a - b * b - c * c), a * b};
}

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
