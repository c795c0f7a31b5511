#pragma once
// The conoscope's inner loop: one pair of opposite directions (ξ, −ξ) at every wavelength, written as
// straight-line loops over wavelength arrays so that the compiler vectorises them. Samples whose Newton
// iterations do not converge, or that sit exactly on a binormal, are flagged and recomputed by the
// reference path (optics/slab.hpp), which the tests compare this kernel against.
#include "petroscope/optics/indicatrix.hpp"

#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <vector>

namespace petroscope::detail {

/// Arrays are padded to a multiple of this many samples (repeating the last wavelength) so that every
/// sample goes through the vector loop; 8 doubles fill an AVX-512 register.
constexpr std::size_t kLanes = 8;

/// Per-wavelength crystal and stack constants, one array element per wavelength (plus padding).
struct SpectralCrystal {
    explicit SpectralCrystal(const std::vector<BinormalFrame>& frames, const std::vector<double>& surround_n,
                             const std::vector<double>& k0_thickness);

    std::size_t size() const { return count; }                 // wavelengths
    std::size_t padded_size() const { return half_sum.size(); }  // array length
    std::size_t count = 0;
    bool uniaxial = false;
    double uniaxial_orientation = 1.0;  // b₁·b₂ = ±1 for a uniaxial crystal
    std::vector<double> half_sum, half_difference, inverse_n_beta2;  // (a + c)/2, (a − c)/2, b
    std::array<std::vector<double>, 3> binormal_1, binormal_2;
    std::array<std::vector<double>, 6> impermeability;  // η_xx, η_yy, η_zz, η_xy, η_xz, η_yz
    std::vector<double> surround_n, k0_thickness;
};

/// The polarizer and analyzer.
struct PolarizerPair {
    Eigen::Vector2d polarizer;
    Eigen::Vector2d analyzer;
    bool analyzer_in = true;
};

/// Scratch arrays reused across pixels (one per thread).
struct KernelScratch {
    void resize(std::size_t padded_wavelengths);
    // [side][sheet]: q and the tangential field ψ₁…ψ₄ of each forward mode.
    std::array<std::array<std::vector<double>, 2>, 2> q;
    std::array<std::array<std::array<std::vector<double>, 4>, 2>, 2> psi;
    // Flags are 8-byte integers: a narrower type would make the vectoriser process 64 samples at a time.
    std::array<std::array<std::vector<std::int64_t>, 2>, 2> sheet_failed;  // [side][sheet]
    std::array<std::vector<double>, 2> transmission;                        // [side], padded
    std::vector<std::int64_t> failed;  // per wavelength: recompute this sample with the reference path
};

/// Transmission at every wavelength for ξ (into out_plus) and −ξ (into out_minus). Returns whether any
/// sample was flagged in scratch.failed for the reference path (the caller recomputes those).
bool transmission_pair_kernel(const SpectralCrystal& crystal, const PolarizerPair& polars,
                                             const Eigen::Vector2d& xi, KernelScratch& scratch, double* out_plus,
                                             double* out_minus);

}  // namespace petroscope::detail
