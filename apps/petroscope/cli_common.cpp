#include "cli_common.hpp"

#include "petroscope/core/text.hpp"
#include "petroscope/core/units.hpp"
#include "petroscope/io/json_sidecar.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <unistd.h>

namespace petroscope::cli {

void show_progress(const std::string& label, double fraction_done) {
    static const bool terminal = ::isatty(STDERR_FILENO) != 0;
    if (!terminal) return;
    // The clock starts at the first report of a task; the time left assumes a steady rate.
    static std::string current_label;
    static std::chrono::steady_clock::time_point started;
    static double started_fraction = 0.0;
    const auto now = std::chrono::steady_clock::now();
    if (label != current_label || fraction_done < started_fraction) {
        current_label = label;
        started = now;
        started_fraction = fraction_done;
    }
    const double elapsed = std::chrono::duration<double>(now - started).count();
    const double done = fraction_done - started_fraction;
    const int percent = static_cast<int>(100.0 * fraction_done);
    std::fprintf(stderr, "\r%s %3d%%", label.c_str(), percent);
    if (fraction_done < 1.0 && done > 0.0 && elapsed > 1.0) {
        const long left = std::lround(elapsed * (1.0 - fraction_done) / done);
        std::fprintf(stderr, " (%ld:%02ld left)   ", left / 60, left % 60);
    }
    if (fraction_done >= 1.0) {
        std::fprintf(stderr, " (%.1f s)        \n", elapsed);
        current_label.clear();
    }
    std::fflush(stderr);
}

ImageResult::ImageResult(const std::filesystem::path& output)
    : output_(output), format_(image_format_for(output)) {
    image_temporary_ = pending_.add(output_);
    sidecar_temporary_ = pending_.add(sidecar_path(output_));
}

void ImageResult::write(const Image& linear_rgb, const nlohmann::json& sidecar) {
    write_image(linear_rgb, image_temporary_, format_);
    write_json_file(sidecar, sidecar_temporary_);
    pending_.commit();
}

double positive_length_um(const std::string& option, const std::string& text) {
    const double value = with_option(option, [&] { return parse_length_um(text); });
    if (!(value > 0.0)) throw InputError(option + " " + quote_input(text) + ": must be > 0");
    return value;
}

std::pair<double, double> length_range_um(const std::string& option, const std::string& text) {
    const auto parts = split(text, ':');
    if (parts.size() != 2) throw InputError(option + " " + quote_input(text) + ": expected MIN:MAX with units, e.g. 10um:5mm");
    const double low = positive_length_um(option, parts[0]), high = positive_length_um(option, parts[1]);
    if (!(high > low)) throw InputError(option + " " + quote_input(text) + ": the maximum must exceed the minimum");
    return {low, high};
}

std::string joined_command_line(int argc, char** argv) {
    std::string line;
    for (int i = 0; i < argc; ++i) line += (i ? " " : "") + std::string(argv[i]);
    return line;
}

std::array<double, 3> euler_angles_deg(const std::string& option, const std::string& text) {
    const auto parts = split(text, ',');
    std::array<double, 3> angles{};
    for (std::size_t i = 0; i < angles.size(); ++i) {
        const auto value = parts.size() == angles.size() ? parse_double(parts[i]) : std::nullopt;
        if (!value) {
            throw InputError(option + " " + quote_input(text) + ": expected three angles in degrees, ALPHA,BETA,GAMMA (ZYZ: R = Rz(ALPHA)·Ry(BETA)·Rz(GAMMA), "
                             "docs/conventions.md)");
        }
        angles[i] = *value;
    }
    return angles;
}

}  // namespace petroscope::cli
