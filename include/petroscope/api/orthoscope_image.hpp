#pragma once
// A thin section in orthoscopy as every front end asks for it: the request in the user's terms, validated
// into a plan, rendered to display colours and measured.
#include "petroscope/api/light.hpp"
#include "petroscope/api/measurements.hpp"
#include "petroscope/api/plate.hpp"
#include "petroscope/core/progress.hpp"
#include "petroscope/microscope/orthoscope.hpp"
#include "petroscope/microscope/thin_section.hpp"

#include <optional>
#include <string>
#include <vector>

namespace petroscope {

struct OrthoscopeRequest {
    ThinSection section;                  // from a description file (io/thin_section_file.hpp) or built in memory
    bool analyzer_in = true;              // false: plane-polarized light
    double stage_deg = 0.0;
    double polarizer_deg = 0.0;
    double analyzer_deg = 90.0;
    std::optional<PlateRequest> plate;
    double condenser_na = 0.0;            // 0: parallel light
    int condenser_rings = 0;              // 0: default_condenser_rings
    std::optional<double> thickness_um;   // a uniform thickness instead of the section's
    bool exact = false;                   // coherent 4×4 instead of single pass
    Light light;
};

/// A request checked against the catalog, ready to render; the catalog must outlive it.
struct OrthoscopePlan {
    OrthoscopeSettings settings;
    ThinSection section;
    const MineralCatalog* catalog = nullptr;
    Light light;
    std::vector<std::string> notes;  // each beginning "warning: "
};

/// Throws InputError naming the bad value (no rendering is done).
OrthoscopePlan plan_orthoscope(OrthoscopeRequest request, const MineralCatalog& catalog);

struct OrthoscopeImage {
    DisplayImage image;         // white = the light after the polarizer
    Measurements measurements;  // mean_r, mean_g, mean_b, mean_luminance over the whole field
};

/// Renders and measures; throws Cancelled when `progress` says stop.
OrthoscopeImage render_orthoscope_image(const OrthoscopePlan& plan, const ProgressCallback& progress = {});

}  // namespace petroscope
