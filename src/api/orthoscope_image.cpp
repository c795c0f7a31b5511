#include "petroscope/api/orthoscope_image.hpp"

#include "petroscope/core/error.hpp"
#include "petroscope/microscope/frame_measurements.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace petroscope {

OrthoscopePlan plan_orthoscope(OrthoscopeRequest request, const MineralCatalog& catalog) {
    request.light.validate();
    if (request.condenser_rings < 0 || request.condenser_rings > kMaxCondenserRings) {
        throw InputError("condenser rings must be 0 (automatic) to " + std::to_string(kMaxCondenserRings));
    }
    OrthoscopePlan plan;
    MicroscopeSettings& microscope = plan.settings.microscope;
    microscope.stage_deg = request.stage_deg;
    microscope.polars = {request.polarizer_deg, request.analyzer_deg, request.analyzer_in};
    microscope.condenser_na = request.condenser_na;
    microscope.condenser_rings = request.condenser_rings;
    microscope.exact = request.exact;
    microscope.wavelengths_nm = request.light.wavelengths_nm();
    plan.settings.mounting = standard_mounting(catalog);
    microscope.plate = make_plate(request.plate, catalog);
    plan.settings.validate();
    plan.section = std::move(request.section);
    if (request.thickness_um) {
        if (!(*request.thickness_um > 0.0) || !std::isfinite(*request.thickness_um)) throw InputError("the thickness must be a positive length");
        plan.section.thickness_kind = ThicknessKind::uniform;
        plan.section.thickness_um = *request.thickness_um;
    }
    plan.section.validate();
    microscope.condenser_rings = section_condenser_rings(plan.section, catalog, microscope);
    plan.catalog = &catalog;
    plan.light = request.light;
    std::vector<std::string> warned;
    for (const ThinSectionGrain& grain : plan.section.grains) {
        if (std::find(warned.begin(), warned.end(), grain.mineral) != warned.end()) continue;
        warned.push_back(grain.mineral);
        for (const std::string& warning : catalog.find(grain.mineral).range_warnings(microscope.wavelengths_nm)) {
            plan.notes.push_back("warning: " + warning);
        }
    }
    return plan;
}

OrthoscopeImage render_orthoscope_image(const OrthoscopePlan& plan, const ProgressCallback& progress) {
    OrthoscopeImage result;
    result.image = render_in_light(plan.light, [&](const SpectralIntegrator* integrator) {
        return render_orthoscope(plan.section, *plan.catalog, plan.settings, integrator, progress);
    });
    // Whole-field means: between crossed polars a grain at extinction darkens the field.
    const MeanColour mean = mean_colour(result.image.linear_rgb, false);
    result.measurements = {{"mean_r", mean.r}, {"mean_g", mean.g}, {"mean_b", mean.b}, {"mean_luminance", mean.luminance}};
    return result;
}

}  // namespace petroscope
