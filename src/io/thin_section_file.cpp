#include "petroscope/io/thin_section_file.hpp"

#include "petroscope/core/error.hpp"
#include "petroscope/core/text.hpp"
#include "petroscope/core/units.hpp"
#include "petroscope/io/atomic_file.hpp"
#include "petroscope/io/data_files.hpp"
#include "petroscope/io/label_image.hpp"
#include "petroscope/optics/orientation.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>

namespace petroscope {
namespace {

namespace fs = std::filesystem;

const std::vector<std::string> kKeys{"name", "note", "grain_map", "size_px", "pixel_size_um", "thickness_um",
                                     "thickness_wedge_um", "thickness_map", "grain LABEL"};

struct Entry {
    std::string value;
    int line = 0;
};

// Removes a comment: '#' at the start of the line or after a space or tab (minerals/README.md).
std::string_view strip_comment(std::string_view line) {
    for (std::size_t i = 0; i < line.size(); ++i) {
        if (line[i] == '#' && (i == 0 || line[i - 1] == ' ' || line[i - 1] == '\t')) return line.substr(0, i);
    }
    return line;
}

std::optional<long long> parse_integer(std::string_view text) {
    text = trim(text);
    if (!text.empty() && text.front() == '+') text.remove_prefix(1);
    long long value = 0;
    const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (text.empty() || error != std::errc() || end != text.data() + text.size()) return std::nullopt;
    return value;
}

// The description's lines, split into plain keys and grain lines, each key once and each label once.
struct Description {
    std::string file;
    std::map<std::string, Entry> keys;
    std::vector<std::pair<int, Entry>> grains;  // label, "mineral, …" in file order
    int last_line = 1;

