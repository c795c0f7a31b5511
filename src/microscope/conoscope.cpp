#include "petroscope/microscope/conoscope.hpp"

#include "conoscope_evaluator.hpp"
#include "conoscope_stack.hpp"

#include "petroscope/core/error.hpp"
#include "petroscope/core/text.hpp"

#include <atomic>
#include <cmath>

namespace petroscope {

void ConoscopeSettings::validate() const {
    const auto fail = [](const std::string& what) { throw InputError(what); };
    if (size_px < 64 || size_px > 4096) fail("image size " + std::to_string(size_px) + " px is out of range (expected 64 to 4096)");
    if (!(numerical_aperture > 0.0 && numerical_aperture < 1.0)) {
        fail("numerical aperture " + format_number(numerical_aperture) + " is out of range (expected 0 < NA < 1, objective in air)");
    }
    if (!(thickness_um > 0.0) || !std::isfinite(thickness_um)) fail("thickness must be a positive length, e.g. 30um");
    if (!(surround_n >= 1.0) || !std::isfinite(surround_n)) fail("surrounding-medium index must be a finite number >= 1");
    if (!mounting && surround_n <= numerical_aperture) fail("surrounding-medium index must exceed the numerical aperture");
    if (exact && !mounting) fail("the exact 4x4 mode needs the whole stack (a mounting)");
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
    const detail::ConoscopeEvaluator evaluator(settings, principal_n);
    std::vector<double> transmission(evaluator.wavelength_count()), opposite(evaluator.wavelength_count());
    detail::KernelScratch scratch;
    evaluator.spectral_pair(xi, scratch, false, transmission.data(), opposite.data());
    return transmission;
}

ConoscopeTerms::ConoscopeTerms(const ConoscopeSettings& settings, const PrincipalIndexFunction& principal_n)
    : settings_(settings) {
    settings_.validate();
    if (settings_.plate || settings_.mounting) throw InputError("interference terms are defined for a slab without a plate or mounting only");
    wavelength_count_ = settings_.wavelengths_nm.size();
    evaluator_ = std::make_unique<detail::ConoscopeEvaluator>(settings_, principal_n);
}

ConoscopeTerms::~ConoscopeTerms() = default;

void ConoscopeTerms::evaluate(const std::vector<Eigen::Vector2d>& xis, std::vector<InterferenceTerms>& out) const {
    const std::size_t count = wavelength_count_;
    out.resize(xis.size() * count);
    const int points = static_cast<int>(xis.size());
#pragma omp parallel
    {
        detail::KernelScratch scratch;
        bool continues = false;
#pragma omp for schedule(static)
        for (int k = 0; k < points; ++k) {
            evaluator_->spectral_terms(xis[static_cast<std::size_t>(k)], scratch, continues, out.data() + static_cast<std::size_t>(k) * count);
            continues = true;
        }
    }
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
    if (settings.mounting) return detail::render_conoscope_through_stack(settings, principal_n, integrator, progress);
    const detail::ConoscopeEvaluator evaluator(settings, principal_n);
    const int size = settings.size_px;
    Image image(size, size, integrator != nullptr ? 3 : 1);
    ProgressRelay relay(progress);
    std::atomic<int> rows_done{0};
    const double aperture_squared = settings.numerical_aperture * settings.numerical_aperture;

    // Pixels are done in pairs (column, row) and (size−1−column, size−1−row), whose directions are
    // opposite (ξ and −ξ): rows 0 … ⌈size/2⌉−1, and of the middle row of an odd size its first half.
    const int paired_rows = (size + 1) / 2;
    // White light: XYZ of the transmission spectrum.
    const auto store = [&](int column, int row, const std::vector<double>& transmission) {
        const Eigen::Vector3d xyz = integrator->integrate(transmission);
        for (int c = 0; c < 3; ++c) image.at(column, row, c) = static_cast<float>(xyz[c]);
    };
#pragma omp parallel
    {
        std::vector<double> plus(evaluator.wavelength_count()), minus(evaluator.wavelength_count());
        std::vector<Eigen::Vector2d> batch_xi;
        std::vector<std::pair<int, int>> batch_pixels;
        std::vector<double> batch_plus(detail::ConoscopeEvaluator::kMonochromaticBatch), batch_minus(batch_plus.size());
        detail::KernelScratch scratch;
        // Monochromatic light: the row's pixel pairs go through the kernel together.
        const auto flush_batch = [&] {
            evaluator.monochromatic_pairs(batch_xi, scratch, batch_plus.data(), batch_minus.data());
            for (std::size_t k = 0; k < batch_xi.size(); ++k) {
                const auto [column, row] = batch_pixels[k];
                image.at(column, row, 0) = static_cast<float>(batch_plus[k]);
                image.at(size - 1 - column, size - 1 - row, 0) = static_cast<float>(batch_minus[k]);
            }
            batch_xi.clear();
            batch_pixels.clear();
        };
#pragma omp for schedule(dynamic, 2)
        for (int row = 0; row < paired_rows; ++row) {
            if (relay.cancelled()) continue;
            const int columns = (size % 2 == 1 && row == size / 2) ? size / 2 + 1 : size;
            bool continues_row = false;  // white light: the previous pixel's roots start the iterations
            for (int column = 0; column < columns; ++column) {
                const Eigen::Vector2d xi = conoscope_tangential_wavevector(settings, column, row);
                if (xi.squaredNorm() > aperture_squared) {
                    continues_row = false;
                    continue;
                }
                if (integrator == nullptr) {
                    batch_xi.push_back(xi);
                    batch_pixels.emplace_back(column, row);
                    if (batch_xi.size() == detail::ConoscopeEvaluator::kMonochromaticBatch) flush_batch();
                    continue;
                }
                evaluator.spectral_pair(xi, scratch, continues_row, plus.data(), minus.data());
                continues_row = true;
                store(column, row, plus);
                store(size - 1 - column, size - 1 - row, minus);
            }
            if (!batch_xi.empty()) flush_batch();
            relay.count_done(rows_done, paired_rows);
        }
    }
    relay.finish();
    return image;
}

}  // namespace petroscope
