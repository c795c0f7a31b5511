#include "photo_model.hpp"

#include "petroscope/core/fast_math.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace petroscope::detail {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

Eigen::Vector2d rotated(const Eigen::Vector2d& v, double angle_rad) {
    const double c = std::cos(angle_rad), s = std::sin(angle_rad);
    return {c * v.x() - s * v.y(), s * v.x() + c * v.y()};
}

}  // namespace

SampleLattice sample_lattice(const Eigen::Vector2d& centre, double radius_px, int stride_px, int width_px, int height_px) {
    SampleLattice lattice;
    lattice.stride_px = stride_px;
    // Lattice columns and rows through the centre's pixel, so that the lattice is symmetric about it.
    const int centre_column = static_cast<int>(std::floor(centre.x())), centre_row = static_cast<int>(std::floor(centre.y()));
    const int reach = static_cast<int>(radius_px / stride_px) + 1;
    std::vector<int> index((2 * reach + 1) * (2 * reach + 1), -1);
    const auto slot = [&](int i, int j) { return (j + reach) * (2 * reach + 1) + (i + reach); };
    for (int j = -reach; j <= reach; ++j) {
        for (int i = -reach; i <= reach; ++i) {
            const int column = centre_column + i * stride_px, row = centre_row + j * stride_px;
            if (column < 0 || row < 0 || column >= width_px || row >= height_px) continue;
            const Eigen::Vector2d pixel(column + 0.5, row + 0.5);
            if ((pixel - centre).norm() > radius_px) continue;
            index[slot(i, j)] = static_cast<int>(lattice.pixels.size());
            lattice.pixels.push_back(pixel);
        }
    }
    lattice.neighbours.resize(lattice.pixels.size());
    for (int j = -reach; j <= reach; ++j) {
        for (int i = -reach; i <= reach; ++i) {
            const int k = index[slot(i, j)];
            if (k < 0) continue;
            const auto neighbour = [&](int di, int dj) {
                const int ni = i + di, nj = j + dj;
                return (std::abs(ni) > reach || std::abs(nj) > reach) ? -1 : index[slot(ni, nj)];
            };
            lattice.neighbours[k] = {neighbour(-1, 0), neighbour(1, 0), neighbour(0, -1), neighbour(0, 1)};
        }
    }
    return lattice;
}

namespace {

/// |ξ| at u field radii from the centre, and its derivatives by u and by the distortion.
struct RadialMap {
    double value, d_u, d_distortion;
};

RadialMap radial_map(const ConoscopePhotoModel& model, double distortion, double u) {
    const double na = model.settings.numerical_aperture;  // below 1: the objective or lens is in air
    const double v = u * (1.0 + distortion * u * u), dv_du = 1.0 + 3.0 * distortion * u * u, dv_dk = u * u * u;
    // Past the fold of a barrel distortion the lens shows nothing of the figure: as beyond grazing, dark.
    constexpr double kDark = 1.0;  // |ξ| = 1: grazing in air
    if (dv_du <= 0.0) return {kDark, 0.0, 0.0};
    double value = 0.0, slope = 0.0;  // |ξ| = sin θ_air and d|ξ|/dv
    switch (model.projection) {
    case Projection::sine:  // v ∝ sin θ: |ξ| = NA·v (Abbe's sine condition; Born & Wolf §4.5.1)
        value = na * v;
        slope = na;
        break;
    case Projection::tangent: {  // v ∝ tan θ: |ξ| = sin(atan(v tan θ_NA)) = w/√(1 + w²), w = v tan θ_NA
        const double tan_edge = na / std::sqrt(1.0 - na * na);
        const double w = v * tan_edge, root = std::sqrt(1.0 + w * w);
        value = w / root;
        slope = tan_edge / (root * root * root);
        break;
    }
    case Projection::equidistant: {  // v ∝ θ: |ξ| = sin(v θ_NA), dark beyond θ = 90°
        const double edge = std::asin(na), theta = v * edge;
        if (theta >= 0.5 * std::numbers::pi) return {kDark, 0.0, 0.0};
        value = std::sin(theta);
        slope = std::cos(theta) * edge;
        break;
    }
    }
    return {value, slope * dv_du, slope * dv_dk};
}

/// The pixel's offset from the centre in field radii, in the lab frame: R(−ρ)·(x − cx, cy − y)/r.
Eigen::Vector2d lab_offset(const PhotoParameters& values, const Eigen::Vector2d& pixel) {
    const Eigen::Vector2d offset(pixel.x() - at(values, PhotoParameter::center_x_px), at(values, PhotoParameter::center_y_px) - pixel.y());
    return rotated(offset, -at(values, PhotoParameter::rotation_deg) * kDegree) / at(values, PhotoParameter::field_radius_px);
}

}  // namespace

