#pragma once
// Everything of a conoscopic figure that does not depend on the image point, and the evaluation of pairs
// of opposite directions: the vectorised kernel, with the reference path (optics/slab.hpp) for the
// samples it flags; in white light the modes at a few spectral nodes, interpolated (spectral_nodes.hpp).
#include "conoscope_kernel.hpp"
#include "node_colour.hpp"
#include "plate_terms.hpp"
#include "spectral_nodes.hpp"

#include "petroscope/microscope/conoscope.hpp"
#include "petroscope/optics/slab.hpp"

#include <optional>

namespace petroscope::detail {

/// A thread's arrays for white light.
struct SpectralScratch {
    KernelScratch nodes;                    // the modes at the spectral nodes
    KernelScratch every_wavelength;         // the modes at every wavelength (exact spectrum; points the nodes cannot serve)
    bool nodes_usable = false;              // `nodes` holds this point's modes, smooth enough over the spectrum
    bool every_wavelength_current = false;  // `every_wavelength` holds this point's modes
    bool interpolated = false;              // the last spectral_pair interpolated
};

/// A pair's colour, where an evaluator made with colour weights takes it straight from the spectral nodes.
struct PairColour {
    bool written = false;               // xyz holds the colour of ξ and −ξ; the spectra were not written
    std::array<Eigen::Vector3d, 2> xyz;  // XYZ of ξ and −ξ
};

class ConoscopeEvaluator {
public:
    /// Pixel pairs evaluated together in monochromatic light.
    static constexpr std::size_t kMonochromaticBatch = 256;

    /// `colour_weights` (SpectralIntegrator::weights of the settings' grid): spectral_pair may give colours
    /// instead of spectra (PairColour).
    ConoscopeEvaluator(const ConoscopeSettings& settings, const PrincipalIndexFunction& principal_n,
                       const std::vector<Eigen::Vector3d>* colour_weights = nullptr);

    std::size_t wavelength_count() const { return frames_.size(); }

    /// Transmission at every wavelength for ξ (out_plus) and −ξ (out_minus). `continues_row`: the previous
    /// call with this scratch was for a neighbouring ξ, whose roots can start the iterations. Interpolated
    /// from the spectral nodes unless the settings ask for the exact spectrum or ξ is too near an optic axis
    /// for the interpolated spectrum (then every wavelength is solved). With `colour` and an evaluator made with
    /// colour weights, a point interpolated without a plate gets its colour from the nodes
    /// (NodeColour) and `colour->written` says so.
    void spectral_pair(const Eigen::Vector2d& xi, SpectralScratch& scratch, bool continues_row, double* out_plus,
                       double* out_minus, PairColour* colour = nullptr) const;

    /// After spectral_pair for the same ξ and scratch by an evaluator of the same crystal, stage, thickness and
    /// wavelengths (only polars and plate differ): this evaluator's transmission, from the modes in `scratch`.
    /// It interpolates or solves every wavelength exactly where spectral_pair of this evaluator would.
    void spectral_pair_same_modes(const Eigen::Vector2d& xi, SpectralScratch& scratch, double* out_plus, double* out_minus,
                                  PairColour* colour = nullptr) const;

    /// Monochromatic light: transmission for each ξ of `xis` (at most kMonochromaticBatch) and its −ξ.
    void monochromatic_pairs(const std::vector<Eigen::Vector2d>& xis, KernelScratch& scratch, double* out_plus,
                             double* out_minus) const;

    /// The thickness dependence of ξ at every wavelength (no plate): transmission = mean +
    /// modulation·cos(phase_per_um·d) for a slab d µm thick. `continues_row` as for spectral_pair.
    void spectral_terms(const Eigen::Vector2d& xi, KernelScratch& scratch, bool continues_row, InterferenceTerms* out) const;

    /// spectral_terms from the spectral nodes: the terms formed at the nodes (node_rotation_terms) and interpolated
    /// (interpolated_terms), their phase that of the settings' thickness, at which its interpolation error (1e-3 rad at
    /// most) is judged. False, with nothing written, where the settings do not interpolate the spectrum or have a plate,
    /// the modes at the nodes failed or lie too near a binormal, or (when `checked`) a term is too rough to interpolate
    /// (interpolable). `continues_row` as for spectral_pair, for the nodes in `scratch`.
    bool node_terms(const Eigen::Vector2d& xi, KernelScratch& scratch, bool continues_row, bool checked, InterferenceTerms* out) const;

