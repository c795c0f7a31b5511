#pragma once
// The conoscope's inner loop: batches of samples, each a pair of opposite directions (ξ, −ξ) at one
// wavelength, written as straight-line loops over sample arrays so that the compiler vectorises them.
// White light: one pixel pair at every wavelength (warm-started from the previous pixel of the row);
// monochromatic light: many pixel pairs at one wavelength. Samples whose Newton iterations do not
// converge, or that lie within 1e-6 rad of a binormal, are flagged and recomputed by the reference path
// (optics/slab.hpp), which the tests compare this kernel against.
#include "petroscope/optics/indicatrix.hpp"

#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <vector>

namespace petroscope::detail {

/// Sample arrays are padded to a multiple of this many samples (repeating the last one) so that every
/// sample goes through the vector loop; 8 doubles fill an AVX-512 register.
constexpr std::size_t kLanes = 8;

std::size_t padded_length(std::size_t samples);

/// Crystal and stack constants per sample: one BinormalFrame per sample (a wavelength each in white
/// light, the same one repeated in monochromatic light).
struct SampleCrystal {
    SampleCrystal(const std::vector<const BinormalFrame*>& frames, const std::vector<double>& surround_n,
                  const std::vector<double>& k0_thickness);

    std::size_t size() const { return count; }
    std::size_t padded_size() const { return half_sum.size(); }
    std::size_t count = 0;
    bool uniaxial = false;
    double uniaxial_orientation = 1.0;  // b₁·b₂ = ±1 for a uniaxial crystal
    std::vector<double> half_sum, half_difference, inverse_n_beta2;  // (a + c)/2, (a − c)/2, b
    std::array<std::vector<double>, 3> binormal_1, binormal_2;
    std::array<std::vector<double>, 6> impermeability;  // η_xx, η_yy, η_zz, η_xy, η_xz, η_yz
    std::vector<double> surround_n, k0_thickness;

    /// An accessory plate after the crystal makes the analyzed intensity |bᵀE| with a complex effective
    /// analyzer b (E the lab field leaving the crystal): b = Jᵀa with the analyzer a, or each row of J
    /// without one (|JE|² = Σ_rows |J_r·E|²), J the plate's Jones matrix at the sample's wavelength.
    /// plate_analyzer[k]: Re b_x, Re b_y, Im b_x, Im b_y; the second only without an analyzer.
    bool with_plate = false;
    std::array<std::array<std::vector<double>, 4>, 2> plate_analyzer;

    /// Optical activity: the gyration tensor g per sample in the lab frame (optics/gyration.hpp), components
    /// g_xx, g_yy, g_zz, g_xy, g_xz, g_yz, which couples the two modes as optics/slab.hpp's gyration_coupling.
    bool gyrotropic = false;
    std::array<std::vector<double>, 6> gyration;
};

/// Makes `crystal` optically active: `gyration` per sample (its size() of them; the padding repeats the last).
void set_gyration(SampleCrystal& crystal, const std::vector<Eigen::Matrix3d>& gyration);

/// The polarizer and analyzer.
struct PolarizerPair {
    Eigen::Vector2d polarizer;
    Eigen::Vector2d analyzer;
    bool analyzer_in = true;
};

/// Puts a plate after `crystal`: `jones` per sample (its size() of them; the padding repeats the last).
void set_plate(SampleCrystal& crystal, const std::vector<Eigen::Matrix2cd>& jones, const PolarizerPair& polars);

/// Per-sample arrays reused across batches (one set per thread). Index [side]: 0 for ξ, 1 for −ξ.
struct KernelScratch {
    void resize(std::size_t padded_samples);