Eigen::Vector2d pixel_direction(const ConoscopePhotoModel& model, const PhotoParameters& values, const Eigen::Vector2d& pixel) {
    const Eigen::Vector2d v = lab_offset(values, pixel);
    const double u = v.norm();
    const RadialMap map = radial_map(model, at(values, PhotoParameter::distortion), u);
    return u > 0.0 ? Eigen::Vector2d(map.value / u * v) : Eigen::Vector2d::Zero();
}

std::array<Eigen::Vector2d, 5> direction_derivatives(const ConoscopePhotoModel& model, const PhotoParameters& values,
                                                     const Eigen::Vector2d& pixel) {
    const Eigen::Vector2d v = lab_offset(values, pixel);
    const double u = v.norm(), radius = at(values, PhotoParameter::field_radius_px);
    const RadialMap map = radial_map(model, at(values, PhotoParameter::distortion), u);
    // ξ = S(u)/u · v: ∂ξ/∂v = (S/u)·I + (S' − S/u)·v̂v̂ᵀ (at u = 0, S'·I).
    const double ratio = u > 1e-12 ? map.value / u : map.d_u;
    const Eigen::Vector2d unit = u > 1e-12 ? Eigen::Vector2d(v / u) : Eigen::Vector2d::Zero();
    const Eigen::Matrix2d d_xi_d_v = ratio * Eigen::Matrix2d::Identity() + (map.d_u - ratio) * unit * unit.transpose();
    const double angle = -at(values, PhotoParameter::rotation_deg) * kDegree;
    // v = R(−ρ)·(x − cx, cy − y)/r: ∂v/∂cx = −R(−ρ)x̂/r, ∂v/∂cy = R(−ρ)ŷ/r, ∂v/∂r = −v/r, ∂v/∂ρ = (v_y, −v_x) per radian.
    return {d_xi_d_v * (-rotated(Eigen::Vector2d::UnitX(), angle) / radius), d_xi_d_v * (rotated(Eigen::Vector2d::UnitY(), angle) / radius),
            d_xi_d_v * (-v / radius), d_xi_d_v * (kDegree * Eigen::Vector2d(v.y(), -v.x())), map.d_distortion * unit};
}

EnvelopeValue illumination_envelope(const ConoscopePhotoModel& model, const PhotoParameters& values, const Eigen::Vector2d& pixel) {
    if (model.illumination == IlluminationProfile::even) return {};
    const Eigen::Vector2d offset = pixel - Eigen::Vector2d(at(values, PhotoParameter::envelope_center_x_px), at(values, PhotoParameter::envelope_center_y_px));
    const double radius = at(values, PhotoParameter::envelope_radius_px), power = at(values, PhotoParameter::envelope_power);
    // E = exp(−s), s = (r/R)^p = (r²/R²)^(p/2); ∇s = a·(pixel − c) with a = p·(r²)^(p/2 − 1)/R^p, finite at r = 0
    // for p ≥ 2; ∂s/∂c = −∇s, ∂s/∂R = −p·s/R, ∂s/∂p = s·ln(r/R).
    const double r2 = offset.squaredNorm(), s = std::pow(r2 / (radius * radius), 0.5 * power);
    const double value = std::exp(-s);
    const double a = power * std::pow(r2, 0.5 * power - 1.0) / std::pow(radius, power);
    const double log_ratio = s > 0.0 ? 0.5 * std::log(r2 / (radius * radius)) : 0.0;
    EnvelopeValue result;
    result.value = value;
    result.derivatives = {value * a * offset.x(), value * a * offset.y(), value * power * s / radius, -value * s * log_ratio};
    // g = ∇ln E = −a·o (o = pixel − c); ∂a/∂c_x = −a·(p − 2)·o_x/r², ∂a/∂R = −p·a/R, ∂a/∂p = a·(1/p + ln(r/R)).
    result.log_gradient = -a * offset;
    const Eigen::Vector2d radial = r2 > 0.0 ? Eigen::Vector2d(a * (power - 2.0) / r2 * offset) : Eigen::Vector2d::Zero();
    result.log_gradient_derivatives = {radial.x() * offset + a * Eigen::Vector2d::UnitX(), radial.y() * offset + a * Eigen::Vector2d::UnitY(),
                                       power * a / radius * offset, -a * (1.0 / power + log_ratio) * offset};
    return result;
}

