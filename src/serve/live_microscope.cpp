#include "petroscope/serve/live_microscope.hpp"

#include "petroscope/api/grain_optics.hpp"
#include "petroscope/core/error.hpp"
#include "petroscope/core/text.hpp"
#include "petroscope/io/data_files.hpp"
#include "petroscope/io/thin_section_file.hpp"
#include "petroscope/serve/view_requests.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdint>
#include <cstring>

namespace petroscope::serve {
namespace {

constexpr std::uint32_t kHarmonicsMagic = 0x31485350;  // "PSH1" read little-endian
constexpr std::size_t kRandomSectionsKept = 16;
/// Where a grain's numbers are given in white light: the peak of the photopic luminous efficiency.
constexpr double kWhiteLightNumbersNm = 555.0;

/// A random granite-like section, the same for the same seed (thin_sections/granite was made so).
ThinSection random_section(std::uint64_t seed) {
    VoronoiSectionSettings settings;
    settings.minerals = {"quartz", "orthoclase", "albite", "biotite", "muscovite"};
    settings.weights = {28, 26, 24, 14, 8};
    settings.grain_sizes = {1.1, 1.2, 1.1, 0.9, 0.8};
    settings.grain_count = 150;
    settings.size_px = 512;
    settings.pixel_size_um = 8.0;
    settings.seed = seed;
    settings.name = "random " + std::to_string(seed);
    ThinSection section = random_voronoi_section(settings);
    section.validate();
    return section;
}

std::string content_type_of(const std::filesystem::path& file) {
    const std::string extension = file.extension().string();
    if (extension == ".html") return "text/html; charset=utf-8";
    if (extension == ".js") return "text/javascript; charset=utf-8";
    return "text/css; charset=utf-8";
}

Reply json_reply(const nlohmann::json& value, int status = 200) { return {status, "application/json", value.dump()}; }

template <typename Value>
void append_bytes(std::string& bytes, const Value& value) {
    char raw[sizeof(Value)];
    std::memcpy(raw, &value, sizeof(Value));
    bytes.append(raw, sizeof(Value));
}

nlohmann::json optional_json(const std::optional<double>& value) { return value ? nlohmann::json(*value) : nlohmann::json(nullptr); }

nlohmann::json grain_json(const GrainOptics& optics) {
    const OpticalSummary& mineral = optics.mineral;
    return {{"wavelength_nm", optics.wavelength_nm},
            {"n_fast", optics.n_fast},
            {"n_slow", optics.n_slow},
            {"birefringence_in_section", optics.birefringence_in_section},
            {"retardation_nm", optics.retardation_nm},
            {"slow_azimuth_deg", optional_json(optics.slow_azimuth_deg)},
            {"extinction_stage_deg", optional_json(optics.extinction_stage_deg)},
            {"n_alpha", mineral.n_alpha},
            {"n_beta", mineral.n_beta},
            {"n_gamma", mineral.n_gamma},
            {"mineral_birefringence", mineral.birefringence},
            {"two_v_deg", optional_json(mineral.two_v_deg)},
            {"optic_sign", mineral.sign}};
}

}  // namespace

std::string encode_stage_harmonics(const StageHarmonics& harmonics) {
    const Image& image = harmonics.coefficients;
    std::string bytes;
    bytes.reserve(16 + sizeof(float) * (harmonics.outside.size() + image.pixels.size()));
    append_bytes(bytes, kHarmonicsMagic);
    append_bytes(bytes, static_cast<std::uint32_t>(image.width));
    append_bytes(bytes, static_cast<std::uint32_t>(image.height));
    append_bytes(bytes, static_cast<std::uint32_t>(harmonics.resampling == StageResampling::bilinear ? 1 : 0));
    for (const float value : harmonics.outside) append_bytes(bytes, value);
    const auto* raw = reinterpret_cast<const char*>(image.pixels.data());
    bytes.append(raw, image.pixels.size() * sizeof(float));
    return bytes;
}

LiveMicroscope::LiveMicroscope(const MineralCatalog& catalog, const std::filesystem::path& web_dir, const std::filesystem::path& sections_dir)
    : catalog_(catalog), sections_dir_(sections_dir) {
    for (const auto& entry : std::filesystem::directory_iterator(web_dir)) {
        const std::filesystem::path& file = entry.path();
        const std::string extension = file.extension().string();
        if (!entry.is_regular_file() || (extension != ".html" && extension != ".js" && extension != ".css")) continue;
        page_files_["/" + file.filename().string()] = read_text_file(file);
    }
    if (page_files_.find("/index.html") == page_files_.end()) throw InputError(web_dir.string() + ": the page's index.html is missing");
    page_files_["/"] = page_files_["/index.html"];
    for (const auto& entry : std::filesystem::directory_iterator(sections_dir)) {
        if (entry.is_directory() && std::filesystem::exists(entry.path() / "section.txt")) section_names_.push_back(entry.path().filename().string());
    }
    std::sort(section_names_.begin(), section_names_.end());
    section_names_.push_back("random");
}

Reply LiveMicroscope::get(std::string_view path, const QueryParameters& query) const {
    try {
        return answer(path, query);
    } catch (const InputError& error) {
        return json_reply({{"error", error.what()}}, 400);
    } catch (const std::exception& error) {
        return json_reply({{"error", std::string("internal error: ") + error.what()}}, 500);
    }
}

Reply LiveMicroscope::answer(std::string_view path, const QueryParameters& query) const {
    if (path == "/api/catalog") return catalog_reply();
    if (path == "/api/view") return view_reply(query);
    if (path == "/api/grain") return grain_reply(query);
    if (const auto found = page_files_.find(path); found != page_files_.end()) {
        const std::string name = found->first == "/" ? "index.html" : found->first;
        return {200, content_type_of(name), found->second};
    }
    return json_reply({{"error", "no such page: " + quote_input(path)}}, 404);
}

Reply LiveMicroscope::catalog_reply() const {
    nlohmann::json minerals = nlohmann::json::array();
    for (const Mineral& mineral : catalog_.minerals()) {
        minerals.push_back({{"name", mineral.name}, {"optical_class", optical_class_name(mineral.optical_class)}});
    }
    return json_reply({{"minerals", minerals},
                       {"sections", section_names_},
                       {"plates", {"none", "gypsum", "mica", "wedge"}},
                       {"illuminants", {"D65", "A"}},
                       {"cuts", {"optic-axis", "acute-bisectrix", "obtuse-bisectrix", "optic-normal"}},
                       {"max_figure_px", kServerMaxFigurePx}});
}

std::shared_ptr<const ThinSection> LiveMicroscope::section(const QueryParameters& query) const {
    const std::string name = query.choice("section", section_names_);
    const std::string key = name == "random" ? "random " + std::to_string(query.integer("seed", 0, 2147483647, 1)) : name;
    const std::lock_guard<std::mutex> lock(sections_mutex_);
    if (const auto found = sections_.find(key); found != sections_.end()) return found->second;
    if (sections_.size() >= section_names_.size() + kRandomSectionsKept) sections_.clear();
    std::shared_ptr<const ThinSection> loaded =
        name == "random" ? std::make_shared<const ThinSection>(random_section(static_cast<std::uint64_t>(query.integer("seed", 0, 2147483647, 1))))
                         : std::make_shared<const ThinSection>(read_thin_section(sections_dir_ / name, catalog_));
    sections_[key] = loaded;
    return loaded;
}

Reply LiveMicroscope::view_reply(const QueryParameters& query) const {
    query.refuse_unknown(view_parameter_names());
    const SectionLookup sections = [this](const QueryParameters& q) { return section(q); };
    const bool conoscope = query.choice("optics", {"orthoscope", "conoscope"}) == "conoscope";
    StageHarmonics harmonics;
    if (conoscope) {
        const ConoscopeRequest request = conoscope_view_request(query, catalog_, sections);
        const std::lock_guard<std::mutex> lock(render_mutex_);
        harmonics = conoscope_stage_harmonics(request, catalog_);
    } else {
        const OrthoscopeRequest request = orthoscope_view_request(query, catalog_, sections);
        const std::lock_guard<std::mutex> lock(render_mutex_);
        harmonics = orthoscope_stage_harmonics(request, catalog_);
    }
    return {200, "application/octet-stream", encode_stage_harmonics(harmonics)};
}

Reply LiveMicroscope::grain_reply(const QueryParameters& query) const {
    query.refuse_unknown(view_parameter_names());
    const double wavelength_nm = query.optional_number("wavelength_nm", 360.0, 830.0).value_or(kWhiteLightNumbersNm);
    if (query.has("section")) {
        const PickedGrain picked = picked_grain(query, [this](const QueryParameters& q) { return section(q); });
        nlohmann::json numbers = grain_json(grain_optics(catalog_.find(picked.grain->mineral), picked.grain->crystal_axes, picked.thickness_um, wavelength_nm));
        numbers["label"] = picked.grain->label;
        numbers["mineral"] = picked.grain->mineral;
        numbers["thickness_um"] = picked.thickness_um;
        return json_reply(numbers);
    }
    const ThinSection crystal = single_crystal_section(query, catalog_);
    const ThinSectionGrain& grain = crystal.grains.front();
    nlohmann::json numbers = grain_json(grain_optics(catalog_.find(grain.mineral), grain.crystal_axes, crystal.thickness_um, wavelength_nm));
    numbers["mineral"] = grain.mineral;
    numbers["thickness_um"] = crystal.thickness_um;
    return json_reply(numbers);
}

}  // namespace petroscope::serve
