#pragma once
// Shared set-up for the conoscope tests: minerals from the repository's database, figure settings.
#include "petroscope/io/data_files.hpp"
#include "petroscope/microscope/conoscope.hpp"
#include "petroscope/optics/orientation.hpp"

#include <cmath>

namespace petroscope::testing {

inline const MineralCatalog& repository_minerals() {
    static const MineralCatalog catalog = load_mineral_catalog(std::filesystem::path(PETROSCOPE_SOURCE_DIR) / "minerals");
    return catalog;
}

inline PrincipalIndexFunction indices_of(const Mineral& mineral) {
    return [&mineral](double wavelength_nm) { return mineral.principal_n(wavelength_nm); };
}

/// Monochromatic figure settings for a named cut of `mineral`.
inline ConoscopeSettings figure_settings(const Mineral& mineral, Cut cut, double thickness_um, int size_px,
                                         double wavelength_nm = 589.3) {
    ConoscopeSettings settings;
    settings.size_px = size_px;
    settings.thickness_um = thickness_um;
    settings.wavelengths_nm = {wavelength_nm};
    settings.crystal_axes = cut_orientation(cut, mineral.optical_class, mineral.principal_n(mineral.reference_wavelength_nm), 0, 0);
    return settings;
}

/// Pixel values along the diagonal from the centre toward NE (sign +1) or SW (−1): sample k is the pixel
/// whose centre lies at distance √2·(k + 0.5) px from the image centre on the line x = y.
inline std::vector<double> diagonal_profile(const Image& image, int sign) {
    const int half = image.width / 2;
    std::vector<double> profile;
    for (int k = 0; k < half; ++k) {
        const int column = sign > 0 ? half + k : half - 1 - k;
        const int row = sign > 0 ? half - 1 - k : half + k;
        profile.push_back(image.at(column, row, 0));
    }
    return profile;
}

// Retardation map: Σ over crossed polars at β = 0°, 22.5°, 45°, 67.5° of sin²(2(ψ − β))·sin²(δ/2) is
// 2 sin²(δ/2), whatever the vibration directions ψ: dark only where δ = 2πm, at the melatopes for a
// thin slab, so it locates them in both directions.
inline Image retardation_map(ConoscopeSettings settings, const PrincipalIndexFunction& indices) {
    Image sum(settings.size_px, settings.size_px, 1);
    for (const double polarizer_deg : {0.0, 22.5, 45.0, 67.5}) {
        settings.polarizer_deg = polarizer_deg;
        settings.analyzer_deg = polarizer_deg + 90.0;
        const Image figure = render_conoscope(settings, indices, nullptr);
        for (std::size_t i = 0; i < sum.pixels.size(); ++i) sum.pixels[i] += figure.pixels[i];
    }
    return sum;
}

// The darkest point of `map` within `window` px of `guess` (pixel coordinates), refined by a parabola in
// x and in y; returned relative to the image centre with y up.
inline Eigen::Vector2d darkest_point(const Image& map, const Eigen::Vector2d& guess, int window) {
    int best_x = 0, best_y = 0;
    double best = 1e300;
    for (int y = static_cast<int>(guess.y()) - window; y <= static_cast<int>(guess.y()) + window; ++y) {
        for (int x = static_cast<int>(guess.x()) - window; x <= static_cast<int>(guess.x()) + window; ++x) {
            if (map.at(x, y, 0) < best) {
                best = map.at(x, y, 0);
                best_x = x;
                best_y = y;
            }
        }
    }
    const auto vertex = [](double left, double centre, double right) {
        return 0.5 * (left - right) / (left - 2.0 * centre + right);
    };
    const double x = best_x + 0.5 + vertex(map.at(best_x - 1, best_y, 0), best, map.at(best_x + 1, best_y, 0));
    const double y = best_y + 0.5 + vertex(map.at(best_x, best_y - 1, 0), best, map.at(best_x, best_y + 1, 0));
    const double half = 0.5 * map.width;
    return {x - half, half - y};
}

}  // namespace petroscope::testing