void leaked_terms(const AnalyzerTerms& terms, double extinction_ratio, std::vector<InterferenceTerms>& out) {
    out = terms.passed;
    if (terms.blocked.empty()) return;
    for (std::size_t k = 0; k < out.size(); ++k) {
        out[k].mean += extinction_ratio * terms.blocked[k].mean;
        out[k].modulation += extinction_ratio * terms.blocked[k].modulation;
        out[k].sine_modulation += extinction_ratio * terms.blocked[k].sine_modulation;
    }
}

PhotoModelEvaluator::PhotoModelEvaluator(const ConoscopePhotoModel& model, SampleLattice lattice)
    : model_(model), lattice_(std::move(lattice)) {}

void PhotoModelEvaluator::analyzer_terms(const PhotoParameters& values, bool with_blocked, AnalyzerTerms& out, const Eigen::Vector2d& xi_offset,
                                         const std::vector<unsigned char>* as_before) const {
    ConoscopeSettings settings = model_.settings;
    settings.thickness_um = std::max(settings.thickness_um, at(values, PhotoParameter::thickness_um));
    settings.crystal_axes = model_.orientation(at(values, PhotoParameter::tilt_deg), at(values, PhotoParameter::azimuth_deg));
    settings.analyzer_deg += at(values, PhotoParameter::analyzer_offset_deg);
    std::vector<Eigen::Vector2d> xis(sample_count());
    for (std::size_t k = 0; k < xis.size(); ++k) xis[k] = pixel_direction(model_, values, lattice_.pixels[k]) + xi_offset;
    if (as_before != nullptr) out.from_nodes = *as_before;
    ConoscopeTerms(settings, model_.principal_n).evaluate(xis, out.passed, as_before == nullptr ? &out.from_nodes : nullptr, as_before);
    out.blocked.clear();
    if (with_blocked || at(values, PhotoParameter::extinction_ratio) != 0.0) {
        settings.analyzer_deg += 90.0;
        ConoscopeTerms(settings, model_.principal_n).evaluate(xis, out.blocked, nullptr, &out.from_nodes);
    }
    // No light reaches the objective (in air) from beyond grazing, |ξ| ≥ 1: where a projection shows no
    // direction, and where a geometry far from the photo's (a small field, a centre off the image) maps
    // samples. Such a sample is dark but keeps its phase: it is still a neighbour in the stencils of the
    // phase's derivatives over the photo, which would otherwise see the phase step to 0 as it crosses grazing
    // and blur its lit neighbours' fringes away at once. Beyond |ξ| ≥ n of the immersion no wave propagates
    // and the kernel's phase is undefined: 0 there.
    const std::size_t w_count = wavelength_count();
    for (std::size_t k = 0; k < xis.size(); ++k) {
        if (xis[k].norm() < 1.0) continue;
        for (std::vector<InterferenceTerms>* part : {&out.passed, &out.blocked}) {
            if (part->empty()) continue;
            for (std::size_t i = k * w_count; i < (k + 1) * w_count; ++i) {
                const double phase_per_um = (*part)[i].phase_per_um;
                (*part)[i] = InterferenceTerms{};
                (*part)[i].phase_per_um = std::isfinite(phase_per_um) ? phase_per_um : 0.0;
            }
        }
    }
}

void PhotoModelEvaluator::terms(const PhotoParameters& values, std::vector<InterferenceTerms>& out, const Eigen::Vector2d& xi_offset,
                                const std::vector<unsigned char>* as_before) const {
    AnalyzerTerms parts;
    parts.passed.swap(out);  // the caller's buffer, reused (the terms fill tens of megabytes)
    analyzer_terms(values, false, parts, xi_offset, as_before);
    if (parts.blocked.empty()) {
        out.swap(parts.passed);
        return;
    }
    leaked_terms(parts, at(values, PhotoParameter::extinction_ratio), out);
}

std::vector<EnvelopeValue> PhotoModelEvaluator::envelope(const PhotoParameters& values) const {
    std::vector<EnvelopeValue> result(sample_count());
#pragma omp parallel for schedule(static)
    for (int k = 0; k < static_cast<int>(result.size()); ++k) {
        const auto i = static_cast<std::size_t>(k);
        result[i] = illumination_envelope(model_, values, lattice_.pixels[i]);
    }
    return result;
}

void PhotoModelEvaluator::illuminate(const std::vector<EnvelopeValue>& envelope, LinearSamples& samples) const {
    if (model_.illumination == IlluminationProfile::even) return;
    for (std::size_t k = 0; k < samples.rgb.size(); ++k) {
        samples.rgb[k] *= envelope[k].value;
        if (!samples.d_thickness.empty()) samples.d_thickness[k] *= envelope[k].value;
        if (!samples.d_blur2.empty()) samples.d_blur2[k] *= envelope[k].value;
    }
}

