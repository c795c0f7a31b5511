#include "petroscope/api/conoscope_figure.hpp"

#include "petroscope/core/error.hpp"
#include "petroscope/core/text.hpp"
#include "petroscope/microscope/frame_measurements.hpp"
#include "petroscope/microscope/orthoscope.hpp"

#include <cmath>
#include <numbers>

namespace petroscope {

SlabMounting parse_slab_mounting(std::string_view name) {
    if (name == "immersed") return SlabMounting::immersed;
    if (name == "thin-section") return SlabMounting::thin_section;
    if (name == "thin-section-exact") return SlabMounting::thin_section_exact;
    throw InputError("mounting " + quote_input(name) + ": expected immersed, thin-section or thin-section-exact");
}

ConoscopePlan plan_conoscope(const ConoscopeRequest& request, const MineralCatalog& catalog) {
    request.light.validate();
    ConoscopePlan plan;
    ConoscopeSettings& settings = plan.settings;
    settings.thickness_um = request.thickness_um;
    settings.numerical_aperture = request.numerical_aperture;
    settings.size_px = request.size_px;
    settings.stage_deg = request.stage_deg;
    settings.polarizer_deg = request.polarizer_deg;
    settings.analyzer_deg = request.analyzer_deg;
    settings.analyzer_in = request.analyzer_in;
    settings.surround_n = request.surround_n;
    settings.wavelengths_nm = request.light.wavelengths_nm();
    settings.spectrum = request.spectrum;
    settings.validate();

    const Mineral& mineral = catalog.find(request.mineral);
    plan.mineral = &mineral;
    settings.plate = make_plate(request.plate, catalog);
    if (request.mounting != SlabMounting::immersed) {
        settings.mounting = standard_mounting(catalog);
        settings.exact = request.mounting == SlabMounting::thin_section_exact;
    }
    settings.crystal_axes = indicatrix_axes(mineral, request.orientation);
    if (mineral.optically_active()) {
        plan.handedness = request.handedness;
        settings.gyration = mineral_gyration(mineral, request.handedness);
    } else if (request.handedness != Handedness::right) {
        plan.notes.push_back("note: " + mineral.name + " is not optically active; the handedness has no effect");
    }
    settings.validate();
    plan.cut = cut_used(mineral, request.orientation);
    plan.light = request.light;
    if (request.light.monochromatic()) plan.axes_wavelength_nm = *request.light.wavelength_nm;
    if (mineral.absorbing()) {
        plan.notes.push_back("note: " + mineral.name + " absorbs (pleochroism); the conoscope uses its refractive indices only, absorption is left out");
    }
    for (const std::string& warning : mineral.range_warnings(settings.wavelengths_nm)) plan.notes.push_back("warning: " + warning);
    return plan;
}

namespace {

// Per optic axis: its image point where the exact model puts it, and the dark spot found there when the
// polars are crossed and no plate is in (a melatope).
void measure_optic_axes(const Image& linear_rgb, const ConoscopePlan& plan, Measurements& measurements) {
    const ConoscopeSettings& settings = plan.settings;
    const std::vector<Eigen::Vector2d> axes = conoscope_optic_axis_points(settings, plan.mineral->principal_n(plan.axes_wavelength_nm));
    const double crossed = std::remainder(settings.analyzer_deg - settings.polarizer_deg, 180.0);
    const bool dark_melatopes = settings.analyzer_in && std::abs(std::abs(crossed) - 90.0) < 1e-9 && !settings.plate;
    for (std::size_t k = 0; k < 2; ++k) {
        const std::string number = std::to_string(k + 1);
        std::optional<Eigen::Vector2d> predicted, found;
        if (k < axes.size() && axes[k].norm() < 1.0) predicted = axes[k];
        if (predicted && dark_melatopes) found = dark_spot_near(linear_rgb, *predicted, settings.size_px / 32, settings.size_px / 256.0);
        for (const auto& [name, point] : {std::pair{"optic_axis_" + number, predicted}, std::pair{"melatope_" + number, found}}) {
            const auto value = [&point](double number_if_any) { return point ? std::optional(number_if_any) : std::nullopt; };
            const Eigen::Vector2d p = point.value_or(Eigen::Vector2d::Zero());
            const double azimuth_deg = std::atan2(p.y(), p.x()) * 180.0 / std::numbers::pi;
            measurements.push_back({name + "_x", value(p.x())});
            measurements.push_back({name + "_y", value(p.y())});
            measurements.push_back({name + "_azimuth_deg", value(azimuth_deg < 0.0 ? azimuth_deg + 360.0 : azimuth_deg)});
            measurements.push_back({name + "_radius", value(p.norm())});
        }
    }
}

}  // namespace

ConoscopeFigure render_conoscope_figure(const ConoscopePlan& plan, const ProgressCallback& progress) {
    const Mineral& mineral = *plan.mineral;
    const PrincipalIndexFunction principal_n = [&mineral](double nm) { return mineral.principal_n(nm); };
    ConoscopeFigure figure;
    figure.image = render_in_light(plan.light, [&](const SpectralIntegrator* integrator) {
        return render_conoscope(plan.settings, principal_n, integrator, progress);
    });
    const MeanColour mean = mean_colour(figure.image.linear_rgb, true);
    figure.measurements = {{"mean_r", mean.r}, {"mean_g", mean.g}, {"mean_b", mean.b}, {"mean_luminance", mean.luminance}};
    measure_optic_axes(figure.image.linear_rgb, plan, figure.measurements);
    return figure;
}

}  // namespace petroscope
