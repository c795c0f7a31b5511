#pragma once
// Everything of a conoscopic figure that does not depend on the image point, and the evaluation of one
// pair of opposite directions: the vectorised kernel, with the reference path (optics/slab.hpp) for the
// samples it flags.
#include "conoscope_kernel.hpp"

#include "petroscope/microscope/conoscope.hpp"
#include "petroscope/optics/slab.hpp"

namespace petroscope::detail {

class ConoscopeEvaluator {
public:
    ConoscopeEvaluator(const ConoscopeSettings& settings, const PrincipalIndexFunction& principal_n);

    std::size_t wavelength_count() const { return frames_.size(); }

    /// Transmission at every wavelength for ξ (out_plus) and −ξ (out_minus): the kernel, then the
    /// reference path for flagged samples.
    void transmission_pair(const Eigen::Vector2d& xi, KernelScratch& scratch, double* out_plus, double* out_minus) const;

    /// The reference path alone, at wavelength index `w`: returns the transmission for (ξ, −ξ).
    std::array<double, 2> reference_pair(std::size_t w, const Eigen::Vector2d& xi) const;

private:
    double analyzed_intensity(const SlabTransfer& transfer, const TangentialWavevector& direction, double k0_thickness) const;

    const ConoscopeSettings& settings_;
    PolarizerPair polars_;
    std::vector<BinormalFrame> frames_;
    std::vector<double> k0_thickness_;
    SpectralCrystal crystal_;
};

}  // namespace petroscope::detail
