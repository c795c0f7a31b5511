#pragma once
// Reading the data that ships with petroscope: CIE tables and mineral records.
#include "petroscope/minerals/mineral_catalog.hpp"
#include "petroscope/spectral/colorimetry.hpp"

#include <filesystem>
#include <string>

namespace petroscope {

/// The folder of CIE tables: $PETROSCOPE_DATA_DIR if set, else the source tree's data/.
std::filesystem::path data_directory();
/// The mineral folder: `override_dir` if not empty, else $PETROSCOPE_MINERALS, else the source tree's minerals/.
std::filesystem::path minerals_directory(const std::string& override_dir = {});

/// A folder that ships with petroscope beside minerals/ (web, thin_sections): $PETROSCOPE_SHIPPED_DIR/NAME
/// if that is set, else the source tree's.
std::filesystem::path shipped_directory(const std::string& name);

/// The whole file as text; throws InputError naming the file if it cannot be read.
std::string read_text_file(const std::filesystem::path& path);

ColorMatchingFunctions load_cie_1931_observer();
/// "D65", "A" (CIE tables) or "blackbody:TEMPERATUREK" (Planck); throws InputError listing the names.
LightSource load_light_source(const std::string& name);

/// Every *.txt record in `directory` (errors name the file and line).
MineralCatalog load_mineral_catalog(const std::filesystem::path& directory);

}  // namespace petroscope
