#pragma once
// The set of known minerals, looked up by name or alias.
#include "petroscope/minerals/mineral.hpp"

#include <string_view>
#include <vector>

namespace petroscope {

class MineralCatalog {
public:
    /// Throws InputError when two records share a name or alias (naming both files).
    explicit MineralCatalog(std::vector<Mineral> minerals);

    /// Case-insensitive match on name or alias. Throws InputError for an unknown name, suggesting the
    /// closest known names.
    const Mineral& find(std::string_view name) const;
    const std::vector<Mineral>& minerals() const { return minerals_; }

private:
    std::vector<Mineral> minerals_;  // sorted by name
};

}  // namespace petroscope
