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

}  // namespace petroscope::testing
