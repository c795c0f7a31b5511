#pragma once
// JSON files: the sidecar "out.png.json" that records every parameter of a result.
#include <nlohmann/json.hpp>

#include <filesystem>

namespace petroscope {

/// The sidecar path of an output: "<output>.json".
std::filesystem::path sidecar_path(const std::filesystem::path& output);

/// Writes `document` pretty-printed; throws InputError naming the file on failure.
void write_json_file(const nlohmann::json& document, const std::filesystem::path& path);

}  // namespace petroscope