    const Entry* find(const std::string& key) const {
        const auto it = keys.find(key);
        return it == keys.end() ? nullptr : &it->second;
    }
    const Entry& require(const std::string& key, const std::string& what) const {
        if (const Entry* entry = find(key)) return *entry;
        throw located_error(file, last_line, "missing key " + quote_input(key) + " (" + what + ")");
    }
    InputError error(const Entry& entry, const std::string& what) const { return located_error(file, entry.line, what); }
};

Description split_description(std::string_view text, const std::string& file) {
    Description description;
    description.file = file;
    std::map<int, int> label_lines;
    for_each_line(text, [&](int line_number, std::string_view raw) {
        description.last_line = line_number;
        const std::string_view line = trim(strip_comment(raw));
        if (line.empty()) return;
        const std::size_t colon = line.find(':');
        if (colon == std::string_view::npos) {
            throw located_error(file, line_number, "expected 'key: value', found " + quote_input(line));
        }
        const std::string key(trim(line.substr(0, colon)));
        const std::string value(trim(line.substr(colon + 1)));
        if (key.empty()) throw located_error(file, line_number, "missing key before ':'");
        if (value.empty()) throw located_error(file, line_number, "key " + quote_input(key) + " has no value");
        const auto words = split_whitespace(key);
        if (words.front() == "grain") {
            const auto label = words.size() == 2 ? parse_integer(words[1]) : std::nullopt;
            if (!label || *label < 0 || *label > 65535) {
                throw located_error(file, line_number, "expected 'grain LABEL: MINERAL, …' with LABEL an integer 0 … 65535 (a value of the grain map), found " + quote_input(key));
            }
            const int label_value = static_cast<int>(*label);
            if (const auto previous = label_lines.find(label_value); previous != label_lines.end()) {
                throw located_error(file, line_number, "grain " + std::to_string(label_value) + " is defined twice (first on line " +
                                                           std::to_string(previous->second) + "); expected one line per label");
            }
            label_lines[label_value] = line_number;
            description.grains.push_back({label_value, Entry{value, line_number}});
            return;
        }
        if (std::find(kKeys.begin(), kKeys.end(), key) == kKeys.end()) {
            std::string list;
            for (const auto& name : kKeys) list += (list.empty() ? "" : ", ") + name;
            throw located_error(file, line_number, "unknown key " + quote_input(key) + " (valid keys: " + list + ")");
        }
        if (const auto previous = description.keys.find(key); previous != description.keys.end()) {
            throw located_error(file, line_number, "key " + quote_input(key) + " appears twice (first on line " + std::to_string(previous->second.line) + ")");
        }
        description.keys[key] = Entry{value, line_number};
    });
    return description;
}

double positive_number(const Description& description, const Entry& entry, const std::string& key, const std::string& what) {
    const auto value = parse_double(entry.value);
    if (!value || !(*value > 0.0)) throw description.error(entry, key + ": expected " + what + ", found " + quote_input(entry.value));
    return *value;
}

double angle_deg(const Description& description, const Entry& entry, const std::string& context, const std::string& text) {
    const auto value = parse_double(text);
    if (!value) throw description.error(entry, context + ": expected an angle in degrees (a bare number), found " + quote_input(text));
    return *value;
}

// "MINERAL, euler A B C | cut NAME [azimuth DEG] [tilt DEG] [, thickness LENGTH] [, handedness right|left]".
ThinSectionGrain parse_grain(const Description& description, int label, const Entry& entry, const MineralCatalog& catalog) {
    const std::string context = "grain " + std::to_string(label);
    const auto fields = split(entry.value, ',');
    if (fields[0].empty()) throw description.error(entry, context + ": expected a mineral name first ('grain " + std::to_string(label) + ": quartz, euler 0 0 0')");
    ThinSectionGrain grain;
    grain.label = label;
    grain.line = entry.line;
    const Mineral* mineral = nullptr;
    try {
        mineral = &catalog.find(fields[0]);
    } catch (const InputError& e) {
        throw description.error(entry, context + ": " + e.what());
    }
    grain.mineral = mineral->name;
    const std::string expected =
        "expected 'euler A B C', 'cut NAME [azimuth DEG] [tilt DEG]', 'thickness LENGTH' or 'handedness right|left' after the mineral";
    bool oriented = false;
    for (std::size_t f = 1; f < fields.size(); ++f) {
        const auto words = split_whitespace(fields[f]);
        if (words.empty()) throw description.error(entry, context + ": empty field between commas; " + expected);
        const std::string& keyword = words[0];
        if ((keyword == "euler" || keyword == "cut") && oriented) {
            throw description.error(entry, context + ": a second orientation " + quote_input(fields[f]) + "; expected one 'euler' or 'cut'");
        }
        if (keyword == "euler") {
            if (words.size() != 4) throw description.error(entry, context + ": expected 'euler A B C' (ZYZ angles in degrees), found " + quote_input(fields[f]));
            grain.crystal_axes = euler_zyz_deg(angle_deg(description, entry, context + " euler", words[1]),
                                               angle_deg(description, entry, context + " euler", words[2]),
                                               angle_deg(description, entry, context + " euler", words[3]));
            oriented = true;
        } else if (keyword == "cut") {
            if (words.size() < 2) throw description.error(entry, context + ": expected 'cut optic-axis|acute-bisectrix|obtuse-bisectrix|optic-normal [azimuth DEG] [tilt DEG]'");
            std::optional<double> azimuth_deg, tilt_deg;
            for (std::size_t w = 2; w < words.size(); w += 2) {
                std::optional<double>* slot = words[w] == "azimuth" ? &azimuth_deg : words[w] == "tilt" ? &tilt_deg : nullptr;
                if (!slot || w + 1 >= words.size() || slot->has_value()) {
                    throw description.error(entry, context + ": after the cut name expected 'azimuth DEG' and/or 'tilt DEG' once each, found " + quote_input(fields[f]));
                }
                *slot = angle_deg(description, entry, context + " " + words[w], words[w + 1]);
            }
            try {
                grain.crystal_axes = cut_orientation(parse_cut(words[1]), mineral->optical_class,
                                                     mineral->principal_n(mineral->reference_wavelength_nm),
                                                     azimuth_deg.value_or(0.0), tilt_deg.value_or(0.0));
            } catch (const InputError& e) {
                throw description.error(entry, context + " (" + mineral->name + "): " + e.what());
            }
            oriented = true;
        } else if (keyword == "thickness") {
            if (grain.thickness_um) throw description.error(entry, context + ": 'thickness' given twice");
            double thickness_um = 0.0;
            try {
                if (words.size() != 2) throw InputError("expected 'thickness LENGTH' with a unit, e.g. 'thickness 28um'");
                thickness_um = parse_length_um(words[1]);
            } catch (const InputError& e) {
                throw description.error(entry, context + ": " + e.what());
            }
            if (!(thickness_um > 0.0)) throw description.error(entry, context + ": the grain's thickness must be > 0, found " + quote_input(words[1]));
            grain.thickness_um = thickness_um;
        } else if (keyword == "handedness") {
            if (grain.handedness) throw description.error(entry, context + ": 'handedness' given twice");
            if (!mineral->optically_active()) {
                throw description.error(entry, context + ": " + mineral->name + " is not optically active: it has no handedness");
            }
            try {
                if (words.size() != 2) throw InputError("expected 'handedness right' or 'handedness left'");
                grain.handedness = parse_handedness(words[1]);
            } catch (const InputError& e) {
                throw description.error(entry, context + ": " + e.what());
            }
        } else {
            throw description.error(entry, context + ": " + expected + ", found " + quote_input(fields[f]));
        }
    }
    if (!oriented && mineral->optical_class != OpticalClass::isotropic) {
        throw description.error(entry, context + ": " + mineral->name + " is " + std::string(optical_class_name(mineral->optical_class)) +
                                           "; expected an orientation, 'euler A B C' or 'cut NAME [azimuth DEG] [tilt DEG]'");
    }
    return grain;
}

void read_thickness(const Description& description, const ThinSectionMapResolver& map_path, ThinSection& section) {
    const Entry* uniform = description.find("thickness_um");
    const Entry* wedge = description.find("thickness_wedge_um");
    const Entry* map = description.find("thickness_map");
    const int given = (uniform ? 1 : 0) + (wedge ? 1 : 0) + (map ? 1 : 0);
    const std::string choices = "'thickness_um: 30', 'thickness_wedge_um: START END [x|y]' or 'thickness_map: FILE'";
    if (given == 0) throw located_error(description.file, description.last_line, "missing the section's thickness: expected one of " + choices);
    if (given > 1) {
        const Entry& second = *std::max({uniform, wedge, map}, [](const Entry* a, const Entry* b) { return (a ? a->line : 0) < (b ? b->line : 0); });
        throw description.error(second, "the thickness is given more than once; expected exactly one of " + choices);
    }
    if (uniform) {
        section.thickness_kind = ThicknessKind::uniform;
        section.thickness_um = positive_number(description, *uniform, "thickness_um", "a thickness in micrometres > 0 (a bare number)");
    } else if (wedge) {
        const auto words = split_whitespace(wedge->value);
        const auto start = words.size() >= 2 ? parse_double(words[0]) : std::nullopt;
        const auto end = words.size() >= 2 ? parse_double(words[1]) : std::nullopt;
        const bool axis_ok = words.size() == 2 || (words.size() == 3 && (words[2] == "x" || words[2] == "y"));
        if (!start || !end || !axis_ok || *start < 0.0 || *end < 0.0 || *start + *end <= 0.0) {
            throw description.error(*wedge, "thickness_wedge_um: expected 'START END [x|y]', two thicknesses in micrometres >= 0 (not both 0) and the "
                                            "direction (x: left to right, the default; y: top to bottom), found " + quote_input(wedge->value));
        }
        section.thickness_kind = ThicknessKind::wedge;
        section.wedge_start_um = *start;
        section.wedge_end_um = *end;
        section.wedge_along_x = words.size() == 2 || words[2] == "x";
    } else {
        FloatImage image;
        try {
            image = read_float_image(map_path(map->value));
        } catch (const InputError& e) {
            throw description.error(*map, std::string("thickness_map: ") + e.what());
        }
        if (image.width != section.width_px || image.height != section.height_px) {
            throw description.error(*map, "thickness_map " + map->value + " is " + std::to_string(image.width) + "x" + std::to_string(image.height) +
                                              " pixels; expected size_px " + std::to_string(section.width_px) + "x" + std::to_string(section.height_px));
        }
        for (std::size_t i = 0; i < image.values.size(); ++i) {
            if (!(std::isfinite(image.values[i]) && image.values[i] >= 0.0f)) {
                throw description.error(*map, "thickness_map " + map->value + " holds " + std::to_string(image.values[i]) + " at (x " +
                                                  std::to_string(i % static_cast<std::size_t>(image.width)) + ", y " +
                                                  std::to_string(i / static_cast<std::size_t>(image.width)) + "); expected thicknesses in micrometres >= 0");
            }
        }
        section.thickness_kind = ThicknessKind::map;
        section.thickness_map_um = std::move(image.values);
    }
}

// Every label of the map must have a grain line; names the first few that have none.
void check_labels_have_grains(const ThinSection& section, const std::string& file, const std::string& map_name) {
    std::vector<std::pair<std::uint16_t, std::size_t>> missing;
    for (const auto& [label, count] : section.label_counts()) {
        if (section.grain_index_of_label[label] < 0) missing.emplace_back(label, count);
    }
    if (missing.empty()) return;
    const auto first = std::find(section.labels.begin(), section.labels.end(), missing[0].first) - section.labels.begin();
    std::ostringstream what;
    what << file << ": grain map " << map_name << " has label " << missing[0].first << " (" << missing[0].second << " pixel"
         << (missing[0].second == 1 ? "" : "s") << ", first at x " << first % section.width_px << ", y " << first / section.width_px
         << ") but no 'grain " << missing[0].first << ": MINERAL, ORIENTATION' line";
    if (missing.size() > 1) {
        what << "; labels without a grain line: ";
        for (std::size_t i = 0; i < missing.size() && i < 10; ++i) what << (i ? ", " : "") << missing[i].first;
        if (missing.size() > 10) what << " and " << missing.size() - 10 << " more";
    }
    throw InputError(what.str());
}

// A number in the shortest text that reads back exactly.
std::string number(double value) { return format_number(value == 0.0 ? 0.0 : value); }

void check_writable_text(const std::string& what, const std::string& text, bool comma_allowed) {
    const bool comment = !text.empty() && (text.front() == '#' || text.find(" #") != std::string::npos || text.find("\t#") != std::string::npos);
    if (text.empty() || text.find('\n') != std::string::npos || text.find('\r') != std::string::npos || comment ||
        (!comma_allowed && text.find(',') != std::string::npos) || trim(text) != text) {
        throw InputError("cannot write the thin section: " + what + " " + quote_input(text) + " cannot be written on one description line "
                         "(not empty, no line breaks, no '#' after a space, no surrounding spaces" + (comma_allowed ? "" : ", no commas") + ")");
    }
}

void write_text(const std::string& text, const fs::path& path) {
    std::ofstream file(path, std::ios::binary | std::ios::trunc);
    file << text;
    file.close();
    if (!file) throw InputError("cannot write " + path.string());
}

}  // namespace

fs::path thin_section_description_path(const fs::path& description_or_dir) {
    std::error_code error;
    if (fs::is_directory(description_or_dir, error)) return description_or_dir / kThinSectionDescriptionName;
    return description_or_dir;
}

ThinSection read_thin_section(const fs::path& description_or_dir, const MineralCatalog& catalog) {
    std::error_code error;
    if (!fs::exists(description_or_dir, error)) {
        throw InputError("thin section " + description_or_dir.string() + ": no such folder or description file (a section folder holds " +
                         kThinSectionDescriptionName + ")");
    }
    const fs::path path = thin_section_description_path(description_or_dir);
    const fs::path folder = path.parent_path();
    return read_thin_section(path, catalog, [&folder](const std::string& name) { return folder / name; });
}

ThinSection read_thin_section(const fs::path& path, const MineralCatalog& catalog, const ThinSectionMapResolver& map_path) {
    const std::string file = path.string();
    const Description description = split_description(read_text_file(path), file);

    ThinSection section;
    section.name = description.require("name", "the section's name").value;
    if (const Entry* note = description.find("note")) section.note = note->value;
    const Entry& map_entry = description.require("grain_map", "the PNG of grain labels, relative to this file");
    const Entry& size_entry = description.require("size_px", "the map's width and height in pixels, 'size_px: 512 512'");
    {
        const auto words = split_whitespace(size_entry.value);
        const auto width = words.size() == 2 ? parse_integer(words[0]) : std::nullopt;
        const auto height = words.size() == 2 ? parse_integer(words[1]) : std::nullopt;
        if (!width || !height || *width < 1 || *height < 1 || *width > 65536 || *height > 65536) {
            throw description.error(size_entry, "size_px: expected the width and height in pixels, two integers 1 … 65536, found " + quote_input(size_entry.value));
        }
        section.width_px = static_cast<int>(*width);
        section.height_px = static_cast<int>(*height);
    }
    section.pixel_size_um = positive_number(description, description.require("pixel_size_um", "the edge of a pixel on the specimen in micrometres"),
                                            "pixel_size_um", "the edge of a pixel in micrometres > 0 (a bare number)");
    if (description.grains.empty()) {
        throw located_error(file, description.last_line, "no grains: expected one line 'grain LABEL: MINERAL, ORIENTATION' per label of the map");
    }
    for (const auto& [label, entry] : description.grains) section.grains.push_back(parse_grain(description, label, entry, catalog));

    LabelImage map;
    try {
        map = read_label_png(map_path(map_entry.value));
    } catch (const InputError& e) {
        throw description.error(map_entry, std::string("grain_map: ") + e.what());
    }
    if (map.width != section.width_px || map.height != section.height_px) {
        throw description.error(size_entry, "size_px is " + std::to_string(section.width_px) + "x" + std::to_string(section.height_px) + " but grain map " +
                                                map_entry.value + " is " + std::to_string(map.width) + "x" + std::to_string(map.height) +
                                                " pixels; expected them to agree");
    }
    section.labels = std::move(map.labels);
    read_thickness(description, map_path, section);

    section.index_grains();  // labels are unique (checked per line above)
    check_labels_have_grains(section, file, map_entry.value);
    section.validate();
    return section;
}

std::string thin_section_description(const ThinSection& section) {
    check_writable_text("the name", section.name, true);
    if (!section.note.empty()) check_writable_text("the note", section.note, true);
    std::ostringstream text;
    text << "# petroscope thin section (format: thin_sections/README.md)\n";
    text << "name: " << section.name << '\n';
    if (!section.note.empty()) text << "note: " << section.note << '\n';
    text << "grain_map: " << kThinSectionGrainMapName << '\n';
    text << "size_px: " << section.width_px << ' ' << section.height_px << '\n';
    text << "pixel_size_um: " << number(section.pixel_size_um) << '\n';
    switch (section.thickness_kind) {
        case ThicknessKind::uniform: text << "thickness_um: " << number(section.thickness_um) << '\n'; break;
        case ThicknessKind::wedge:
            text << "thickness_wedge_um: " << number(section.wedge_start_um) << ' ' << number(section.wedge_end_um) << ' '
                 << (section.wedge_along_x ? 'x' : 'y') << '\n';
            break;
        case ThicknessKind::map: text << "thickness_map: " << kThinSectionThicknessMapName << '\n'; break;
    }
    text << "\n# grain LABEL: MINERAL, euler A B C (ZYZ, degrees: R = Rz(A) Ry(B) Rz(C))[, thickness LENGTH][, handedness right|left]\n";
    for (const ThinSectionGrain& grain : section.grains) {
        check_writable_text("the mineral name", grain.mineral, false);
        const Eigen::Vector3d euler = euler_zyz_deg_of(grain.crystal_axes);
        text << "grain " << grain.label << ": " << grain.mineral << ", euler " << number(euler[0]) << ' ' << number(euler[1]) << ' '
             << number(euler[2]);
        if (grain.thickness_um) text << ", thickness " << number(*grain.thickness_um) << "um";
        if (grain.handedness) text << ", handedness " << handedness_name(*grain.handedness);
        text << '\n';
    }
    return text.str();
}

void write_thin_section(const ThinSection& section, const fs::path& dir) {
    ThinSection checked = section;
    checked.validate();
    const std::string description = thin_section_description(checked);

    std::error_code error;
    bool created = false;
    if (!fs::exists(dir, error)) {
        const fs::path parent = dir.parent_path().empty() ? fs::path(".") : dir.parent_path();
        if (!fs::is_directory(parent, error)) {
            throw InputError("cannot write the thin section to " + dir.string() + ": folder " + parent.string() + " does not exist");
        }
        if (!fs::create_directory(dir, error)) {
            throw InputError("cannot create the folder " + dir.string() + ": " + error.message());
        }
        created = true;
    } else if (!fs::is_directory(dir, error)) {
        throw InputError("cannot write the thin section to " + dir.string() + ": it exists and is not a folder");
    }
    try {
        PendingOutputs pending;
        const fs::path description_temporary = pending.add(dir / kThinSectionDescriptionName);
        const fs::path map_temporary = pending.add(dir / kThinSectionGrainMapName);
        std::optional<fs::path> thickness_temporary;
        if (checked.thickness_kind == ThicknessKind::map) thickness_temporary = pending.add(dir / kThinSectionThicknessMapName);
        write_label_png(checked.labels, checked.width_px, checked.height_px, map_temporary);
        if (thickness_temporary) write_float_tiff(checked.thickness_map_um, checked.width_px, checked.height_px, *thickness_temporary);
        write_text(description, description_temporary);
        pending.commit();
    } catch (...) {
        if (created) fs::remove(dir, error);  // only if still empty: nothing else was there
        throw;
    }
}

}  // namespace petroscope
