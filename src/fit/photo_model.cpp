#include "photo_model.hpp"

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

Eigen::Vector2d pixel_direction(const PhotoParameters& values, double numerical_aperture, const Eigen::Vector2d& pixel) {
    const Eigen::Vector2d offset(pixel.x() - at(values, PhotoParameter::center_x_px), at(values, PhotoParameter::center_y_px) - pixel.y());
    const double scale = numerical_aperture / at(values, PhotoParameter::field_radius_px);
    return scale * rotated(offset, -at(values, PhotoParameter::rotation_deg) * kDegree);
}

std::array<Eigen::Vector2d, 4> direction_derivatives(const PhotoParameters& values, double numerical_aperture,
                                                     const Eigen::Vector2d& xi) {
    const double scale = numerical_aperture / at(values, PhotoParameter::field_radius_px);
    const double angle = -at(values, PhotoParameter::rotation_deg) * kDegree;
    // ξ = s·R(−ρ)·(x − cx, cy − y): ∂ξ/∂cx = −s·R(−ρ)x̂, ∂ξ/∂cy = s·R(−ρ)ŷ, ∂ξ/∂r = −ξ/r,
    // ∂ξ/∂ρ = (ξ_y, −ξ_x) per radian.
    return {-scale * rotated(Eigen::Vector2d::UnitX(), angle), scale * rotated(Eigen::Vector2d::UnitY(), angle),
            -xi / at(values, PhotoParameter::field_radius_px), kDegree * Eigen::Vector2d(xi.y(), -xi.x())};
}

PhotoModelEvaluator::PhotoModelEvaluator(const ConoscopePhotoModel& model, SampleLattice lattice)
    : model_(model), lattice_(std::move(lattice)) {}

void PhotoModelEvaluator::terms(const PhotoParameters& values, std::vector<InterferenceTerms>& out,
                                const Eigen::Vector2d& xi_offset) const {
    ConoscopeSettings settings = model_.settings;
    settings.crystal_axes = model_.orientation(at(values, PhotoParameter::tilt_deg), at(values, PhotoParameter::azimuth_deg));
    const ConoscopeTerms figure(settings, model_.principal_n);
    std::vector<Eigen::Vector2d> xis(sample_count());
    for (std::size_t k = 0; k < xis.size(); ++k) {
        xis[k] = pixel_direction(values, settings.numerical_aperture, lattice_.pixels[k]) + xi_offset;
    }
    figure.evaluate(xis, out);
    // A geometry far from the photo's (a small field, a centre off the image) maps samples beyond grazing
    // in the immersion, |ξ| ≥ n, where no wave propagates and the kernel's terms are undefined: no light.
    const std::size_t w_count = wavelength_count();
    for (std::size_t k = 0; k < xis.size(); ++k) {
        if (xis[k].norm() >= settings.surround_n) std::fill_n(out.begin() + static_cast<std::ptrdiff_t>(k * w_count), w_count, InterferenceTerms{});
    }
}

void PhotoModelEvaluator::phase_derivatives(const std::vector<InterferenceTerms>& terms, PhaseDerivatives& out) const {
    const std::size_t w_count = wavelength_count();
    out.gradient2.assign(terms.size(), 0.0);
    out.laplacian.assign(terms.size(), 0.0);
    const int samples = static_cast<int>(sample_count());
    const double stride = lattice_.stride_px;
#pragma omp parallel for schedule(static)
    for (int k = 0; k < samples; ++k) {
        const std::array<int, 4>& n = lattice_.neighbours[static_cast<std::size_t>(k)];
        const auto phase = [&](int sample, std::size_t w) { return terms[static_cast<std::size_t>(sample) * w_count + w].phase_per_um; };
        for (std::size_t w = 0; w < w_count; ++w) {
            const double centre = phase(k, w);
            double gradient2 = 0.0, laplacian = 0.0;
            bool interior = true;
            for (int axis = 0; axis < 2; ++axis) {
                const int minus = n[2 * axis], plus = n[2 * axis + 1];
                const double low = minus >= 0 ? phase(minus, w) : centre, high = plus >= 0 ? phase(plus, w) : centre;
                const int span = (minus >= 0 ? 1 : 0) + (plus >= 0 ? 1 : 0);
                const double slope = span > 0 ? (high - low) / (span * stride) : 0.0;
                gradient2 += slope * slope;
                interior = interior && span == 2;
                laplacian += (high - 2.0 * centre + low) / (stride * stride);
            }
            out.gradient2[static_cast<std::size_t>(k) * w_count + w] = gradient2;
            out.laplacian[static_cast<std::size_t>(k) * w_count + w] = interior ? laplacian : 0.0;
        }
    }
}

