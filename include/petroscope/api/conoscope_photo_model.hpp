#pragma once
// The model a conoscope fit compares with a photo, built from what the user knows of the photo: the
// mineral and its cut, the light, the microscope. Shared by every front end and the tests.
#include "petroscope/api/light.hpp"
#include "petroscope/fit/conoscope_fit.hpp"
#include "petroscope/minerals/mineral.hpp"
#include "petroscope/optics/gyration.hpp"
#include "petroscope/optics/orientation.hpp"

#include <optional>
#include <utility>

namespace petroscope {

struct ConoscopePhotoSetup {
    std::optional<Cut> cut;  // none: default_cut of the mineral's optical class
    Light light;
    double numerical_aperture = 0.85;
    double polarizer_deg = 0.0;
    double analyzer_deg = 90.0;
    double surround_n = 1.54;  // index on both faces of the slab
    Handedness handedness = Handedness::right;  // of an optically active mineral (quartz)
    Projection projection = Projection::sine;     // how the photo maps directions (sine: a microscope objective)
    FieldStop field_stop = FieldStop::sharp;      // the objective's aperture bounds the field, or nothing does
    IlluminationProfile illumination = IlluminationProfile::even;
};

/// The model of photos of `mineral` (which must outlive it); its orientation is the cut tilted and turned
/// (cut_orientation), its colours the light's display colours. Throws InputError for a bad setting.
ConoscopePhotoModel conoscope_photo_model(const Mineral& mineral, const ConoscopePhotoSetup& setup);

/// Frees the illumination envelope's four parameters for IlluminationProfile::falloff (fix them afterwards to hold
/// one). InputError when one of them is free under even light, where the model has no envelope.
void free_envelope_with_falloff(ConoscopeFitOptions& options, const ConoscopePhotoModel& model);

/// Where the fit searches the thickness: around a starting thickness (÷3 … ×3), over a range MIN … MAX
/// (starting at its geometric mean), or a range with a start; with neither, the options' own range.
/// Throws InputError for a non-positive start or an empty range.
void set_thickness_search(ConoscopeFitOptions& options, std::optional<double> start_um, std::optional<std::pair<double, double>> range_um);

}  // namespace petroscope