std::vector<Eigen::Vector2d> PhotoModelEvaluator::blur_shifts(const std::vector<EnvelopeValue>& envelope, double blur2_px2) const {
    if (model_.illumination == IlluminationProfile::even) return {};
    std::vector<Eigen::Vector2d> shifts(envelope.size());
    for (std::size_t k = 0; k < shifts.size(); ++k) shifts[k] = blur2_px2 * envelope[k].log_gradient;
    return shifts;
}

namespace {

/// Whether a lattice sample has all four neighbours (where the Laplacian and the curvature are taken).
bool interior(const std::array<int, 4>& neighbours) {
    return std::all_of(neighbours.begin(), neighbours.end(), [](int neighbour) { return neighbour >= 0; });
}

/// A lattice sample's central differences (one-sided at the lattice's edge, 0 where it has no neighbour on an
/// axis) and five-point Laplacian, per pixel.
struct Stencil {
    double slope_x, slope_y, laplacian;
};

/// The stencil of a sample with all four neighbours, from its own value and theirs.
inline Stencil interior_stencil(double centre, double left, double right, double up, double down, double stride) {
    const double stride2 = stride * stride;
    return {(right - left) / (2 * stride), (down - up) / (2 * stride), (right - 2.0 * centre + left) / stride2 + (down - 2.0 * centre + up) / stride2};
}

/// Calls visit(w, stencil) for every wavelength w of sample k, with the stencil over the lattice of value(sample, w).
/// An interior sample takes a loop without branches, which the compiler vectorises.
template <typename Value, typename Visit>
void for_each_stencil(const SampleLattice& lattice, std::size_t k, std::size_t w_count, const Value& value, const Visit& visit) {
    const std::array<int, 4>& n = lattice.neighbours[k];
    const double stride = lattice.stride_px;
    if (interior(n)) {
        const std::size_t left = static_cast<std::size_t>(n[0]), right = static_cast<std::size_t>(n[1]);
        const std::size_t up = static_cast<std::size_t>(n[2]), down = static_cast<std::size_t>(n[3]);
#pragma GCC ivdep
        for (std::size_t w = 0; w < w_count; ++w) {
            visit(w, interior_stencil(value(k, w), value(left, w), value(right, w), value(up, w), value(down, w), stride));
        }
        return;
    }
    for (std::size_t w = 0; w < w_count; ++w) {
        const double centre = value(k, w);
        std::array<double, 2> slopes{};
        double laplacian = 0.0;  // used at interior samples only
        for (std::size_t axis = 0; axis < 2; ++axis) {
            const int minus = n[2 * axis], plus = n[2 * axis + 1];
            const double low = minus >= 0 ? value(static_cast<std::size_t>(minus), w) : centre;
            const double high = plus >= 0 ? value(static_cast<std::size_t>(plus), w) : centre;
            const int span = (minus >= 0 ? 1 : 0) + (plus >= 0 ? 1 : 0);
            slopes[axis] = span > 0 ? (high - low) / (span * stride) : 0.0;
            laplacian += (high - 2.0 * centre + low) / (stride * stride);
        }
        visit(w, Stencil{slopes[0], slopes[1], laplacian});
    }
}

/// The gradient (central differences; one-sided at the lattice's edge) and, when asked for, the Laplacian
/// (interior only) over the lattice of field(sample·W + w), per pixel.
template <typename Field>
void lattice_derivatives(const SampleLattice& lattice, std::size_t w_count, const Field& field, std::vector<double>& gradient_x,
                         std::vector<double>& gradient_y, std::vector<double>* laplacian_out) {
    const std::size_t size = lattice.pixels.size() * w_count;  // every entry is written below
    gradient_x.resize(size);
    gradient_y.resize(size);
    if (laplacian_out != nullptr) laplacian_out->resize(size);
    double* laplacian = laplacian_out != nullptr ? laplacian_out->data() : nullptr;
    const int samples = static_cast<int>(lattice.pixels.size());
#pragma omp parallel for schedule(static)
    for (int sample = 0; sample < samples; ++sample) {
        const auto k = static_cast<std::size_t>(sample);
        const bool inside = interior(lattice.neighbours[k]);
        const auto value = [&](std::size_t at, std::size_t w) { return field(at * w_count + w); };
        for_each_stencil(lattice, k, w_count, value, [&](std::size_t w, const Stencil& at) {
            const std::size_t i = k * w_count + w;
            gradient_x[i] = at.slope_x;
            gradient_y[i] = at.slope_y;
            if (laplacian != nullptr) laplacian[i] = inside ? at.laplacian : 0.0;
        });
    }
}

/// out[sample·W + w] = value(sample·W + w) at the lattice's interior samples (all four neighbours present), 0 at its
/// edge (as the Laplacian).
template <typename Value>
void fill_interior(const SampleLattice& lattice, std::size_t w_count, const Value& value, std::vector<double>& out) {
    out.resize(lattice.pixels.size() * w_count);
    const int samples = static_cast<int>(lattice.pixels.size());
#pragma omp parallel for schedule(static)
    for (int sample = 0; sample < samples; ++sample) {
        const auto k = static_cast<std::size_t>(sample);
        const bool inside = interior(lattice.neighbours[k]);
        for (std::size_t i = k * w_count; i < (k + 1) * w_count; ++i) out[i] = inside ? value(i) : 0.0;
    }
}

/// The gradient of |∇Φ|² over the lattice, from the phase's gradient, and the phase's curvature along its
/// gradient ∇Φᵀ·HessΦ·∇Φ = ½∇Φ·∇|∇Φ|².
void curvature_along_gradient(const SampleLattice& lattice, std::size_t w_count, PhaseDerivatives& phase) {
    const auto squared_gradient = [&phase](std::size_t i) {
        return phase.gradient_x[i] * phase.gradient_x[i] + phase.gradient_y[i] * phase.gradient_y[i];
    };
    lattice_derivatives(lattice, w_count, squared_gradient, phase.squared_gradient_x, phase.squared_gradient_y, nullptr);
    const auto curvature = [&phase](std::size_t i) {
        return 0.5 * (phase.gradient_x[i] * phase.squared_gradient_x[i] + phase.gradient_y[i] * phase.squared_gradient_y[i]);
    };
    fill_interior(lattice, w_count, curvature, phase.curvature_along_gradient);
}

}  // namespace

