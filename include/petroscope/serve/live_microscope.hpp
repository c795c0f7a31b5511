#pragma once
// The live microscope's answers, apart from HTTP (`petroscope serve` puts them on a socket; the tests and
// the fuzzer call them directly): the page's files, the catalog, a view's stage harmonics and a grain's
// numbers. The API: docs/browser.md.
#include "petroscope/api/stage_harmonics.hpp"
#include "petroscope/microscope/thin_section.hpp"
#include "petroscope/minerals/mineral_catalog.hpp"
#include "petroscope/serve/query.hpp"

#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <string_view>
#include <vector>

namespace petroscope::serve {

struct Reply {
    int status = 200;
    std::string content_type = "application/json";
    std::string body;
};

/// A view's harmonics as the page reads them, little-endian: four uint32 (the magic 0x31485350 "PSH1",
/// width, height, resampling 0 = containing pixel, 1 = bilinear), then float32: the 15 outside values, then
/// 15 per pixel, rows from the top (StageHarmonics).
std::string encode_stage_harmonics(const StageHarmonics& harmonics);

class LiveMicroscope {
public:
    /// Reads the page's files (*.html, *.js, *.css) from `web_dir` and lists the example sections in
    /// `sections_dir` (each folder with a section.txt). No request names a file: only these are read.
    LiveMicroscope(const MineralCatalog& catalog, const std::filesystem::path& web_dir, const std::filesystem::path& sections_dir);

    /// Answers a GET of `path` (without the query). Bad input gives 400 and {"error": message}; an unknown
    /// path 404. Renders one at a time (each uses every core); safe to call from several threads.
    Reply get(std::string_view path, const QueryParameters& query) const;

    const std::vector<std::string>& section_names() const { return section_names_; }

private:
    Reply answer(std::string_view path, const QueryParameters& query) const;
    Reply catalog_reply() const;
    Reply view_reply(const QueryParameters& query) const;
    Reply grain_reply(const QueryParameters& query) const;
    std::shared_ptr<const ThinSection> section(const QueryParameters& query) const;

    const MineralCatalog& catalog_;
    std::map<std::string, std::string, std::less<>> page_files_;  // "/name" → contents
    std::filesystem::path sections_dir_;
    std::vector<std::string> section_names_;  // the examples, then "random"
    mutable std::mutex sections_mutex_;
    mutable std::map<std::string, std::shared_ptr<const ThinSection>> sections_;
    mutable std::mutex render_mutex_;
};

}  // namespace petroscope::serve
