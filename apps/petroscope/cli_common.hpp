#pragma once
// Pieces every petroscope subcommand uses: error reporting, progress, and all-or-nothing output.
#include "petroscope/core/error.hpp"
#include "petroscope/core/image.hpp"
#include "petroscope/io/atomic_file.hpp"
#include "petroscope/io/image_writer.hpp"

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <array>
#include <filesystem>
#include <functional>
#include <string>

namespace petroscope::cli {

/// A progress line on standard error ("rendering  42%"), drawn only when it is a terminal.
void show_progress(const std::string& label, double fraction_done);

/// An image result and its JSON sidecar, reserved before the work starts (so an unwritable path fails at
/// once) and written under temporary names, renamed together at the end.
class ImageResult {
public:
    explicit ImageResult(const std::filesystem::path& output);
    /// Reserves one more file (a CSV beside the image) to be committed with the image; returns the
    /// temporary path to write it to before write().
    std::filesystem::path add_companion(const std::filesystem::path& destination) { return pending_.add(destination); }
    void write(const Image& linear_rgb, const nlohmann::json& sidecar);
    const std::filesystem::path& path() const { return output_; }

private:
    std::filesystem::path output_;
    ImageFormat format_;
    PendingOutputs pending_;
    std::filesystem::path image_temporary_, sidecar_temporary_;
};

/// Thrown by a subcommand to end with this exit code after printing its own report (no error message).
struct ExitCode {
    int code = 1;
};

/// Runs a value parser, prefixing any InputError with the option it came from ("--thickness: …").
template <typename Parse>
auto with_option(const std::string& option, Parse parse) {
    try {
        return parse();
    } catch (const InputError& error) {
        throw InputError(option + ": " + error.what());
    }
}

/// A length option's value in µm, which must be > 0 ("--thickness '0um': must be > 0"); throws InputError.
double positive_length_um(const std::string& option, const std::string& text);

/// A range of lengths "MIN:MAX" with units (10um:5mm) in µm, 0 < MIN < MAX; throws InputError naming `option`.
std::pair<double, double> length_range_um(const std::string& option, const std::string& text);

/// Three ZYZ Euler angles in degrees, "ALPHA,BETA,GAMMA" (R = Rz(ALPHA)·Ry(BETA)·Rz(GAMMA),
/// docs/conventions.md); throws InputError naming `option`.
std::array<double, 3> euler_angles_deg(const std::string& option, const std::string& text);

/// The command line as one string, for sidecars.
std::string joined_command_line(int argc, char** argv);

void add_minerals_command(CLI::App& app, std::string& minerals_dir);
void add_interface_command(CLI::App& app, const std::string& minerals_dir);
void add_verify_command(CLI::App& app, const std::string& minerals_dir);
void add_section_command(CLI::App& app, const std::string& minerals_dir);
void add_chart_command(CLI::App& app, const std::string& minerals_dir, const std::string& command_line);
void add_sweep_command(CLI::App& app, const std::string& minerals_dir);
void add_fit_command(CLI::App& app, const std::string& minerals_dir);
void add_serve_command(CLI::App& app, const std::string& minerals_dir);
void add_fit_orthoscope_command(CLI::App* fit, const std::string& minerals_dir);

}  // namespace petroscope::cli
