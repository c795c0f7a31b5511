#pragma once
// Interface cases: one plane wave meeting one interface, as JSON (format: docs/interface.md), and the
// solver's answer as JSON.
#include "petroscope/minerals/mineral_catalog.hpp"
#include "petroscope/optics/interface.hpp"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>

namespace petroscope {

struct InterfaceCase {
    std::string file;
    std::string name, statement;  // optional in the file
    double wavelength_nm = 589.3;
    Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
    InterfaceIncidence incidence;
    OpticalMedium medium1, medium2;
    nlohmann::json document;  // the whole case, for its "expected" block and reports
};

/// Reads a case; errors name the file and the key path. Minerals are looked up in `catalog`.
InterfaceCase parse_interface_case(const nlohmann::json& document, const std::string& file, const MineralCatalog& catalog);
InterfaceCase load_interface_case(const std::filesystem::path& path, const MineralCatalog& catalog);

/// {"waves": [{"kind", "mode", "direction", "ray_direction", "n", "power", "stokes", "evanescent",
///  "ellipticity", "handedness", "jones_sp"?, "amplitude"?}], "incident": {"n", "ray_direction"}}.
nlohmann::json interface_result_json(const InterfaceResult& result);

}  // namespace petroscope
