#include "petroscope/api/stage_harmonics.hpp"

#include "petroscope/core/angles.hpp"
#include "petroscope/core/error.hpp"
#include "petroscope/microscope/conoscope.hpp"

#include <cmath>
#include <functional>

namespace petroscope {
namespace {

constexpr double kSampleStepDeg = 36.0;  // φ_k = 36°·k, k = 0 … 4

/// The basis of I(φ): 1, cos 2φ, sin 2φ, cos 4φ, sin 4φ.
std::array<double, kStageHarmonicCount> harmonic_basis(double stage_deg) {
    const double angle = stage_deg * kDegree;
    return {1.0, std::cos(2.0 * angle), std::sin(2.0 * angle), std::cos(4.0 * angle), std::sin(4.0 * angle)};
}

/// The request with the polarizer, the plate and the analyzer turned by `turn_deg` (counter-clockwise).
template <typename Request>
Request with_tube_turned(Request request, double turn_deg) {
    request.polarizer_deg += turn_deg;
    request.analyzer_deg += turn_deg;
    if (request.plate) request.plate->slow_deg += turn_deg;
    return request;
}

template <typename Request>
void require_stage_zero(const Request& request) {
    if (request.stage_deg != 0.0) throw InputError("stage harmonics describe every stage angle: leave the request's stage at 0");
}

/// The coefficients from the pictures at φ_k (`render(k, progress)` gives linear sRGB, 3 channels), by the
/// five-point discrete Fourier transform: c₀ = ⅕ Σ I_k, the others ⅖ Σ I_k·basis(φ_k).
Image harmonic_coefficients(const std::function<DisplayImage(int, const ProgressCallback&)>& render, const ProgressCallback& progress,
                            std::string* illuminant) {
    Image coefficients;
    for (int k = 0; k < kStageHarmonicCount; ++k) {
        const ProgressCallback part = [&](double fraction) { return !progress || progress((k + fraction) / kStageHarmonicCount); };
        const DisplayImage picture = render(k, part);
        const Image& rgb = picture.linear_rgb;
        if (k == 0) {
            coefficients = Image(rgb.width, rgb.height, kStageHarmonicChannels);
            if (illuminant != nullptr) *illuminant = picture.illuminant;
        }
        const std::array<double, kStageHarmonicCount> basis = harmonic_basis(kSampleStepDeg * k);
        std::array<float, kStageHarmonicCount> weights{};
        for (int j = 0; j < kStageHarmonicCount; ++j) weights[j] = static_cast<float>((j == 0 ? 1.0 : 2.0) / kStageHarmonicCount * basis[j]);
        const std::size_t pixels = static_cast<std::size_t>(rgb.width) * static_cast<std::size_t>(rgb.height);
        for (std::size_t p = 0; p < pixels; ++p) {
            for (int j = 0; j < kStageHarmonicCount; ++j) {
                for (int c = 0; c < 3; ++c) coefficients.pixels[p * kStageHarmonicChannels + 3 * j + c] += weights[j] * rgb.pixels[p * 3 + c];
            }
        }
    }
    return coefficients;
}

/// A section of one pixel whose grain is the mounting cement: the field outside the turned section.
ThinSection cement_only_section(double thickness_um) {
    ThinSection section;
    section.name = "outside the section";
    section.width_px = section.height_px = 1;
    section.labels = {1};
    section.grains = {ThinSectionGrain{1, "canada balsam", Eigen::Matrix3d::Identity(), std::nullopt, 0, std::nullopt}};
    section.thickness_um = thickness_um;
    return section;
}

/// The harmonic colour at one point of the field: basis · coefficients.
void add_composed(const float* coefficients, const std::array<double, kStageHarmonicCount>& basis, float weight, float* rgb) {
    for (int j = 0; j < kStageHarmonicCount; ++j) {
        for (int c = 0; c < 3; ++c) rgb[c] += weight * static_cast<float>(basis[j]) * coefficients[3 * j + c];
    }
}

StageHarmonics polarized_conoscope_harmonics(const ConoscopeRequest& request, const MineralCatalog& catalog, const ProgressCallback& progress) {
    StageHarmonics harmonics;
    harmonics.resampling = StageResampling::bilinear;  // beyond the objective's aperture the figure is black: `outside` stays 0
    std::vector<ConoscopePlan> plans;
    for (int k = 0; k < kStageHarmonicCount; ++k) plans.push_back(plan_conoscope(with_tube_turned(request, -kSampleStepDeg * k), catalog));
    if (request.light.monochromatic() || request.mounting != SlabMounting::immersed) {
        const auto render = [&](int k, const ProgressCallback& part) { return render_conoscope_figure(plans[static_cast<std::size_t>(k)], part).image; };
        harmonics.coefficients = harmonic_coefficients(render, progress, &harmonics.illuminant);
        return harmonics;
    }
    // White light through an immersed slab: the five figures share each image point's eigenmodes.
    std::vector<ConoscopeSettings> settings;
    for (const ConoscopePlan& plan : plans) settings.push_back(plan.settings);
    const Mineral& mineral = *plans.front().mineral;
    const std::vector<Image> xyz = render_conoscope_polarization_set(
        settings, [&mineral](double nm) { return mineral.principal_n(nm); }, white_light_integrator(request.light), progress);
    const auto display = [&](int k, const ProgressCallback&) {
        return render_in_light(request.light, [&](const SpectralIntegrator*) { return xyz[static_cast<std::size_t>(k)]; });
    };
    harmonics.coefficients = harmonic_coefficients(display, {}, &harmonics.illuminant);
    return harmonics;
}

StageHarmonics polarized_orthoscope_harmonics(const OrthoscopeRequest& request, const MineralCatalog& catalog, const ProgressCallback& progress) {
    StageHarmonics harmonics;
    harmonics.resampling = StageResampling::containing_pixel;
    double middle_thickness_um = 0.0;
    const auto render = [&](int k, const ProgressCallback& part) {
        const OrthoscopePlan plan = plan_orthoscope(with_tube_turned(request, -kSampleStepDeg * k), catalog);
        middle_thickness_um = plan.section.section_thickness_at(plan.section.width_px / 2, plan.section.height_px / 2);
        return render_orthoscope_image(plan, part).image;
    };
    harmonics.coefficients = harmonic_coefficients(render, progress, &harmonics.illuminant);

    OrthoscopeRequest outside_request = request;
    outside_request.thickness_um.reset();
    outside_request.section = cement_only_section(middle_thickness_um);
    const auto render_outside = [&](int k, const ProgressCallback&) {
        return render_orthoscope_image(plan_orthoscope(with_tube_turned(outside_request, -kSampleStepDeg * k), catalog)).image;
    };
    const Image outside = harmonic_coefficients(render_outside, {}, nullptr);
    std::copy(outside.pixels.begin(), outside.pixels.end(), harmonics.outside.begin());
    return harmonics;
}

/// `polarized(request, progress)` once, or for unpolarized light the mean of it with the polarizer at
/// polarizer_deg and at polarizer_deg + 90°.
template <typename Request, typename Polarized>
StageHarmonics harmonics_in(const Request& request, Illumination illumination, const ProgressCallback& progress, const Polarized& polarized) {
    require_stage_zero(request);
    if (illumination == Illumination::polarized) return polarized(request, progress);
    Request crossed = request;
    crossed.polarizer_deg += 90.0;
    StageHarmonics mean = polarized(request, [&](double f) { return !progress || progress(0.5 * f); });
    const StageHarmonics other = polarized(crossed, [&](double f) { return !progress || progress(0.5 + 0.5 * f); });
    for (std::size_t k = 0; k < mean.coefficients.pixels.size(); ++k) mean.coefficients.pixels[k] = 0.5f * (mean.coefficients.pixels[k] + other.coefficients.pixels[k]);
    for (std::size_t k = 0; k < mean.outside.size(); ++k) mean.outside[k] = 0.5f * (mean.outside[k] + other.outside[k]);
    return mean;
}

}  // namespace

StageHarmonics conoscope_stage_harmonics(const ConoscopeRequest& request, const MineralCatalog& catalog, Illumination illumination,
                                         const ProgressCallback& progress) {
    return harmonics_in(request, illumination, progress, [&](const ConoscopeRequest& r, const ProgressCallback& p) {
        return polarized_conoscope_harmonics(r, catalog, p);
    });
}

StageHarmonics orthoscope_stage_harmonics(const OrthoscopeRequest& request, const MineralCatalog& catalog, Illumination illumination,
                                          const ProgressCallback& progress) {
    return harmonics_in(request, illumination, progress, [&](const OrthoscopeRequest& r, const ProgressCallback& p) {
        return polarized_orthoscope_harmonics(r, catalog, p);
    });
}

Image compose_at_stage(const StageHarmonics& harmonics, double stage_deg) {
    const Image& source = harmonics.coefficients;
    const int width = source.width, height = source.height;
    Image picture(width, height, 3);
    const std::array<double, kStageHarmonicCount> basis = harmonic_basis(stage_deg);
    const double c = std::cos(stage_deg * kDegree), s = std::sin(stage_deg * kDegree);
    const double cx = 0.5 * width, cy = 0.5 * height;
    const auto coefficients_at = [&](int x, int y) {
        if (x < 0 || y < 0 || x >= width || y >= height) return harmonics.outside.data();
        return &source.pixels[(static_cast<std::size_t>(y) * width + x) * kStageHarmonicChannels];
    };
#pragma omp parallel for schedule(static)
    for (int row = 0; row < height; ++row) {
        for (int column = 0; column < width; ++column) {
            // The image point (x to the E, y to the N) shows the unturned picture at R(−φ)·(x, y), as in
            // render_orthoscope; in pixel coordinates of the source, columns to the E, rows down.
            const double x = column + 0.5 - cx, y = cy - (row + 0.5);
            const double source_column = c * x + s * y + cx, source_row = cy - (-s * x + c * y);
            float* rgb = &picture.pixels[(static_cast<std::size_t>(row) * width + column) * 3];
            if (harmonics.resampling == StageResampling::containing_pixel) {
                add_composed(coefficients_at(static_cast<int>(std::floor(source_column)), static_cast<int>(std::floor(source_row))), basis, 1.0f, rgb);
                continue;
            }
            const double u = source_column - 0.5, v = source_row - 0.5;  // between pixel centres
            const int x0 = static_cast<int>(std::floor(u)), y0 = static_cast<int>(std::floor(v));
            const auto fx = static_cast<float>(u - x0), fy = static_cast<float>(v - y0);
            add_composed(coefficients_at(x0, y0), basis, (1 - fx) * (1 - fy), rgb);
            add_composed(coefficients_at(x0 + 1, y0), basis, fx * (1 - fy), rgb);
            add_composed(coefficients_at(x0, y0 + 1), basis, (1 - fx) * fy, rgb);
            add_composed(coefficients_at(x0 + 1, y0 + 1), basis, fx * fy, rgb);
        }
    }
    return picture;
}

}  // namespace petroscope
