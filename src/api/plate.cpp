#include "petroscope/api/plate.hpp"

namespace petroscope {

std::optional<AccessoryPlate> make_plate(const std::optional<PlateRequest>& request, const MineralCatalog& catalog) {
    if (!request) return std::nullopt;
    return make_accessory_plate(request->kind, catalog.find(plate_mineral_name(request->kind)), request->slow_deg, request->wedge_position);
}

}  // namespace petroscope
