#include "petroscope/api/conoscope_photo_model.hpp"

#include "petroscope/api/crystal_orientation.hpp"

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
    return model;
}

}  // namespace petroscope
