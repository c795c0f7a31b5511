#include "petroscope/api/sweep.hpp"

#include "petroscope/core/error.hpp"
#include "petroscope/core/grid_index.hpp"
#include "petroscope/core/text.hpp"

#include <omp.h>

#include <atomic>
#include <cmath>
#include <exception>
#include <set>

namespace petroscope {
namespace {

// The plate's fields exist only with a plate: sweeping them without one is a mistake, not a no-op.
PlateRequest& swept_plate(std::optional<PlateRequest>& plate, std::string_view field) {
    if (!plate) throw InputError(std::string(field) + " is swept, but there is no plate: choose one (gypsum, mica or wedge)");
    return *plate;
}

template <class Request>
void set_plate_slow_deg(Request& request, double value) {
    swept_plate(request.plate, "plate_slow_deg").slow_deg = value;
}
template <class Request>
void set_wedge_position(Request& request, double value) {
    swept_plate(request.plate, "wedge_position").wedge_position = value;
}

constexpr SweepField<ConoscopeRequest> conoscope_fields[] = {
    {"thickness_um", [](ConoscopeRequest& r, double v) { r.thickness_um = v; }},
    {"azimuth_deg", [](ConoscopeRequest& r, double v) { r.orientation.azimuth_deg = v; }},
    {"tilt_deg", [](ConoscopeRequest& r, double v) { r.orientation.tilt_deg = v; }},
    {"numerical_aperture", [](ConoscopeRequest& r, double v) { r.numerical_aperture = v; }},
    {"stage_deg", [](ConoscopeRequest& r, double v) { r.stage_deg = v; }},
    {"polarizer_deg", [](ConoscopeRequest& r, double v) { r.polarizer_deg = v; }},
    {"analyzer_deg", [](ConoscopeRequest& r, double v) { r.analyzer_deg = v; }},
    {"surround_n", [](ConoscopeRequest& r, double v) { r.surround_n = v; }},
    {"wavelength_nm", [](ConoscopeRequest& r, double v) { r.light.wavelength_nm = v; }},
    {"exposure", [](ConoscopeRequest& r, double v) { r.light.exposure = v; }},
    {"plate_slow_deg", &set_plate_slow_deg<ConoscopeRequest>},
    {"wedge_position", &set_wedge_position<ConoscopeRequest>},
};

constexpr SweepField<OrthoscopeRequest> orthoscope_fields[] = {
    {"stage_deg", [](OrthoscopeRequest& r, double v) { r.stage_deg = v; }},
    {"polarizer_deg", [](OrthoscopeRequest& r, double v) { r.polarizer_deg = v; }},
    {"analyzer_deg", [](OrthoscopeRequest& r, double v) { r.analyzer_deg = v; }},
    {"thickness_um", [](OrthoscopeRequest& r, double v) { r.thickness_um = v; }},
    {"condenser_na", [](OrthoscopeRequest& r, double v) { r.condenser_na = v; }},
    {"wavelength_nm", [](OrthoscopeRequest& r, double v) { r.light.wavelength_nm = v; }},
    {"exposure", [](OrthoscopeRequest& r, double v) { r.light.exposure = v; }},
    {"plate_slow_deg", &set_plate_slow_deg<OrthoscopeRequest>},
    {"wedge_position", &set_wedge_position<OrthoscopeRequest>},
};

constexpr SweepField<ConicalRequest> conical_fields[] = {
    {"length_um", [](ConicalRequest& r, double v) { r.length_um = v; }},
    {"wavelength_nm", [](ConicalRequest& r, double v) { r.wavelength_nm = v; }},
    {"waist_um", [](ConicalRequest& r, double v) { r.waist_um = v; }},
    {"pinhole_um", [](ConicalRequest& r, double v) { r.pinhole_um = v; }},
    {"filter_um", [](ConicalRequest& r, double v) { r.filter_um = v; }},
    {"z", [](ConicalRequest& r, double v) { r.z = v; }},
    {"rotate_deg", [](ConicalRequest& r, double v) { r.rotate_deg = v; }},
    {"tilt_deg", [](ConicalRequest& r, double v) { r.tilt_deg = v; }},
    {"screen_distance_um", [](ConicalRequest& r, double v) { r.screen_distance_um = v; }},
};

}  // namespace

template <>
std::span<const SweepField<ConoscopeRequest>> sweep_fields<ConoscopeRequest>() {
    return conoscope_fields;
}
template <>
std::span<const SweepField<OrthoscopeRequest>> sweep_fields<OrthoscopeRequest>() {
    return orthoscope_fields;
}
template <>
std::span<const SweepField<ConicalRequest>> sweep_fields<ConicalRequest>() {
    return conical_fields;
}

void throw_unknown_sweep_field(std::string_view field, std::string_view request_kind, const std::string& known) {
    throw InputError("sweep: " + quote_input(field) + " is not a numeric field of " + std::string(request_kind) + "; these can be swept: " + known);
}

std::size_t SweepGrid::frame_count() const {
    std::size_t count = axes.empty() ? 0 : 1;
    for (const SweepAxis& axis : axes) count *= axis.values.size();
    return count;
}

std::vector<double> SweepGrid::values_of(std::size_t frame) const {
    std::vector<std::size_t> counts;
    for (const SweepAxis& axis : axes) counts.push_back(axis.values.size());
    const std::vector<std::size_t> indices = grid_indices(frame, counts);
    std::vector<double> values(axes.size());
    for (std::size_t a = 0; a < axes.size(); ++a) values[a] = axes[a].values[indices[a]];
    return values;
}

std::string SweepGrid::label(std::size_t frame) const {
    const std::vector<double> values = values_of(frame);
    std::string text;
    for (std::size_t a = 0; a < axes.size(); ++a) text += (a ? ", " : "") + axes[a].field + " " + format_number(values[a]);
    return text;
}

void SweepGrid::validate(std::size_t max_frames) const {
    if (axes.empty()) throw InputError("sweep: no field to sweep; give at least one with its values");
    std::set<std::string> seen;
    double frames = 1.0;  // in floating point: the count itself could overflow
    for (const SweepAxis& axis : axes) {
        if (!seen.insert(axis.field).second) throw InputError("sweep: " + quote_input(axis.field) + " is swept twice");
        if (axis.values.empty()) throw InputError("sweep: " + quote_input(axis.field) + " has no values");
        for (const double value : axis.values) {
            if (!std::isfinite(value)) throw InputError("sweep: " + quote_input(axis.field) + " has a value that is not a finite number");
        }
        frames *= static_cast<double>(axis.values.size());
    }
    if (frames > static_cast<double>(max_frames)) {
        const std::string count = frames < 1e18 ? std::to_string(static_cast<long long>(frames)) : format_number(frames);
        throw InputError("sweep: " + count + " frames; at most " + std::to_string(max_frames) + " can be swept");
    }
}

void run_sweep_frames(const std::vector<std::size_t>& frames, int jobs,
                      const std::function<void(std::size_t, const ProgressCallback&)>& render_frame, const ProgressCallback& progress) {
    ProgressRelay relay(progress);
    // Within a frame: let the caller's callback run now and then (Ctrl-C in Python), and stop when it says so.
    const ProgressCallback frame_progress = [&relay](double) {
        relay.poll();
        return !relay.cancelled();
    };
    const int total = static_cast<int>(frames.size());
    std::atomic<int> done{0};
    std::atomic<bool> failed{false};
    std::exception_ptr first_error;
#pragma omp parallel for schedule(dynamic, 1) num_threads(jobs > 0 ? jobs : omp_get_max_threads())
    for (int k = 0; k < total; ++k) {
        if (failed || relay.cancelled()) continue;
        omp_set_num_threads(1);  // the frame's own parallel loops run on this thread alone
        try {
            render_frame(frames[static_cast<std::size_t>(k)], frame_progress);
            relay.count_done(done, total);
        } catch (...) {
#pragma omp critical(petroscope_sweep_error)
            if (!first_error) first_error = std::current_exception();
            failed = true;
        }
    }
    relay.stop_if_cancelled();  // what the callback threw, or Cancelled, before the frames' own Cancelled
    if (first_error) std::rethrow_exception(first_error);
    relay.finish();
}

}  // namespace petroscope