    /// The reference path alone, at wavelength index `w`: the transmission for (ξ, −ξ).
    std::array<double, 2> reference_pair(std::size_t w, const Eigen::Vector2d& xi) const;

private:
    /// spectral_pair with the modes solved at every wavelength.
    void exact_pair(const Eigen::Vector2d& xi, KernelScratch& scratch, bool continues_row, double* out_plus, double* out_minus) const;
    /// Whether the modes of ξ and −ξ left at the nodes in `scratch` are smooth enough over the spectrum to be
    /// interpolated: each wave normal N̂ stays far from each binormal b compared with how far N̂ × b moves
    /// over the spectrum (that motion puts the nearest singularity of the modes in the complex σ plane).
    bool smooth_over_spectrum(const KernelScratch& scratch) const;
    /// The transmission at every wavelength from the node fields in `scratch` (run with KernelOutput::fields);
    /// false, with nothing written, where the fields or δ cannot be interpolated accurately enough. `colour`: as
    /// for spectral_pair.
    bool interpolated_pair(const KernelScratch& scratch, double* out_plus, double* out_minus, PairColour* colour) const;
    /// The colour of both sides from their node fields and δ (NodeColour, behind a plate its plate_xyz); false where this
    /// evaluator has no colour weights or the product of the amplitudes is too rough to interpolate.
    bool colour_from_nodes(const KernelScratch& scratch, const std::array<std::array<NodeValues, 4>, 2>& side_fields,
                           const std::array<NodeValues, 2>& side_phase, PairColour& colour) const;
    /// ξ's transmission S + X cos θ + Y sin θ at the nodes, from the node fields in `scratch` (run with KernelOutput::fields):
    /// the analyzed pairs' c₀² + c₁² and 2c₀c₁ with θ = δ, or an optically active crystal's active_node_terms; none where
    /// those are (Ω vanishes at a node).
    std::optional<RotationNodeTerms> node_rotation_terms(const KernelScratch& scratch) const;
    /// The node fields of one side in the lab: x of the fast and slow mode, then y of the fast and slow mode.
    std::array<NodeValues, 4> lab_node_fields(const KernelScratch& scratch, int side, const std::array<NodeValues, 4>& fields) const;
    /// The node amplitude pairs behind the analyzer (one pair) or on ŝ and ρ̂ without it (two) of one side without
    /// a plate, as for interpolated_transmission; `pairs` says how many.
    std::array<NodeValues, 4> analyzed_node_amplitudes(const KernelScratch& scratch, int side, const std::array<NodeValues, 4>& fields,
                                                       int& pairs) const;
    /// An optically active crystal's node quantities of one side (ActiveNodeFields): the components behind the
    /// analyzer, on ŝ and ρ̂ without it, or on the lab's x and y before a plate.
    ActiveNodeFields active_node_fields(const KernelScratch& scratch, int side, const std::array<NodeValues, 4>& fields,
                                        const std::array<NodeValues, 4>& coupled, const NodeValues& product) const;
    /// The colour of both sides of an optically active crystal from their node quantities (NodeColour::active_xyz);
    /// false where this evaluator has no colour weights or a term is too rough to interpolate.
    bool active_colour_from_nodes(const std::array<ActiveNodeFields, 2>& side_active, const std::array<NodeValues, 2>& side_phase,
                                  PairColour& colour) const;
    /// interpolated_pair's transmission of one side of an optically active crystal from its node quantities.
    void active_interpolated_side(const ActiveNodeFields& active, const NodeValues& phase, double* out) const;
    /// The kernel's transmission at every wavelength, the reference path's where a sample failed.
    void collect_pair(const Eigen::Vector2d& xi, const KernelScratch& scratch, bool any_failed, double* out_plus, double* out_minus) const;
    /// The slab's transfer for ξ (index 0) and −ξ (1) at wavelength index `w`; none where a sheet has no
    /// propagating mode (no power crosses the slab).
    std::optional<std::array<SlabTransfer, 2>> reference_transfers(std::size_t w, const Eigen::Vector2d& xi) const;
    InterferenceTerms reference_terms(std::size_t w, const Eigen::Vector2d& xi) const;
    /// reference_terms of an optically active crystal (interference.hpp, active_terms).
    InterferenceTerms reference_active_terms(const SlabTransfer& transfer, const TangentialWavevector& direction, std::size_t w) const;
    /// The analyzed field as pairs of real mode amplitudes (c₀, c₁), one pair per analyzed component (one
    /// behind the analyzer, two without it); `count` says how many.
    std::array<Eigen::Vector2d, 2> analyzed_amplitude_pairs(const SlabTransfer& transfer, const TangentialWavevector& direction,
                                                            int& count) const;
    double analyzed_intensity(const SlabTransfer& transfer, const TangentialWavevector& direction, double k0_thickness) const;
    /// With an accessory plate or an optically active crystal: the field leaves the slab as a_s·ŝ + a_p·ρ̂ (complex
    /// mode amplitudes, slab_propagation), crosses the plate if any (lab Jones matrix of wavelength `w`), then the
    /// analyzer.
    double analyzed_intensity_complex(const SlabTransfer& transfer, const TangentialWavevector& direction,
                                      double k0_thickness, std::size_t w) const;

    const ConoscopeSettings& settings_;
    PolarizerPair polars_;
    std::vector<BinormalFrame> frames_;
    std::vector<double> k0_thickness_;
    std::vector<double> k0_per_um_;
    SampleCrystal spectral_samples_;                     // one sample per wavelength
    std::optional<SampleCrystal> monochromatic_samples_;  // the single wavelength, kMonochromaticBatch times
    std::vector<Eigen::Matrix2cd> plate_jones_lab_;       // per wavelength; empty without a plate
    std::vector<Eigen::Matrix3d> gyration_lab_;           // per wavelength; empty for an inactive crystal
    // White light from spectral nodes (none: every wavelength solved).
    std::optional<SpectralNodes> nodes_;
    std::optional<SampleCrystal> node_samples_;
    std::optional<PlateFrame> plate_frame_;  // with colour weights and a plate diagonal on its axes
    std::optional<NodeColour> node_colour_;  // with colour weights, without a plate or with plate_frame_
};

}  // namespace petroscope::detail
