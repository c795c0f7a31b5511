#include "petroscope/microscope/conoscope.hpp"

#include "petroscope/core/error.hpp"
#include "petroscope/optics/indicatrix.hpp"
#include "petroscope/optics/orientation.hpp"
#include "petroscope/optics/slab.hpp"

#include <atomic>
#ifdef _OPENMP
#include <omp.h>
#endif
#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>

namespace petroscope {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

// Everything that does not depend on the image point, per wavelength.
class ConoscopeEvaluator {
public:
    ConoscopeEvaluator(const ConoscopeSettings& settings, const PrincipalIndexFunction& principal_n)
        : settings_(settings),
          polarizer_(std::cos(settings.polarizer_deg * kDegree), std::sin(settings.polarizer_deg * kDegree)),
          analyzer_(std::cos(settings.analyzer_deg * kDegree), std::sin(settings.analyzer_deg * kDegree)) {
        const Eigen::Matrix3d axes = rotation_z_deg(settings.stage_deg) * settings.crystal_axes;
        for (const double wavelength_nm : settings.wavelengths_nm) {
            Indicatrix indicatrix{principal_n(wavelength_nm), axes};
            if (!indicatrix.principal_n.allFinite() || indicatrix.principal_n.minCoeff() <= 0.0) {
                std::ostringstream what;
                what << "the crystal's principal indices at " << wavelength_nm << " nm are not positive and finite";
                throw InputError(what.str());
            }
            frames_.emplace_back(indicatrix);
            k0_thickness_.push_back(2.0 * std::numbers::pi * settings.thickness_um * 1e3 / wavelength_nm);
        }
    }

    // Transmission after the analyzer (or total, analyzer out) relative to the incident intensity, for
    // the direction with tangential wavevector ξ, at every wavelength.
    void transmission(const Eigen::Vector2d& xi, double* out) const {
        const TangentialWavevector direction = TangentialWavevector::from_xi(xi);
        // An aplanatic condenser and objective keep the s and p amplitudes of each ray (Born & Wolf §8.8,
        // Richards & Wolf 1959): the polarizer's field P splits as (P·ŝ, P·ρ̂) in the (s, p) basis.
        const Eigen::Vector2d incident(polarizer_.dot(direction.azimuthal), polarizer_.dot(direction.radial));
        const Eigen::Vector2d analyzer(analyzer_.dot(direction.azimuthal), analyzer_.dot(direction.radial));
        Eigen::Vector2d guess = Eigen::Vector2d::Constant(std::numeric_limits<double>::quiet_NaN());
        const double n = settings_.surround_n;
        for (std::size_t w = 0; w < frames_.size(); ++w) {
            const SlabModes modes = solve_slab_modes(frames_[w], direction, guess);
            const SlabTransfer transfer = slab_transfer(modes, direction, n, n);
            if (!transfer.propagating) {
                out[w] = 0.0;
                guess.setConstant(std::numeric_limits<double>::quiet_NaN());
                continue;
            }
            guess = transfer.q;
            // Mode amplitudes are real for a lossless crystal between lossless media below the critical
            // angle, so each output amplitude is Σₘ cₘ·exp(iφₘ) with real cₘ, and
            // |c₀e^{iφ₀} + c₁e^{iφ₁}|² = (c₀ − c₁)² + 4c₀c₁cos²(δ/2) = (c₀ + c₁)² − 4c₀c₁sin²(δ/2),
            // δ = φ₀ − φ₁; the form whose terms are both non-negative is used, so rounding never makes an
            // intensity negative.
            const Eigen::Vector2d mode_amplitudes = transfer.entry * incident;
            const double half_phase_sine = std::sin(0.5 * k0_thickness_[w] * (transfer.q[0] - transfer.q[1]));
            const double sin2 = half_phase_sine * half_phase_sine;
            const auto intensity = [&](const Eigen::Vector2d& c) {
                const double product = c[0] * c[1];
                return product >= 0.0 ? (c[0] - c[1]) * (c[0] - c[1]) + 4.0 * product * (1.0 - sin2)
                                      : (c[0] + c[1]) * (c[0] + c[1]) - 4.0 * product * sin2;
            };
            if (settings_.analyzer_in) {
                const Eigen::Vector2d c = (analyzer.transpose() * transfer.exit).transpose().cwiseProduct(mode_amplitudes);
                out[w] = intensity(c);
            } else {
                out[w] = intensity(transfer.exit.row(0).transpose().cwiseProduct(mode_amplitudes)) +
                         intensity(transfer.exit.row(1).transpose().cwiseProduct(mode_amplitudes));
            }
        }
    }

