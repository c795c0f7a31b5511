#include "conoscope_evaluator.hpp"

#include "interference.hpp"

#include "petroscope/core/error.hpp"

#include "petroscope/core/angles.hpp"
#include "petroscope/core/text.hpp"
#include "petroscope/optics/gyration.hpp"
#include "petroscope/optics/orientation.hpp"

#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>

namespace petroscope::detail {
namespace {

template <typename Wavelengths>
std::vector<BinormalFrame> frames_for(const ConoscopeSettings& settings, const PrincipalIndexFunction& principal_n,
                                      const Wavelengths& wavelengths) {
    const Eigen::Matrix3d axes = rotation_z_deg(settings.stage_deg) * settings.crystal_axes;
    std::vector<BinormalFrame> frames;
    for (const double wavelength_nm : wavelengths) {
        const Indicatrix indicatrix{principal_n(wavelength_nm), axes};
        if (!indicatrix.principal_n.allFinite() || indicatrix.principal_n.minCoeff() < 1.0) {
            std::ostringstream what;
            what << "the crystal's principal indices at " << wavelength_nm << " nm are not finite numbers >= 1";
            throw InputError(what.str());
        }
        frames.emplace_back(indicatrix);
    }
    return frames;
}

// The gyration tensor in the lab frame per wavelength: g_lab = A·g·Aᵀ with A the indicatrix axes turned by the stage.
template <typename Wavelengths>
std::vector<Eigen::Matrix3d> gyration_for(const ConoscopeSettings& settings, const Wavelengths& wavelengths) {
    std::vector<Eigen::Matrix3d> tensors;
    if (!settings.gyration) return tensors;
    const Eigen::Matrix3d axes = rotation_z_deg(settings.stage_deg) * settings.crystal_axes;
    for (const double wavelength_nm : wavelengths) {
        const Eigen::Matrix3d g = settings.gyration(wavelength_nm);
        if (!g.allFinite()) throw InputError("the crystal's gyration tensor is not finite at " + format_number(wavelength_nm) + " nm");
        tensors.push_back(turned_gyration(g, axes));
    }
    return tensors;
}

template <typename Wavelengths>
std::vector<double> k0_thickness_for(const Wavelengths& wavelengths, double thickness_um) {
    std::vector<double> values;
    for (const double wavelength_nm : wavelengths) {
        values.push_back(2.0 * std::numbers::pi * thickness_um * 1e3 / wavelength_nm);
    }
    return values;
}

SampleCrystal samples_of(const std::vector<BinormalFrame>& frames, const std::vector<double>& k0_thickness,
                         double surround_n, std::size_t repeat) {
    std::vector<const BinormalFrame*> pointers;
    std::vector<double> thickness;
    for (std::size_t r = 0; r < repeat; ++r) {
        for (std::size_t w = 0; w < frames.size(); ++w) {
            pointers.push_back(&frames[w]);
            thickness.push_back(k0_thickness[w]);
        }
    }
    return SampleCrystal(pointers, std::vector<double>(pointers.size(), surround_n), thickness);
}

/// The modes of the pair (ξ, −ξ) for every sample of `samples` into `scratch` (resized when needed): the
/// Newton iterations start from the previous point's roots when `continues_row` and the last run allow,
/// and start again cold, still vectorised, when that warm start fails (coarse pixels). Whether any sample
/// was flagged.
bool solve_modes(const SampleCrystal& samples, const PolarizerPair& polars, const Eigen::Vector2d& xi, KernelScratch& scratch,
                 bool continues_row, KernelOutput output) {
    if (scratch.failed.size() != samples.padded_size()) {
        scratch.resize(samples.padded_size());
        scratch.warm_ready = false;
    }
    set_sample_directions(scratch, 0, samples.padded_size(), xi);
    const bool warm = continues_row && scratch.warm_ready;
    const bool any_failed = run_kernel(samples, polars, scratch, warm, output);
    return any_failed && warm ? run_kernel(samples, polars, scratch, false, output) : any_failed;
}

}  // namespace

ConoscopeEvaluator::ConoscopeEvaluator(const ConoscopeSettings& settings, const PrincipalIndexFunction& principal_n,
                                       const std::vector<Eigen::Vector3d>* colour_weights)
    : settings_(settings),
      polars_{unit_at(settings.polarizer_deg), unit_at(settings.analyzer_deg), settings.analyzer_in},
      frames_(frames_for(settings, principal_n, settings.wavelengths_nm)),
      k0_thickness_(k0_thickness_for(settings.wavelengths_nm, settings.thickness_um)),
      k0_per_um_(k0_thickness_for(settings.wavelengths_nm, 1.0)),
      spectral_samples_(samples_of(frames_, k0_thickness_, settings.surround_n, 1)),
      gyration_lab_(gyration_for(settings, settings.wavelengths_nm)) {
    if (frames_.size() == 1) monochromatic_samples_ = samples_of(frames_, k0_thickness_, settings.surround_n, kMonochromaticBatch);
    if (!gyration_lab_.empty()) {
        set_gyration(spectral_samples_, gyration_lab_);
        if (monochromatic_samples_) set_gyration(*monochromatic_samples_, gyration_lab_);  // one wavelength: repeated
    }
    if (settings.plate) {
        for (const double wavelength_nm : settings.wavelengths_nm) plate_jones_lab_.push_back(plate_jones_lab(*settings.plate, wavelength_nm, false));
        set_plate(spectral_samples_, plate_jones_lab_, polars_);
        if (monochromatic_samples_) set_plate(*monochromatic_samples_, plate_jones_lab_, polars_);  // one wavelength: repeated
    }
    if (interpolates_spectrum(settings)) {
        nodes_.emplace(settings.wavelengths_nm);
        const std::vector<BinormalFrame> node_frames = frames_for(settings, principal_n, nodes_->wavelengths_nm());
        node_samples_ = samples_of(node_frames, k0_thickness_for(nodes_->wavelengths_nm(), settings.thickness_um), settings.surround_n, 1);
        if (settings.gyration) set_gyration(*node_samples_, gyration_for(settings, nodes_->wavelengths_nm()));
        if (colour_weights != nullptr && !settings.plate) node_colour_.emplace(*nodes_, *colour_weights);
        if (colour_weights != nullptr && settings.plate) {
            plate_frame_ = plate_frame(*settings.plate, plate_jones_lab_, *nodes_, polars_.analyzer, polars_.analyzer_in);
            if (plate_frame_) node_colour_.emplace(*nodes_, *colour_weights, plate_frame_->phase_rad);
        }
    }
}

void ConoscopeEvaluator::spectral_pair(const Eigen::Vector2d& xi, SpectralScratch& scratch, bool continues_row, double* out_plus,
                                       double* out_minus, PairColour* colour) const {
    // The every-wavelength roots can start the iterations only if they are the previous point's.
    const bool every_wavelength_continues = continues_row && scratch.every_wavelength_current;
    if (colour != nullptr) colour->written = false;
    scratch.nodes_usable = scratch.every_wavelength_current = scratch.interpolated = false;
    if (nodes_) {
        const bool any_failed = solve_modes(*node_samples_, polars_, xi, scratch.nodes, continues_row, KernelOutput::fields);
        scratch.nodes_usable = !any_failed && smooth_over_spectrum(scratch.nodes);
        scratch.interpolated = scratch.nodes_usable && interpolated_pair(scratch.nodes, out_plus, out_minus, colour);
    }
    if (scratch.interpolated) return;
    exact_pair(xi, scratch.every_wavelength, every_wavelength_continues, out_plus, out_minus);
    scratch.every_wavelength_current = true;
}

void ConoscopeEvaluator::spectral_pair_same_modes(const Eigen::Vector2d& xi, SpectralScratch& scratch, double* out_plus, double* out_minus,
                                                  PairColour* colour) const {
    // The modes are those of every evaluator of the set. The fields depend on the polarizer, so whether they
    // can be interpolated is decided here again, as spectral_pair of this evaluator would.
    if (colour != nullptr) colour->written = false;
    if (scratch.nodes_usable) {
        retransmit(*node_samples_, polars_, scratch.nodes, KernelOutput::fields);
        if (interpolated_pair(scratch.nodes, out_plus, out_minus, colour)) return;
    }
    if (scratch.every_wavelength_current) {
        collect_pair(xi, scratch.every_wavelength, retransmit(spectral_samples_, polars_, scratch.every_wavelength), out_plus, out_minus);
        return;
    }
    exact_pair(xi, scratch.every_wavelength, false, out_plus, out_minus);
    scratch.every_wavelength_current = true;
}

void ConoscopeEvaluator::exact_pair(const Eigen::Vector2d& xi, KernelScratch& scratch, bool continues_row, double* out_plus,
                                    double* out_minus) const {
    const bool any_failed = solve_modes(spectral_samples_, polars_, xi, scratch, continues_row, KernelOutput::transmission);
    collect_pair(xi, scratch, any_failed, out_plus, out_minus);
}

void ConoscopeEvaluator::collect_pair(const Eigen::Vector2d& xi, const KernelScratch& scratch, bool any_failed, double* out_plus,
                                      double* out_minus) const {
    for (std::size_t w = 0; w < spectral_samples_.size(); ++w) {
        if (any_failed && scratch.failed[w] != 0) {
            const std::array<double, 2> reference = reference_pair(w, xi);
            out_plus[w] = reference[0];
            out_minus[w] = reference[1];
        } else {
            out_plus[w] = scratch.transmission[0][w];
            out_minus[w] = scratch.transmission[1][w];
        }
    }
}

void ConoscopeEvaluator::spectral_terms(const Eigen::Vector2d& xi, KernelScratch& scratch, bool continues_row,
                                        InterferenceTerms* out) const {
    if (!plate_jones_lab_.empty()) throw InputError("interference terms are defined without an accessory plate only");
    const bool any_failed = solve_modes(spectral_samples_, polars_, xi, scratch, continues_row, KernelOutput::terms);
    for (std::size_t w = 0; w < spectral_samples_.size(); ++w) {
        if (any_failed && scratch.failed[w] != 0) {
            out[w] = reference_terms(w, xi);
        } else {
            const double phase_per_k0 = gyration_lab_.empty() ? scratch.q[0][0][w] - scratch.q[0][1][w] : scratch.phase_difference[0][w];
            out[w] = {scratch.mean[0][w], scratch.modulation[0][w], k0_per_um_[w] * phase_per_k0, scratch.sine_modulation[0][w]};
        }
    }
}

bool ConoscopeEvaluator::node_terms(const Eigen::Vector2d& xi, KernelScratch& scratch, bool continues_row, bool checked,
                                    InterferenceTerms* out) const {
    if (!nodes_ || !plate_jones_lab_.empty()) return false;
    if (solve_modes(*node_samples_, polars_, xi, scratch, continues_row, KernelOutput::fields) || !smooth_over_spectrum(scratch)) return false;
    const std::optional<RotationNodeTerms> terms = node_rotation_terms(scratch);
    if (!terms || (checked && !interpolable(*nodes_, *terms))) return false;
    interpolated_terms(*nodes_, *terms, settings_.thickness_um, out);
    return true;
}

void ConoscopeEvaluator::monochromatic_pairs(const std::vector<Eigen::Vector2d>& xis, KernelScratch& scratch,
                                             double* out_plus, double* out_minus) const {
    if (xis.empty()) return;
    // A shorter batch uses the first samples; the rest of the arrays repeat its last direction.
    const SampleCrystal& samples = *monochromatic_samples_;
    if (scratch.failed.size() != samples.padded_size()) scratch.resize(samples.padded_size());
    for (std::size_t k = 0; k < xis.size(); ++k) set_sample_directions(scratch, k, 1, xis[k]);
    set_sample_directions(scratch, xis.size(), samples.padded_size() - xis.size(), xis.back());
    const bool any_failed = run_kernel(samples, polars_, scratch, false);
    for (std::size_t k = 0; k < xis.size(); ++k) {
        if (any_failed && scratch.failed[k] != 0) {
            const std::array<double, 2> reference = reference_pair(0, xis[k]);
            out_plus[k] = reference[0];
            out_minus[k] = reference[1];
        } else {
            out_plus[k] = scratch.transmission[0][k];
            out_minus[k] = scratch.transmission[1][k];
        }
    }
}

std::optional<std::array<SlabTransfer, 2>> ConoscopeEvaluator::reference_transfers(std::size_t w, const Eigen::Vector2d& xi) const {
    const std::array<TangentialWavevector, 2> directions{TangentialWavevector::from_xi(xi), TangentialWavevector::from_xi(-xi)};
    const Eigen::Vector2d no_guess = Eigen::Vector2d::Constant(std::numeric_limits<double>::quiet_NaN());
    std::array<std::array<SlabMode, 2>, 2> forward;
    for (int side = 0; side < 2; ++side) {
        if (!solve_forward_modes(frames_[w], directions[side].xi, no_guess, forward[side])) return std::nullopt;
    }
    std::array<SlabTransfer, 2> transfers;
    for (int side = 0; side < 2; ++side) {
        SlabModes modes;
        modes.forward = forward[side];
        for (int sheet = 0; sheet < 2; ++sheet) modes.backward[sheet] = time_reversed(forward[1 - side][sheet]);
        transfers[side] = slab_transfer(modes, directions[side], settings_.surround_n, settings_.surround_n);
        if (!gyration_lab_.empty()) transfers[side].gyration_coupling = gyration_coupling(forward[side], directions[side].xi, gyration_lab_[w]);
    }
    return transfers;
}

std::array<double, 2> ConoscopeEvaluator::reference_pair(std::size_t w, const Eigen::Vector2d& xi) const {
    const auto transfers = reference_transfers(w, xi);
    std::array<double, 2> result{0.0, 0.0};
    if (!transfers) return result;
    for (int side = 0; side < 2; ++side) {
        const TangentialWavevector direction = TangentialWavevector::from_xi(side == 0 ? xi : Eigen::Vector2d(-xi));
        result[side] = plate_jones_lab_.empty() && gyration_lab_.empty()
                           ? analyzed_intensity((*transfers)[side], direction, k0_thickness_[w])
                           : analyzed_intensity_complex((*transfers)[side], direction, k0_thickness_[w], w);
    }
    return result;
}

InterferenceTerms ConoscopeEvaluator::reference_terms(std::size_t w, const Eigen::Vector2d& xi) const {
    const auto transfers = reference_transfers(w, xi);
    if (!transfers) return {};
    const SlabTransfer& transfer = (*transfers)[0];
    if (!gyration_lab_.empty()) return reference_active_terms(transfer, TangentialWavevector::from_xi(xi), w);
    int count = 0;
    const std::array<Eigen::Vector2d, 2> pairs = analyzed_amplitude_pairs(transfer, TangentialWavevector::from_xi(xi), count);
    InterferenceTerms terms{0.0, 0.0, k0_per_um_[w] * (transfer.q[0] - transfer.q[1])};
    for (int k = 0; k < count; ++k) {
        const PairTerms pair = pair_terms(pairs[k][0], pairs[k][1]);
        terms.mean += pair.mean;
        terms.modulation += pair.modulation;
    }
    return terms;
}

InterferenceTerms ConoscopeEvaluator::reference_active_terms(const SlabTransfer& transfer, const TangentialWavevector& direction,
                                                             std::size_t w) const {
    const Eigen::Vector2d incident(polars_.polarizer.dot(direction.azimuthal), polars_.polarizer.dot(direction.radial));
    const Eigen::Vector2d t = transfer.entry * incident;
    // The analyzed components' rows U (fast, slow): the analyzer's, or ŝ and ρ̂ without it.
    const Eigen::Vector2d analyzer(polars_.analyzer.dot(direction.azimuthal), polars_.analyzer.dot(direction.radial));
    const std::array<Eigen::Vector2d, 2> rows = polars_.analyzer_in
                                                   ? std::array<Eigen::Vector2d, 2>{(analyzer.transpose() * transfer.exit).transpose(), Eigen::Vector2d::Zero()}
                                                   : std::array<Eigen::Vector2d, 2>{transfer.exit.row(0).transpose(), transfer.exit.row(1).transpose()};
    const Eigen::Vector2d& c = transfer.gyration_coupling;
    const double half_split = 0.5 * (transfer.q[0] - transfer.q[1]);
    const double width = std::sqrt(half_split * half_split + c[0] * c[1]);
    InterferenceTerms terms{0.0, 0.0, k0_per_um_[w] * 2.0 * width, 0.0};
    for (const Eigen::Vector2d& row : rows) {
        const ActiveTerms part = active_terms(row[0], row[1], t[0], t[1], c[0], c[1], half_split, width > 0.0 ? 1.0 / width : 0.0);
        terms.mean += part.mean;
        terms.modulation += part.modulation;
        terms.sine_modulation += part.sine_modulation;
    }
    return terms;
}

std::array<Eigen::Vector2d, 2> ConoscopeEvaluator::analyzed_amplitude_pairs(const SlabTransfer& transfer,
                                                                             const TangentialWavevector& direction, int& count) const {
    // An aplanatic condenser and objective keep the s and p amplitudes of each ray (Born & Wolf §8.8,
    // Richards & Wolf 1959): the polarizer's field P splits as (P·ŝ, P·ρ̂) in the (s, p) basis.
    const Eigen::Vector2d incident(polars_.polarizer.dot(direction.azimuthal), polars_.polarizer.dot(direction.radial));
    // Mode amplitudes are real for a lossless crystal between lossless media below the critical angle, so
    // each output amplitude is Σₘ cₘ·exp(iφₘ) with real cₘ (interference.hpp).
    const Eigen::Vector2d mode_amplitudes = transfer.entry * incident;
    if (polars_.analyzer_in) {
        count = 1;
        const Eigen::Vector2d analyzer(polars_.analyzer.dot(direction.azimuthal), polars_.analyzer.dot(direction.radial));
        return {(analyzer.transpose() * transfer.exit).transpose().cwiseProduct(mode_amplitudes), Eigen::Vector2d::Zero()};
    }
    count = 2;
    return {transfer.exit.row(0).transpose().cwiseProduct(mode_amplitudes), transfer.exit.row(1).transpose().cwiseProduct(mode_amplitudes)};
}

double ConoscopeEvaluator::analyzed_intensity(const SlabTransfer& transfer, const TangentialWavevector& direction,
                                              double k0_thickness) const {
    const double half_phase_sine = std::sin(0.5 * k0_thickness * (transfer.q[0] - transfer.q[1]));
    const double sin2 = half_phase_sine * half_phase_sine;
    int count = 0;
    const std::array<Eigen::Vector2d, 2> pairs = analyzed_amplitude_pairs(transfer, direction, count);
    double intensity = 0.0;
    for (int k = 0; k < count; ++k) intensity += pair_intensity(pairs[k][0], pairs[k][1], sin2);
    return intensity;
}

double ConoscopeEvaluator::analyzed_intensity_complex(const SlabTransfer& transfer, const TangentialWavevector& direction,
                                                      double k0_thickness, std::size_t w) const {
    const Eigen::Vector2d incident(polars_.polarizer.dot(direction.azimuthal), polars_.polarizer.dot(direction.radial));
    const Eigen::Vector2cd modes = slab_propagation(transfer, k0_thickness) * (transfer.entry * incident).cast<std::complex<double>>();
    const Eigen::Vector2cd out_sp = transfer.exit.cast<std::complex<double>>() * modes;
    const Eigen::Vector2cd lab = direction.azimuthal.cast<std::complex<double>>() * out_sp[0] +
                                 direction.radial.cast<std::complex<double>>() * out_sp[1];
    const Eigen::Vector2cd after_plate = plate_jones_lab_.empty() ? lab : Eigen::Vector2cd(plate_jones_lab_[w] * lab);
    if (!polars_.analyzer_in) return after_plate.squaredNorm();
    return std::norm(polars_.analyzer.cast<std::complex<double>>().dot(after_plate));
}

}  // namespace petroscope::detail