void PhotoModelEvaluator::phase_derivatives(const std::vector<InterferenceTerms>& terms, PhaseDerivatives& out) const {
    lattice_derivatives(lattice_, wavelength_count(), [&terms](std::size_t i) { return terms[i].phase_per_um; }, out.gradient_x,
                        out.gradient_y, &out.laplacian);
    curvature_along_gradient(lattice_, wavelength_count(), out);
}

void PhotoModelEvaluator::blur_response(const LinearSamples& linear, const PhaseDerivatives& phase, double thickness_um, double blur2_px2,
                                        const std::vector<Eigen::Vector2d>& shifts, const std::array<std::vector<double>, 2>& phase_per_xi,
                                        const std::vector<Eigen::Vector2d>& xi_change, PhaseChangeRoom& room,
                                        std::vector<Eigen::Vector3d>& out) const {
    const std::size_t w_count = wavelength_count();
    const int samples = static_cast<int>(sample_count());
    for (std::vector<double>* part : {&room.gradient_x, &room.gradient_y, &room.laplacian, &room.squared_gradient}) part->resize(phase_per_xi[0].size());
    // The phase change δΦ = ∂Φ/∂ξ·δξ: its gradient and Laplacian over the photo (the stencils of phase_derivatives) and
    // the change of |∇Φ|², 2∇Φ·∇δΦ, whose gradient the second pass takes. δΦ is formed where the stencil reads it.
    const auto change = [&](std::size_t sample, std::size_t w) {
        const std::size_t i = sample * w_count + w;
        return phase_per_xi[0][i] * xi_change[sample].x() + phase_per_xi[1][i] * xi_change[sample].y();
    };
#pragma omp parallel for schedule(static)
    for (int sample = 0; sample < samples; ++sample) {
        const auto k = static_cast<std::size_t>(sample);
        const bool inside = interior(lattice_.neighbours[k]);
        for_each_stencil(lattice_, k, w_count, change, [&](std::size_t w, const Stencil& at) {
            const std::size_t i = k * w_count + w;
            room.gradient_x[i] = at.slope_x;
            room.gradient_y[i] = at.slope_y;
            room.laplacian[i] = inside ? at.laplacian : 0.0;
            room.squared_gradient[i] = 2.0 * (phase.gradient_x[i] * at.slope_x + phase.gradient_y[i] * at.slope_y);
        });
    }
    const double d = thickness_um, d2 = thickness_um * thickness_um;
    const Eigen::Matrix<double, Eigen::Dynamic, 3> weights = colour_weights();
    out.resize(sample_count());
    const auto squared_gradient = [&room, w_count](std::size_t sample, std::size_t w) { return room.squared_gradient[sample * w_count + w]; };
#pragma omp parallel
    {
        Eigen::VectorXd responses(static_cast<Eigen::Index>(w_count));  // per wavelength, summed with the colour weights
#pragma omp for schedule(static)
        for (int sample = 0; sample < samples; ++sample) {
            const auto k = static_cast<std::size_t>(sample);
            const bool inside = interior(lattice_.neighbours[k]);
            const Eigen::Vector2d shift = shifts.empty() ? Eigen::Vector2d::Zero() : shifts[k];
            for_each_stencil(lattice_, k, w_count, squared_gradient, [&](std::size_t w, const Stencil& squared) {
                const std::size_t j = k * w_count + w;
                const double dgx = room.gradient_x[j], dgy = room.gradient_y[j];
                // The change of the curvature along the gradient, ½∇δΦ·∇|∇Φ|² + ½∇Φ·∇δ|∇Φ|² (interior only, as the curvature).
                const double curvature_change = inside ? 0.5 * (dgx * phase.squared_gradient_x[j] + dgy * phase.squared_gradient_y[j] +
                                                                 phase.gradient_x[j] * squared.slope_x + phase.gradient_y[j] * squared.slope_y)
                                                       : 0.0;
                // T = mean + fringes(attenuation(∇Φ), phase(∇Φ, ∇²Φ, q)) with q = ∇ΦᵀHessΦ∇Φ: ∂T/∂∇Φ = −σ²d²∇Φ·fringes +
                // d·shift·∂fringes/∂phase, ∂T/∂∇²Φ = ½σ²d·∂fringes/∂phase, ∂T/∂q = −½σ⁴d³·∂fringes/∂phase.
                const double rate_change = 0.5 * blur2_px2 * (room.laplacian[j] - blur2_px2 * d2 * curvature_change);
                responses[static_cast<Eigen::Index>(w)] =
                    -blur2_px2 * d2 * (phase.gradient_x[j] * dgx + phase.gradient_y[j] * dgy) * linear.fringes[j] +
                    d * (rate_change + shift.x() * dgx + shift.y() * dgy) * linear.fringes_per_phase[j];
            });
            out[k] = weights.transpose() * responses;
        }
    }
}

