#pragma once
// The light through the microscope, as every front end describes it: white light (an illuminant sampled
// on a wavelength grid) or one wavelength; and the conversion of a rendered figure to display colours.
#include "petroscope/core/image.hpp"
#include "petroscope/spectral/colorimetry.hpp"
#include "petroscope/spectral/wavelength_grid.hpp"

#include <Eigen/Core>

#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace petroscope {

struct Light {
    std::optional<double> wavelength_nm;  // monochromatic light at this wavelength; none: white light
    WavelengthGrid grid;                  // white light: the wavelengths sampled
    std::string illuminant = "D65";       // white light: D65, A (halogen) or blackbody:<T>K
    bool white_balance = true;            // white light: a white object shows white (von Kries in XYZ)
    double exposure = 1.0;                // every pixel value is multiplied by it

    bool monochromatic() const { return wavelength_nm.has_value(); }
    std::vector<double> wavelengths_nm() const;
    /// Throws InputError naming the bad value (a non-positive wavelength or exposure).
    void validate() const;
};

/// A figure in display colours: linear sRGB, 3 channels; `illuminant` is the illuminant's name in white
/// light and empty in monochromatic light (where every channel is the transmitted intensity).
struct DisplayImage {
    Image linear_rgb;
    std::string illuminant;
};

/// Renders with `render`, given the colour integrator of the light (nullptr in monochromatic light, where
/// `render` returns one channel of transmission), and converts to linear sRGB, white balanced as asked.
DisplayImage render_in_light(const Light& light, const std::function<Image(const SpectralIntegrator*)>& render);

/// The colour integrator of white light: its wavelengths, the CIE 1931 observer, its illuminant.
SpectralIntegrator white_light_integrator(const Light& light);

/// Linear sRGB per unit transmission at each wavelength of the light: the colour integrator's weights
/// through the display conversion in white light, (exposure, exposure, exposure) in monochromatic light.
std::vector<Eigen::Vector3d> rgb_per_transmission(const Light& light);

}  // namespace petroscope
