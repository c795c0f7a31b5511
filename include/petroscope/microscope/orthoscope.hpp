#pragma once
// Orthoscopy: the image of a thin section between the polars, as the eye sees it through the eyepieces.
// The physics of each grain is microscope/polarizing_microscope.hpp; this file maps it over the section.
#include "petroscope/core/image.hpp"
#include "petroscope/core/progress.hpp"
#include "petroscope/microscope/polarizing_microscope.hpp"
#include "petroscope/microscope/thin_section.hpp"
#include "petroscope/minerals/mineral_catalog.hpp"
#include "petroscope/spectral/colorimetry.hpp"

namespace petroscope {

struct OrthoscopeSettings {
    MicroscopeSettings microscope;
    SectionMounting mounting;  // the media must outlive the render
    /// Checks every field; throws InputError naming the setting and the accepted range.
    void validate() const;
};

/// The mounting of a standard thin section: crown-glass slide (1 mm) and cover (170 µm), Canada balsam
/// (5 µm on each face), from the catalog's "crown glass" and "canada balsam" records.
SectionMounting standard_mounting(const MineralCatalog& catalog);

/// The condenser's rings for this section: the settings' own, or (0, automatic) enough for every grain at its
/// thickest anywhere in the section (condenser_rings_for), so that turning the stage keeps the sampling.
int section_condenser_rings(const ThinSection& section, const MineralCatalog& catalog, const MicroscopeSettings& microscope);

/// Renders the section as seen with the stage turned by settings.microscope.stage_deg (the section turns
/// counter-clockwise about the image centre; where it leaves the field the light crosses glass and balsam
/// only). With `integrator` (white light): 3 channels, CIE XYZ, Y = 1 for a perfect transmitter. Without:
/// 1 channel, the transmission at the single wavelength. Each pixel shows the transmission of its grain at
/// its thickness: the work grows with grains × wavelengths (× thickness steps where the thickness varies
/// inside a grain, at most 1 nm of retardation apart, interpolated linearly) plus pixels.
Image render_orthoscope(const ThinSection& section, const MineralCatalog& catalog, const OrthoscopeSettings& settings,
                        const SpectralIntegrator* integrator, const ProgressCallback& progress = {});

}  // namespace petroscope
