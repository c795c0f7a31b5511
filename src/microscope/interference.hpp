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

}  // namespace petroscope::detail