void PhotoModelEvaluator::linear(const std::vector<InterferenceTerms>& terms, const PhaseDerivatives& phase_derivatives,
                                 double thickness_um, double blur2_px2, bool derivatives, LinearSamples& out) const {
    const std::size_t w_count = wavelength_count();
    const int samples = static_cast<int>(sample_count());
    out.rgb.resize(sample_count());
    if (derivatives) {
        out.d_thickness.resize(sample_count());
        out.d_blur2.resize(sample_count());
    }
    const double d2 = thickness_um * thickness_um;
#pragma omp parallel for schedule(static)
    for (int k = 0; k < samples; ++k) {
        Eigen::Vector3d rgb = Eigen::Vector3d::Zero(), d_thickness = Eigen::Vector3d::Zero(), d_blur2 = Eigen::Vector3d::Zero();
        const std::size_t first = static_cast<std::size_t>(k) * w_count;
        for (std::size_t w = 0; w < w_count; ++w) {
            const InterferenceTerms& t = terms[first + w];
            const double g2 = phase_derivatives.gradient2[first + w];
            const double half_laplacian = 0.5 * phase_derivatives.laplacian[first + w];
            const double attenuation = std::exp(-0.5 * blur2_px2 * d2 * g2);
            const double rate = t.phase_per_um + blur2_px2 * half_laplacian;  // ∂phase/∂d
            const double phase = rate * thickness_um;
            const double cosine = std::cos(phase), sine = std::sin(phase);
            // The cosine fringe and, for an optically active crystal, the sine one (InterferenceTerms).
            const double fringe = t.modulation * attenuation, sine_fringe = t.sine_modulation * attenuation;
            rgb += model_.rgb_per_transmission[w] * (t.mean + fringe * cosine + sine_fringe * sine);
            if (derivatives) {
                const double damping = blur2_px2 * thickness_um * g2;  // −∂(ln attenuation)/∂d
                const double dt = -fringe * (sine * rate + cosine * damping) + sine_fringe * (cosine * rate - sine * damping);
                d_thickness += model_.rgb_per_transmission[w] * dt;
                const double shift = half_laplacian * thickness_um;  // ∂phase/∂blur²
                d_blur2 += model_.rgb_per_transmission[w] * (-fringe * (0.5 * d2 * g2 * cosine + sine * shift) +
                                                             sine_fringe * (cosine * shift - 0.5 * d2 * g2 * sine));
            }
        }
        out.rgb[static_cast<std::size_t>(k)] = rgb;
        if (derivatives) {
            out.d_thickness[static_cast<std::size_t>(k)] = d_thickness;
            out.d_blur2[static_cast<std::size_t>(k)] = d_blur2;
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

std::vector<Eigen::Vector3d> camera_values(const std::vector<Eigen::Vector3d>& linear_rgb, const PhotoParameters& values) {
    std::vector<Eigen::Vector3d> result(linear_rgb.size());
    const std::size_t gain = static_cast<std::size_t>(PhotoParameter::gain_r);
    for (std::size_t k = 0; k < result.size(); ++k) {
        for (int c = 0; c < 3; ++c) {
            result[k][c] = camera_value(linear_rgb[k][c], values[gain + static_cast<std::size_t>(c)], at(values, PhotoParameter::black_level),
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
    b.lower = {0.5 * thickness_min_um, -size, -size, 0.05 * size, -360.0, -89.0, -720.0, 1e-3, 1e-3, 1e-3, -0.5, 0.5, 0.0};
    b.upper = {2.0 * thickness_max_um, 2.0 * size, 2.0 * size, 5.0 * size, 360.0, 89.0, 720.0, 1e3, 1e3, 1e3, 0.9, 5.0, 2500.0};
    return b;
}

}  // namespace petroscope::detail
