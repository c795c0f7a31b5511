#pragma once
// The model a conoscope fit compares with a photo, built from what the user knows of the photo: the
// mineral and its cut, the light, the microscope. Shared by every front end and the tests.
#include "petroscope/api/light.hpp"
#include "petroscope/fit/conoscope_fit.hpp"
#include "petroscope/minerals/mineral.hpp"
#include "petroscope/optics/orientation.hpp"

#include <optional>

namespace petroscope {

struct ConoscopePhotoSetup {
    std::optional<Cut> cut;  // none: default_cut of the mineral's optical class
    Light light;
    double numerical_aperture = 0.85;
    double polarizer_deg = 0.0;
    double analyzer_deg = 90.0;
    double surround_n = 1.54;  // index on both faces of the slab
};

/// The model of photos of `mineral` (which must outlive it); its orientation is the cut tilted and turned
/// (cut_orientation), its colours the light's display colours. Throws InputError for a bad setting.
ConoscopePhotoModel conoscope_photo_model(const Mineral& mineral, const ConoscopePhotoSetup& setup);

}  // namespace petroscope
