#pragma once
// A picture as a function of the stage angle, for a live microscope (`petroscope serve`, docs/browser.md):
// five harmonic images from which the picture at any stage angle is composed exactly, without rendering.
//
// Turning the stage by φ turns the crystal; seen from the crystal, the polarizer, the plate and the
// analyzer turn by −φ, and the image point q shows what the unturned crystal shows at R(−φ)·q. Seen from
// the turned tube the crystal's Jones matrix is R(φ)ᵀ·J·R(φ), whose entries are combinations of 1, cos 2φ
// and sin 2φ; the intensity is quadratic in them. So at every image point, wavelength and illumination
// direction, and therefore in every linear colour channel:
//     I(φ) = c₀ + c₁ cos 2φ + s₁ sin 2φ + c₂ cos 4φ + s₂ sin 4φ,
// a trigonometric polynomial of degree 2 in 2φ. Five renders with the tube turned by −φ_k, φ_k = 36°·k,
// give its coefficients by the discrete Fourier transform of five points, exactly (no aliasing below the
// third harmonic).
#include "petroscope/api/conoscope_figure.hpp"
#include "petroscope/api/orthoscope_image.hpp"
#include "petroscope/core/image.hpp"
#include "petroscope/core/progress.hpp"
#include "petroscope/minerals/mineral_catalog.hpp"

#include <array>
#include <string>

namespace petroscope {

/// The five coefficients c₀, c₁, s₁, c₂, s₂ of I(φ), in this order.
inline constexpr int kStageHarmonicCount = 5;
/// Channels of a harmonic image: per coefficient, linear sRGB (r, g, b).
inline constexpr int kStageHarmonicChannels = 3 * kStageHarmonicCount;

/// How the picture turned with the stage is sampled.
enum class StageResampling {
    containing_pixel,  // the pixel that contains the turned point (orthoscopy: what render_orthoscope does)
    bilinear,          // bilinear between the four nearest pixel centres (a conoscopic figure, a smooth field)
};

struct StageHarmonics {
    Image coefficients;  // kStageHarmonicChannels per pixel, at stage 0
    /// What the field shows where the turned picture leaves it (orthoscopy: glass and balsam only; a
    /// conoscopic figure: black beyond its aperture).
    std::array<float, kStageHarmonicChannels> outside{};
    StageResampling resampling = StageResampling::bilinear;
    std::string illuminant;  // as DisplayImage::illuminant
};

/// The light below the specimen.
enum class Illumination {
    polarized,    // through the polarizer (the request's polarizer_deg)
    unpolarized,  // the polarizer out: the mean of two renders with the polarizer at 90° to each other
                  // (unpolarized light is an incoherent equal mixture of any two orthogonal polarizations)
};

/// The 5 harmonics of a figure (its stage_deg must be 0: every stage is composed from the result). Throws
/// InputError as plan_conoscope does, Cancelled when `progress` says stop.
StageHarmonics conoscope_stage_harmonics(const ConoscopeRequest& request, const MineralCatalog& catalog,
                                         Illumination illumination = Illumination::polarized, const ProgressCallback& progress = {});
/// The same for a thin section; outside the turned section the light crosses glass and balsam at the
/// section's thickness in the middle of the field, as in render_orthoscope.
StageHarmonics orthoscope_stage_harmonics(const OrthoscopeRequest& request, const MineralCatalog& catalog,
                                          Illumination illumination = Illumination::polarized, const ProgressCallback& progress = {});

/// The picture at `stage_deg` in linear sRGB (3 channels): what the browser composes on every frame.
Image compose_at_stage(const StageHarmonics& harmonics, double stage_deg);

}  // namespace petroscope
