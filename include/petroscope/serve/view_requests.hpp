#pragma once
// The live microscope's requests from a URL query: which specimen (a thin section, or one crystal), the
// light, the polars and the plate, as the library's OrthoscopeRequest and ConoscopeRequest. The
// parameters and their limits: docs/browser.md ("The server's API").
#include "petroscope/api/conoscope_figure.hpp"
#include "petroscope/api/orthoscope_image.hpp"
#include "petroscope/api/stage_harmonics.hpp"
#include "petroscope/microscope/thin_section.hpp"
#include "petroscope/serve/query.hpp"

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace petroscope::serve {

/// Finds a thin section by the query's `section` (and `seed` for "random"); throws InputError for an unknown one.
using SectionLookup = std::function<std::shared_ptr<const ThinSection>(const QueryParameters&)>;

/// The pixel edge of a single crystal's picture in orthoscopy: a uniform field, turned with the stage.
inline constexpr int kCrystalFieldPx = 64;
/// The largest conoscopic figure the server renders (the command line allows 4096).
inline constexpr int kServerMaxFigurePx = 1024;

/// Where the query points in a section: the grain at section pixel (x, y) and its thickness there.
struct PickedGrain {
    std::shared_ptr<const ThinSection> section;
    const ThinSectionGrain* grain = nullptr;
    double thickness_um = 0.0;
};
/// From `section`, `x`, `y` (section pixels, x to the E from the left edge, y down from the top) and an
/// optional `thickness_um` overriding the section's.
PickedGrain picked_grain(const QueryParameters& query, const SectionLookup& sections);

/// A single crystal from `mineral`, `cut` | `euler`, `azimuth_deg`, `tilt_deg`, `thickness_um`: its
/// mineral, orientation and thickness, as a one-grain section of kCrystalFieldPx².
ThinSection single_crystal_section(const QueryParameters& query, const MineralCatalog& catalog);

/// The view in orthoscopy: a section (`section`, `seed`, optional `thickness_um`) or, without `section`, a
/// single crystal; `condenser_na`; the light (`wavelength_nm`, `illuminant`), `analyzer`, `plate`, `wedge_position`.
OrthoscopeRequest orthoscope_view_request(const QueryParameters& query, const MineralCatalog& catalog, const SectionLookup& sections);

/// The view through the Bertrand lens: the grain picked in a section (`section`, `x`, `y`) or a single
/// crystal; `na`, `size_px`; light, polars and plate.
ConoscopeRequest conoscope_view_request(const QueryParameters& query, const MineralCatalog& catalog, const SectionLookup& sections);

/// `polarizer`: in (default) or out (unpolarized light).
Illumination illumination_from(const QueryParameters& query);

/// The parameters every view takes besides the specimen's.
const std::vector<std::string>& view_parameter_names();

}  // namespace petroscope::serve
