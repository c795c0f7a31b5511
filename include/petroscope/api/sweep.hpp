#pragma once
// A sweep in the library's terms: numeric fields of a request (conoscope, orthoscope, conical) stepped over
// a grid of values, and the frames rendered in parallel, each on one thread so that a frame's pixels never
// depend on how the work was split. The command line's sweep folder (docs/sweep.md) and Python's
// petroscope.sweep run their frames through run_sweep_frames.
#include "petroscope/api/conical_screen.hpp"
#include "petroscope/api/conoscope_figure.hpp"
#include "petroscope/api/orthoscope_image.hpp"
#include "petroscope/core/progress.hpp"

#include <algorithm>
#include <cstddef>
#include <functional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace petroscope {

/// One swept field, named as in the request with its unit ("thickness_um", "azimuth_deg"), and its values.
struct SweepAxis {
    std::string field;
    std::vector<double> values;
};

/// The frames of a grid of one or more axes, the last axis running fastest (row-major).
struct SweepGrid {
    std::vector<SweepAxis> axes;

    std::size_t frame_count() const;
    /// The value of every axis in `frame`, in the order of the axes.
    std::vector<double> values_of(std::size_t frame) const;
    /// "thickness_um 20, azimuth_deg 30".
    std::string label(std::size_t frame) const;
    /// Throws InputError: no axis, an empty axis, a value that is not finite, a field swept twice, or more
    /// than `max_frames` frames.
    void validate(std::size_t max_frames = 1000000) const;
};

/// A numeric field of a request that a sweep can step, and how a value is put in place.
template <class Request>
struct SweepField {
    std::string_view name;
    void (*set)(Request& request, double value);
};

/// The fields a sweep can step, per request. Conoscope: thickness_um, azimuth_deg, tilt_deg,
/// numerical_aperture, stage_deg, polarizer_deg, analyzer_deg, surround_n, wavelength_nm (monochromatic
/// light), exposure, plate_slow_deg, wedge_position. Orthoscope: stage_deg, polarizer_deg, analyzer_deg,
/// thickness_um, condenser_na, wavelength_nm, exposure, plate_slow_deg, wedge_position. Conical: length_um,
/// wavelength_nm, waist_um, pinhole_um, filter_um, z, rotate_deg, tilt_deg, screen_distance_um.
template <class Request>
std::span<const SweepField<Request>> sweep_fields();
template <>
std::span<const SweepField<ConoscopeRequest>> sweep_fields<ConoscopeRequest>();
template <>
std::span<const SweepField<OrthoscopeRequest>> sweep_fields<OrthoscopeRequest>();
template <>
std::span<const SweepField<ConicalRequest>> sweep_fields<ConicalRequest>();

/// The names of sweep_fields<Request>(), comma separated (for messages).
template <class Request>
std::string sweep_field_names() {
    std::string names;
    for (const SweepField<Request>& field : sweep_fields<Request>()) names += (names.empty() ? "" : ", ") + std::string(field.name);
    return names;
}

/// Throws InputError when an axis names no field of Request, listing those that can be swept.
void throw_unknown_sweep_field(std::string_view field, std::string_view request_kind, const std::string& known);

/// `base` with the values of `frame` put in place. Throws InputError for an axis that names no field of
/// Request, or a value the field cannot take yet (a plate's angle without a plate).
template <class Request>
Request frame_request(const Request& base, std::string_view request_kind, const SweepGrid& grid, std::size_t frame) {
    Request request = base;
    const std::vector<double> values = grid.values_of(frame);
    const std::span<const SweepField<Request>> fields = sweep_fields<Request>();
    for (std::size_t a = 0; a < grid.axes.size(); ++a) {
        const auto field = std::find_if(fields.begin(), fields.end(), [&](const auto& f) { return f.name == grid.axes[a].field; });
        if (field == fields.end()) throw_unknown_sweep_field(grid.axes[a].field, request_kind, sweep_field_names<Request>());
        field->set(request, values[a]);
    }
    return request;
}

/// Calls render_frame(frame, progress) for each of `frames`, `jobs` frames at once (0: one per core), each
/// frame on one thread. `progress` hears the fraction of frames done and can cancel (then Cancelled is
/// thrown); the callback each frame gets lets it stop within a frame. The first exception a frame throws
/// stops the frames not yet started and is rethrown.
void run_sweep_frames(const std::vector<std::size_t>& frames, int jobs,
                      const std::function<void(std::size_t frame, const ProgressCallback& frame_progress)>& render_frame,
                      const ProgressCallback& progress = {});

}  // namespace petroscope
