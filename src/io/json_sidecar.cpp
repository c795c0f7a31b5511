#include "petroscope/io/json_sidecar.hpp"

#include "petroscope/core/error.hpp"

#include <fstream>

namespace petroscope {

std::filesystem::path sidecar_path(const std::filesystem::path& output) {
    return output.string() + ".json";
}

void write_json_file(const nlohmann::json& document, const std::filesystem::path& path) {
    std::ofstream file(path, std::ios::binary | std::ios::trunc);
    file << document.dump(2) << '\n';
    file.close();
    if (!file) throw InputError("cannot write " + path.string());
}

}  // namespace petroscope
