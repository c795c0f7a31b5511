#include "petroscope/api/michel_levy_chart.hpp"

#include "petroscope/core/error.hpp"
#include "petroscope/microscope/orthoscope.hpp"
#include "petroscope/spectral/color.hpp"

namespace petroscope {

MichelLevyColours michel_levy_chart_colours(const MichelLevyRequest& request, const MineralCatalog& catalog) {
    if (request.light.monochromatic()) throw InputError("the Michel-Lévy chart needs white light (its colours are white light's)");
    Light light = request.light;
    light.exposure = 1.0;
    MichelLevyColours chart;
    MichelLevySettings& settings = chart.settings;
    settings.max_retardation_nm = request.max_retardation_nm;
    settings.step_nm = request.step_nm;
    settings.wavelengths_nm = light.wavelengths_nm();
    if (request.mineral) settings.mineral = &catalog.find(*request.mineral);
    settings.validate();
    michel_levy_plate(settings, chart.birefringence_at_reference);
    const SectionMounting mounting = standard_mounting(catalog);
    DisplayImage display = render_in_light(light, [&](const SpectralIntegrator* integrator) {
        chart.steps = michel_levy_colours(settings, mounting, *integrator);
        Image xyz(static_cast<int>(chart.steps.size()), 1, 3);
        for (std::size_t k = 0; k < chart.steps.size(); ++k) {
            for (int c = 0; c < 3; ++c) xyz.at(static_cast<int>(k), 0, c) = static_cast<float>(chart.steps[k].xyz[c]);
        }
        return xyz;
    });
    for (int k = 0; k < display.linear_rgb.width; ++k) {
        chart.linear_srgb.emplace_back(display.linear_rgb.at(k, 0, 0), display.linear_rgb.at(k, 0, 1), display.linear_rgb.at(k, 0, 2));
    }
    chart.illuminant = display.illuminant;
    return chart;
}

}  // namespace petroscope
