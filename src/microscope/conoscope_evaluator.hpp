#pragma once
// Everything of a conoscopic figure that does not depend on the image point, and the evaluation of pairs
// of opposite directions: the vectorised kernel, with the reference path (optics/slab.hpp) for the
// samples it flags.
#include "conoscope_kernel.hpp"

#include "petroscope/microscope/conoscope.hpp"
#include "petroscope/optics/slab.hpp"

#include <optional>

namespace petroscope::detail {

class ConoscopeEvaluator {
public:
    /// Pixel pairs evaluated together in monochromatic light.
    static constexpr std::size_t kMonochromaticBatch = 256;

    ConoscopeEvaluator(const ConoscopeSettings& settings, const PrincipalIndexFunction& principal_n);

    std::size_t wavelength_count() const { return frames_.size(); }

    /// Transmission at every wavelength for ξ (out_plus) and −ξ (out_minus). `continues_row`: the previous
    /// call with this scratch was for a neighbouring ξ, whose roots can start the iterations.
    void spectral_pair(const Eigen::Vector2d& xi, KernelScratch& scratch, bool continues_row, double* out_plus,
                       double* out_minus) const;

    /// Monochromatic light: transmission for each ξ of `xis` (at most kMonochromaticBatch) and its −ξ.
    void monochromatic_pairs(const std::vector<Eigen::Vector2d>& xis, KernelScratch& scratch, double* out_plus,
                             double* out_minus) const;

    /// The reference path alone, at wavelength index `w`: the transmission for (ξ, −ξ).
    std::array<double, 2> reference_pair(std::size_t w, const Eigen::Vector2d& xi) const;

private:
    double analyzed_intensity(const SlabTransfer& transfer, const TangentialWavevector& direction, double k0_thickness) const;
    /// With an accessory plate: the field leaves the slab as a_s·ŝ + a_p·ρ̂, crosses the plate (lab Jones
    /// matrix of wavelength `w`), then the analyzer.
    double analyzed_intensity_with_plate(const SlabTransfer& transfer, const TangentialWavevector& direction,
                                         double k0_thickness, std::size_t w) const;

    const ConoscopeSettings& settings_;
    PolarizerPair polars_;
    std::vector<BinormalFrame> frames_;
    std::vector<double> k0_thickness_;
    SampleCrystal spectral_samples_;                     // one sample per wavelength
    std::optional<SampleCrystal> monochromatic_samples_;  // the single wavelength, kMonochromaticBatch times
    std::vector<Eigen::Matrix2cd> plate_jones_lab_;       // per wavelength; empty without a plate
};

}  // namespace petroscope::detail
