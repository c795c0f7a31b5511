#include "petroscope/minerals/mineral_catalog.hpp"

#include "petroscope/core/error.hpp"
#include "petroscope/core/text.hpp"

#include <algorithm>
#include <map>

namespace petroscope {
namespace {

std::vector<std::string> names_of(const Mineral& mineral) {
    std::vector<std::string> names{mineral.name};
    names.insert(names.end(), mineral.aliases.begin(), mineral.aliases.end());
    return names;
}

}  // namespace

MineralCatalog::MineralCatalog(std::vector<Mineral> minerals) : minerals_(std::move(minerals)) {
    std::sort(minerals_.begin(), minerals_.end(),
              [](const Mineral& a, const Mineral& b) { return to_lower(a.name) < to_lower(b.name); });
    std::map<std::string, const Mineral*> seen;
    for (const Mineral& mineral : minerals_) {
        for (const std::string& name : names_of(mineral)) {
            const auto [it, inserted] = seen.emplace(to_lower(name), &mineral);
            if (!inserted) {
                throw InputError("mineral name " + quote_input(name) + " is used by both " + it->second->file + " and " + mineral.file);
            }
        }
    }
}

const Mineral& MineralCatalog::find(std::string_view name) const {
    const std::string wanted = to_lower(trim(name));
    for (const Mineral& mineral : minerals_) {
        for (const std::string& candidate : names_of(mineral)) {
            if (to_lower(candidate) == wanted) return mineral;
        }
    }
    // Suggest the names within a small edit distance, or sharing a prefix, closest first.
    std::vector<std::pair<std::size_t, std::string>> close;
    for (const Mineral& mineral : minerals_) {
        std::size_t best = std::string::npos;
        for (const std::string& candidate : names_of(mineral)) {
            const std::string lower = to_lower(candidate);
            std::size_t distance = edit_distance(wanted, lower);
            if (!wanted.empty() && lower.starts_with(wanted)) distance = std::min<std::size_t>(distance, 1);
            best = std::min(best, distance);
        }
        if (best <= std::max<std::size_t>(2, wanted.size() / 3)) close.emplace_back(best, mineral.name);
    }
    std::sort(close.begin(), close.end());
    std::string message = "unknown mineral " + quote_input(name);
    if (!close.empty()) {
        message += "; did you mean ";
        for (std::size_t i = 0; i < close.size() && i < 3; ++i) message += (i ? ", " : "") + close[i].second;
        message += "?";
    }
    message += " ('petroscope minerals' lists all " + std::to_string(minerals_.size()) + ")";
    throw InputError(message);
}

}  // namespace petroscope
