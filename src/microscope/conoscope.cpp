#include "petroscope/microscope/conoscope.hpp"

#include "conoscope_evaluator.hpp"
#include "conoscope_stack.hpp"

#include "petroscope/core/error.hpp"
#include "petroscope/core/text.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <functional>
#include <memory>
#include <stdexcept>

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

bool interpolates_spectrum(const ConoscopeSettings& settings) {
    std::vector<double> distinct = settings.wavelengths_nm;
    std::sort(distinct.begin(), distinct.end());
    distinct.erase(std::unique(distinct.begin(), distinct.end()), distinct.end());
    return settings.spectrum == SpectrumSampling::interpolated && !settings.mounting &&
           distinct.size() >= 2 * static_cast<std::size_t>(kSpectralNodeCount);
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
    detail::SpectralScratch scratch;
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

void ConoscopeTerms::evaluate(const std::vector<Eigen::Vector2d>& xis, std::vector<InterferenceTerms>& out, std::vector<unsigned char>* from_nodes,
                              const std::vector<unsigned char>* as_before) const {
    const std::size_t count = wavelength_count_;
    if (as_before != nullptr && as_before->size() != xis.size()) throw std::invalid_argument("ConoscopeTerms: as_before has another number of points");
    out.resize(xis.size() * count);
    if (from_nodes != nullptr) from_nodes->assign(xis.size(), 0);
    const int points = static_cast<int>(xis.size());
#pragma omp parallel
    {
        detail::KernelScratch nodes, every_wavelength;
        // Each scratch's roots start the next point's iterations once it has solved a point.
        bool nodes_continue = false, every_wavelength_continues = false;
        // Points solved at every wavelength cost several times those from the nodes, and they gather in parts of
        // the field (its rim, a melatope): the points are dealt to the threads in runs of 32, in turn, so that each
        // thread gets its share of both; a run is neighbours, whose roots start each other's iterations.
#pragma omp for schedule(static, 32)
        for (int k = 0; k < points; ++k) {
            const auto point = static_cast<std::size_t>(k);
            InterferenceTerms* terms = out.data() + point * count;
            const bool try_nodes = as_before == nullptr || (*as_before)[point] != 0;
            bool interpolated = false;
            if (try_nodes) {
                interpolated = evaluator_->node_terms(xis[point], nodes, nodes_continue, as_before == nullptr, terms);
                nodes_continue = true;
            }
            if (!interpolated) {
                evaluator_->spectral_terms(xis[point], every_wavelength, every_wavelength_continues, terms);
                every_wavelength_continues = true;
            }
            if (from_nodes != nullptr) (*from_nodes)[point] = interpolated ? 1 : 0;
        }
    }
}

namespace {

void require_one_crystal(const std::vector<ConoscopeSettings>& settings) {
    if (settings.empty()) throw InputError("no figures to render");
    const ConoscopeSettings& first = settings.front();
    for (const ConoscopeSettings& other : settings) {
        other.validate();
        if (other.mounting) throw InputError("figures that share their modes are of an immersed slab");
        const bool same_crystal = other.crystal_axes == first.crystal_axes && other.stage_deg == first.stage_deg &&
                                  other.thickness_um == first.thickness_um && other.wavelengths_nm == first.wavelengths_nm &&
                                  other.numerical_aperture == first.numerical_aperture && other.size_px == first.size_px &&
                                  other.surround_n == first.surround_n && other.spectrum == first.spectrum &&
                                  static_cast<bool>(other.gyration) == static_cast<bool>(first.gyration);
        if (!same_crystal) throw InputError("figures that share their modes may differ in their polars and plate only");
    }
}

/// Visits the image points inside the aperture in pairs of opposite directions (ξ, −ξ): (column, row) and
/// (size−1−column, size−1−row), rows 0 … ⌈size/2⌉−1 in parallel, and of the middle row of an odd size its
/// first half. `visit(state, column, row, xi, continues_row)` gets its thread's `State`; `flush(state)` ends a row.
template <typename State, typename Visit, typename Flush>
void for_each_point_pair(const ConoscopeSettings& settings, const ProgressCallback& progress, const std::function<State()>& make_state,
                         const Visit& visit, const Flush& flush) {
    const int size = settings.size_px;
    ProgressRelay relay(progress);
    std::atomic<int> rows_done{0};
    const double aperture_squared = settings.numerical_aperture * settings.numerical_aperture;
    const int paired_rows = (size + 1) / 2;
#pragma omp parallel
    {
        State state = make_state();
#pragma omp for schedule(dynamic, 2)
        for (int row = 0; row < paired_rows; ++row) {
            if (relay.cancelled()) continue;
            const int columns = (size % 2 == 1 && row == size / 2) ? size / 2 + 1 : size;
            bool continues_row = false;  // the previous point's roots can start the iterations
            for (int column = 0; column < columns; ++column) {
                const Eigen::Vector2d xi = conoscope_tangential_wavevector(settings, column, row);
                if (xi.squaredNorm() > aperture_squared) {
                    continues_row = false;
                    continue;
                }
                visit(state, column, row, xi, continues_row);
                continues_row = true;
            }
            flush(state);
            relay.count_done(rows_done, paired_rows);
        }
    }
    relay.finish();
}

/// A thread's buffers for white light.
struct SpectralState {
    std::vector<double> plus, minus;
    detail::SpectralScratch scratch;
};

/// A thread's batch of pixel pairs in monochromatic light.
struct MonochromaticState {
    std::vector<Eigen::Vector2d> xis;
    std::vector<std::pair<int, int>> pixels;
    std::vector<double> plus, minus;
    detail::KernelScratch scratch;
};

Image render_monochromatic(const ConoscopeSettings& settings, const PrincipalIndexFunction& principal_n, const ProgressCallback& progress) {
    const detail::ConoscopeEvaluator evaluator(settings, principal_n);
    const int size = settings.size_px;
    Image image(size, size, 1);
    constexpr std::size_t batch = detail::ConoscopeEvaluator::kMonochromaticBatch;
    // The row's pixel pairs go through the kernel together.
    const auto flush = [&](MonochromaticState& state) {
        evaluator.monochromatic_pairs(state.xis, state.scratch, state.plus.data(), state.minus.data());
        for (std::size_t k = 0; k < state.xis.size(); ++k) {
            const auto [column, row] = state.pixels[k];
            image.at(column, row, 0) = static_cast<float>(state.plus[k]);
            image.at(size - 1 - column, size - 1 - row, 0) = static_cast<float>(state.minus[k]);
        }
        state.xis.clear();
        state.pixels.clear();
    };
    const auto visit = [&](MonochromaticState& state, int column, int row, const Eigen::Vector2d& xi, bool) {
        state.xis.push_back(xi);
        state.pixels.emplace_back(column, row);
        if (state.xis.size() == batch) flush(state);
    };
    const std::function<MonochromaticState()> make_state = [] { return MonochromaticState{{}, {}, std::vector<double>(batch), std::vector<double>(batch), {}}; };
    for_each_point_pair(settings, progress, make_state, visit, [&](MonochromaticState& state) {
        if (!state.xis.empty()) flush(state);
    });
    return image;
}

}  // namespace

std::vector<Image> render_conoscope_polarization_set(const std::vector<ConoscopeSettings>& settings, const PrincipalIndexFunction& principal_n,
                                                     const SpectralIntegrator& integrator, const ProgressCallback& progress) {
    require_one_crystal(settings);
    if (integrator.weights().size() != settings.front().wavelengths_nm.size()) {
        throw InputError("the colour integrator and the figure use different wavelength grids");
    }
    std::vector<std::unique_ptr<const detail::ConoscopeEvaluator>> evaluators;
    for (const ConoscopeSettings& each : settings) {
        evaluators.push_back(std::make_unique<const detail::ConoscopeEvaluator>(each, principal_n, &integrator.weights()));
    }
    const int size = settings.front().size_px;
    std::vector<Image> images;
    for (std::size_t k = 0; k < settings.size(); ++k) images.emplace_back(size, size, 3);
    const std::size_t count = evaluators.front()->wavelength_count();
    const auto store = [](Image& image, int column, int row, const Eigen::Vector3d& xyz) {
        for (int c = 0; c < 3; ++c) image.at(column, row, c) = static_cast<float>(xyz[c]);
    };
    const auto visit = [&](SpectralState& state, int column, int row, const Eigen::Vector2d& xi, bool continues_row) {
        for (std::size_t k = 0; k < evaluators.size(); ++k) {
            detail::PairColour colour;
            if (k == 0) {
                evaluators[k]->spectral_pair(xi, state.scratch, continues_row, state.plus.data(), state.minus.data(), &colour);
            } else {
                evaluators[k]->spectral_pair_same_modes(xi, state.scratch, state.plus.data(), state.minus.data(), &colour);
            }
            // XYZ of the transmission spectrum where the evaluator did not give the colour itself.
            if (!colour.written) colour.xyz = {integrator.integrate(state.plus), integrator.integrate(state.minus)};
            store(images[k], column, row, colour.xyz[0]);
            store(images[k], size - 1 - column, size - 1 - row, colour.xyz[1]);
        }
    };
    const std::function<SpectralState()> make_state = [count] { return SpectralState{std::vector<double>(count), std::vector<double>(count), {}}; };
    for_each_point_pair(settings.front(), progress, make_state, visit, [](SpectralState&) {});
    return images;
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
    if (integrator == nullptr) return render_monochromatic(settings, principal_n, progress);
    return std::move(render_conoscope_polarization_set({settings}, principal_n, *integrator, progress).front());
}

}  // namespace petroscope
