#include "fuzz_inputs.hpp"

#include "petroscope/core/error.hpp"
#include "petroscope/core/text.hpp"
#include "petroscope/core/units.hpp"
#include "petroscope/io/data_files.hpp"
#include "petroscope/io/image_writer.hpp"
#include "petroscope/io/interface_case.hpp"
#include "petroscope/io/jpeg_encoding.hpp"
#include "petroscope/io/json_reader.hpp"
#include "petroscope/io/label_image.hpp"
#include "petroscope/io/scene_file.hpp"
#include "petroscope/io/sweep_plan.hpp"
#include "petroscope/io/thin_section_file.hpp"
#include "petroscope/minerals/mineral_parser.hpp"
#include "petroscope/serve/live_microscope.hpp"
#include "petroscope/serve/view_requests.hpp"

#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <unistd.h>

namespace petroscope::fuzz {
namespace {

const MineralCatalog& catalog() {
    static const MineralCatalog minerals = load_mineral_catalog(std::filesystem::path(PETROSCOPE_SOURCE_DIR) / "minerals");
    return minerals;
}

/// A scratch folder of this process, with a 4 × 4 grain map of labels 1 … 3 (grains.png) for thin sections.
const std::filesystem::path& scratch() {
    static const std::filesystem::path folder = [] {
        const std::filesystem::path base = std::filesystem::exists("/dev/shm") ? "/dev/shm" : std::filesystem::temp_directory_path();
        const std::filesystem::path path = base / ("petroscope-fuzz-" + std::to_string(::getpid()));
        std::filesystem::create_directories(path);
        write_label_png({1, 1, 2, 2, 1, 1, 2, 2, 3, 3, 3, 3, 3, 3, 3, 3}, 4, 4, path / "grains.png");
        return path;
    }();
    return folder;
}

std::filesystem::path write_input(const std::string& name, std::string_view input) {
    const std::filesystem::path path = scratch() / name;
    std::ofstream(path, std::ios::binary | std::ios::trunc).write(input.data(), static_cast<std::streamsize>(input.size()));
    return path;
}

void values(std::string_view input) {
    if (input.empty()) return;
    const std::string_view text = input.substr(1);
    switch (static_cast<unsigned char>(input[0]) % 5) {
    case 0:
        parse_length_um(text);
        break;
    case 1:
        parse_wavelength_nm(text);
        break;
    case 2:
        parse_sweep_parameter(text, 10000);
        break;
    case 3:
        parse_sweep_shard(text);
        break;
    default:
        parse_double(text);
        split(text, ',');
        break;
    }
}

/// A query of the live microscope's server, "name=value&…" as the server has it after decoding: the grain's
/// numbers answered, and both views' requests built and planned (not rendered: a view takes a second).
void serve_query(std::string_view input) {
    static const serve::LiveMicroscope microscope(catalog(), shipped_directory("web"), shipped_directory("thin_sections"));
    static const auto granite = std::make_shared<const ThinSection>(read_thin_section(shipped_directory("thin_sections") / "granite", catalog()));
    std::vector<std::pair<std::string, std::string>> pairs;
    for (const std::string& part : split(input, '&')) {
        const std::size_t equals = part.find('=');
        pairs.emplace_back(part.substr(0, equals), equals == std::string::npos ? "" : part.substr(equals + 1));
    }
    const serve::QueryParameters query(pairs);
    const serve::Reply reply = microscope.get("/api/grain", query);
    if (reply.status != 200 && reply.status != 400) throw std::logic_error("status " + std::to_string(reply.status) + ": " + reply.body);
    const serve::SectionLookup sections = [](const serve::QueryParameters&) { return granite; };
    plan_orthoscope(serve::orthoscope_view_request(query, catalog(), sections), catalog());
    plan_conoscope(serve::conoscope_view_request(query, catalog(), sections), catalog());
}

void dispatch(const std::string& name, std::string_view input) {
    if (name == "mineral") {
        parse_mineral(input, "fuzz.txt");
    } else if (name == "thin_section") {
        read_thin_section(write_input("section.txt", input), catalog());
    } else if (name == "interface_case") {
        parse_interface_case(parse_json_text(std::string(input), "case.json"), "case.json", catalog());
    } else if (name == "scene") {
        static const RenderSpectrum spectrum = render_spectrum(load_cie_1931_observer(), load_light_source("D65"));
        parse_scene(std::string(input), scratch() / "scene.json", catalog(), spectrum);
    } else if (name == "values") {
        values(input);
    } else if (name == "serve_query") {
        serve_query(input);
    } else if (name == "image_file") {
        read_image(write_input("image", input));  // PNG, TIFF, OpenEXR or JPEG, by the file's signature
    } else if (name == "jpeg_header") {
        (void)jpeg_encoding_of({reinterpret_cast<const std::uint8_t*>(input.data()), input.size()}, "fuzz.jpg");
    } else {
        throw std::invalid_argument("unknown fuzz target " + name);
    }
}

}  // namespace

const std::vector<std::string>& target_names() {
    static const std::vector<std::string> names{"mineral", "thin_section", "interface_case", "scene", "values", "jpeg_header", "serve_query", "image_file"};
    return names;
}

void run_target(const std::string& name, std::string_view input) {
    try {
        dispatch(name, input);
    } catch (const InputError&) {
        // Rejected with a message: what bad input should get.
    }
}

}  // namespace petroscope::fuzz
