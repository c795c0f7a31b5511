#pragma once
// Small file helpers shared by the test suites.
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>

namespace petroscope::testing {

inline std::string read_text(const std::filesystem::path& path) {
    std::ifstream file(path, std::ios::binary);
    std::ostringstream text;
    text << file.rdbuf();
    return text.str();
}

inline void write_text(const std::filesystem::path& path, const std::string& text) {
    std::ofstream(path, std::ios::binary) << text;
}

/// Every name in `folder`, hidden ones (".x.tmp-…") included.
inline std::set<std::string> listing(const std::filesystem::path& folder) {
    std::set<std::string> names;
    for (const auto& entry : std::filesystem::directory_iterator(folder)) names.insert(entry.path().filename().string());
    return names;
}

}  // namespace petroscope::testing
