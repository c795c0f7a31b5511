#pragma once
// Conoscopic interference figures: the image in the back focal plane of the objective, seen through the
// Bertrand lens, of a crystal slab between polarizer and analyzer.
#include "petroscope/core/image.hpp"
#include "petroscope/core/progress.hpp"
#include "petroscope/microscope/polarizing_microscope.hpp"
#include "petroscope/spectral/colorimetry.hpp"

#include <Eigen/Core>

#include <cmath>

#include <functional>
#include <memory>
#include <optional>
#include <vector>

namespace petroscope {

/// How white light is sampled over the spectrum.
enum class SpectrumSampling {
    /// The crystal's modes are solved at a few wavelengths (spectral nodes) and interpolated to the others,
    /// where the interference is evaluated exactly; near an optic axis, where the modes change too fast with
    /// wavelength, every wavelength is solved (docs/theory.md, "White light from spectral nodes").
    interpolated,
    /// The modes are solved at every wavelength (the reference the interpolation is tested against).
    exact,
};
/// The wavelengths at which SpectrumSampling::interpolated solves the modes.
inline constexpr int kSpectralNodeCount = 8;

struct ConoscopeSettings {
    int size_px = 512;                  // square image, 64 … 4096
    double numerical_aperture = 0.85;   // of the objective, in air: r/r_max = sin θ_air / NA (Abbe sine condition)
    double thickness_um = 30.0;         // slab thickness
    double surround_n = 1.54;           // isotropic medium on both faces (Canada balsam ≈ 1.54)
    double polarizer_deg = 0.0;         // transmission direction, from E toward N
    double analyzer_deg = 90.0;
    bool analyzer_in = true;
    double stage_deg = 0.0;             // stage rotation, counter-clockwise seen from the observer
    Eigen::Matrix3d crystal_axes = Eigen::Matrix3d::Identity();  // indicatrix X, Y, Z (columns) at stage 0
    std::vector<double> wavelengths_nm{589.3};
    /// White light in an immersed slab: how the spectrum is sampled (the mounting's stack solves every wavelength).
    SpectrumSampling spectrum = SpectrumSampling::interpolated;
    /// An accessory plate in the tube, crossed at normal incidence by the light of every image point (the same
    /// retardation over the figure).
    std::optional<AccessoryPlate> plate;
    /// The whole thin-section stack instead of a slab in balsam half-spaces: air, slide glass, balsam, crystal,
    /// balsam, cover glass, air (microscope/polarizing_microscope.hpp), each image point on its own (slower).
    std::optional<SectionMounting> mounting;
    /// With `mounting`: the coherent 4×4 solution (every multiple reflection) instead of single pass.
    bool exact = false;
    /// Natural optical activity: the crystal's gyration tensor in its indicatrix frame; empty for an inactive
    /// crystal.
    GyrationFunction gyration;

    /// Checks every field; throws InputError naming the setting and the accepted range.
    void validate() const;
};


/// The lab-frame direction of the wave that reaches image point (x, y) ∈ [−1, 1]² (x to the E, y to the
/// N): tangential wavevector ξ = NA·(x, y) in units of k₀ (sin θ_air = NA·r).
Eigen::Vector2d conoscope_tangential_wavevector(const ConoscopeSettings& settings, int column, int row);

/// Whether a figure of `settings` is interpolated from spectral nodes: SpectrumSampling::interpolated, an
/// immersed slab (no mounting) and at least 2·kSpectralNodeCount distinct wavelengths.
bool interpolates_spectrum(const ConoscopeSettings& settings);

/// Transmission spectrum of one image point: intensity after the analyzer relative to the incident
/// intensity after the polarizer, per wavelength of `settings`. Single pass (no multiple reflections);
/// interpolated from spectral nodes where interpolates_spectrum(settings) says so, as in the figure.
std::vector<double> conoscope_point_transmission(const ConoscopeSettings& settings,
                                                 const PrincipalIndexFunction& principal_n,
                                                 const Eigen::Vector2d& xi);

/// How one image point's transmission at one wavelength depends on the slab thickness d (single pass,
/// no plate): mean + modulation·cos(phase_per_um·d) + sine_modulation·sin(phase_per_um·d), the interference of
/// the two modes. Inactive crystal: phase_per_um = k₀(q_fast − q_slow) in rad/µm and no sine term. Optically
/// active crystal: the modes' coupling across the slab (optics/slab.hpp, slab_propagation) makes each analyzed
/// amplitude cos(Wd)·A + sin(Wd)·(B + iC) with W = k₀√(((q_fast − q_slow)/2)² + c₀c₁), so phase_per_um = 2W and
/// the transmission (A² + B² + C²)/2 + ((A² − B² − C²)/2)·cos 2Wd + AB·sin 2Wd, summed over the analyzed
/// components. Fitting a thickness needs these only once.
struct InterferenceTerms {
    double mean = 0.0;
    double modulation = 0.0;
    double phase_per_um = 0.0;
    double sine_modulation = 0.0;

