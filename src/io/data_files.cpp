#include "petroscope/io/data_files.hpp"

#include "petroscope/core/error.hpp"
#include "petroscope/core/text.hpp"
#include "petroscope/minerals/mineral_parser.hpp"

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <sstream>

namespace petroscope {
namespace {

TabulatedSpectrum single_column(const std::filesystem::path& path, std::size_t expected_columns, std::size_t column) {
    const SpectralTable table = parse_spectral_csv(read_text_file(path), path.string());
    if (table.columns.size() != expected_columns) {
        throw InputError(path.string() + ": expected " + std::to_string(expected_columns) + " data columns after the wavelength");
    }
    return table.columns[column];
}

}  // namespace

std::filesystem::path data_directory() {
    if (const char* override_dir = std::getenv("PETROSCOPE_DATA_DIR"); override_dir != nullptr && *override_dir != '\0') {
        return override_dir;
    }
    return std::filesystem::path(PETROSCOPE_SOURCE_DIR) / "data";
}

std::filesystem::path minerals_directory(const std::string& override_dir) {
    if (!override_dir.empty()) return override_dir;
    if (const char* env = std::getenv("PETROSCOPE_MINERALS"); env != nullptr && *env != '\0') return env;
    return std::filesystem::path(PETROSCOPE_SOURCE_DIR) / "minerals";
}

std::filesystem::path shipped_directory(const std::string& name) {
    if (const char* env = std::getenv("PETROSCOPE_SHIPPED_DIR"); env != nullptr && *env != '\0') return std::filesystem::path(env) / name;
    return std::filesystem::path(PETROSCOPE_SOURCE_DIR) / name;
}

std::string read_text_file(const std::filesystem::path& path) {
    std::ifstream file(path, std::ios::binary);
    if (!file) throw InputError("cannot read " + path.string() + ": no such file or not readable");
    std::ostringstream text;
    text << file.rdbuf();
    if (file.bad()) throw InputError("error while reading " + path.string());
    return text.str();
}

ColorMatchingFunctions load_cie_1931_observer() {
    const std::filesystem::path path = data_directory() / "cie" / "cie1931_2deg_cmf_1nm.csv";
    const SpectralTable table = parse_spectral_csv(read_text_file(path), path.string());
    if (table.columns.size() != 3) throw InputError(path.string() + ": expected the columns X, Y, Z after the wavelength");
    return {table.columns[0], table.columns[1], table.columns[2]};
}

LightSource load_light_source(const std::string& name) {
    const std::string lower = to_lower(name);
    if (lower == "d65" || lower == "a") {
        const std::string file = lower == "d65" ? "cie_illuminant_d65_1nm.csv" : "cie_illuminant_a_1nm.csv";
        const TabulatedSpectrum spectrum = single_column(data_directory() / "cie" / file, 1, 0);
        return LightSource{lower == "d65" ? "D65" : "A", [spectrum](double nm) { return spectrum(nm); }};
    }
    if (lower.starts_with("blackbody:")) {
        std::string temperature = lower.substr(10);
        if (temperature.ends_with('k')) temperature.pop_back();
        if (const auto kelvin = parse_double(temperature); kelvin && *kelvin >= 500.0 && *kelvin <= 100000.0) {
            return blackbody_source(*kelvin);
        }
    }
    throw InputError("unknown light source " + quote_input(name) + " (expected D65, A, or blackbody:TEMPERATUREK with 500 to 100000 K, e.g. blackbody:3200K)");
}

MineralCatalog load_mineral_catalog(const std::filesystem::path& directory) {
    std::error_code error;
    if (!std::filesystem::is_directory(directory, error)) {
        throw InputError("mineral folder " + directory.string() + " does not exist or is not a folder");
    }
    std::vector<std::filesystem::path> files;
    for (const auto& entry : std::filesystem::directory_iterator(directory)) {
        if (entry.is_regular_file() && entry.path().extension() == ".txt") files.push_back(entry.path());
    }
    std::sort(files.begin(), files.end());
    std::vector<Mineral> minerals;
    for (const auto& file : files) minerals.push_back(parse_mineral(read_text_file(file), file.string()));
    if (minerals.empty()) throw InputError("mineral folder " + directory.string() + " holds no *.txt records");
    return MineralCatalog(std::move(minerals));
}

}  // namespace petroscope
