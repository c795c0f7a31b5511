#pragma once
// The Michel-Lévy chart's colours as every front end asks for them: a plate (classic, or a mineral's real
// dispersion) between crossed polars at retardations 0 … max, in white light, as XYZ and display colours.
// Drawing the chart is io/chart_drawing.hpp's.
#include "petroscope/api/light.hpp"
#include "petroscope/microscope/michel_levy.hpp"
#include "petroscope/minerals/mineral_catalog.hpp"

#include <Eigen/Core>

#include <optional>
#include <string>
#include <vector>

namespace petroscope {

struct MichelLevyRequest {
    std::optional<std::string> mineral;  // its real dispersion of birefringence; none: the classic chart
    double max_retardation_nm = 2000.0;
    double step_nm = 1.0;
    Light light;  // white light; its exposure is not used (the chart's white is the light itself)
};

struct MichelLevyColours {
    std::vector<MichelLevyStep> steps;           // retardation, plate thickness, XYZ (Y = 1 for the light)
    std::vector<Eigen::Vector3d> linear_srgb;    // the display colour of each step
    std::string illuminant;
    double birefringence_at_reference = 0.0;     // of the plate, at settings.reference_wavelength_nm
    MichelLevySettings settings;                 // as used (the mineral: the catalog's, which must outlive it)
};

/// Throws InputError naming the bad value (monochromatic light included: the chart is of white light).
MichelLevyColours michel_levy_chart_colours(const MichelLevyRequest& request, const MineralCatalog& catalog);

}  // namespace petroscope