    double transmission(double thickness_um) const {
        return mean + modulation * std::cos(phase_per_um * thickness_um) + sine_modulation * std::sin(phase_per_um * thickness_um);
    }
};

namespace detail {
class ConoscopeEvaluator;
}

/// The terms of many image points at every wavelength of a figure's settings (a plate or a mounting is refused
/// with InputError). In white light with settings.spectrum interpolated, an inactive crystal's terms come from the
/// modes at the spectral nodes where they are smooth enough (as the figure's spectra do: docs/theory.md, "White light
/// from spectral nodes"), every wavelength solved elsewhere; settings.thickness_um is then the thickest slab the terms
/// are meant for: the phase's interpolation error is held to 1e-3 rad at that thickness.
class ConoscopeTerms {
public:
    ConoscopeTerms(const ConoscopeSettings& settings, const PrincipalIndexFunction& principal_n);
    ~ConoscopeTerms();
    std::size_t wavelength_count() const { return wavelength_count_; }
    /// out[k·W + w] for xis[k] and wavelength w, on all threads (neighbouring ξ in order are faster). `from_nodes`
    /// (where given) gets 1 for each point whose terms came from the spectral nodes, 0 for one solved at every
    /// wavelength. `as_before` (where given) makes each point take the way it took in an earlier call (1: from the
    /// nodes, without the error checks, unless its modes there fail; 0: every wavelength), so that the terms of nearby
    /// directions, differenced for a derivative, come the same way.
    void evaluate(const std::vector<Eigen::Vector2d>& xis, std::vector<InterferenceTerms>& out, std::vector<unsigned char>* from_nodes = nullptr,
                  const std::vector<unsigned char>* as_before = nullptr) const;

private:
    ConoscopeSettings settings_;
    std::size_t wavelength_count_ = 0;
    std::unique_ptr<detail::ConoscopeEvaluator> evaluator_;
};

/// Renders the figure. With `integrator` (white light): 3 channels, CIE XYZ with Y = 1 for a perfect
/// transmitter. Without it: 1 channel, the transmission at the single wavelength of `settings`. Pixels
/// outside the aperture circle are 0.
Image render_conoscope(const ConoscopeSettings& settings, const PrincipalIndexFunction& principal_n,
                       const SpectralIntegrator* integrator, const ProgressCallback& progress = {});

/// White-light figures of one crystal that differ only in polarizer, analyzer and plate (the same stage,
/// thickness, wavelengths, NA, size and surround, the slab immersed): each image point's eigenmodes are
/// solved once for all of them, which is most of the work. Each image is render_conoscope's for its
/// settings. Throws InputError when the settings differ otherwise or have a mounting.
std::vector<Image> render_conoscope_polarization_set(const std::vector<ConoscopeSettings>& settings, const PrincipalIndexFunction& principal_n,
                                                     const SpectralIntegrator& integrator, const ProgressCallback& progress = {});

}  // namespace petroscope