    std::size_t wavelength_count() const { return frames_.size(); }

private:
    const ConoscopeSettings& settings_;
    Eigen::Vector2d polarizer_, analyzer_;
    std::vector<BinormalFrame> frames_;
    std::vector<double> k0_thickness_;
};

}  // namespace

void ConoscopeSettings::validate() const {
    const auto fail = [](const std::string& what) { throw InputError(what); };
    if (size_px < 64 || size_px > 4096) fail("image size " + std::to_string(size_px) + " px is out of range (expected 64 to 4096)");
    if (!(numerical_aperture > 0.0 && numerical_aperture < 1.0)) {
        fail("numerical aperture " + std::to_string(numerical_aperture) + " is out of range (expected 0 < NA < 1, objective in air)");
    }
    if (!(thickness_um > 0.0) || !std::isfinite(thickness_um)) fail("thickness must be a positive length, e.g. 30um");
    if (!(surround_n >= 1.0) || !std::isfinite(surround_n)) fail("surrounding-medium index must be a finite number >= 1");
    if (surround_n <= numerical_aperture) fail("surrounding-medium index must exceed the numerical aperture");
    for (const double angle : {polarizer_deg, analyzer_deg, stage_deg}) {
        if (!std::isfinite(angle)) fail("angles must be finite numbers of degrees");
    }
    if (wavelengths_nm.empty()) fail("no wavelengths to evaluate");
    for (const double wavelength : wavelengths_nm) {
        if (!(wavelength > 0.0) || !std::isfinite(wavelength)) fail("wavelengths must be positive numbers of nanometres");
    }
    if (!crystal_axes.allFinite() || !(crystal_axes.transpose() * crystal_axes).isIdentity(1e-9)) {
        fail("crystal orientation is not a rotation");
    }
}

Eigen::Vector2d conoscope_tangential_wavevector(const ConoscopeSettings& settings, int column, int row) {
    const double half = 0.5 * settings.size_px;
    const double x = (column + 0.5 - half) / half;
    const double y = -(row + 0.5 - half) / half;
    return settings.numerical_aperture * Eigen::Vector2d(x, y);
}

std::vector<double> conoscope_point_transmission(const ConoscopeSettings& settings,
                                                 const PrincipalIndexFunction& principal_n,
                                                 const Eigen::Vector2d& xi) {
    settings.validate();
    const ConoscopeEvaluator evaluator(settings, principal_n);
    std::vector<double> transmission(evaluator.wavelength_count());
    evaluator.transmission(xi, transmission.data());
    return transmission;
}

Image render_conoscope(const ConoscopeSettings& settings, const PrincipalIndexFunction& principal_n,
                       const SpectralIntegrator* integrator, const ProgressCallback& progress) {
    settings.validate();
    if (integrator == nullptr && settings.wavelengths_nm.size() != 1) {
        throw InputError("a monochromatic figure needs exactly one wavelength");
    }
    if (integrator != nullptr && integrator->weights().size() != settings.wavelengths_nm.size()) {
        throw InputError("the colour integrator and the figure use different wavelength grids");
    }
    const ConoscopeEvaluator evaluator(settings, principal_n);
    const int size = settings.size_px;
    Image image(size, size, integrator != nullptr ? 3 : 1);
    std::atomic<int> rows_done{0};
    const double aperture_squared = settings.numerical_aperture * settings.numerical_aperture;

#pragma omp parallel
    {
        std::vector<double> transmission(evaluator.wavelength_count());
#pragma omp for schedule(dynamic, 4)
        for (int row = 0; row < size; ++row) {
            for (int column = 0; column < size; ++column) {
                const Eigen::Vector2d xi = conoscope_tangential_wavevector(settings, column, row);
                if (xi.squaredNorm() > aperture_squared) continue;
                evaluator.transmission(xi, transmission.data());
                if (integrator == nullptr) {
                    image.at(column, row, 0) = static_cast<float>(transmission[0]);
                } else {
                    const Eigen::Vector3d xyz = integrator->integrate(transmission);
                    for (int c = 0; c < 3; ++c) image.at(column, row, c) = static_cast<float>(xyz[c]);
                }
            }
            const int done = ++rows_done;
#ifdef _OPENMP
            const bool reporter = omp_get_thread_num() == 0;
#else
            const bool reporter = true;
#endif
            if (progress && reporter) progress(static_cast<double>(done) / size);
        }
    }
    if (progress) progress(1.0);
    return image;
}

}  // namespace petroscope