Eigen::Matrix<double, Eigen::Dynamic, 3> PhotoModelEvaluator::colour_weights() const {
    static_assert(sizeof(Eigen::Vector3d) == 3 * sizeof(double));
    return Eigen::Map<const Eigen::Matrix<double, 3, Eigen::Dynamic>>(model_.rgb_per_transmission.front().data(), 3,
                                                                      static_cast<Eigen::Index>(wavelength_count()))
        .transpose();
}

namespace {

/// Per wavelength, what a sample's colour and its derivatives sum (PhotoModelEvaluator::linear): the
/// transmission, its derivatives by thickness, blur² and the two shifts, and the fringes and their derivative
/// by phase (kept for the blur's part of the geometry's derivatives).
enum WavelengthColumn { kTransmission, kByThickness, kByBlur2, kByShiftX, kByShiftY, kFringes, kFringesPerPhase, kWavelengthColumns };
using WavelengthTable = Eigen::Matrix<double, Eigen::Dynamic, kWavelengthColumns>;

/// One sample's table at `thickness_um` and `blur2_px2` with the figure sampled `shift` px from the sample: per
/// wavelength its interference terms and the phase's derivatives over the photo, from entry `first` of each (as
/// many as the table's rows).
/// The loop has no branches or library calls, and its outputs (the table's columns) overlap none of its inputs:
/// the compiler vectorises it. sine_cosine is exact to a few ulp for phases below 2¹⁹π (a slab of 300 mm of
/// rutile in the violet) and loses only the phase's own rounding beyond.
void fill_wavelength_table(const InterferenceTerms* terms, const PhaseDerivatives& phase_derivatives, std::size_t first, double thickness_um,
                           double blur2_px2, const Eigen::Vector2d& shift, WavelengthTable& table) {
    const double d = thickness_um, d2 = thickness_um * thickness_um, shift_x = shift.x(), shift_y = shift.y();
    const double* gradient_x = phase_derivatives.gradient_x.data() + first;
    const double* gradient_y = phase_derivatives.gradient_y.data() + first;
    const double* laplacian = phase_derivatives.laplacian.data() + first;
    const double* curvature = phase_derivatives.curvature_along_gradient.data() + first;
    double* transmission = table.col(kTransmission).data();
    double* by_thickness = table.col(kByThickness).data();
    double* by_blur2 = table.col(kByBlur2).data();
    double* by_shift_x = table.col(kByShiftX).data();
    double* by_shift_y = table.col(kByShiftY).data();
    double* fringes_out = table.col(kFringes).data();
    double* per_phase_out = table.col(kFringesPerPhase).data();
    const auto count = static_cast<std::size_t>(table.rows());
#pragma GCC ivdep
    for (std::size_t w = 0; w < count; ++w) {
        const double gx = gradient_x[w], gy = gradient_y[w];
        const double g2 = gx * gx + gy * gy;
        const double half_laplacian = 0.5 * laplacian[w];
        const double attenuation = exponential(-0.5 * blur2_px2 * d2 * g2);
        // The blur's phase ½σ²∇²φ − ½σ⁴∇φᵀHessφ∇φ with φ = Φ·d (docs/fitting.md): the phase is (Φ + ½σ²∇²Φ + sigma4_rate)·d.
        const double sigma4_rate_per_blur2 = -0.5 * blur2_px2 * d2 * curvature[w], sigma4_rate = blur2_px2 * sigma4_rate_per_blur2;
        const double rate = terms[w].phase_per_um + blur2_px2 * half_laplacian + sigma4_rate + gx * shift_x + gy * shift_y;  // phase / d
        const SineCosine phase = sine_cosine(rate * d);
        // The cosine fringe and, for an optically active crystal, the sine one (InterferenceTerms).
        const double fringe = terms[w].modulation * attenuation, sine_fringe = terms[w].sine_modulation * attenuation;
        const double fringes = fringe * phase.cosine + sine_fringe * phase.sine;
        const double per_phase = -fringe * phase.sine + sine_fringe * phase.cosine;  // ∂(fringes)/∂phase
        const double damping = blur2_px2 * d * g2;                                      // −∂(ln attenuation)/∂d
        transmission[w] = terms[w].mean + fringes;
        by_thickness[w] = per_phase * (rate + 2.0 * sigma4_rate) - fringes * damping;  // sigma4_rate·d goes as d³
        // ∂/∂blur² through the blur's phase and the attenuation (the shifts' own part: the caller's).
        by_blur2[w] = per_phase * (half_laplacian + 2.0 * sigma4_rate_per_blur2) * d - 0.5 * d2 * g2 * fringes;
        by_shift_x[w] = per_phase * d * gx;
        by_shift_y[w] = per_phase * d * gy;
        fringes_out[w] = fringes;
        per_phase_out[w] = per_phase;
    }
}

}  // namespace

