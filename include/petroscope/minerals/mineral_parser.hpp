#pragma once
// The mineral record format of minerals/README.md.
#include "petroscope/minerals/mineral.hpp"

#include <string>
#include <string_view>

namespace petroscope {

/// Parses one mineral record. `file_name` appears in errors, which read "file:line: what was expected".
Mineral parse_mineral(std::string_view text, const std::string& file_name);

}  // namespace petroscope