    // Geometry of side 0 per sample; side 1 has −ξ and ρ̂ times `reversal` (−1, or +1 at ξ = 0).
    std::vector<double> xi_x, xi_y, rho_x, rho_y, reversal;
    // [side][sheet]: the Newton start, q, ∂q/∂ξ (for the next pixel's start) and ψ₁…ψ₄ of each mode.
    std::array<std::array<std::vector<double>, 2>, 2> q_start, q, dq_dxi_x, dq_dxi_y;
    std::array<std::array<std::array<std::vector<double>, 4>, 2>, 2> psi;
    std::array<std::array<std::vector<double>, 2>, 2> e_z;  // [side][sheet]: E·ẑ of each mode (ψ has E·ρ̂ and E·ŝ)
    std::array<std::vector<double>, 2> previous_xi_x, previous_xi_y;  // [side], for the warm start
    // Flags are 8-byte integers: a narrower type would make the vectoriser process 64 samples at a time.
    std::array<std::array<std::vector<std::int64_t>, 2>, 2> sheet_failed;
    std::array<std::vector<double>, 2> transmission;
    // KernelOutput::terms: transmission = mean + modulation·cos(k₀d(q_fast − q_slow)) (microscope/interference.hpp);
    // for an optically active crystal + sine_modulation·sin(2k₀Wd), with 2W in phase_difference (interference.hpp,
    // active_terms).
    std::array<std::vector<double>, 2> mean, modulation, sine_modulation;
    // KernelOutput::fields: the field each mode leaves the slab with, before its phase, and the phase
    // difference δ = k₀d(q_fast − q_slow). mode_field[side]: s component of the fast and slow mode, then
    // p component of the fast and slow mode (rows s, p of ŝ, ρ̂; real in a lossless crystal). Unlike ψ
    // these do not depend on the sign chosen for each eigenvector, so they are smooth in wavelength.
    std::array<std::array<std::vector<double>, 4>, 2> mode_field;
    std::array<std::vector<double>, 2> phase_difference;
    // KernelOutput::fields of an optically active crystal, also sign-free and smooth: coupled_field[side] holds
    // b₀·E_fast·t_slow and b₁·E_slow·t_fast (s of both, then p of both), E_m the mode's exit column and t_m its
    // entrance amplitude, and coupling_product[side] = b₀b₁, with bₘ = k₀d·cₘ (the coupling of optics/slab.hpp).
    std::array<std::array<std::vector<double>, 4>, 2> coupled_field;
    std::array<std::vector<double>, 2> coupling_product;
    std::vector<std::int64_t> failed;  // per sample: recompute with the reference path
    bool warm_ready = false;           // the last run's roots can start the next run's iterations
};

/// Sets the geometry of samples first … first + count − 1 to the pair (ξ, −ξ).
void set_sample_directions(KernelScratch& scratch, std::size_t first, std::size_t count, const Eigen::Vector2d& xi);

/// What run_kernel leaves in the scratch.
enum class KernelOutput {
    transmission,  // the transmission
    terms,         // the transmission, scratch.mean and scratch.modulation (no plate), and with optical activity
                   // scratch.sine_modulation and 2W in scratch.phase_difference
    fields,        // scratch.mode_field and scratch.phase_difference, with optical activity also scratch.coupled_field
                   // and scratch.coupling_product; the transmission's slot holds a number that is finite exactly
                   // where all of them are
};

/// Transmission of every sample into scratch.transmission[side] (but see KernelOutput::fields). With `warm` (allowed when
/// scratch.warm_ready), each sample's Newton iterations start from the previous run's roots moved along
/// ∂q/∂ξ: the samples must be the same wavelengths as then, at a nearby ξ. `output` says what else is
/// kept. Returns whether any sample was flagged in scratch.failed.
bool run_kernel(const SampleCrystal& crystal, const PolarizerPair& polars, KernelScratch& scratch, bool warm,
                KernelOutput output = KernelOutput::transmission);

/// The transmission through other polars and another plate from the modes that a run_kernel left in
/// `scratch`, for `crystal` with the same frames and directions (only its plate may differ); flags failures
/// as run_kernel does and leaves the warm start alone. The modes are most of the work: figures that differ
/// only in polars and plate cost little more than one (the live microscope's stage harmonics).
bool retransmit(const SampleCrystal& crystal, const PolarizerPair& polars, KernelScratch& scratch,
                KernelOutput output = KernelOutput::transmission);

}  // namespace petroscope::detail
