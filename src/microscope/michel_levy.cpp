#include "petroscope/microscope/michel_levy.hpp"

#include "petroscope/core/error.hpp"
#include "petroscope/core/text.hpp"
#include "petroscope/optics/orientation.hpp"

#include <cmath>

namespace petroscope {
namespace {

/// The classic chart's plate: n_fast = 1.544, n_slow = 1.553 at every wavelength (quartz-like, no dispersion).
constexpr double kClassicFastN = 1.544;
constexpr double kClassicBirefringence = 0.009;

}  // namespace

void MichelLevySettings::validate() const {
    if (!(max_retardation_nm > 0.0 && max_retardation_nm <= 20000.0)) {
        throw InputError("maximum retardation " + format_number(max_retardation_nm) + " nm is out of range (expected 0 < max <= 20000)");
    }
    if (!(step_nm > 0.0) || max_retardation_nm / step_nm > 1e6) {
        throw InputError("retardation step " + format_number(step_nm) + " nm is out of range (expected > 0, at most 1e6 steps)");
    }
    if (!(reference_wavelength_nm > 0.0)) throw InputError("reference wavelength must be > 0");
    if (wavelengths_nm.empty()) throw InputError("no wavelengths to evaluate");
    if (mineral != nullptr && mineral->optical_class == OpticalClass::isotropic) {
        throw InputError(mineral->name + " is isotropic: it has no birefringence to chart");
    }
}

DispersiveMedium michel_levy_plate(const MichelLevySettings& settings, double& birefringence_at_reference) {
    // X (fast) along NW–SE, Z (slow) along NE–SW, Y along the microscope axis.
    const double half = std::sqrt(0.5);
    Eigen::Matrix3d axes;
    axes << -half, 0.0, half,  //
        half, 0.0, half,       //
        0.0, 1.0, 0.0;
    if (settings.mineral == nullptr) {
        DispersiveMedium plate;
        plate.principal_n = [](double) {
            return Eigen::Vector3d(kClassicFastN, kClassicFastN + 0.5 * kClassicBirefringence, kClassicFastN + kClassicBirefringence);
        };
        plate.axes = axes;
        birefringence_at_reference = kClassicBirefringence;
        return plate;
    }
    const Mineral& mineral = *settings.mineral;
    const Eigen::Vector3d n = mineral.principal_n(settings.reference_wavelength_nm);
    birefringence_at_reference = n[2] - n[0];
    DispersiveMedium plate = DispersiveMedium::of(mineral, axes);
    plate.principal_kappa = nullptr;  // the chart shows interference colours, not body colours
    if (birefringence_at_reference < 0.0) {
        // A negative uniaxial crystal: Z (the optic axis) is its fast direction.
        birefringence_at_reference = -birefringence_at_reference;
    }
    return plate;
}

std::vector<MichelLevyStep> michel_levy_colours(const MichelLevySettings& settings, const SectionMounting& mounting,
                                                const SpectralIntegrator& integrator) {
    settings.validate();
    if (integrator.weights().size() != settings.wavelengths_nm.size()) {
        throw InputError("the colour integrator and the chart use different wavelength grids");
    }
    double birefringence = 0.0;
    const DispersiveMedium plate = michel_levy_plate(settings, birefringence);
    MicroscopeSettings microscope;
    microscope.wavelengths_nm = settings.wavelengths_nm;
    const MicroscopeOptics optics(microscope, mounting);
    const GrainResponse response(optics, plate);
    std::vector<MichelLevyStep> steps;
    std::vector<double> spectrum;
    const auto count = static_cast<long>(std::floor(settings.max_retardation_nm / settings.step_nm + 1e-9));
    for (long k = 0; k <= count; ++k) {
        MichelLevyStep step;
        step.retardation_nm = static_cast<double>(k) * settings.step_nm;
        step.thickness_um = step.retardation_nm * 1e-3 / birefringence;
        response.transmission(step.thickness_um, spectrum);
        step.xyz = integrator.integrate(spectrum);
        steps.push_back(step);
    }
    return steps;
}

}  // namespace petroscope
