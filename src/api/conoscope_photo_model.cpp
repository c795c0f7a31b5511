#include "petroscope/api/conoscope_photo_model.hpp"

#include "petroscope/api/crystal_orientation.hpp"
#include "petroscope/core/error.hpp"
#include "petroscope/microscope/polarizing_microscope.hpp"

#include <array>
#include <cmath>
#include <string>
#include <tuple>

namespace petroscope {

ConoscopePhotoModel conoscope_photo_model(const Mineral& mineral, const ConoscopePhotoSetup& setup) {
    ConoscopePhotoModel model;
    model.settings.numerical_aperture = setup.numerical_aperture;
    model.settings.polarizer_deg = setup.polarizer_deg;
    model.settings.analyzer_deg = setup.analyzer_deg;
    model.settings.surround_n = setup.surround_n;
    model.settings.wavelengths_nm = setup.light.wavelengths_nm();
    model.settings.validate();
    model.principal_n = [&mineral](double nm) { return mineral.principal_n(nm); };
    const Cut cut = setup.cut.value_or(default_cut(mineral.optical_class));
    const Eigen::Vector3d reference_n = mineral.principal_n(mineral.reference_wavelength_nm);
    const OpticalClass optical_class = mineral.optical_class;
    cut_orientation(cut, optical_class, reference_n, 0.0, 0.0);  // throws now for a cut the class does not have
    model.orientation = [cut, optical_class, reference_n](double tilt_deg, double azimuth_deg) {
        return cut_orientation(cut, optical_class, reference_n, azimuth_deg, tilt_deg);
    };
    model.rgb_per_transmission = rgb_per_transmission(setup.light);
    model.settings.gyration = mineral_gyration(mineral, setup.handedness);
    model.projection = setup.projection;
    model.field_stop = setup.field_stop;
    model.illumination = setup.illumination;
    return model;
}

void free_envelope_with_falloff(ConoscopeFitOptions& options, const ConoscopePhotoModel& model) {
    constexpr std::array<PhotoParameter, 4> kEnvelope{PhotoParameter::envelope_center_x_px, PhotoParameter::envelope_center_y_px,
                                                      PhotoParameter::envelope_radius_px, PhotoParameter::envelope_power};
    for (const PhotoParameter p : kEnvelope) {
        bool& free = options.free[static_cast<std::size_t>(p)];
        if (model.illumination == IlluminationProfile::falloff) {
            free = true;
        } else if (free) {
            throw InputError("the illumination is even, so there is no envelope to fit (" + std::string(photo_parameter_name(p)) +
                             "); choose the falloff illumination");
        }
    }
}

void set_thickness_search(ConoscopeFitOptions& options, std::optional<double> start_um, std::optional<std::pair<double, double>> range_um) {
    if (start_um && !(*start_um > 0.0 && std::isfinite(*start_um))) throw InputError("the starting thickness must be a positive length");
    if (range_um && !(range_um->first > 0.0 && range_um->second > range_um->first && std::isfinite(range_um->second))) {
        throw InputError("the thickness range must be MIN < MAX, both positive");
    }
    if (start_um) {
        options.thickness_min_um = *start_um / 3.0;
        options.thickness_max_um = *start_um * 3.0;
    }
    if (range_um) std::tie(options.thickness_min_um, options.thickness_max_um) = *range_um;
    at(options.initial, PhotoParameter::thickness_um) = start_um.value_or(std::sqrt(options.thickness_min_um * options.thickness_max_um));
}

}  // namespace petroscope
