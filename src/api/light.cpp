#include "petroscope/api/light.hpp"

#include "petroscope/core/error.hpp"
#include "petroscope/io/data_files.hpp"
#include "petroscope/spectral/color.hpp"

#include <cmath>

namespace petroscope {

std::vector<double> Light::wavelengths_nm() const {
    return monochromatic() ? std::vector<double>{*wavelength_nm} : grid.wavelengths_nm();
}

void Light::validate() const {
    if (!(exposure > 0.0) || !std::isfinite(exposure)) throw InputError("the exposure must be a finite number > 0");
    if (monochromatic() && !(*wavelength_nm > 0.0 && std::isfinite(*wavelength_nm))) {
        throw InputError("the wavelength must be a finite number > 0 nm");
    }
    if (!monochromatic()) grid.validate();
}

namespace {

SpectralIntegrator white_light_integrator(const Light& light, const LightSource& source) {
    return SpectralIntegrator(light.wavelengths_nm(), load_cie_1931_observer(), source);
}

}  // namespace

SpectralIntegrator white_light_integrator(const Light& light) {
    return white_light_integrator(light, load_light_source(light.illuminant));
}

DisplayImage render_in_light(const Light& light, const std::function<Image(const SpectralIntegrator*)>& render) {
    light.validate();
    if (light.monochromatic()) return {gray_image_to_rgb(render(nullptr), light.exposure), ""};
    const LightSource source = load_light_source(light.illuminant);
    const SpectralIntegrator integrator = white_light_integrator(light, source);
    const Image xyz = render(&integrator);
    return {xyz_image_to_linear_srgb(xyz, integrator.white_xyz(), light.white_balance, light.exposure), source.name};
}

std::vector<Eigen::Vector3d> rgb_per_transmission(const Light& light) {
    light.validate();
    if (light.monochromatic()) return {Eigen::Vector3d::Constant(light.exposure)};
    const SpectralIntegrator integrator = white_light_integrator(light, load_light_source(light.illuminant));
    const Eigen::Matrix3d display = xyz_to_display_matrix(integrator.white_xyz(), light.white_balance, light.exposure);
    std::vector<Eigen::Vector3d> weights;
    for (const Eigen::Vector3d& weight : integrator.weights()) weights.push_back(display * weight);
    return weights;
}

}  // namespace petroscope
