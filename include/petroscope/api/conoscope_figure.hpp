#pragma once
// A conoscopic figure as every front end asks for it (the CLI's `conoscope`, Python, a browser): the
// request in the user's terms, validated into a plan, rendered to display colours and measured.
#include "petroscope/api/crystal_orientation.hpp"
#include "petroscope/api/light.hpp"
#include "petroscope/api/measurements.hpp"
#include "petroscope/api/plate.hpp"
#include "petroscope/core/progress.hpp"
#include "petroscope/microscope/conoscope.hpp"
#include "petroscope/minerals/mineral_catalog.hpp"
#include "petroscope/optics/gyration.hpp"

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace petroscope {

/// What surrounds the crystal slab.
enum class SlabMounting {
    immersed,            // half-spaces of index surround_n on both faces (fastest)
    thin_section,        // the whole thin section: air, slide, balsam, crystal, balsam, cover, air; single pass
    thin_section_exact,  //   … solved with the coherent 4×4 transfer matrix (every multiple reflection)
};
/// "immersed", "thin-section", "thin-section-exact"; throws InputError listing them.
SlabMounting parse_slab_mounting(std::string_view name);

struct ConoscopeRequest {
    std::string mineral = "muscovite";  // name or alias in the catalog
    double thickness_um = 30.0;
    CrystalOrientation orientation;
    double numerical_aperture = 0.85;
    int size_px = 512;
    Light light;
    double stage_deg = 0.0;
    double polarizer_deg = 0.0;
    double analyzer_deg = 90.0;
    bool analyzer_in = true;
    double surround_n = 1.54;  // immersed only
    SlabMounting mounting = SlabMounting::immersed;
    std::optional<PlateRequest> plate;
    /// White light in an immersed slab: modes at spectral nodes, interpolated (default), or at every wavelength.
    SpectrumSampling spectrum = SpectrumSampling::interpolated;
    /// Which enantiomorph of an optically active mineral (quartz); no effect on an inactive one.
    Handedness handedness = Handedness::right;
};

/// A request checked and resolved against the catalog, ready to render. It refers to the catalog's
/// mineral: the catalog must outlive it.
struct ConoscopePlan {
    ConoscopeSettings settings;
    const Mineral* mineral = nullptr;
    std::optional<Cut> cut;  // the cut used; none with Euler angles
    Light light;
    std::optional<Handedness> handedness;  // of an optically active mineral; none for an inactive one
    /// Where the optic axes are measured: the light's wavelength, in white light 555 nm (the peak of the
    /// photopic luminous efficiency, CIE 1924).
    double axes_wavelength_nm = 555.0;
    /// For the user, each beginning "note: " or "warning: " (e.g. wavelengths beyond the mineral's data).
    std::vector<std::string> notes;
};

/// Throws InputError naming the bad value (no rendering is done).
ConoscopePlan plan_conoscope(const ConoscopeRequest& request, const MineralCatalog& catalog);

struct ConoscopeFigure {
    DisplayImage image;  // white = parallel polars without the crystal
    /// mean_r, mean_g, mean_b, mean_luminance; per optic axis k = 1, 2 its image point optic_axis_k_x, _y,
    /// _azimuth_deg, _radius (field units, x to the E, y to the N, 1 = the field's edge) and the dark spot
    /// found there between crossed polars without a plate, melatope_k_… (none where there is nothing).
    Measurements measurements;
};

/// Renders and measures; throws Cancelled when `progress` says stop.
ConoscopeFigure render_conoscope_figure(const ConoscopePlan& plan, const ProgressCallback& progress = {});

}  // namespace petroscope
