#include "petroscope/serve/live_microscope.hpp"

#include "render_thread.hpp"

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
#include <fstream>
#include <stdlib.h>

namespace petroscope::serve {
namespace {

constexpr std::uint32_t kHarmonicsMagic = 0x31485350;  // "PSH1" read little-endian
constexpr std::size_t kRandomSectionsKept = 16;
constexpr std::size_t kUploadsKept = 8;
constexpr std::string_view kUploadPrefix = "upload-";
/// Where a grain's numbers are given in white light: the peak of the photopic luminous efficiency.
constexpr double kWhiteLightNumbersNm = 555.0;

/// A random granite-like section, the same for the same seed (thin_sections/granite was made so).
ThinSection random_section(std::uint64_t seed, const MineralCatalog& catalog) {
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
    draw_handedness(section, catalog, seed);
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

/// A file's own name as it may appear in a description: a plain name, no folders, printable.
bool plain_file_name(std::string_view name) {
    if (name.empty() || name.size() > 255 || name == "." || name == "..") return false;
    return std::all_of(name.begin(), name.end(), [](char c) { return c != '/' && c != '\\' && static_cast<unsigned char>(c) >= 0x20; });
}

/// The width and height in a PNG's IHDR chunk (big-endian at bytes 16 … 23), before anything decodes it.
std::pair<std::uint32_t, std::uint32_t> png_size(const UploadedFile& file) {
    static constexpr std::string_view kSignature("\x89PNG\r\n\x1a\n", 8);
    const std::string& bytes = file.content;
    if (bytes.size() < 24 || std::string_view(bytes).substr(0, 8) != kSignature) {
        throw InputError(quote_input(file.filename) + " is not a PNG file; a section sent to the server has PNG grain maps only");
    }
    const auto word = [&](std::size_t at) {
        std::uint32_t value = 0;
        for (std::size_t k = 0; k < 4; ++k) value = (value << 8) | static_cast<unsigned char>(bytes[at + k]);
        return value;
    };
    return {word(16), word(20)};
}

void replace_all(std::string& text, const std::string& from, const std::string& to) {
    for (std::size_t at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size())) text.replace(at, from.size(), to);
}

/// A folder of this process's own, removed with everything in it when the object goes.
class PrivateFolder {
public:
    PrivateFolder() {
        std::string pattern = (std::filesystem::temp_directory_path() / "petroscope-upload-XXXXXX").string();
        if (mkdtemp(pattern.data()) == nullptr) throw std::runtime_error("cannot create a temporary folder for a section sent to the server");
        path_ = pattern;
    }
    ~PrivateFolder() {
        std::error_code ignored;
        std::filesystem::remove_all(path_, ignored);
    }
    PrivateFolder(const PrivateFolder&) = delete;
    PrivateFolder& operator=(const PrivateFolder&) = delete;
    const std::filesystem::path& path() const { return path_; }

private:
    std::filesystem::path path_;
};

void write_bytes(const std::filesystem::path& path, const std::string& bytes) {
    std::ofstream file(path, std::ios::binary);
    file.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    if (!file) throw std::runtime_error("cannot write a section sent to the server to its temporary folder");
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
    : catalog_(catalog), sections_dir_(sections_dir), render_thread_(std::make_unique<RenderThread>()) {
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

LiveMicroscope::~LiveMicroscope() = default;

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
        minerals.push_back({{"name", mineral.name},
                            {"optical_class", optical_class_name(mineral.optical_class)},
                            {"optically_active", mineral.optically_active()}});
    }
    return json_reply({{"minerals", minerals},
                       {"sections", section_names_},
                       {"plates", {"none", "gypsum", "mica", "wedge"}},
                       {"illuminants", {"D65", "A"}},
                       {"cuts", {"optic-axis", "acute-bisectrix", "obtuse-bisectrix", "optic-normal"}},
                       {"max_figure_px", kServerMaxFigurePx}});
}

std::shared_ptr<const ThinSection> LiveMicroscope::section(const QueryParameters& query) const {
    if (const std::optional<std::string> sent = query.text("section"); sent && sent->rfind(kUploadPrefix, 0) == 0) {
        const std::lock_guard<std::mutex> lock(sections_mutex_);
        if (const auto found = uploads_.find(*sent); found != uploads_.end()) return found->second;
        throw InputError(parameter_message("section", "no section " + quote_input(*sent) + " was sent to this server (or it was dropped to make room)"));
    }
    const std::string name = query.choice("section", section_names_);
    const bool random = name == "random";
    const std::uint64_t seed = random ? static_cast<std::uint64_t>(query.integer("seed", 0, 2147483647, 1)) : 0;
    const std::string key = random ? "random " + std::to_string(seed) : name;
    const std::lock_guard<std::mutex> lock(sections_mutex_);
    if (const auto found = sections_.find(key); found != sections_.end()) return found->second;
    if (sections_.size() >= section_names_.size() + kRandomSectionsKept) sections_.clear();
    std::shared_ptr<const ThinSection> loaded = random ? std::make_shared<const ThinSection>(random_section(seed, catalog_))
                                                       : std::make_shared<const ThinSection>(read_thin_section(sections_dir_ / name, catalog_));
    sections_[key] = loaded;
    return loaded;
}

Reply LiveMicroscope::view_reply(const QueryParameters& query) const {
    query.refuse_unknown(view_parameter_names());
    const SectionLookup sections = [this](const QueryParameters& q) { return section(q); };
    const bool conoscope = query.choice("optics", {"orthoscope", "conoscope"}) == "conoscope";
    const Illumination illumination = illumination_from(query);
    if (conoscope) {
        const ConoscopeRequest request = conoscope_view_request(query, catalog_, sections);
        return render_thread_->run([&] { return Reply{200, "application/octet-stream", encode_stage_harmonics(conoscope_stage_harmonics(request, catalog_, illumination))}; });
    }
    const OrthoscopeRequest request = orthoscope_view_request(query, catalog_, sections);
    return render_thread_->run([&] { return Reply{200, "application/octet-stream", encode_stage_harmonics(orthoscope_stage_harmonics(request, catalog_, illumination))}; });
}

ThinSection LiveMicroscope::read_upload(const std::vector<UploadedFile>& files) const {
    const UploadedFile* description = nullptr;
    std::vector<const UploadedFile*> maps;
    for (const UploadedFile& file : files) {
        if (file.field == "description" && description == nullptr) {
            description = &file;
        } else if (file.field == "map") {
            if (!plain_file_name(file.filename)) throw InputError("a grain map's file name must be a plain name, got " + quote_input(file.filename));
            const auto [width, height] = png_size(file);
            if (width > static_cast<std::uint32_t>(kUploadMaxSidePx) || height > static_cast<std::uint32_t>(kUploadMaxSidePx)) {
                throw InputError(quote_input(file.filename) + " is " + std::to_string(width) + "x" + std::to_string(height) +
                                 " pixels; a section sent to the server may have at most " + std::to_string(kUploadMaxSidePx) + " per side");
            }
            maps.push_back(&file);
        } else {
            throw InputError("unexpected form field " + quote_input(file.field, 40) + "; expected one 'description' and its grain maps as 'map'");
        }
    }
    if (description == nullptr) throw InputError("no section description: send its section.txt as 'description' with its grain map as 'map'");
    const PrivateFolder folder;
    write_bytes(folder.path() / "section.txt", description->content);
    for (std::size_t k = 0; k < maps.size(); ++k) write_bytes(folder.path() / ("map-" + std::to_string(k) + ".png"), maps[k]->content);
    const auto map_path = [&](const std::string& name) {
        for (std::size_t k = 0; k < maps.size(); ++k) {
            if (maps[k]->filename == name) return folder.path() / ("map-" + std::to_string(k) + ".png");
        }
        throw InputError(quote_input(name) + " was not sent with the description (send the maps it names beside it)");
    };
    try {
        ThinSection section = read_thin_section(folder.path() / "section.txt", catalog_, map_path);
        section.note = "sent to the server as " + quote_input(description->filename);
        return section;
    } catch (const InputError& error) {  // messages name the files as the user knows them, not the private folder
        std::string message = error.what();
        replace_all(message, (folder.path() / "section.txt").string(), quote_input(description->filename));
        for (std::size_t k = 0; k < maps.size(); ++k) replace_all(message, (folder.path() / ("map-" + std::to_string(k) + ".png")).string(), quote_input(maps[k]->filename));
        throw InputError(message);
    }
}

Reply LiveMicroscope::post_section(const std::vector<UploadedFile>& files) const {
    try {
        const auto section = std::make_shared<const ThinSection>(read_upload(files));
        const std::lock_guard<std::mutex> lock(sections_mutex_);
        ++upload_count_;
        uploads_.erase(std::string(kUploadPrefix) + std::to_string(upload_count_ - static_cast<int>(kUploadsKept)));  // the oldest kept
        const std::string key = std::string(kUploadPrefix) + std::to_string(upload_count_);
        uploads_[key] = section;
        return json_reply({{"section", key}, {"name", section->name}, {"width_px", section->width_px}, {"height_px", section->height_px},
                           {"grains", section->grains.size()}});
    } catch (const InputError& error) {
        return json_reply({{"error", std::string(error.what())}}, 400);
    } catch (const std::exception& error) {
        return json_reply({{"error", std::string("internal error: ") + error.what()}}, 500);
    }
}

Reply LiveMicroscope::grain_reply(const QueryParameters& query) const {
    query.refuse_unknown(view_parameter_names());
    const double wavelength_nm = query.optional_number("wavelength_nm", 360.0, 830.0).value_or(kWhiteLightNumbersNm);
    // The form of an optically active grain as rendered (a section grain naming none is right-handed; a single
    // crystal's is the one chosen on the page); null when inactive.
    const auto form = [&](const ThinSectionGrain& grain) {
        if (!catalog_.find(grain.mineral).optically_active()) return nlohmann::json(nullptr);
        return nlohmann::json(handedness_name(grain.handedness.value_or(Handedness::right)));
    };
    if (query.has("section")) {
        const PickedGrain picked = picked_grain(query, [this](const QueryParameters& q) { return section(q); });
        nlohmann::json numbers = grain_json(grain_optics(catalog_.find(picked.grain->mineral), picked.grain->crystal_axes, picked.thickness_um, wavelength_nm));
        numbers["label"] = picked.grain->label;
        numbers["mineral"] = picked.grain->mineral;
        numbers["thickness_um"] = picked.thickness_um;
        numbers["handedness"] = form(*picked.grain);
        return json_reply(numbers);
    }
    const ThinSection crystal = single_crystal_section(query, catalog_);
    const ThinSectionGrain& grain = crystal.grains.front();
    nlohmann::json numbers = grain_json(grain_optics(catalog_.find(grain.mineral), grain.crystal_axes, crystal.thickness_um, wavelength_nm));
    numbers["mineral"] = grain.mineral;
    numbers["thickness_um"] = crystal.thickness_um;
    numbers["handedness"] = form(grain);
    return json_reply(numbers);
}

}  // namespace petroscope::serve
