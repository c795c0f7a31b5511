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

class RenderThread;

struct Reply {
    int status = 200;
    std::string content_type = "application/json";
    std::string body;
};

/// A file of a form the page posts: the form's field, the file's own name, its bytes.
struct UploadedFile {
    std::string field;
    std::string filename;
    std::string content;
};

/// The largest grain map a section sent to the server may have, per side (the command line reads any).
inline constexpr int kUploadMaxSidePx = 4096;

/// A view's harmonics as the page reads them, little-endian: four uint32 (the magic 0x31485350 "PSH1",
/// width, height, resampling 0 = containing pixel, 1 = bilinear), then float32: the 15 outside values, then
/// 15 per pixel, rows from the top (StageHarmonics).
std::string encode_stage_harmonics(const StageHarmonics& harmonics);

class LiveMicroscope {
public:
    /// Reads the page's files (*.html, *.js, *.css) from `web_dir` and lists the example sections in
    /// `sections_dir` (each folder with a section.txt). No request names a file: only these are read.
    LiveMicroscope(const MineralCatalog& catalog, const std::filesystem::path& web_dir, const std::filesystem::path& sections_dir);
    ~LiveMicroscope();

    /// Answers a GET of `path` (without the query). Bad input gives 400 and {"error": message}; an unknown
    /// path 404. Renders one at a time (each uses every core); safe to call from several threads.
    Reply get(std::string_view path, const QueryParameters& query) const;

    /// A section the user sends (dropped on the page): the field `description` (its section.txt) and one
    /// field `map` per grain map it names, PNG only (thin_sections/README.md). It is read through a private
    /// folder that the server names and removes, its maps resolved only to the files sent with it; kept
    /// under the name in the answer, {"section": "upload-N", "name", "width_px", "height_px", "grains"}.
    /// Bad input gives 400 naming the file and line.
    Reply post_section(const std::vector<UploadedFile>& files) const;

    const std::vector<std::string>& section_names() const { return section_names_; }

private:
    Reply answer(std::string_view path, const QueryParameters& query) const;
    Reply catalog_reply() const;
    Reply view_reply(const QueryParameters& query) const;
    Reply grain_reply(const QueryParameters& query) const;
    std::shared_ptr<const ThinSection> section(const QueryParameters& query) const;
    ThinSection read_upload(const std::vector<UploadedFile>& files) const;

    const MineralCatalog& catalog_;
    std::map<std::string, std::string, std::less<>> page_files_;  // "/name" → contents
    std::filesystem::path sections_dir_;
    std::vector<std::string> section_names_;  // the examples, then "random"
    mutable std::mutex sections_mutex_;
    mutable std::map<std::string, std::shared_ptr<const ThinSection>> sections_;
    std::unique_ptr<RenderThread> render_thread_;  // renders one at a time, on one warm thread
    mutable std::map<std::string, std::shared_ptr<const ThinSection>> uploads_;  // under sections_mutex_
    mutable int upload_count_ = 0;
};

}  // namespace petroscope::serve
