#pragma once
// The subcommands that render one image (conoscope, orthoscope, conical) seen through one interface, so
// that the same options run a single image or every frame of a sweep (command_sweep.cpp).
#include "petroscope/api/measurements.hpp"
#include "petroscope/core/image.hpp"
#include "petroscope/core/progress.hpp"
#include "petroscope/io/thin_section_file.hpp"
#include "petroscope/minerals/mineral_catalog.hpp"

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace petroscope::cli {

/// One rendered image: linear sRGB, the sidecar of every parameter used (without the command line and the
/// run time, which the caller adds) whose "measurements" maps a name to a number measured on the image (or
/// null: not measurable), and a few words for the terminal.
struct RenderedFrame {
    Image linear_rgb;
    nlohmann::json sidecar;
    std::string summary;  // "512x512, 81 wavelengths"
};

/// The sidecar's "measurements": name → number, or null where there was nothing to measure.
nlohmann::json measurements_json(const Measurements& measurements);

/// Validated options, ready to render: nothing has been written yet.
struct PreparedFrame {
    std::vector<std::string> notes;  // "warning: …" lines for the terminal
    std::function<RenderedFrame(const ProgressCallback&)> render;
};

/// What the frames of one run share: the mineral catalog and thin sections, loaded once.
class FrameContext {
public:
    explicit FrameContext(std::string minerals_dir) : minerals_dir_(std::move(minerals_dir)) {}
    const MineralCatalog& catalog();
    const ThinSection& section(const std::string& description_or_dir);

private:
    std::string minerals_dir_;
    std::optional<MineralCatalog> catalog_;
    std::map<std::string, ThinSection> sections_;
};

/// A rendering subcommand's options. add_options binds them to this object; prepare checks them.
class FrameOptions {
public:
    virtual ~FrameOptions() = default;
    virtual std::string command() const = 0;
    virtual std::string description() const = 0;
    /// Registers every option but the output file.
    virtual void add_options(CLI::App* command) = 0;
    /// Checks every option and loads what the rendering needs; throws InputError naming the option.
    virtual PreparedFrame prepare(FrameContext& context) const = 0;
};

std::unique_ptr<FrameOptions> make_conoscope_options();
std::unique_ptr<FrameOptions> make_orthoscope_options();
std::unique_ptr<FrameOptions> make_conical_options();
std::unique_ptr<FrameOptions> make_render_options();

/// The rendering subcommands by name, in the order of the help text.
const std::vector<std::pair<std::string, std::function<std::unique_ptr<FrameOptions>()>>>& frame_commands();

/// Adds the subcommand that renders one image to -o FILE with its sidecar.
void add_frame_command(CLI::App& app, std::unique_ptr<FrameOptions> options, const std::string& minerals_dir,
                       const std::string& command_line);

/// Type names of the options whose value is a length or a wavelength with a unit (shown by --help; the
/// sweep appends the unit to the values it generates).
inline constexpr const char* length_type = "LENGTH";
inline constexpr const char* wavelength_type = "WAVELENGTH";

}  // namespace petroscope::cli
