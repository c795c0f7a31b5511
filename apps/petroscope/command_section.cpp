// petroscope section: make random thin sections and describe existing ones (format: thin_sections/README.md).
#include "cli_common.hpp"

#include "petroscope/core/error.hpp"
#include "petroscope/core/text.hpp"
#include "petroscope/core/units.hpp"
#include "petroscope/io/data_files.hpp"
#include "petroscope/io/thin_section_file.hpp"
#include "petroscope/microscope/thin_section.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <map>
#include <memory>
#include <numbers>

namespace petroscope::cli {
namespace {

struct RandomOptions {
    std::string minerals;
    std::string weights;
    std::string sizes;
    int grains = 200;
    int size_px = 512;
    std::string pixel_size = "2um";
    std::string thickness = "30um";
    std::string wedge;
    std::uint64_t seed = 1;
    std::string name;
    std::string output;
};

struct SectionShowOptions {
    std::string path;
    bool json = false;
};

// "5,3,1" → {5, 3, 1}; every value a finite number.
std::vector<double> parse_number_list(const std::string& option, const std::string& text) {
    std::vector<double> values;
    for (const std::string& part : split(text, ',')) {
        const auto value = parse_double(part);
        if (!value) throw InputError(option + " " + quote_input(text) + ": expected comma-separated numbers, e.g. 5,3,1");
        values.push_back(*value);
    }
    return values;
}

// "0um,60um[,x|y]" → the wedge of `section`.
void apply_wedge(const std::string& text, ThinSection& section) {
    const auto parts = split(text, ',');
    const std::string expected = "--wedge " + quote_input(text) + ": expected START,END[,x|y], two thicknesses with units (e.g. 0um,60um) and the "
                                 "direction (x: left to right, the default; y: top to bottom)";
    if (parts.size() < 2 || parts.size() > 3 || (parts.size() == 3 && parts[2] != "x" && parts[2] != "y")) throw InputError(expected);
    section.thickness_kind = ThicknessKind::wedge;
    section.wedge_start_um = with_option("--wedge", [&] { return parse_length_um(parts[0]); });
    section.wedge_end_um = with_option("--wedge", [&] { return parse_length_um(parts[1]); });
    section.wedge_along_x = parts.size() == 2 || parts[2] == "x";
    if (section.wedge_start_um < 0.0 || section.wedge_end_um < 0.0 || section.wedge_start_um + section.wedge_end_um <= 0.0) {
        throw InputError(expected + " (thicknesses >= 0, not both 0)");
    }
}

// The command that makes the same section, in canonical form (recorded in the description's note).
std::string canonical_command(const VoronoiSectionSettings& settings, const ThinSection& section) {
    std::string minerals, weights, sizes;
    for (std::size_t m = 0; m < settings.minerals.size(); ++m) {
        minerals += (m ? "," : "") + settings.minerals[m];
        if (!settings.weights.empty()) weights += (m ? "," : "") + format_number(settings.weights[m]);
        if (!settings.grain_sizes.empty()) sizes += (m ? "," : "") + format_number(settings.grain_sizes[m]);
    }
    if (minerals.find(' ') != std::string::npos) minerals = "'" + minerals + "'";  // a name with a space, for the shell
    std::string command = "petroscope section random --minerals " + minerals;
    if (!weights.empty()) command += " --weights " + weights;
    if (!sizes.empty()) command += " --sizes " + sizes;
    command += " --grains " + std::to_string(settings.grain_count) + " --size " + std::to_string(settings.size_px) +
               " --pixel-size " + format_number(settings.pixel_size_um) + "um";
    if (section.thickness_kind == ThicknessKind::wedge) {
        command += " --wedge " + format_number(section.wedge_start_um) + "um," + format_number(section.wedge_end_um) + "um," +
                   (section.wedge_along_x ? "x" : "y");
    } else {
        command += " --thickness " + format_number(settings.thickness_um) + "um";
    }
    command += " --seed " + std::to_string(settings.seed) + " --name " + settings.name;
    return command;
}

void run_random(const RandomOptions& options, const std::string& minerals_dir) {
    const auto started = std::chrono::steady_clock::now();
    const MineralCatalog catalog = load_mineral_catalog(minerals_directory(minerals_dir));
    VoronoiSectionSettings settings;
    for (const std::string& name : split(options.minerals, ',')) {
        if (name.empty()) throw InputError("--minerals " + quote_input(options.minerals) + ": expected comma-separated mineral names, e.g. quartz,orthoclase,biotite");
        settings.minerals.push_back(with_option("--minerals", [&] { return catalog.find(name).name; }));
    }
    if (!options.weights.empty()) settings.weights = parse_number_list("--weights", options.weights);
    if (!options.sizes.empty()) settings.grain_sizes = parse_number_list("--sizes", options.sizes);
    settings.grain_count = options.grains;
    settings.size_px = options.size_px;
    settings.pixel_size_um = positive_length_um("--pixel-size", options.pixel_size);
    settings.thickness_um = positive_length_um("--thickness", options.thickness);
    settings.seed = options.seed;
    settings.name = options.name.empty() ? std::filesystem::path(options.output).lexically_normal().filename().string() : options.name;
    if (settings.name.empty() || settings.name == "." || settings.name == "..") settings.name = "random";
    if (settings.size_px < 16 || settings.size_px > 8192) {
        throw InputError("--size " + std::to_string(settings.size_px) + ": expected 16 to 8192 pixels");
    }
    const long long most_grains = std::min<long long>(static_cast<long long>(settings.size_px) * settings.size_px, 65535);
    if (settings.grain_count < 1 || settings.grain_count > most_grains) {
        throw InputError("--grains " + std::to_string(settings.grain_count) + ": expected 1 to " + std::to_string(most_grains) +
                         " (at most one grain per pixel, --size squared, and 65535 labels in a 16-bit map)");
    }
    for (const auto& [option, values] : {std::pair{std::string("--weights"), &settings.weights}, {std::string("--sizes"), &settings.grain_sizes}}) {
        if (!values->empty() && values->size() != settings.minerals.size()) {
            throw InputError(option + ": " + std::to_string(values->size()) + " values for " + std::to_string(settings.minerals.size()) +
                             " minerals; expected one per mineral, in the order of --minerals");
        }
    }
    settings.validate();
    ThinSection wedge_holder;
    if (!options.wedge.empty()) apply_wedge(options.wedge, wedge_holder);

    ThinSection section = random_voronoi_section(settings);
    draw_handedness(section, catalog, settings.seed);
    if (!options.wedge.empty()) {
        section.thickness_kind = ThicknessKind::wedge;
        section.wedge_start_um = wedge_holder.wedge_start_um;
        section.wedge_end_um = wedge_holder.wedge_end_um;
        section.wedge_along_x = wedge_holder.wedge_along_x;
    }
    section.note = "made by: " + canonical_command(settings, section);
    write_thin_section(section, options.output);

    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    std::map<std::string, int> per_mineral;
    for (const ThinSectionGrain& grain : section.grains) ++per_mineral[grain.mineral];
    std::string counts;
    for (const auto& [mineral, count] : per_mineral) counts += (counts.empty() ? "" : ", ") + mineral + " " + std::to_string(count);
    const std::filesystem::path dir(options.output);
    std::cerr << "petroscope: wrote " << (dir / kThinSectionDescriptionName).string() << " and " << (dir / kThinSectionGrainMapName).string()
              << " (" << section.width_px << "x" << section.height_px << ", " << section.grains.size() << " grains: " << counts << "; "
              << seconds << " s)\n";
}

struct MineralStatistics {
    int grains = 0;
    std::size_t pixels = 0;
    double diameter_sum_um = 0.0;  // equivalent circular diameters 2√(A/π)
    int own_thickness = 0;
};

void run_show(const SectionShowOptions& options, const std::string& minerals_dir) {
    const MineralCatalog catalog = load_mineral_catalog(minerals_directory(minerals_dir));
    const std::filesystem::path description = thin_section_description_path(options.path);
    const ThinSection section = read_thin_section(description, catalog);

    const double pixel_area_um2 = section.pixel_size_um * section.pixel_size_um;
    std::map<std::string, MineralStatistics> statistics;
    int grains_in_map = 0;
    for (const auto& [label, count] : section.label_counts()) {
        const ThinSectionGrain& grain = section.grains[static_cast<std::size_t>(section.grain_index_of_label[label])];
        MineralStatistics& entry = statistics[grain.mineral];
        ++entry.grains;
        ++grains_in_map;
        entry.pixels += count;
        entry.diameter_sum_um += 2.0 * std::sqrt(static_cast<double>(count) * pixel_area_um2 / std::numbers::pi);
        if (grain.thickness_um) ++entry.own_thickness;
    }
    const int unused = static_cast<int>(section.grains.size()) - grains_in_map;
    const double total_pixels = static_cast<double>(section.labels.size());

    nlohmann::json thickness;
    std::string thickness_text;
    switch (section.thickness_kind) {
        case ThicknessKind::uniform:
            thickness = {{"kind", "uniform"}, {"thickness_um", section.thickness_um}};
            thickness_text = "uniform " + format_number(section.thickness_um) + " um";
            break;
        case ThicknessKind::wedge:
            thickness = {{"kind", "wedge"}, {"start_um", section.wedge_start_um}, {"end_um", section.wedge_end_um},
                         {"along", section.wedge_along_x ? "x" : "y"}};
            thickness_text = "wedge " + format_number(section.wedge_start_um) + " -> " + format_number(section.wedge_end_um) + " um " +
                             (section.wedge_along_x ? "from the left edge to the right" : "from the top edge to the bottom");
            break;
        case ThicknessKind::map: {
            const auto [low, high] = std::minmax_element(section.thickness_map_um.begin(), section.thickness_map_um.end());
            double sum = 0.0;
            for (const float value : section.thickness_map_um) sum += value;
            const double mean = sum / total_pixels;
            thickness = {{"kind", "map"}, {"min_um", *low}, {"max_um", *high}, {"mean_um", mean}};
            char buffer[128];
            std::snprintf(buffer, sizeof buffer, "map, %.3g … %.3g um (mean %.3g)", static_cast<double>(*low), static_cast<double>(*high), mean);
            thickness_text = buffer;
            break;
        }
    }

    if (options.json) {
        nlohmann::json minerals = nlohmann::json::object();
        for (const auto& [mineral, entry] : statistics) {
            minerals[mineral] = {{"grains", entry.grains}, {"area_fraction", static_cast<double>(entry.pixels) / total_pixels},
                                 {"mean_equivalent_diameter_um", entry.diameter_sum_um / entry.grains},
                                 {"grains_with_own_thickness", entry.own_thickness}};
        }
        const nlohmann::json document{
            {"name", section.name}, {"file", description.string()}, {"note", section.note},
            {"size_px", {section.width_px, section.height_px}}, {"pixel_size_um", section.pixel_size_um},
            {"size_um", {section.width_px * section.pixel_size_um, section.height_px * section.pixel_size_um}},
            {"thickness", thickness}, {"grains", grains_in_map}, {"unused_grain_entries", unused}, {"minerals", minerals}};
        std::cout << document.dump(2) << '\n';
        return;
    }
    std::printf("%s  (%s)\n", section.name.c_str(), description.string().c_str());
    if (!section.note.empty()) std::printf("  note: %s\n", section.note.c_str());
    std::printf("  %d x %d px, pixel %s um: %s x %s um\n", section.width_px, section.height_px, format_number(section.pixel_size_um).c_str(),
                format_number(section.width_px * section.pixel_size_um).c_str(), format_number(section.height_px * section.pixel_size_um).c_str());
    std::printf("  thickness: %s\n", thickness_text.c_str());
    std::printf("  %d grains in the map", grains_in_map);
    if (unused > 0) std::printf(" (%d more grain lines name labels the map does not use)", unused);
    std::printf("\n\n  %-16s %7s %8s %20s %16s\n", "mineral", "grains", "area %", "mean diameter (um)", "own thickness");
    for (const auto& [mineral, entry] : statistics) {
        std::printf("  %-16s %7d %8.1f %20.1f %16d\n", mineral.c_str(), entry.grains, 100.0 * static_cast<double>(entry.pixels) / total_pixels,
                    entry.diameter_sum_um / entry.grains, entry.own_thickness);
    }
    std::printf("  (mean diameter: of the circle with the grain's area)\n");
}

}  // namespace

void add_section_command(CLI::App& app, const std::string& minerals_dir) {
    CLI::App* section = app.add_subcommand("section", "Thin sections: grain maps with minerals and orientations (thin_sections/README.md)");
    section->require_subcommand(1);

    auto random = std::make_shared<RandomOptions>();
    CLI::App* make = section->add_subcommand(
        "random",
        "Make a random thin section: Voronoi cells (power cells with --sizes) of randomly chosen minerals,\n"
        "each uniformly randomly oriented; the same --seed gives the same section. Writes DIR/section.txt and\n"
        "DIR/grains.png together, or nothing.");
    make->add_option("--minerals", random->minerals, "Comma-separated minerals ('petroscope minerals' lists them)")->required();
    make->add_option("--weights", random->weights, "Relative frequency of each mineral among the grains, e.g. 5,3,1 (default: equal)");
    make->add_option("--sizes", random->sizes, "Relative grain size of each mineral, e.g. 3,3,1 (default: equal, plain Voronoi cells)");
    make->add_option("--grains", random->grains, "Number of grains (seeds), 1 to min(size^2, 65535)")->capture_default_str();
    make->add_option("--size", random->size_px, "Width and height of the map in pixels (16 to 8192)")->capture_default_str();
    make->add_option("--pixel-size", random->pixel_size, "Edge of a pixel on the specimen, with unit")->capture_default_str();
    auto* thickness = make->add_option("--thickness", random->thickness, "Uniform section thickness, with unit")->capture_default_str();
    make->add_option("--wedge", random->wedge, "A wedge instead: START,END[,x|y] with units (0um,60um: 0 at the left edge, 60 um at the right)")
        ->excludes(thickness);
    make->add_option("--seed", random->seed, "Random seed (std::mt19937_64)")->capture_default_str();
    make->add_option("--name", random->name, "Section name (default: the folder's name)");
    make->add_option("-o,--output", random->output, "Folder to write (created if missing; its parent must exist)")->required();
    make->callback([random, &minerals_dir] { run_random(*random, minerals_dir); });

    auto show_options = std::make_shared<SectionShowOptions>();
    CLI::App* show = section->add_subcommand("show", "Summarise a thin section: size, thickness, grains per mineral");
    show->add_option("section", show_options->path, "A section folder (its section.txt) or a description file")->required();
    show->add_flag("--json", show_options->json, "Print JSON");
    show->callback([show_options, &minerals_dir] { run_show(*show_options, minerals_dir); });
}

}  // namespace petroscope::cli