void PhotoModelEvaluator::linear(const std::vector<InterferenceTerms>& terms, const PhaseDerivatives& phase_derivatives,
                                 double thickness_um, double blur2_px2, const std::vector<Eigen::Vector2d>& shifts, bool derivatives,
                                 LinearSamples& out) const {
    const std::size_t w_count = wavelength_count();
    const int samples = static_cast<int>(sample_count());
    out.rgb.resize(sample_count());
    const bool keep = derivatives && out.keep_fringe_terms;
    if (derivatives) {
        for (std::vector<Eigen::Vector3d>* d : {&out.d_thickness, &out.d_blur2, &out.d_shift_x, &out.d_shift_y}) d->resize(sample_count());
    }
    if (keep) {
        out.fringes.resize(terms.size());
        out.fringes_per_phase.resize(terms.size());
    }
    // Every sum over the wavelengths below is a product with the colour weights, each of its entries a dot product of
    // two contiguous columns (lazy: too small for a blocked product).
    const Eigen::Matrix<double, Eigen::Dynamic, 3> weights = colour_weights();
#pragma omp parallel
    {
        WavelengthTable table(static_cast<Eigen::Index>(w_count), static_cast<Eigen::Index>(kWavelengthColumns));
#pragma omp for schedule(static)
        for (int k = 0; k < samples; ++k) {
            const auto i = static_cast<std::size_t>(k);
            const std::size_t first = i * w_count;
            const Eigen::Vector2d shift = shifts.empty() ? Eigen::Vector2d::Zero() : shifts[i];
            fill_wavelength_table(terms.data() + first, phase_derivatives, first, thickness_um, blur2_px2, shift, table);
            if (!derivatives) {
                out.rgb[i] = weights.transpose() * table.col(kTransmission);
                continue;
            }
            const Eigen::Matrix<double, 3, 5> sums = weights.transpose().lazyProduct(table.leftCols<5>());
            out.rgb[i] = sums.col(kTransmission);
            out.d_thickness[i] = sums.col(kByThickness);
            out.d_blur2[i] = sums.col(kByBlur2);
            out.d_shift_x[i] = sums.col(kByShiftX);
            out.d_shift_y[i] = sums.col(kByShiftY);
            if (keep) {
                Eigen::Map<Eigen::VectorXd>(out.fringes.data() + first, static_cast<Eigen::Index>(w_count)) = table.col(kFringes);
                Eigen::Map<Eigen::VectorXd>(out.fringes_per_phase.data() + first, static_cast<Eigen::Index>(w_count)) = table.col(kFringesPerPhase);
            }
        }
    }
}

