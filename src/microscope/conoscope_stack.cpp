// The conoscope through the whole thin-section stack: each image point is the plane wave of its tangential
// wavevector ξ = NA·(x, y) (in air), sent through the same optical train as the orthoscope's
// (polarizing_microscope.hpp). One MicroscopeOptics per image point (what depends on the wavelength only is shared), single pass or exact 4×4.
#include "conoscope_stack.hpp"

#include <atomic>

namespace petroscope::detail {

Image render_conoscope_through_stack(const ConoscopeSettings& settings, const PrincipalIndexFunction& principal_n,
                                     const SpectralIntegrator* integrator, const ProgressCallback& progress) {
    MicroscopeSettings microscope;
    microscope.polars = {settings.polarizer_deg, settings.analyzer_deg, settings.analyzer_in};
    microscope.stage_deg = settings.stage_deg;
    microscope.plate = settings.plate;
    microscope.exact = settings.exact;
    microscope.wavelengths_nm = settings.wavelengths_nm;
    DispersiveMedium crystal;
    crystal.principal_n = principal_n;
    crystal.gyration = settings.gyration;
    crystal.axes = settings.crystal_axes;
    const MicroscopeOptics common(microscope, *settings.mounting, {});

    const int size = settings.size_px;
    Image image(size, size, integrator != nullptr ? 3 : 1);
    const double aperture_squared = settings.numerical_aperture * settings.numerical_aperture;
    ProgressRelay relay(progress);
    std::atomic<int> rows_done{0};
#pragma omp parallel
    {
        std::vector<double> spectrum;
#pragma omp for schedule(dynamic, 1)
        for (int row = 0; row < size; ++row) {
            if (relay.cancelled()) continue;
            for (int column = 0; column < size; ++column) {
                const Eigen::Vector2d xi = conoscope_tangential_wavevector(settings, column, row);
                if (xi.squaredNorm() > aperture_squared) continue;
                const MicroscopeOptics optics = common.for_directions({IlluminationSample{xi, 1.0}});
                GrainResponse(optics, crystal).transmission(settings.thickness_um, spectrum);
                if (integrator == nullptr) {
                    image.at(column, row, 0) = static_cast<float>(spectrum[0]);
                    continue;
                }
                const Eigen::Vector3d xyz = integrator->integrate(spectrum);
                for (int c = 0; c < 3; ++c) image.at(column, row, c) = static_cast<float>(xyz[c]);
            }
            relay.count_done(rows_done, size);
        }
    }
    relay.finish();
    return image;
}

}  // namespace petroscope::detail
