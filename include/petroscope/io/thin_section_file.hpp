#pragma once
// Thin-section files (format: thin_sections/README.md): a folder holding the description section.txt,
// the grain map (PNG, 8- or 16-bit grey, one label per pixel) and, optionally, a thickness map.
#include "petroscope/microscope/thin_section.hpp"
#include "petroscope/minerals/mineral_catalog.hpp"

#include <filesystem>
#include <functional>
#include <string>

namespace petroscope {

/// The fixed names inside a section folder written by write_thin_section (a description read from
/// elsewhere may name its maps freely).
inline constexpr const char* kThinSectionDescriptionName = "section.txt";
inline constexpr const char* kThinSectionGrainMapName = "grains.png";
inline constexpr const char* kThinSectionThicknessMapName = "thickness.tif";

/// `description_or_dir` itself, or DIR/section.txt when it is a folder.
std::filesystem::path thin_section_description_path(const std::filesystem::path& description_or_dir);

/// Reads a section: the description, its grain map and thickness map (paths relative to the description's
/// folder). Minerals are looked up in `catalog` and stored under their canonical names; named cuts use
/// the mineral's principal indices at its reference wavelength. Throws InputError as "file:line: what was
/// expected" (or "file: …" for what has no line, such as a label of the map without a grain entry).
ThinSection read_thin_section(const std::filesystem::path& description_or_dir, const MineralCatalog& catalog);

/// Where the maps a description names are: the file for a name as written, or an InputError for a name
/// the caller does not allow (a section sent to the server names only the files sent with it).
using ThinSectionMapResolver = std::function<std::filesystem::path(const std::string& name_as_written)>;
/// Reads the description file `description` with its maps found by `map_path`.
ThinSection read_thin_section(const std::filesystem::path& description, const MineralCatalog& catalog, const ThinSectionMapResolver& map_path);

/// The description text write_thin_section writes, naming the maps by their fixed names. Numbers are
/// written in the shortest form that reads back as the same double; orientations as ZYZ Euler angles
/// (euler_zyz_deg_of), whose axes agree with crystal_axes to rounding (~1e-15).
std::string thin_section_description(const ThinSection& section);

/// Writes DIR/section.txt, DIR/grains.png (8-bit when every label is ≤ 255, else 16-bit) and, for a
/// thickness map, DIR/thickness.tif (32-bit float). DIR is created if missing (its parent must exist).
/// All or nothing: the files appear together or not at all (a DIR created here is removed again).
/// Validates the section first; throws InputError.
void write_thin_section(const ThinSection& section, const std::filesystem::path& dir);

}  // namespace petroscope