CameraValue camera_value(double linear, double gain, double black, double gamma) {
    constexpr double kFloor = 1e-6;
    const double exposed = std::max(gain * linear, kFloor);
    const double encoded = std::pow(exposed, 1.0 / gamma);
    const double slope = exposed > kFloor ? encoded / (gamma * exposed) : 0.0;  // d encoded / d exposed
    return {black + encoded, slope * gain, slope * linear, -encoded * std::log(exposed) / (gamma * gamma)};
}

Eigen::Matrix3d colour_matrix(const PhotoParameters& values) {
    Eigen::Matrix3d matrix = Eigen::Matrix3d::Identity();
    std::size_t k = static_cast<std::size_t>(PhotoParameter::crosstalk_rg);
    for (int row = 0; row < 3; ++row) {
        for (int column = 0; column < 3; ++column) {
            if (row != column) matrix(row, column) = values[k++];
        }
    }
    return matrix;
}

std::vector<Eigen::Vector3d> camera_values(const std::vector<Eigen::Vector3d>& linear_rgb, const PhotoParameters& values) {
    std::vector<Eigen::Vector3d> result(linear_rgb.size());
    const std::size_t gain = static_cast<std::size_t>(PhotoParameter::gain_r);
    const Eigen::Matrix3d colours = colour_matrix(values);
    for (std::size_t k = 0; k < result.size(); ++k) {
        const Eigen::Vector3d mixed = colours * linear_rgb[k];
        for (int c = 0; c < 3; ++c) {
            result[k][c] = camera_value(mixed[c], values[gain + static_cast<std::size_t>(c)], at(values, PhotoParameter::black_level),
                                        at(values, PhotoParameter::gamma)).value;
        }
    }
    return result;
}

Image gaussian_blur(const Image& image, double sigma_px) {
    if (!(sigma_px > 0.0)) return image;
    const int radius = static_cast<int>(std::ceil(3.0 * sigma_px));
    std::vector<double> kernel(2 * radius + 1);
    double sum = 0.0;
    for (int i = -radius; i <= radius; ++i) sum += kernel[i + radius] = std::exp(-0.5 * i * i / (sigma_px * sigma_px));
    for (double& weight : kernel) weight /= sum;
    Image horizontal(image.width, image.height, image.channels), result(image.width, image.height, image.channels);
    const auto blur_pass = [&](const Image& in, Image& out, int dx, int dy) {
#pragma omp parallel for schedule(static)
        for (int y = 0; y < in.height; ++y) {
            for (int x = 0; x < in.width; ++x) {
                for (int c = 0; c < in.channels; ++c) {
                    double value = 0.0;
                    for (int i = -radius; i <= radius; ++i) {
                        const int sx = std::clamp(x + i * dx, 0, in.width - 1), sy = std::clamp(y + i * dy, 0, in.height - 1);
                        value += kernel[i + radius] * in.at(sx, sy, c);
                    }
                    out.at(x, y, c) = static_cast<float>(value);
                }
            }
        }
    };
    blur_pass(image, horizontal, 1, 0);
    blur_pass(horizontal, result, 0, 1);
    return result;
}

PhotoBounds photo_parameter_bounds(double thickness_min_um, double thickness_max_um, int width_px, int height_px) {
    const double size = std::max(width_px, height_px);
    PhotoBounds b;
    b.lower = {0.5 * thickness_min_um, -size, -size, 0.05 * size, -360.0, -89.0, -720.0, 1e-3, 1e-3, 1e-3, -0.5, 0.5, 0.0,
               -size, -size, 0.05 * size, 2.0, -0.3, -45.0, 0.0, -0.5, -0.5, -0.5, -0.5, -0.5, -0.5};
    b.upper = {2.0 * thickness_max_um, 2.0 * size, 2.0 * size, 5.0 * size, 360.0, 89.0, 720.0, 1e3, 1e3, 1e3, 0.9, 5.0, 2500.0,
               2.0 * size, 2.0 * size, 100.0 * size, 40.0, 0.3, 45.0, 0.2, 0.5, 0.5, 0.5, 0.5, 0.5, 0.5};
    return b;
}

}  // namespace petroscope::detail
