#include "plate_terms.hpp"

#include "petroscope/core/angles.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>

namespace petroscope::detail {
namespace {

// The lab Jones matrix J on the plate's axes (columns of `axes`): (μ₁, μ₂), or none where its off-diagonal exceeds 1e-12
// of its diagonal.
std::optional<Eigen::Vector2cd> plate_eigenvalues(const Eigen::Matrix2cd& jones_lab, const Eigen::Matrix2d& axes) {
    const Eigen::Matrix2cd on_axes = axes.transpose() * jones_lab * axes;
    if (!(std::abs(on_axes(0, 1)) + std::abs(on_axes(1, 0)) <= 1e-12 * (std::abs(on_axes(0, 0)) + std::abs(on_axes(1, 1))))) return std::nullopt;
    return Eigen::Vector2cd(on_axes(0, 0), on_axes(1, 1));
}

}  // namespace

std::optional<PlateFrame> plate_frame(const AccessoryPlate& plate, const std::vector<Eigen::Matrix2cd>& grid_jones_lab, const SpectralNodes& nodes,
                                      const Eigen::Vector2d& analyzer, bool analyzer_in) {
    PlateFrame frame;
    frame.slow = unit_at(plate.slow_deg);
    frame.fast = Eigen::Vector2d(-frame.slow.y(), frame.slow.x());
    Eigen::Matrix2d axes;
    axes << frame.slow, frame.fast;
    const Eigen::Vector2d on_axes = axes.transpose() * analyzer;
    const Eigen::Matrix2d g = analyzer_in ? Eigen::Matrix2d(on_axes * on_axes.transpose()) : Eigen::Matrix2d::Identity();
    frame.cross = std::abs(g(0, 1)) > 1e-15;
    for (std::size_t j = 0; j < kSpectralNodes; ++j) {
        const std::optional<Eigen::Vector2cd> mu = plate_eigenvalues(plate_jones_lab(plate, nodes.wavelengths_nm()[j], false), axes);
        if (!mu) return std::nullopt;
        frame.slow_weight[j] = std::norm((*mu)[0]) * g(0, 0);
        frame.fast_weight[j] = std::norm((*mu)[1]) * g(1, 1);
        frame.cross_weight[j] = 2.0 * std::abs((*mu)[0]) * std::abs((*mu)[1]) * g(0, 1);
    }
    for (const Eigen::Matrix2cd& jones_lab : grid_jones_lab) {
        const std::optional<Eigen::Vector2cd> mu = plate_eigenvalues(jones_lab, axes);
        if (!mu) return std::nullopt;
        frame.phase_rad.push_back(std::arg(std::conj((*mu)[0]) * (*mu)[1]));
    }
    return frame;
}

void plate_terms(const PlateFrame& plate, const std::array<NodeValues, 4>& lab_fields, const NodeValues& phase_difference, PlateNodeTerms& terms) {
    // On the plate's axes the field is ρ̃ = ρ₀e^{iδ} + ρ₁ (slow axis) and π̃ = π₀e^{iδ} + π₁ (fast axis), up to a common
    // phase. EᴴHE = p₁|ρ̃|² + p₂|π̃|² + g·Re(e^{iΓ}·ρ̃*π̃) (PlateFrame's weights p₁, p₂, g) with |ρ̃|² = ρ₀² + ρ₁² + 2ρ₀ρ₁cos δ
    // and Re(e^{iΓ}·ρ̃*π̃) = cos Γ·(ρ₀π₀ + ρ₁π₁ + (ρ₀π₁ + ρ₁π₀)·cos δ) − sin Γ·(ρ₁π₀ − ρ₀π₁)·sin δ.
    terms.active = false;
    terms.cross = plate.cross;
    terms.angle = phase_difference;
    const Eigen::Vector2d &slow = plate.slow, &fast = plate.fast;
#pragma omp simd
    for (std::size_t j = 0; j < kSpectralNodes; ++j) {
        const double rho_0 = slow.x() * lab_fields[0][j] + slow.y() * lab_fields[2][j];
        const double rho_1 = slow.x() * lab_fields[1][j] + slow.y() * lab_fields[3][j];
        const double pi_0 = fast.x() * lab_fields[0][j] + fast.y() * lab_fields[2][j];
        const double pi_1 = fast.x() * lab_fields[1][j] + fast.y() * lab_fields[3][j];
        const double p1 = plate.slow_weight[j], p2 = plate.fast_weight[j], g = plate.cross_weight[j];
        terms.smooth[j] = p1 * (rho_0 * rho_0 + rho_1 * rho_1) + p2 * (pi_0 * pi_0 + pi_1 * pi_1);
        terms.cosine[j] = 2.0 * (p1 * rho_0 * rho_1 + p2 * pi_0 * pi_1);
        terms.sine[j] = 0.0;
        terms.in_phase[j] = g * (rho_0 * pi_0 + rho_1 * pi_1);
        terms.in_phase_cosine[j] = g * (rho_0 * pi_1 + rho_1 * pi_0);
        terms.in_phase_sine[j] = 0.0;
        terms.quadrature[j] = 0.0;
        terms.quadrature_cosine[j] = 0.0;
        terms.quadrature_sine[j] = g * (rho_1 * pi_0 - rho_0 * pi_1);
    }
}

bool active_plate_terms(const PlateFrame& plate, const ActiveNodeFields& fields, const NodeValues& phase_difference, PlateNodeTerms& terms) {
    // With h = δ/2, Ω = √(h² + b₀b₁), cos²Ω = (1 + cos 2Ω)/2, cos Ω·sin Ω/Ω = sin 2Ω/(2Ω) and sin²Ω/Ω² = (1 − cos 2Ω)/(2Ω²),
    // each |R + iI|² is S + X cos 2Ω + Y sin 2Ω (NodeColour::active_xyz), and ρ̃*π̃ = (R_ρR_π + I_ρI_π) + i(R_ρI_π − I_ρR_π) is
    // (T_r + U_r cos 2Ω + V_r sin 2Ω) + i(T_i + U_i cos 2Ω + V_i sin 2Ω), so that g·Re(e^{iΓ}·ρ̃*π̃) gives the cos Γ and
    // sin Γ terms of PlateNodeTerms.
    terms.active = true;
    terms.cross = plate.cross;
    const auto& [x, y] = fields.component;
    const double slow_x = plate.slow.x(), slow_y = plate.slow.y(), fast_x = plate.fast.x(), fast_y = plate.fast.y();
    double least_omega = std::numeric_limits<double>::infinity();
#pragma omp simd reduction(min : least_omega)
    for (std::size_t j = 0; j < kSpectralNodes; ++j) {
        const double h = 0.5 * phase_difference[j];
        const double omega = active_rotation(h, fields.coupling_product[j]);
        least_omega = std::min(least_omega, omega);
        terms.angle[j] = 2.0 * omega;
        // A, B and C on the lab's x and y, then on the plate's axes.
        const ActiveSums on_x = active_sums(x, j), on_y = active_sums(y, j);
        const ActiveSums rho{slow_x * on_x.a + slow_y * on_y.a, slow_x * on_x.b + slow_y * on_y.b, slow_x * on_x.c + slow_y * on_y.c};
        const ActiveSums pi{fast_x * on_x.a + fast_y * on_y.a, fast_x * on_x.b + fast_y * on_y.b, fast_x * on_x.c + fast_y * on_y.c};
        const double inverse_omega = 1.0 / std::max(omega, kLeastRotation_rad), inverse_omega_squared = inverse_omega * inverse_omega;
        const double p1 = plate.slow_weight[j], p2 = plate.fast_weight[j], half_g = 0.5 * plate.cross_weight[j];
        const double d_rho = (rho.b * rho.b + h * h * rho.c * rho.c) * inverse_omega_squared;
        const double d_pi = (pi.b * pi.b + h * h * pi.c * pi.c) * inverse_omega_squared;
        terms.smooth[j] = 0.5 * (p1 * (rho.a * rho.a + d_rho) + p2 * (pi.a * pi.a + d_pi));
        terms.cosine[j] = 0.5 * (p1 * (rho.a * rho.a - d_rho) + p2 * (pi.a * pi.a - d_pi));
        terms.sine[j] = (p1 * rho.a * rho.b + p2 * pi.a * pi.b) * inverse_omega;
        const double e = (rho.b * pi.b + h * h * rho.c * pi.c) * inverse_omega_squared;
        terms.in_phase[j] = half_g * (rho.a * pi.a + e);
        terms.in_phase_cosine[j] = half_g * (rho.a * pi.a - e);
        terms.in_phase_sine[j] = half_g * (rho.a * pi.b + rho.b * pi.a) * inverse_omega;
        terms.quadrature[j] = half_g * h * (rho.b * pi.c - rho.c * pi.b) * inverse_omega_squared;
        terms.quadrature_cosine[j] = -terms.quadrature[j];
        terms.quadrature_sine[j] = half_g * h * (rho.a * pi.c - rho.c * pi.a) * inverse_omega;
    }
    return least_omega > kLeastRotation_rad;
}

}  // namespace petroscope::detail
