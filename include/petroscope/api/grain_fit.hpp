#pragma once
// A grain's thickness (and optic orientation) fitted to its colours in orthoscopic photos, as every front
// end asks for it (the CLI's `fit orthoscope`, Python's fit_orthoscope): the photos' measured colours and
// how each was taken, what is known of the grain, the light. The method: fit/orthoscope_fit.hpp.
#include "petroscope/api/light.hpp"
#include "petroscope/api/plate.hpp"
#include "petroscope/core/progress.hpp"
#include "petroscope/fit/orthoscope_fit.hpp"
#include "petroscope/minerals/mineral_catalog.hpp"

#include <Eigen/Core>

#include <optional>
#include <string>
#include <vector>

namespace petroscope {

/// One photo of the grain: its colour (grain_colour) and how it was taken.
struct GrainFitPhoto {
    GrainColour colour;
    double stage_deg = 0.0;
    std::optional<PlateRequest> plate;
    std::string label;  // for messages and reports, e.g. the file name
    std::optional<GrainColour> reference;  // the reference region's colour (GrainPhoto::reference), if given
};

struct GrainFitRequest {
    std::string mineral;
    std::vector<GrainFitPhoto> photos;
    GrainOrientation orientation = GrainOrientation::max_birefringence;
    std::optional<Eigen::Vector3d> euler_zyz_deg;  // the indicatrix at stage 0: needed with `known`, only then
    double thickness_min_um = 1.0, thickness_max_um = 200.0;  // the global search range
    bool exposure_free = false;
    int candidates = 4;  // grid minima refined, 1 … 20
    double condenser_na = 0.0;
    double polarizer_deg = 0.0, analyzer_deg = 90.0;
    Light light;  // white: the photos' interference colours
    Handedness handedness = Handedness::right;  // the form of an optically active mineral (quartz)
};

/// A request checked and resolved against the catalog; the catalog must outlive it.
struct GrainFitPlan {
    const Mineral* mineral = nullptr;
    std::vector<GrainPhoto> photos;
    OrthoscopeFitOptions options;
    Light light;
};

/// Throws InputError naming the bad value (monochromatic light, an orientation without its angles, …).
GrainFitPlan plan_grain_fit(const GrainFitRequest& request, const MineralCatalog& catalog);

/// Fits; throws Cancelled when `progress` says stop.
OrthoscopeFitResult fit_grain(const GrainFitPlan& plan, const ProgressCallback& progress = {});

}  // namespace petroscope
