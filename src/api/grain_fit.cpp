#include "petroscope/api/grain_fit.hpp"

#include "petroscope/core/error.hpp"
#include "petroscope/microscope/orthoscope.hpp"
#include "petroscope/optics/orientation.hpp"

#include <cmath>

namespace petroscope {
namespace {

OrthoscopeFitOptions fit_options(const GrainFitRequest& request, const MineralCatalog& catalog) {
    OrthoscopeFitOptions options;
    options.microscope.wavelengths_nm = request.light.wavelengths_nm();
    options.microscope.condenser_na = request.condenser_na;
    options.microscope.polars = {request.polarizer_deg, request.analyzer_deg, true};
    options.mounting = standard_mounting(catalog);
    options.orientation = request.orientation;
    if (request.euler_zyz_deg) {
        const Eigen::Vector3d& angles = *request.euler_zyz_deg;
        if (!angles.allFinite()) throw InputError("the grain's Euler angles must be finite numbers (degrees)");
        options.known_axes = euler_zyz_deg(angles.x(), angles.y(), angles.z());
    }
    options.thickness_min_um = request.thickness_min_um;
    options.thickness_max_um = request.thickness_max_um;
    options.exposure = request.light.exposure;
    options.white_balance = request.light.white_balance;
    options.exposure_free = request.exposure_free;
    options.candidates = request.candidates;
    options.handedness = request.handedness;
    return options;
}

}  // namespace

GrainFitPlan plan_grain_fit(const GrainFitRequest& request, const MineralCatalog& catalog) {
    request.light.validate();
    if (request.light.monochromatic()) throw InputError("the grain fit needs white light: it reads interference colours");
    if ((request.orientation == GrainOrientation::known) != request.euler_zyz_deg.has_value()) {
        throw InputError(request.euler_zyz_deg ? "the grain's Euler angles give its orientation: they go with the orientation 'known'"
                                               : "the orientation 'known' needs the grain's Euler angles");
    }
    if (request.candidates < 1 || request.candidates > 20) throw InputError("candidates must be 1 to 20");
    if (request.photos.empty()) throw InputError("no photo to fit");
    GrainFitPlan plan{&catalog.find(request.mineral), {}, fit_options(request, catalog), request.light};
    OrthoscopeSettings check;
    check.microscope = plan.options.microscope;
    check.mounting = plan.options.mounting;
    check.validate();
    for (const GrainFitPhoto& photo : request.photos) {
        if (!std::isfinite(photo.stage_deg)) throw InputError("photo " + photo.label + ": the stage angle must be a finite number (degrees)");
        plan.photos.push_back({photo.colour, photo.stage_deg, make_plate(photo.plate, catalog), photo.label, photo.reference});
    }
    return plan;
}

OrthoscopeFitResult fit_grain(const GrainFitPlan& plan, const ProgressCallback& progress) {
    return fit_orthoscope_grain(plan.photos, *plan.mineral, plan.options, white_light_integrator(plan.light), progress);
}

}  // namespace petroscope
