#pragma once
// An accessory plate as every front end asks for it: which plate, its slow direction, the wedge's position.
#include "petroscope/microscope/polarizing_microscope.hpp"
#include "petroscope/minerals/mineral_catalog.hpp"

#include <optional>

namespace petroscope {

struct PlateRequest {
    PlateKind kind = PlateKind::gypsum;
    double slow_deg = 45.0;        // the plate's slow direction, degrees from E toward N (45: NE–SW)
    double wedge_position = 0.5;   // the quartz wedge pushed in, 0 … 1 (0 … 4 orders)
};

/// The plate made of its mineral in `catalog`; none for none. Throws InputError for an out-of-range value.
std::optional<AccessoryPlate> make_plate(const std::optional<PlateRequest>& request, const MineralCatalog& catalog);

}  // namespace petroscope
