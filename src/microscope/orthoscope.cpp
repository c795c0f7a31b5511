#include "petroscope/microscope/orthoscope.hpp"

#include "petroscope/core/angles.hpp"
#include "petroscope/core/error.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>

namespace petroscope {
namespace {

/// Thickness steps of a grain's table: at most 1 nm of retardation apart, and no more than this many.
constexpr double kRetardationStepUm = 1e-3;
constexpr int kMaxTableEntries = 1 << 16;

/// The grain of each output pixel (index into section.grains, or grains.size() outside the section) and
/// its thickness, with the stage turned: the output pixel q shows the section point R(−stage)·q. A section
/// of uniform thickness has no per-pixel thickness (each grain has one: its own or the section's).
struct PixelGrains {
    std::vector<int> grain;
    std::vector<float> thickness_um;  // empty for a uniform section
};

PixelGrains pixel_grains(const ThinSection& section, double stage_deg) {
    const int width = section.width_px, height = section.height_px;
    const std::size_t count = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
    const bool per_pixel = section.thickness_kind != ThicknessKind::uniform;
    PixelGrains result{std::vector<int>(count), std::vector<float>(per_pixel ? count : 0)};
    const int outside = static_cast<int>(section.grains.size());
    const double c = std::cos(stage_deg * kDegree), s = std::sin(stage_deg * kDegree);
    const double cx = 0.5 * width, cy = 0.5 * height;
    // Outside the turned section: glass and balsam at the section's thickness in the middle of the field.
    const auto outside_thickness_um = static_cast<float>(per_pixel ? section.section_thickness_at(width / 2, height / 2) : 0.0);
#pragma omp parallel for schedule(static)
    for (int row = 0; row < height; ++row) {
        for (int column = 0; column < width; ++column) {
            // Image coordinates: x to the E, y to the N (rows go down).
            const double x = column + 0.5 - cx, y = cy - (row + 0.5);
            const double source_x = c * x + s * y, source_y = -s * x + c * y;
            const int sx = static_cast<int>(std::floor(source_x + cx));
            const int sy = static_cast<int>(std::floor(cy - source_y));
            const std::size_t index = static_cast<std::size_t>(row) * width + column;
            if (sx < 0 || sy < 0 || sx >= width || sy >= height) {
                result.grain[index] = outside;
                if (per_pixel) result.thickness_um[index] = outside_thickness_um;
                continue;
            }
            const int grain = section.grain_index_of_label[section.labels[static_cast<std::size_t>(sy) * width + sx]];
            result.grain[index] = grain;
            if (per_pixel) result.thickness_um[index] = static_cast<float>(section.thickness_at(sx, sy, section.grains[grain]));
        }
    }
    return result;
}

/// One grain's appearance over the thicknesses it takes: `channels` values per entry, entry k at
/// thickness first_um + k·step_um.
struct GrainTable {
    double first_um = 0.0, step_um = 0.0;
    int entries = 1;
    std::vector<float> values;
};

}  // namespace

int section_condenser_rings(const ThinSection& section, const MineralCatalog& catalog, const MicroscopeSettings& microscope) {
    if (microscope.condenser_rings > 0 || microscope.condenser_na == 0.0) return microscope.condenser_rings;
    std::vector<double> thickest(section.grains.size(), 0.0);
    if (section.thickness_kind == ThicknessKind::uniform) {
        for (std::size_t g = 0; g < section.grains.size(); ++g) thickest[g] = section.grains[g].thickness_um.value_or(section.thickness_um);
    } else {
        for (int y = 0; y < section.height_px; ++y) {
            for (int x = 0; x < section.width_px; ++x) {
                const int g = section.grain_index_of_label[section.labels[static_cast<std::size_t>(y) * section.width_px + x]];
                thickest[g] = std::max(thickest[g], section.thickness_at(x, y, section.grains[g]));
            }
        }
    }
    double spread = 0.0;
    for (std::size_t g = 0; g < section.grains.size(); ++g) {
        const DispersiveMedium medium = DispersiveMedium::of(catalog.find(section.grains[g].mineral));
        spread = std::max(spread, condenser_phase_spread_rad(microscope, medium, thickest[g]));
    }
    return condenser_rings_for(microscope.condenser_na, spread);
}

void OrthoscopeSettings::validate() const {
    const MicroscopeSettings& m = microscope;
    for (const double angle : {m.polars.polarizer_deg, m.polars.analyzer_deg, m.stage_deg}) {
        if (!std::isfinite(angle)) throw InputError("angles must be finite numbers of degrees");
    }
    condenser_samples(m.condenser_na, 0);  // checks the NA (its own message) without sampling the cone
    if (m.wavelengths_nm.empty()) throw InputError("no wavelengths to evaluate");
    for (const double wavelength : m.wavelengths_nm) {
        if (!(wavelength > 0.0) || !std::isfinite(wavelength)) throw InputError("wavelengths must be positive numbers of nanometres");
    }
    for (const double thickness : {mounting.slide_um, mounting.lower_cement_um, mounting.upper_cement_um, mounting.cover_um}) {
        if (!(thickness >= 0.0) || !std::isfinite(thickness)) throw InputError("mounting layer thicknesses must be finite and >= 0");
    }
}

SectionMounting standard_mounting(const MineralCatalog& catalog) {
    SectionMounting mounting;
    mounting.slide = DispersiveMedium::of(catalog.find("crown glass"));
    mounting.cover = mounting.slide;
    mounting.cement = DispersiveMedium::of(catalog.find("canada balsam"));
    return mounting;
}

Image render_orthoscope(const ThinSection& section, const MineralCatalog& catalog, const OrthoscopeSettings& settings,
                        const SpectralIntegrator* integrator, const ProgressCallback& progress) {
    settings.validate();
    const std::vector<double>& wavelengths = settings.microscope.wavelengths_nm;
    if (integrator == nullptr && wavelengths.size() != 1) throw InputError("a monochromatic image needs exactly one wavelength");
    if (integrator != nullptr && integrator->weights().size() != wavelengths.size()) {
        throw InputError("the colour integrator and the image use different wavelength grids");
    }
    if (section.grain_index_of_label.empty()) throw InputError("the thin section's grains are not indexed (call validate())");
    const int channels = integrator != nullptr ? 3 : 1;
    const PixelGrains pixels = pixel_grains(section, settings.microscope.stage_deg);

    // The thickness range of each grain (the last entry: outside the section, glass and balsam only).
    const std::size_t grain_count = section.grains.size() + 1;
    std::vector<double> thinnest(grain_count, std::numeric_limits<double>::infinity());
    std::vector<double> thickest(grain_count, -std::numeric_limits<double>::infinity());
    const auto grain_thickness = [&](std::size_t g) {  // uniform sections
        return g < section.grains.size() && section.grains[g].thickness_um ? *section.grains[g].thickness_um : section.thickness_um;
    };
    for (std::size_t k = 0; k < pixels.grain.size(); ++k) {
        const auto g = static_cast<std::size_t>(pixels.grain[k]);
        const double thickness = pixels.thickness_um.empty() ? grain_thickness(g) : pixels.thickness_um[k];
        thinnest[g] = std::min(thinnest[g], thickness);
        thickest[g] = std::max(thickest[g], thickness);
    }
    std::vector<DispersiveMedium> media;
    for (const ThinSectionGrain& grain : section.grains) {
        media.push_back(DispersiveMedium::of(catalog.find(grain.mineral), grain.crystal_axes, grain.handedness.value_or(Handedness::right)));
    }
    media.push_back(settings.mounting.cement);

    const double middle_wavelength_nm = wavelengths[wavelengths.size() / 2];
    MicroscopeSettings microscope = settings.microscope;
    microscope.condenser_rings = section_condenser_rings(section, catalog, microscope);
    const MicroscopeOptics optics(microscope, settings.mounting);
    std::vector<GrainTable> tables(grain_count);
    ProgressRelay relay(progress);
    std::atomic<int> grains_done{0};
#pragma omp parallel for schedule(dynamic)
    for (std::size_t g = 0; g < grain_count; ++g) {
        if (!std::isfinite(thinnest[g]) || relay.cancelled()) continue;  // not in view, or cancelled
        GrainTable& table = tables[g];
        const double span = thickest[g] - thinnest[g];
        table.first_um = thinnest[g];
        if (span > 0.0) {
            const double birefringence = std::max(media[g].birefringence(middle_wavelength_nm), 1e-4);
            table.entries = std::min(kMaxTableEntries, static_cast<int>(std::ceil(span * birefringence / kRetardationStepUm)) + 1);
            table.step_um = span / (table.entries - 1);
        }
        const GrainResponse response(optics, media[g]);
        table.values.resize(static_cast<std::size_t>(table.entries) * channels);
        response.transmission_series(table.first_um, table.step_um, table.entries, [&](int k, const std::vector<double>& spectrum) {
            if (integrator != nullptr) {
                const Eigen::Vector3d xyz = integrator->integrate(spectrum);
                for (int c = 0; c < 3; ++c) table.values[static_cast<std::size_t>(k) * 3 + c] = static_cast<float>(xyz[c]);
            } else {
                table.values[k] = static_cast<float>(spectrum[0]);
            }
        });
        relay.count_done(grains_done, static_cast<int>(grain_count));
    }
    relay.stop_if_cancelled();

    Image image(section.width_px, section.height_px, channels);
#pragma omp parallel for schedule(static)
    for (std::size_t k = 0; k < pixels.grain.size(); ++k) {
        const GrainTable& table = tables[pixels.grain[k]];
        double position = table.step_um > 0.0 ? (pixels.thickness_um[k] - table.first_um) / table.step_um : 0.0;  // step 0: one entry
        position = std::clamp(position, 0.0, static_cast<double>(table.entries - 1));
        const int below = std::min(static_cast<int>(position), table.entries - 1);
        const int above = std::min(below + 1, table.entries - 1);
        const float fraction = static_cast<float>(position - below);
        for (int c = 0; c < channels; ++c) {
            const float low = table.values[static_cast<std::size_t>(below) * channels + c];
            const float high = table.values[static_cast<std::size_t>(above) * channels + c];
            image.pixels[k * channels + c] = low + fraction * (high - low);
        }
    }
    return image;
}

}  // namespace petroscope
