#include "petroscope/microscope/conical_ray.hpp"

#include "petroscope/core/angles.hpp"
#include "petroscope/core/error.hpp"
#include "petroscope/microscope/layer_stack.hpp"
#include "petroscope/optics/medium.hpp"
#include "petroscope/optics/orientation.hpp"
#include "petroscope/optics/polarization.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <utility>
#include <vector>

namespace petroscope {
namespace {

// Each ray's own random stream, SplitMix64 (Steele, Lea & Flood, OOPSLA 2014): the state advances by the
// golden-ratio increment and is mixed by two xor-shift-multiply rounds. Seeding is one addition, so every ray
// can start its own stream (the result does not depend on how rays are split over threads).
class RayRandom {
public:
    using result_type = std::uint64_t;
    explicit RayRandom(std::uint64_t seed) : state_(seed) {}
    static constexpr result_type min() { return 0; }
    static constexpr result_type max() { return ~result_type{0}; }
    result_type operator()() {
        state_ += 0x9E3779B97F4A7C15ULL;
        result_type z = state_;
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
        return z ^ (z >> 31);
    }

private:
    std::uint64_t state_;
};

Eigen::Vector2d uniform_in_disc(RayRandom& rng, double radius) {
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    const double r = radius * std::sqrt(unit(rng)), phi = 2.0 * std::numbers::pi * unit(rng);
    return {r * std::cos(phi), r * std::sin(phi)};
}

// Single precision keeps the landings of 10⁶ rays in 24 MB (x, y in µm to about 1e-4 µm at the ring's size).
struct Landing {
    float x, y, weight;
};

double distance(const Landing& landing, const Eigen::Vector2d& centre) {
    const double dx = landing.x - centre.x(), dy = landing.y - centre.y();
    return std::sqrt(dx * dx + dy * dy);
}

struct WeightedValue {
    double value, weight;
    bool operator<(const WeightedValue& other) const { return value != other.value ? value < other.value : weight < other.weight; }
};

// One step of weighted_quantile: the items whose value lies in the one of 4096 bins of value where the running
// sum of the weights (from `below`) reaches `target`, with `below` moved up to that bin; every item when there
// are few. False, with the answer, when no bin is needed: all values equal, or the target never reached.
constexpr std::size_t kQuantileBins = 4096;
template <typename Item, typename ValueOf>
bool narrow_to_crossing_bin(const std::vector<Item>& items, const ValueOf& value_of, double target, double& below,
                            std::vector<WeightedValue>& kept, double& answer) {
    kept.clear();
    if (items.size() <= kQuantileBins) {
        for (const Item& item : items) kept.push_back({value_of(item), item.weight});
        return true;
    }
    double low = value_of(items.front()), high = low;
    for (const Item& item : items) {
        low = std::min(low, value_of(item));
        high = std::max(high, value_of(item));
    }
    answer = high;
    if (!(high > low)) return false;
    const double per_value = static_cast<double>(kQuantileBins) / (high - low);
    const auto bin_of = [&](double value) { return std::min(kQuantileBins - 1, static_cast<std::size_t>((value - low) * per_value)); };
    std::vector<double> bin_weight(kQuantileBins, 0.0);
    for (const Item& item : items) bin_weight[bin_of(value_of(item))] += item.weight;
    std::size_t crossing = 0;
    while (crossing < kQuantileBins && below + bin_weight[crossing] < target) below += bin_weight[crossing++];
    if (crossing == kQuantileBins) return false;
    for (const Item& item : items) {
        if (bin_of(value_of(item)) == crossing) kept.push_back({value_of(item), item.weight});
    }
    return true;
}

// The first value, in increasing order of (value, weight), at which the running sum of the weights reaches
// `target` (the largest value if it never does), as a sort and a scan would give it, in O(n): bins narrow the
// items down to those where the sum crosses the target, and only those are sorted and scanned.
template <typename Item, typename ValueOf>
double weighted_quantile(const std::vector<Item>& items, const ValueOf& value_of, double target) {
    if (items.empty()) return 0.0;
    double below = 0.0, answer = 0.0;
    std::vector<WeightedValue> kept, candidates;
    if (!narrow_to_crossing_bin(items, value_of, target, below, kept, answer)) return answer;
    while (kept.size() > kQuantileBins) {
        std::swap(candidates, kept);
        if (!narrow_to_crossing_bin(candidates, [](const WeightedValue& c) { return c.value; }, target, below, kept, answer)) return answer;
    }
    std::sort(kept.begin(), kept.end());
    for (const WeightedValue& item : kept) {
        below += item.weight;
        if (below >= target) return item.value;
    }
    return kept.empty() ? answer : kept.back().value;
}

// The radial power density of landings given by their radius (in x) in rings of width `bin`, smoothed over
// 2·half_window + 1 bins.
std::vector<double> radial_density(const std::vector<Landing>& landings, double bin, std::size_t bins, std::size_t half_window) {
    std::vector<double> power(bins, 0.0);
    for (const Landing& landing : landings) {
        const auto index = static_cast<std::size_t>(landing.x / bin);
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

ConicalRayRings measure_rings(std::vector<Landing> landings, double ring_radius) {
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
    for (Landing& landing : landings) landing.x = static_cast<float>(distance(landing, rings.centre_um));  // from here on x is the radius
    const auto radius = [](const Landing& landing) -> double { return landing.x; };
    const double median = weighted_quantile(landings, radius, 0.5 * total);
    const double spread = weighted_quantile(landings, [median](const Landing& landing) { return std::abs(landing.x - median); }, 0.5 * total);
    const std::size_t half_window = std::max<std::size_t>(1, static_cast<std::size_t>(0.25 * spread / bin));
    const std::size_t separation = std::max<std::size_t>(2, static_cast<std::size_t>(spread / bin));
    const std::vector<double> density = radial_density(landings, bin, bins, half_window);
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

// A ray's (s, p) basis (docs/interface.md): columns ŝ = ẑ × k̂ normalised (ŷ at normal incidence) and p̂ = ŝ × k̂.
Eigen::Matrix<double, 3, 2> sp_basis(const Eigen::Vector3d& k_hat) {
    Eigen::Vector3d s_hat = Eigen::Vector3d::UnitZ().cross(k_hat);
    s_hat = s_hat.norm() > 1e-15 ? Eigen::Vector3d(s_hat.normalized()) : Eigen::Vector3d::UnitY();
    Eigen::Matrix<double, 3, 2> basis;
    basis << s_hat, s_hat.cross(k_hat);
    return basis;
}

// The incident state, given by a Stokes vector in the lab frame (x, y), in the ray's own (s, p) basis:
// C_sp = T·C_xy·T† with T's rows the transverse parts of ŝ and p̂.
CoherencyMatrix ray_coherency(const Eigen::Vector4d& lab_stokes, const Eigen::Vector3d& k_hat) {
    const Eigen::Matrix2cd transform = sp_basis(k_hat).topRows<2>().transpose().cast<std::complex<double>>();
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

SlabCrossing cross_slab(const Eigen::Matrix3cd& crystal_epsilon, const Eigen::Vector3d& direction, const CoherencyMatrix& coherency_sp) {
    const Eigen::Vector2d xi = direction.head<2>();
    const MediumWaves air = berreman_modes(Eigen::Matrix3cd::Identity(), xi);
    const MediumWaves crystal = berreman_modes(crystal_epsilon, xi);
    // The incident coherency in the air's forward waves (unit E fields): the (s, p) basis projected on them.
    const Eigen::Matrix<std::complex<double>, 3, 2> basis = sp_basis(direction).cast<std::complex<double>>();
    Eigen::Matrix2cd to_waves;
    for (int m = 0; m < 2; ++m) to_waves.row(m) = air[m].e_field.adjoint() * basis;
    const Eigen::Matrix2cd incident = to_waves * coherency_sp * to_waves.adjoint();
    // Waves of one direction in a lossless medium carry no cross flux, so powers add: Σₘ |S_z,ₘ|·Cₘₘ. Only the
    // diagonal of a coherency a·C·aᴴ carried by an amplitude matrix a is formed.
    const auto diagonal = [](const Eigen::Matrix2cd& a, const Eigen::Matrix2cd& coherency) -> Eigen::Vector2d {
        return (a * coherency).cwiseProduct(a.conjugate()).rowwise().sum().real();
    };
    const auto power = [](const BerremanMode& first, const BerremanMode& second, const Eigen::Vector2d& coherency_diagonal) {
        return std::abs(first.flux_z) * coherency_diagonal[0] + std::abs(second.flux_z) * coherency_diagonal[1];
    };
    const double incident_flux = power(air[0], air[1], incident.diagonal().real());
    const ForwardBoundary entry = forward_boundary(air, crystal);
    const Eigen::Vector2d inside = diagonal(entry.transmission, incident);
    SlabCrossing crossing;
    crossing.largest_power_sum =
        (power(crystal[0], crystal[1], inside) + power(air[2], air[3], diagonal(entry.reflection, incident))) / incident_flux;
    const ForwardBoundary exit = forward_boundary(crystal, air);
    for (int m = 0; m < 2; ++m) {
        const double carried = crystal[m].flux_z * inside[m] / incident_flux;
        if (crystal[m].evanescent || !(carried > 0.0)) continue;
        // Wave m alone (coherency e_m e_mᵀ): the squared moduli of column m.
        const double transmitted = power(air[0], air[1], exit.transmission.col(m).cwiseAbs2()) / crystal[m].flux_z;
        const double reflected = power(crystal[2], crystal[3], exit.reflection.col(m).cwiseAbs2()) / crystal[m].flux_z;
        crossing.largest_power_sum = std::max(crossing.largest_power_sum, transmitted + reflected);
        const Eigen::Vector3d poynting = crystal[m].e_field.cross(crystal[m].h_field.conjugate()).real();
        crossing.waves[m] = {poynting.normalized(), carried * transmitted};
    }
    return crossing;
}

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
    const Eigen::Matrix3cd crystal_epsilon = OpticalMedium{settings.principal_n.cast<std::complex<double>>(), axes}.permittivity();
    const double azimuth = settings.rotate_deg * kDegree;
    result.ring_centre_um = result.ring_radius_um * Eigen::Vector2d(std::cos(azimuth), std::sin(azimuth));
    const double half_width = settings.half_width_um > 0.0 ? settings.half_width_um : 2.0 * result.ring_radius_um;
    const int size = settings.size_px;
    result.screen = Image(size, size, 1);
    // Two slots per ray (its two waves), so that threads write without merging; unused slots keep weight 0.
    std::vector<Landing> landings(2 * static_cast<std::size_t>(settings.rays), Landing{0.0F, 0.0F, 0.0F});
    const double pixel_um = 2.0 * half_width / size;
    double max_sum = 0.0;
    std::int64_t non_finite = 0;
    ProgressRelay relay(progress);

#pragma omp parallel reduction(max : max_sum) reduction(+ : non_finite)
    {
        Image local(size, size, 1);
#pragma omp for schedule(dynamic, 256)
        for (std::int64_t ray = 0; ray < settings.rays; ++ray) {
            if (relay.cancelled()) continue;
            RayRandom rng(settings.seed * 0xD1B54A32D192ED03ULL + static_cast<std::uint64_t>(ray) * 0x8CB92BA72F3D8DD7ULL);
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
            const SlabCrossing crossing = cross_slab(crystal_epsilon, direction, ray_coherency(settings.stokes, direction));
            max_sum = std::max(max_sum, crossing.largest_power_sum);
            for (std::size_t k = 0; k < crossing.waves.size(); ++k) {
                const SlabWave& wave = crossing.waves[k];
                if (wave.weight == 0.0) continue;
                // Along the ray (Poynting) direction to the exit face, then on along the incident direction.
                const Eigen::Vector3d exit_point = Eigen::Vector3d(start.x(), start.y(), 0.0) + wave.ray_direction * (settings.slab_um / wave.ray_direction.z());
                const Eigen::Vector3d landing = exit_point + direction * (settings.screen_distance_um / direction.z());
                if (!landing.allFinite() || !std::isfinite(wave.weight)) {
                    ++non_finite;
                    continue;
                }
                const int column = static_cast<int>(std::floor((landing.x() - result.ring_centre_um.x() + half_width) / pixel_um));
                const int row = static_cast<int>(std::floor((half_width - (landing.y() - result.ring_centre_um.y())) / pixel_um));
                if (column >= 0 && column < size && row >= 0 && row < size) local.at(column, row, 0) += static_cast<float>(wave.weight);
                landings[2 * static_cast<std::size_t>(ray) + k] = {static_cast<float>(landing.x()), static_cast<float>(landing.y()), static_cast<float>(wave.weight)};
            }
            if (ray % 4096 == 0) relay.report(static_cast<double>(ray) / static_cast<double>(settings.rays));
        }
#pragma omp critical
        for (std::size_t i = 0; i < local.pixels.size(); ++i) result.screen.pixels[i] += local.pixels[i];
    }
    relay.finish();
    std::erase_if(landings, [](const Landing& landing) { return landing.weight == 0.0; });
    result.rings = measure_rings(std::move(landings), result.ring_radius_um);
    result.max_interface_power_sum = max_sum;
    result.non_finite = non_finite;
    result.rays_traced = settings.rays;
    result.pinhole_point_um = Eigen::Vector2d::Zero();
    return result;
}

}  // namespace petroscope
