#include "petroscope/microscope/thin_section.hpp"

#include "petroscope/core/error.hpp"
#include "petroscope/core/text.hpp"
#include "petroscope/minerals/mineral_catalog.hpp"
#include "petroscope/optics/orientation.hpp"

#include <Eigen/Geometry>
#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>

namespace petroscope {
namespace {

constexpr int kLabelCount = 65536;        // a 16-bit map holds labels 0 … 65535
constexpr double kRotationTolerance = 1e-6;  // |RᵀR − I| and |det R − 1| accepted for crystal axes

std::string pixel_text(int x, int y) { return "(x " + std::to_string(x) + ", y " + std::to_string(y) + ")"; }

}  // namespace

double ThinSection::section_thickness_at(int x, int y) const {
    switch (thickness_kind) {
        case ThicknessKind::uniform: return thickness_um;
        case ThicknessKind::wedge: {
            const double fraction = wedge_along_x ? (x + 0.5) / width_px : (y + 0.5) / height_px;
            return wedge_start_um + (wedge_end_um - wedge_start_um) * fraction;
        }
        case ThicknessKind::map:
            return thickness_map_um[static_cast<std::size_t>(y) * static_cast<std::size_t>(width_px) + static_cast<std::size_t>(x)];
    }
    return thickness_um;
}

double ThinSection::thickness_at(int x, int y, const ThinSectionGrain& grain) const {
    return grain.thickness_um ? *grain.thickness_um : section_thickness_at(x, y);
}

void ThinSection::index_grains() {
    grain_index_of_label.assign(kLabelCount, -1);
    for (std::size_t i = 0; i < grains.size(); ++i) {
        const ThinSectionGrain& grain = grains[i];
        if (grain.label < 0 || grain.label >= kLabelCount) {
            throw InputError("thin section " + quote_input(name) + ": grain label " + std::to_string(grain.label) + " is outside 0 … 65535");
        }
        int& slot = grain_index_of_label[static_cast<std::size_t>(grain.label)];
        if (slot >= 0) {
            const ThinSectionGrain& first = grains[static_cast<std::size_t>(slot)];
            std::string where;
            if (first.line > 0 && grain.line > 0) where = " (lines " + std::to_string(first.line) + " and " + std::to_string(grain.line) + ")";
            throw InputError("thin section " + quote_input(name) + ": grain label " + std::to_string(grain.label) + " is defined twice" + where);
        }
        slot = static_cast<int>(i);
    }
}

const ThinSectionGrain& ThinSection::grain_at(int x, int y) const {
    const std::uint16_t label = labels[static_cast<std::size_t>(y) * static_cast<std::size_t>(width_px) + static_cast<std::size_t>(x)];
    return grains[static_cast<std::size_t>(grain_index_of_label[label])];
}

std::vector<std::pair<std::uint16_t, std::size_t>> ThinSection::label_counts() const {
    std::vector<std::size_t> counts(kLabelCount, 0);
    for (const std::uint16_t label : labels) ++counts[label];
    std::vector<std::pair<std::uint16_t, std::size_t>> used;
    for (int label = 0; label < kLabelCount; ++label) {
        if (counts[static_cast<std::size_t>(label)] > 0) used.emplace_back(static_cast<std::uint16_t>(label), counts[static_cast<std::size_t>(label)]);
    }
    return used;
}

void ThinSection::validate() {
    const std::string what = "thin section " + quote_input(name) + ": ";
    if (width_px < 1 || height_px < 1) throw InputError(what + "the map must be at least 1x1 pixels");
    const std::size_t pixels = static_cast<std::size_t>(width_px) * static_cast<std::size_t>(height_px);
    if (labels.size() != pixels) throw InputError(what + "the label map holds " + std::to_string(labels.size()) + " values, expected width x height = " + std::to_string(pixels));
    if (!(std::isfinite(pixel_size_um) && pixel_size_um > 0.0)) throw InputError(what + "the pixel size must be a finite number of micrometres > 0");
    switch (thickness_kind) {
        case ThicknessKind::uniform:
            if (!(std::isfinite(thickness_um) && thickness_um > 0.0)) throw InputError(what + "the thickness must be a finite number of micrometres > 0");
            break;
        case ThicknessKind::wedge:
            if (!(std::isfinite(wedge_start_um) && std::isfinite(wedge_end_um) && wedge_start_um >= 0.0 && wedge_end_um >= 0.0 &&
                  wedge_start_um + wedge_end_um > 0.0)) {
                throw InputError(what + "the wedge thicknesses must be finite, >= 0 and not both 0");
            }
            break;
        case ThicknessKind::map:
            if (thickness_map_um.size() != pixels) throw InputError(what + "the thickness map holds " + std::to_string(thickness_map_um.size()) + " values, expected " + std::to_string(pixels));
            for (std::size_t i = 0; i < pixels; ++i) {
                if (!(std::isfinite(thickness_map_um[i]) && thickness_map_um[i] >= 0.0f)) {
                    const int x = static_cast<int>(i % static_cast<std::size_t>(width_px)), y = static_cast<int>(i / static_cast<std::size_t>(width_px));
                    throw InputError(what + "the thickness map holds " + std::to_string(thickness_map_um[i]) + " at " + pixel_text(x, y) + ", expected a finite number of micrometres >= 0");
                }
            }
            break;
    }
    for (const ThinSectionGrain& grain : grains) {
        const std::string which = what + "grain " + std::to_string(grain.label) + ": ";
        if (grain.mineral.empty()) throw InputError(which + "no mineral");
        if (grain.thickness_um && !(std::isfinite(*grain.thickness_um) && *grain.thickness_um > 0.0)) {
            throw InputError(which + "its own thickness must be a finite number of micrometres > 0");
        }
        const Eigen::Matrix3d& axes = grain.crystal_axes;
        if (!axes.allFinite() || (axes.transpose() * axes - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() > kRotationTolerance ||
            std::abs(axes.determinant() - 1.0) > kRotationTolerance) {
            throw InputError(which + "the crystal axes are not a rotation (orthonormal columns, determinant +1)");
        }
    }
    index_grains();
    for (std::size_t i = 0; i < pixels; ++i) {
        if (grain_index_of_label[labels[i]] < 0) {
            const int x = static_cast<int>(i % static_cast<std::size_t>(width_px)), y = static_cast<int>(i / static_cast<std::size_t>(width_px));
            throw InputError(what + "label " + std::to_string(labels[i]) + " (first at " + pixel_text(x, y) + ") has no grain");
        }
    }
}

double uniform_unit_interval(std::mt19937_64& rng) {
    return static_cast<double>(rng() >> 11) * 0x1.0p-53;
}

Eigen::Matrix3d shoemake_rotation(double u1, double u2, double u3) {
    const double r1 = std::sqrt(1.0 - u1), r2 = std::sqrt(u1);
    const double theta1 = 2.0 * std::numbers::pi * u2, theta2 = 2.0 * std::numbers::pi * u3;
    // Shoemake's (x, y, z, w); Eigen's constructor takes (w, x, y, z).
    const Eigen::Quaterniond q(r2 * std::cos(theta2), r1 * std::sin(theta1), r1 * std::cos(theta1), r2 * std::sin(theta2));
    return q.normalized().toRotationMatrix();
}

Eigen::Vector3d euler_zyz_deg_of(const Eigen::Matrix3d& rotation) {
    // R = Rz(α)·Ry(β)·Rz(γ) has third column (cos α sin β, sin α sin β, cos β).
    const double sin_beta = std::hypot(rotation(0, 2), rotation(1, 2));
    const double beta = std::atan2(sin_beta, rotation(2, 2));
    const double alpha = sin_beta > 0.0 ? std::atan2(rotation(1, 2), rotation(0, 2)) : 0.0;
    // γ from what remains, Ry(β)ᵀ·Rz(α)ᵀ·R = Rz(γ): exact even when α is ill-determined (β near 0 or π).
    const Eigen::Matrix3d remaining = Eigen::AngleAxisd(beta, Eigen::Vector3d::UnitY()).toRotationMatrix().transpose() *
                                      Eigen::AngleAxisd(alpha, Eigen::Vector3d::UnitZ()).toRotationMatrix().transpose() * rotation;
    const double gamma = std::atan2(remaining(1, 0), remaining(0, 0));
    return Eigen::Vector3d(alpha, beta, gamma) * (180.0 / std::numbers::pi);
}

void VoronoiSectionSettings::validate() const {
    if (minerals.empty()) throw InputError("random section: expected at least one mineral");
    if (!weights.empty()) {
        if (weights.size() != minerals.size()) {
            throw InputError("random section: " + std::to_string(weights.size()) + " weights for " + std::to_string(minerals.size()) +
                             " minerals; expected one weight per mineral");
        }
        double sum = 0.0;
        for (const double weight : weights) {
            if (!(std::isfinite(weight) && weight >= 0.0)) throw InputError("random section: weights must be finite and >= 0");
            sum += weight;
        }
        if (!(sum > 0.0)) throw InputError("random section: at least one weight must be > 0");
    }
    if (!grain_sizes.empty()) {
        if (grain_sizes.size() != minerals.size()) {
            throw InputError("random section: " + std::to_string(grain_sizes.size()) + " grain sizes for " +
                             std::to_string(minerals.size()) + " minerals; expected one size per mineral");
        }
        for (const double size : grain_sizes) {
            if (!(std::isfinite(size) && size > 0.0)) throw InputError("random section: grain sizes must be finite and > 0");
        }
    }
    if (size_px < 16 || size_px > 8192) throw InputError("random section: size " + std::to_string(size_px) + " px is outside 16 … 8192");
    const long long pixels = static_cast<long long>(size_px) * size_px;
    const long long most = std::min<long long>(pixels, kLabelCount - 1);
    if (grain_count < 1 || grain_count > most) {
        throw InputError("random section: " + std::to_string(grain_count) + " grains; expected 1 … " + std::to_string(most) +
                         " (at most one per pixel and 65535 in a 16-bit map)");
    }
    if (!(std::isfinite(pixel_size_um) && pixel_size_um > 0.0)) throw InputError("random section: the pixel size must be > 0");
    if (!(std::isfinite(thickness_um) && thickness_um > 0.0)) throw InputError("random section: the thickness must be > 0");
}

namespace {

struct Seed {
    double x = 0.0, y = 0.0;     // pixel units, 0 … size
    double power_weight = 0.0;   // w in |p − s|² − w
};

// The owning seed of every pixel centre (row-major): the least power distance, ties to the lower index.
// Pixels are processed in square blocks about half a seed spacing wide; for each block only the seeds that
// can win somewhere in it are tried. With c the block's centre and h the half-diagonal of its pixel
// centres, every pixel's best power distance is at most U = min_s (|c − s| + h)² − w_s, and seed s can do
// no better than max(|c − s| − h, 0)² − w_s; seeds whose bound exceeds U are skipped. Seeds are bucketed
// on the same blocks, searched in square rings until no unvisited seed can beat U.
std::vector<std::int32_t> assign_cells(const std::vector<Seed>& seeds, int size_px) {
    const double spacing = size_px / std::sqrt(static_cast<double>(seeds.size()));
    const int block_px = std::max(1, static_cast<int>(std::lround(0.5 * spacing)));
    const int blocks = (size_px + block_px - 1) / block_px;
    const std::size_t block_count = static_cast<std::size_t>(blocks) * static_cast<std::size_t>(blocks);
    double max_weight = 0.0;
    for (const Seed& seed : seeds) max_weight = std::max(max_weight, seed.power_weight);

    // Seeds per block, compressed: bucket b holds order[offset[b] … offset[b + 1]).
    const auto block_of = [&](const Seed& seed) {
        const int bx = std::min(static_cast<int>(seed.x / block_px), blocks - 1);
        const int by = std::min(static_cast<int>(seed.y / block_px), blocks - 1);
        return static_cast<std::size_t>(by) * static_cast<std::size_t>(blocks) + static_cast<std::size_t>(bx);
    };
    std::vector<std::size_t> offset(block_count + 1, 0);
    for (const Seed& seed : seeds) ++offset[block_of(seed) + 1];
    for (std::size_t b = 0; b < block_count; ++b) offset[b + 1] += offset[b];
    std::vector<std::int32_t> order(seeds.size());
    {
        std::vector<std::size_t> fill(offset.begin(), offset.end() - 1);
        for (std::size_t i = 0; i < seeds.size(); ++i) order[fill[block_of(seeds[i])]++] = static_cast<std::int32_t>(i);
    }

    std::vector<std::int32_t> owner(static_cast<std::size_t>(size_px) * static_cast<std::size_t>(size_px), -1);
#pragma omp parallel
    {
        struct Candidate {
            std::int32_t index;
            double lower_bound;
        };
        std::vector<Candidate> visited;
        std::vector<std::int32_t> candidates;
#pragma omp for schedule(dynamic, 16)
        for (std::size_t block = 0; block < block_count; ++block) {
            const int bx = static_cast<int>(block % static_cast<std::size_t>(blocks)), by = static_cast<int>(block / static_cast<std::size_t>(blocks));
            const int x0 = bx * block_px, x1 = std::min(x0 + block_px, size_px);
            const int y0 = by * block_px, y1 = std::min(y0 + block_px, size_px);
            const double cx = 0.5 * (x0 + x1), cy = 0.5 * (y0 + y1);
            const double h = std::hypot(0.5 * (x1 - x0 - 1), 0.5 * (y1 - y0 - 1));
            double upper = std::numeric_limits<double>::infinity();
            visited.clear();
            const auto visit = [&](int qx, int qy) {
                const std::size_t b = static_cast<std::size_t>(qy) * static_cast<std::size_t>(blocks) + static_cast<std::size_t>(qx);
                for (std::size_t k = offset[b]; k < offset[b + 1]; ++k) {
                    const Seed& seed = seeds[static_cast<std::size_t>(order[k])];
                    const double distance = std::hypot(seed.x - cx, seed.y - cy);
                    upper = std::min(upper, (distance + h) * (distance + h) - seed.power_weight);
                    const double near = std::max(distance - h, 0.0);
                    visited.push_back({order[k], near * near - seed.power_weight});
                }
            };
            for (int ring = 0; ring <= blocks; ++ring) {
                // Seeds in ring r lie at least (r − 1) blocks from this block, hence from c.
                const double gap = std::max(0.0, static_cast<double>(ring - 1) * block_px - h);
                if (gap * gap - max_weight > upper + 1e-9 * (1.0 + std::abs(upper) + max_weight)) break;
                for (int qy = by - ring; qy <= by + ring; ++qy) {
                    if (qy < 0 || qy >= blocks) continue;
                    const bool edge_row = qy == by - ring || qy == by + ring;
                    for (int qx = bx - ring; qx <= bx + ring; qx += edge_row ? 1 : 2 * std::max(ring, 1)) {
                        if (qx >= 0 && qx < blocks) visit(qx, qy);
                    }
                }
            }
            // The slack keeps a seed whose bound ties with U to rounding (e.g. a block of one pixel, h = 0, where
            // the bound and U are the same number computed in two ways); extra candidates cost time only.
            const double slack = 1e-9 * (1.0 + std::abs(upper) + max_weight);
            candidates.clear();
            for (const Candidate& candidate : visited) {
                if (candidate.lower_bound <= upper + slack) candidates.push_back(candidate.index);
            }
            std::sort(candidates.begin(), candidates.end());
            for (int y = y0; y < y1; ++y) {
                const double py = y + 0.5;
                for (int x = x0; x < x1; ++x) {
                    const double px = x + 0.5;
                    double best = std::numeric_limits<double>::infinity();
                    std::int32_t best_index = -1;
                    for (const std::int32_t index : candidates) {
                        const Seed& seed = seeds[static_cast<std::size_t>(index)];
                        const double power = (px - seed.x) * (px - seed.x) + (py - seed.y) * (py - seed.y) - seed.power_weight;
                        if (power < best) {
                            best = power;
                            best_index = index;
                        }
                    }
                    owner[static_cast<std::size_t>(y) * static_cast<std::size_t>(size_px) + static_cast<std::size_t>(x)] = best_index;
                }
            }
        }
    }
    return owner;
}

}  // namespace

ThinSection random_voronoi_section(const VoronoiSectionSettings& settings) {
    settings.validate();
    const std::size_t mineral_count = settings.minerals.size();
    std::vector<double> cumulative(mineral_count);
    double total = 0.0;
    for (std::size_t m = 0; m < mineral_count; ++m) {
        total += settings.weights.empty() ? 1.0 : settings.weights[m];
        cumulative[m] = total;
    }
    // Power weights w = L²·(g − g_min)/ḡ (see VoronoiSectionSettings::grain_sizes); g_min's cells are plain Voronoi.
    std::vector<double> power_weight(mineral_count, 0.0);
    if (!settings.grain_sizes.empty()) {
        const double smallest = *std::min_element(settings.grain_sizes.begin(), settings.grain_sizes.end());
        double mean_size = 0.0;
        for (std::size_t m = 0; m < mineral_count; ++m) {
            mean_size += settings.grain_sizes[m] * (settings.weights.empty() ? 1.0 : settings.weights[m]) / total;
        }
        const double spacing = settings.size_px / std::sqrt(static_cast<double>(settings.grain_count));
        for (std::size_t m = 0; m < mineral_count; ++m) {
            power_weight[m] = spacing * spacing * (settings.grain_sizes[m] - smallest) / mean_size;
        }
    }

    std::mt19937_64 rng(settings.seed);
    std::vector<Seed> seeds(static_cast<std::size_t>(settings.grain_count));
    std::vector<std::size_t> mineral_of(seeds.size());
    std::vector<Eigen::Matrix3d> axes_of(seeds.size());
    for (std::size_t i = 0; i < seeds.size(); ++i) {
        seeds[i].x = uniform_unit_interval(rng) * settings.size_px;
        seeds[i].y = uniform_unit_interval(rng) * settings.size_px;
        const double pick = uniform_unit_interval(rng) * total;
        std::size_t m = 0;
        while (m + 1 < mineral_count && !(pick < cumulative[m])) ++m;
        mineral_of[i] = m;
        seeds[i].power_weight = power_weight[m];
        const double u1 = uniform_unit_interval(rng), u2 = uniform_unit_interval(rng), u3 = uniform_unit_interval(rng);
        axes_of[i] = shoemake_rotation(u1, u2, u3);
    }

    const std::vector<std::int32_t> owner = assign_cells(seeds, settings.size_px);
    std::vector<std::size_t> pixels_of(seeds.size(), 0);
    for (const std::int32_t index : owner) ++pixels_of[static_cast<std::size_t>(index)];
    std::vector<std::uint16_t> label_of(seeds.size(), 0);

    ThinSection section;
    section.name = settings.name;
    section.width_px = section.height_px = settings.size_px;
    section.pixel_size_um = settings.pixel_size_um;
    section.thickness_kind = ThicknessKind::uniform;
    section.thickness_um = settings.thickness_um;
    for (std::size_t i = 0; i < seeds.size(); ++i) {
        if (pixels_of[i] == 0) continue;
        ThinSectionGrain grain;
        grain.label = static_cast<int>(section.grains.size()) + 1;
        grain.mineral = settings.minerals[mineral_of[i]];
        grain.crystal_axes = axes_of[i];
        label_of[i] = static_cast<std::uint16_t>(grain.label);
        section.grains.push_back(std::move(grain));
    }
    section.labels.resize(owner.size());
    std::transform(owner.begin(), owner.end(), section.labels.begin(),
                   [&](std::int32_t index) { return label_of[static_cast<std::size_t>(index)]; });
    section.index_grains();
    return section;
}

ThinSection random_voronoi_section(const std::vector<std::string>& minerals, const std::vector<double>& weights,
                                   int grain_count, int size_px, double pixel_size_um, double thickness_um,
                                   std::uint64_t seed) {
    VoronoiSectionSettings settings;
    settings.minerals = minerals;
    settings.weights = weights;
    settings.grain_count = grain_count;
    settings.size_px = size_px;
    settings.pixel_size_um = pixel_size_um;
    settings.thickness_um = thickness_um;
    settings.seed = seed;
    return random_voronoi_section(settings);
}

void draw_handedness(ThinSection& section, const MineralCatalog& catalog, std::uint64_t seed) {
    std::mt19937_64 rng(seed);
    for (ThinSectionGrain& grain : section.grains) {
        if (!catalog.find(grain.mineral).optically_active()) continue;
        grain.handedness = uniform_unit_interval(rng) < 0.5 ? Handedness::right : Handedness::left;
    }
}

}  // namespace petroscope
