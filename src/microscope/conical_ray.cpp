#include "petroscope/microscope/conical_ray.hpp"

#include "petroscope/core/angles.hpp"
#include "petroscope/core/error.hpp"
#include "petroscope/optics/interface.hpp"
#include "petroscope/optics/orientation.hpp"
#include "petroscope/optics/polarization.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

namespace petroscope {
namespace {

Eigen::Vector2d uniform_in_disc(std::mt19937_64& rng, double radius) {
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    const double r = radius * std::sqrt(unit(rng)), phi = 2.0 * std::numbers::pi * unit(rng);
    return {r * std::cos(phi), r * std::sin(phi)};
}

struct Landing {
    double x, y, weight;
};

// The radial power density about `centre` (rings of width `bin`), smoothed over 2·half_window + 1 bins.
std::vector<double> radial_density(const std::vector<Landing>& landings, const Eigen::Vector2d& centre, double bin, std::size_t bins,
                                   std::size_t half_window) {
    std::vector<double> power(bins, 0.0);
    for (const Landing& landing : landings) {
        const auto index = static_cast<std::size_t>(std::hypot(landing.x - centre.x(), landing.y - centre.y()) / bin);
        if (index < bins) power[index] += landing.weight;
    }
    std::vector<double> density(bins, 0.0);
    for (std::size_t i = 0; i < bins; ++i) {
        double sum = 0.0, area = 0.0;
        for (std::size_t j = (i >= half_window ? i - half_window : 0); j <= std::min(bins - 1, i + half_window); ++j) {
            const double inner = static_cast<double>(j) * bin;
            sum += power[j];
            area += std::numbers::pi * (2.0 * inner * bin + bin * bin);
        }
        density[i] = sum / area;
    }
    return density;
}

// Index of the extreme value of `values` in [first, last), refined by a parabola; as a position in bins.
double refined_extremum(const std::vector<double>& values, std::size_t first, std::size_t last, bool maximum) {
    std::size_t best = first;
    for (std::size_t i = first; i < last; ++i) {
        if (maximum ? values[i] > values[best] : values[i] < values[best]) best = i;
    }
    if (best == 0 || best + 1 >= values.size()) return static_cast<double>(best);
    const double left = values[best - 1], centre = values[best], right = values[best + 1];
    const double curvature = left - 2.0 * centre + right;
    return static_cast<double>(best) + (curvature != 0.0 ? 0.5 * (left - right) / curvature : 0.0);
}

ConicalRayRings measure_rings(const std::vector<Landing>& landings, double ring_radius) {
    ConicalRayRings rings;
    double total = 0.0;
    for (const Landing& landing : landings) {
        rings.centre_um += landing.weight * Eigen::Vector2d(landing.x, landing.y);
        total += landing.weight;
    }
    if (!(total > 0.0)) return rings;
    rings.centre_um /= total;
    const std::size_t bins = 4000;
    const double bin = 2.0 * ring_radius / static_cast<double>(bins);  // out to 2 R₀
    // Smoothing and the separation of the two bright rings scale with the pattern's own width: the spread
    // s of the landing radii about their (power-weighted) median; the rings lie about s apart.
    std::vector<std::pair<double, double>> radii;  // (radius, weight)
    for (const Landing& landing : landings) radii.emplace_back(std::hypot(landing.x - rings.centre_um.x(), landing.y - rings.centre_um.y()), landing.weight);
    std::sort(radii.begin(), radii.end());
    const auto weighted_quantile = [&](const std::vector<std::pair<double, double>>& sorted, double fraction) {
        double accumulated = 0.0;
        for (const auto& [value, weight] : sorted) {
            accumulated += weight;
            if (accumulated >= fraction * total) return value;
        }
        return sorted.back().first;
    };
    const double median = weighted_quantile(radii, 0.5);
    std::vector<std::pair<double, double>> deviations;
    for (const auto& [radius, weight] : radii) deviations.emplace_back(std::abs(radius - median), weight);
    std::sort(deviations.begin(), deviations.end());
    const double spread = weighted_quantile(deviations, 0.5);
    const std::size_t half_window = std::max<std::size_t>(1, static_cast<std::size_t>(0.25 * spread / bin));
    const std::size_t separation = std::max<std::size_t>(2, static_cast<std::size_t>(spread / bin));
    const std::vector<double> density = radial_density(landings, rings.centre_um, bin, bins, half_window);
    // The bright rings: the highest maximum, and the highest one at least `separation` from it; the dark
    // ring: the minimum between them.
    const std::size_t first = static_cast<std::size_t>(std::max_element(density.begin(), density.end()) - density.begin());
    std::size_t second = bins;
    for (std::size_t i = 1; i + 1 < bins; ++i) {
        const std::size_t distance = i > first ? i - first : first - i;
        if (distance < separation || density[i] < density[i - 1] || density[i] < density[i + 1]) continue;
        if (second == bins || density[i] > density[second]) second = i;
    }
    if (second == bins) return rings;
    const std::size_t inner = std::min(first, second), outer = std::max(first, second);
    rings.inner_bright_um = (refined_extremum(density, inner, inner + 1, true) + 0.5) * bin;
    rings.outer_bright_um = (refined_extremum(density, outer, outer + 1, true) + 0.5) * bin;
    rings.dark_um = (refined_extremum(density, inner, outer + 1, false) + 0.5) * bin;
    return rings;
}

// The incident state, given by a Stokes vector in the lab frame (x, y), in the ray's own (s, p) basis of
// docs/interface.md: ŝ = ẑ × k̂ normalised (ŷ at normal incidence), p̂ = ŝ × k̂. C_sp = T·C_xy·T† with
// T's rows the transverse parts of ŝ and p̂.
CoherencyMatrix ray_coherency(const Eigen::Vector4d& lab_stokes, const Eigen::Vector3d& k_hat) {
    Eigen::Vector3d s_hat = Eigen::Vector3d::UnitZ().cross(k_hat);
    s_hat = s_hat.norm() > 1e-15 ? Eigen::Vector3d(s_hat.normalized()) : Eigen::Vector3d::UnitY();
    const Eigen::Vector3d p_hat = s_hat.cross(k_hat);
    Eigen::Matrix2cd transform;
    transform << s_hat.x(), s_hat.y(), p_hat.x(), p_hat.y();
    // In the lab's (x, y) basis the Stokes convention of optics/polarization.hpp reads with (x, y) for (s, p).
    const CoherencyMatrix lab = coherency_from_stokes(lab_stokes);
    return transform * lab * transform.adjoint();
}

void validate(const ConicalRaySettings& s) {
    Eigen::Vector3d n = s.principal_n;
    std::sort(n.data(), n.data() + 3);
    if (!n.allFinite() || !(n[0] >= 1.0) || !(n[0] < n[1] && n[1] < n[2])) {
        throw InputError("conical refraction needs a biaxial crystal (three different principal indices)");
    }
    const auto positive = [](double value, const char* what) {
        if (!(value > 0.0) || !std::isfinite(value)) throw InputError(std::string(what) + " must be a positive length");
    };
    positive(s.slab_um, "the slab thickness");
    positive(s.screen_distance_um, "the screen distance");
    if (s.source == ConicalRaySettings::Source::pinhole) {
        positive(s.pinhole_radius_um, "the pinhole radius");
        positive(s.filter_um, "the filter thickness");
        if (s.pinhole_radius_um > 0.5 * s.slab_um) throw InputError("the pinhole is larger than the slab (its radius exceeds half the slab thickness)");
    }
    if (s.rays < 1 || s.size_px < 16 || s.size_px > 8192) throw InputError("ray count or image size out of range");
}

}  // namespace

double conical_cone_angle_rad(const Eigen::Vector3d& principal_n) {
    Eigen::Vector3d n = principal_n;
    std::sort(n.data(), n.data() + 3);
    const double a2 = n[0] * n[0], b2 = n[1] * n[1], g2 = n[2] * n[2];
    return std::atan(std::sqrt((b2 - a2) * (g2 - b2)) / (n[0] * n[2]));
}

ConicalRayResult trace_conical_rays(const ConicalRaySettings& settings, const ProgressCallback& progress) {
    validate(settings);
    ConicalRayResult result;
    const double chi = conical_cone_angle_rad(settings.principal_n);
    result.cone_angle_deg = chi / kDegree;
    result.ring_radius_um = 0.5 * std::tan(chi) * settings.slab_um;  // R₀ = A·d, A = ½ tan χ
    // Binormal 1 along the slab normal; the second binormal's projection (the ring's offset) toward the
    // rotation azimuth (orientation.hpp's optic-axis cut).
    const Eigen::Matrix3d axes =
        cut_orientation(Cut::optic_axis, OpticalClass::biaxial, settings.principal_n, settings.rotate_deg, settings.tilt_deg);
    const OpticalMedium crystal{settings.principal_n.cast<std::complex<double>>(), axes};
    const OpticalMedium air = OpticalMedium::isotropic(1.0);
    const Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
    const double azimuth = settings.rotate_deg * kDegree;
    result.ring_centre_um = result.ring_radius_um * Eigen::Vector2d(std::cos(azimuth), std::sin(azimuth));
    const double half_width = settings.half_width_um > 0.0 ? settings.half_width_um : 2.0 * result.ring_radius_um;
    const int size = settings.size_px;
    result.screen = Image(size, size, 1);
    std::vector<Landing> landings;
    const double pixel_um = 2.0 * half_width / size;
    double max_sum = 0.0;
    std::int64_t non_finite = 0;
    ProgressRelay relay(progress);

#pragma omp parallel reduction(max : max_sum) reduction(+ : non_finite)
    {
        Image local(size, size, 1);
        std::vector<Landing> local_landings;
#pragma omp for schedule(dynamic, 256)
        for (std::int64_t ray = 0; ray < settings.rays; ++ray) {
            if (relay.cancelled()) continue;
            std::mt19937_64 rng(settings.seed * 0x9E3779B97F4A7C15ULL + static_cast<std::uint64_t>(ray));
            Eigen::Vector2d start = Eigen::Vector2d::Zero();
            Eigen::Vector3d direction;
            if (settings.source == ConicalRaySettings::Source::pinhole) {
                // Through both openings of the hole: the top at height h, the bottom on the slab.
                const Eigen::Vector2d top = uniform_in_disc(rng, settings.pinhole_radius_um);
                start = uniform_in_disc(rng, settings.pinhole_radius_um);
                direction = Eigen::Vector3d(start.x() - top.x(), start.y() - top.y(), settings.filter_um).normalized();
            } else {
                std::normal_distribution<double> angle(0.0, settings.angular_width_rad);
                const double tx = angle(rng), ty = angle(rng);
                direction = Eigen::Vector3d(std::tan(tx), std::tan(ty), 1.0).normalized();
            }
            InterfaceIncidence incidence;
            incidence.direction = direction;
            incidence.coherency = ray_coherency(settings.stokes, direction);
            const InterfaceResult entry = solve_interface(normal, incidence, air, crystal);
            double entry_sum = 0.0;
            for (const InterfaceWave& wave : entry.waves) entry_sum += wave.power;
            max_sum = std::max(max_sum, entry_sum);
            for (const InterfaceWave& inside : entry.waves) {
                if (inside.kind != InterfaceWave::Kind::transmitted || inside.evanescent || inside.power <= 0.0) continue;
                // Along the ray (Poynting) direction to the exit face, then out into air.
                const Eigen::Vector3d exit_point = Eigen::Vector3d(start.x(), start.y(), 0.0) + inside.ray_direction * (settings.slab_um / inside.ray_direction.z());
                InterfaceIncidence internal;
                internal.direction = inside.direction;
                internal.mode = inside.mode;
                const InterfaceResult exit = solve_interface(normal, internal, crystal, air);
                double exit_sum = 0.0;
                for (const InterfaceWave& wave : exit.waves) exit_sum += wave.power;
                max_sum = std::max(max_sum, exit_sum);
                for (const InterfaceWave& out : exit.waves) {
                    if (out.kind != InterfaceWave::Kind::transmitted || out.evanescent) continue;
                    const Eigen::Vector3d landing = exit_point + out.direction * (settings.screen_distance_um / out.direction.z());
                    const double weight = inside.power * out.power;
                    if (!landing.allFinite() || !std::isfinite(weight)) {
                        ++non_finite;
                        continue;
                    }
                    const int column = static_cast<int>(std::floor((landing.x() - result.ring_centre_um.x() + half_width) / pixel_um));
                    const int row = static_cast<int>(std::floor((half_width - (landing.y() - result.ring_centre_um.y())) / pixel_um));
                    if (column >= 0 && column < size && row >= 0 && row < size) local.at(column, row, 0) += static_cast<float>(weight);
                    local_landings.push_back({landing.x(), landing.y(), weight});
                }
            }
            if (ray % 4096 == 0) relay.report(static_cast<double>(ray) / static_cast<double>(settings.rays));
        }
#pragma omp critical
        {
            for (std::size_t i = 0; i < local.pixels.size(); ++i) result.screen.pixels[i] += local.pixels[i];
            landings.insert(landings.end(), local_landings.begin(), local_landings.end());
        }
    }
    relay.finish();
    result.rings = measure_rings(landings, result.ring_radius_um);
    result.max_interface_power_sum = max_sum;
    result.non_finite = non_finite;
    result.rays_traced = settings.rays;
    result.pinhole_point_um = Eigen::Vector2d::Zero();
    return result;
}

}  // namespace petroscope
