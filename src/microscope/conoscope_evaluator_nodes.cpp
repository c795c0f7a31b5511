// The conoscope evaluator's white light from spectral nodes (spectral_nodes.hpp).
#include "conoscope_evaluator.hpp"

#include <algorithm>
#include <cmath>

namespace petroscope::detail {
namespace {

// The modes are singular where the wave normal meets a binormal. |N̂ × b| must exceed this many times the
// largest distance of N̂ × b over the nodes from its value at a middle node. The singularity then lies about
// that many half-intervals off the real σ axis, outside the Bernstein ellipse of parameter ρ ≈ 2·2 = 4, in
// which the degree-7 interpolant converges like ρ⁻⁷ (Trefethen, Approximation Theory and Approximation
// Practice, 2013, Theorem 8.2); no feature narrower than the node spacing can then hide from the tail
// estimate below, which decides.
constexpr double kSmoothness = 2.0;
// The product of two amplitudes each within kFieldTolerance (NodeColour) is within about twice that.
constexpr double kProductTolerance = 2.0 * kFieldTolerance;
// An optically active crystal's p = b₀b₁ ≥ 0 enters through Ω = √((δ/2)² + p) ≥ √p: an error e in p moves Ω by
// at most e/(2√p), and by at most √e whatever p. The tolerance on p keeps Ω within kPhaseTolerance_rad.
double coupling_product_tolerance(const NodeValues& product) {
    const double smallest = *std::min_element(product.begin(), product.end());
    return std::max(kPhaseTolerance_rad * kPhaseTolerance_rad, 2.0 * kPhaseTolerance_rad * std::sqrt(std::max(smallest, 0.0)));
}

// This side's ρ̂ and ŝ = ẑ × ρ̂ in the lab (conoscope_kernel.hpp: side 1 has ρ̂ times `reversal`).
struct SideFrame {
    double rho_x, rho_y, s_x, s_y;
};
SideFrame side_frame(const KernelScratch& scratch, int side) {
    const double sign = side == 0 ? 1.0 : scratch.reversal[0];
    const double rho_x = sign * scratch.rho_x[0], rho_y = sign * scratch.rho_y[0];
    return {rho_x, rho_y, -rho_y, rho_x};
}

// One side's node quantities as the kernel left them (KernelOutput::fields): the mode fields and δ, and with optical
// activity (`active`) the coupled fields and b₀b₁.
void copy_side_nodes(const KernelScratch& scratch, int side, bool active, std::array<NodeValues, 4>& fields, NodeValues& phase,
                     std::array<NodeValues, 4>& coupled, NodeValues& product) {
    for (std::size_t j = 0; j < kSpectralNodes; ++j) {
        for (std::size_t c = 0; c < 4; ++c) fields[c][j] = scratch.mode_field[side][c][j];
        phase[j] = scratch.phase_difference[side][j];
        if (!active) continue;
        for (std::size_t c = 0; c < 4; ++c) coupled[c][j] = scratch.coupled_field[side][c][j];
        product[j] = scratch.coupling_product[side][j];
    }
}

// One component of an active crystal's node fields, w_s·(s part) + w_p·(p part): F₀, F₁, G₀, G₁
// (spectral_nodes.hpp, ActiveNodeFields) from mode_field (s fast, s slow, p fast, p slow) and coupled_field.
std::array<NodeValues, 4> projected_active_fields(const std::array<NodeValues, 4>& fields, const std::array<NodeValues, 4>& coupled, double w_s,
                                           double w_p) {
    std::array<NodeValues, 4> component{};
    for (std::size_t j = 0; j < kSpectralNodes; ++j) {
        component[0][j] = w_s * fields[0][j] + w_p * fields[2][j];
        component[1][j] = w_s * fields[1][j] + w_p * fields[3][j];
        component[2][j] = w_s * coupled[0][j] + w_p * coupled[2][j];
        component[3][j] = w_s * coupled[1][j] + w_p * coupled[3][j];
    }
    return component;
}

}  // namespace

bool ConoscopeEvaluator::smooth_over_spectrum(const KernelScratch& scratch) const {
    // A uniaxial crystal's two binormals are the optic axis (b₂ = ±b₁).
    const int binormals = node_samples_->uniaxial ? 1 : 2;
    constexpr std::size_t middle = kSpectralNodes / 2;
    for (int side = 0; side < 2; ++side) {
        const double direction = side == 0 ? 1.0 : -1.0;
        const double xi_x = direction * scratch.xi_x[0], xi_y = direction * scratch.xi_y[0];
        const double* q = scratch.q[side][0].data();  // N = (ξ, q) of the fast sheet: near a binormal both sheets agree
        for (int binormal = 0; binormal < binormals; ++binormal) {
            const auto& axis = binormal == 0 ? node_samples_->binormal_1 : node_samples_->binormal_2;
            const double *b_x = axis[0].data(), *b_y = axis[1].data(), *b_z = axis[2].data();
            // c = N̂ × b at each node.
            std::array<double, kSpectralNodes> c_x{}, c_y{}, c_z{};
            double closest_squared = 1.0;
#pragma omp simd reduction(min : closest_squared)
            for (std::size_t j = 0; j < kSpectralNodes; ++j) {
                const double inverse_length = 1.0 / std::sqrt(xi_x * xi_x + xi_y * xi_y + q[j] * q[j]);
                c_x[j] = (xi_y * b_z[j] - q[j] * b_y[j]) * inverse_length;
                c_y[j] = (q[j] * b_x[j] - xi_x * b_z[j]) * inverse_length;
                c_z[j] = (xi_x * b_y[j] - xi_y * b_x[j]) * inverse_length;
                closest_squared = std::min(closest_squared, c_x[j] * c_x[j] + c_y[j] * c_y[j] + c_z[j] * c_z[j]);
            }
            double motion_squared = 0.0;
#pragma omp simd reduction(max : motion_squared)
            for (std::size_t j = 0; j < kSpectralNodes; ++j) {
                const double d_x = c_x[j] - c_x[middle], d_y = c_y[j] - c_y[middle], d_z = c_z[j] - c_z[middle];
                motion_squared = std::max(motion_squared, d_x * d_x + d_y * d_y + d_z * d_z);
            }
            if (!(closest_squared > kSmoothness * kSmoothness * motion_squared)) return false;
        }
    }
    return true;
}

bool ConoscopeEvaluator::interpolated_pair(const KernelScratch& scratch, double* out_plus, double* out_minus, PairColour* colour) const {
    std::array<std::array<NodeValues, 4>, 2> side_fields, side_coupled;
    std::array<NodeValues, 2> side_phase, side_product;
    const bool active = !gyration_lab_.empty();
    for (int side = 0; side < 2; ++side) {
        copy_side_nodes(scratch, side, active, side_fields[side], side_phase[side], side_coupled[side], side_product[side]);
        if (!(nodes_->tail(side_phase[side]) <= kPhaseTolerance_rad)) return false;
    }
    // The interpolated spectrum, and the colour of an inactive crystal without a plate (quadratic forms in the fields),
    // need the fields themselves smooth; the other colours from the nodes check the terms they interpolate.
    const auto fields_smooth = [&] {
        for (int side = 0; side < 2; ++side) {
            for (const NodeValues& field : side_fields[side]) {
                if (!(nodes_->tail(field) <= kFieldTolerance)) return false;
            }
            if (!active) continue;
            for (const NodeValues& field : side_coupled[side]) {
                if (!(nodes_->tail(field) <= kFieldTolerance)) return false;
            }
            if (!(nodes_->tail(side_product[side]) <= coupling_product_tolerance(side_product[side]))) return false;
        }
        return true;
    };
    if (active) {
        std::array<ActiveNodeFields, 2> side_active;
        for (int side = 0; side < 2; ++side) side_active[side] = active_node_fields(scratch, side, side_fields[side], side_coupled[side], side_product[side]);
        if (colour != nullptr && active_colour_from_nodes(side_active, side_phase, *colour)) return true;
        if (!fields_smooth()) return false;
        for (int side = 0; side < 2; ++side) active_interpolated_side(side_active[side], side_phase[side], side == 0 ? out_plus : out_minus);
        return true;
    }
    if (colour != nullptr && plate_frame_ && colour_from_nodes(scratch, side_fields, side_phase, *colour)) return true;
    if (!fields_smooth()) return false;
    if (colour != nullptr && !plate_frame_ && colour_from_nodes(scratch, side_fields, side_phase, *colour)) return true;
    for (int side = 0; side < 2; ++side) {
        const std::array<NodeValues, 4>& fields = side_fields[side];
        double* out = side == 0 ? out_plus : out_minus;
        if (plate_jones_lab_.empty()) {
            int pairs = 1;
            const std::array<NodeValues, 4> amplitudes = analyzed_node_amplitudes(scratch, side, fields, pairs);
            interpolated_transmission(*nodes_, amplitudes, pairs, side_phase[side], out);
            continue;
        }
        const std::array<NodeValues, 4> lab_fields = lab_node_fields(scratch, side, fields);
        PlateAnalyzers analyzers{polars_.analyzer_in ? 1 : 2, {}};
        for (std::size_t k = 0; k < 2; ++k) {
            for (std::size_t c = 0; c < 4; ++c) analyzers.lab[k][c] = spectral_samples_.plate_analyzer[k][c].data();
        }
        interpolated_transmission(*nodes_, lab_fields, side_phase[side], analyzers, out);
    }
    return true;
}

std::optional<RotationNodeTerms> ConoscopeEvaluator::node_rotation_terms(const KernelScratch& scratch) const {
    std::array<NodeValues, 4> fields, coupled;
    NodeValues phase, product;
    const bool active = !gyration_lab_.empty();
    copy_side_nodes(scratch, 0, active, fields, phase, coupled, product);
    if (active) return active_node_terms(active_node_fields(scratch, 0, fields, coupled, product), phase);
    // |c₀e^{iφ₀} + c₁e^{iφ₁}|² = c₀² + c₁² + 2c₀c₁·cos δ for each analyzed pair (interference.hpp, pair_terms).
    int pairs = 1;
    const std::array<NodeValues, 4> amplitudes = analyzed_node_amplitudes(scratch, 0, fields, pairs);
    RotationNodeTerms terms;
    terms.angle = phase;
    for (std::size_t j = 0; j < kSpectralNodes; ++j) {
        for (std::size_t k = 0; k < 4; k += 2) {
            terms.smooth[j] += amplitudes[k][j] * amplitudes[k][j] + amplitudes[k + 1][j] * amplitudes[k + 1][j];
            terms.cosine[j] += 2.0 * amplitudes[k][j] * amplitudes[k + 1][j];
        }
    }
    return terms;
}

std::array<NodeValues, 4> ConoscopeEvaluator::lab_node_fields(const KernelScratch& scratch, int side, const std::array<NodeValues, 4>& fields) const {
    // E = s ŝ + p ρ̂, where the plate's analyzers are.
    const SideFrame frame = side_frame(scratch, side);
    std::array<NodeValues, 4> lab_fields{};
    for (std::size_t mode = 0; mode < 2; ++mode) {
        for (std::size_t j = 0; j < kSpectralNodes; ++j) {
            lab_fields[mode][j] = fields[mode][j] * frame.s_x + fields[2 + mode][j] * frame.rho_x;
            lab_fields[2 + mode][j] = fields[mode][j] * frame.s_y + fields[2 + mode][j] * frame.rho_y;
        }
    }
    return lab_fields;
}

std::array<NodeValues, 4> ConoscopeEvaluator::analyzed_node_amplitudes(const KernelScratch& scratch, int side, const std::array<NodeValues, 4>& fields,
                                                                       int& pairs) const {
    if (!polars_.analyzer_in) {
        pairs = 2;
        return fields;
    }
    // The amplitude of each mode behind the analyzer: a·(s ŝ + p ρ̂).
    const SideFrame frame = side_frame(scratch, side);
    const double a_s = polars_.analyzer.x() * frame.s_x + polars_.analyzer.y() * frame.s_y;
    const double a_p = polars_.analyzer.x() * frame.rho_x + polars_.analyzer.y() * frame.rho_y;
    std::array<NodeValues, 4> amplitudes{};
    for (std::size_t j = 0; j < kSpectralNodes; ++j) {
        amplitudes[0][j] = a_s * fields[0][j] + a_p * fields[2][j];
        amplitudes[1][j] = a_s * fields[1][j] + a_p * fields[3][j];
    }
    pairs = 1;
    return amplitudes;
}

bool ConoscopeEvaluator::colour_from_nodes(const KernelScratch& scratch, const std::array<std::array<NodeValues, 4>, 2>& side_fields,
                                           const std::array<NodeValues, 2>& side_phase, PairColour& colour) const {
    if (!node_colour_) return false;
    for (int side = 0; side < 2; ++side) {
        std::optional<Eigen::Vector3d> xyz;
        if (plate_frame_) {
            PlateNodeTerms terms;
            plate_terms(*plate_frame_, lab_node_fields(scratch, side, side_fields[side]), side_phase[side], terms);
            xyz = node_colour_->plate_xyz(*nodes_, terms);
        } else {
            int pairs = 1;
            const std::array<NodeValues, 4> amplitudes = analyzed_node_amplitudes(scratch, side, side_fields[side], pairs);
            xyz = node_colour_->xyz(*nodes_, amplitudes, pairs, side_phase[side], kProductTolerance);
        }
        if (!xyz) return false;
        colour.xyz[static_cast<std::size_t>(side)] = *xyz;
    }
    colour.written = true;
    return true;
}

bool ConoscopeEvaluator::active_colour_from_nodes(const std::array<ActiveNodeFields, 2>& side_active, const std::array<NodeValues, 2>& side_phase,
                                                  PairColour& colour) const {
    if (!node_colour_) return false;
    for (std::size_t side = 0; side < 2; ++side) {
        std::optional<Eigen::Vector3d> xyz;
        if (plate_frame_) {
            PlateNodeTerms terms;
            if (active_plate_terms(*plate_frame_, side_active[side], side_phase[side], terms)) xyz = node_colour_->plate_xyz(*nodes_, terms);
        } else {
            xyz = node_colour_->active_xyz(*nodes_, side_active[side], side_phase[side]);
        }
        if (!xyz) return false;
        colour.xyz[side] = *xyz;
    }
    colour.written = true;
    return true;
}

ActiveNodeFields ConoscopeEvaluator::active_node_fields(const KernelScratch& scratch, int side, const std::array<NodeValues, 4>& fields,
                                                        const std::array<NodeValues, 4>& coupled, const NodeValues& product) const {
    const auto [rho_x, rho_y, s_x, s_y] = side_frame(scratch, side);
    ActiveNodeFields active;
    active.coupling_product = product;
    if (!plate_jones_lab_.empty()) {
        active.components = 2;
        active.component = {projected_active_fields(fields, coupled, s_x, rho_x), projected_active_fields(fields, coupled, s_y, rho_y)};
    } else if (polars_.analyzer_in) {
        active.component[0] = projected_active_fields(fields, coupled, polars_.analyzer.x() * s_x + polars_.analyzer.y() * s_y,
                                                      polars_.analyzer.x() * rho_x + polars_.analyzer.y() * rho_y);
    } else {
        active.components = 2;
        active.component = {projected_active_fields(fields, coupled, 1.0, 0.0), projected_active_fields(fields, coupled, 0.0, 1.0)};
    }
    return active;
}

void ConoscopeEvaluator::active_interpolated_side(const ActiveNodeFields& active, const NodeValues& phase, double* out) const {
    if (plate_jones_lab_.empty()) {
        interpolated_active_transmission(*nodes_, active, phase, nullptr, out);
        return;
    }
    PlateAnalyzers analyzers{polars_.analyzer_in ? 1 : 2, {}};
    for (std::size_t k = 0; k < 2; ++k) {
        for (std::size_t c = 0; c < 4; ++c) analyzers.lab[k][c] = spectral_samples_.plate_analyzer[k][c].data();
    }
    interpolated_active_transmission(*nodes_, active, phase, &analyzers, out);
}

}  // namespace petroscope::detail
