// _sweep(): the frames of conoscope(), orthoscope() or conical() over a grid of their numeric arguments,
// rendered in parallel by the library's run_sweep_frames (petroscope.sweep in __init__.py wraps it).
#include "bindings.hpp"
#include "computations.hpp"

#include "petroscope/api/sweep.hpp"
#include "petroscope/core/error.hpp"

#include <pybind11/stl.h>

#include <cstdint>
#include <numeric>
#include <optional>
#include <utility>

namespace petroscope::python {
namespace {

using Axes = std::vector<std::pair<std::string, std::vector<double>>>;

SweepGrid grid_argument(const Axes& axes) {
    SweepGrid grid;
    for (const auto& [field, values] : axes) grid.axes.push_back({field, values});
    grid.validate();
    return grid;
}

// The frames asked for (None: all of them), each checked to be in the grid.
std::vector<std::size_t> frames_argument(const std::optional<std::vector<std::int64_t>>& frames, const SweepGrid& grid) {
    std::vector<std::size_t> result(frames ? frames->size() : grid.frame_count());
    if (!frames) {
        std::iota(result.begin(), result.end(), std::size_t{0});
        return result;
    }
    for (std::size_t k = 0; k < result.size(); ++k) {
        const std::int64_t frame = (*frames)[k];
        if (frame < 0 || static_cast<std::size_t>(frame) >= grid.frame_count()) {
            throw py::value_error("frames: expected frame numbers 0 to " + std::to_string(grid.frame_count() - 1) + ", got " + std::to_string(frame));
        }
        result[k] = static_cast<std::size_t>(frame);
    }
    return result;
}

// Plans and renders the frames with the GIL released, then makes their Results with it held.
template <class Request, class PlanFunction, class RenderFunction, class ResultFunction>
std::vector<Result> sweep(const Request& base, std::string_view kind, const Axes& axes, const std::optional<std::vector<std::int64_t>>& frames,
                          int jobs, const py::object& progress, PlanFunction plan, RenderFunction render, ResultFunction result) {
    if (jobs < 0 || jobs > 1024) throw py::value_error("jobs: expected 0 (one frame per core) to 1024, got " + std::to_string(jobs));
    const SweepGrid grid = grid_argument(axes);
    const std::vector<std::size_t> frame_numbers = frames_argument(frames, grid);
    using Plan = decltype(plan(base, catalog()));
    using Rendered = decltype(render(std::declval<const Plan&>(), ProgressCallback{}));
    if (!frame_numbers.empty()) frame_request(base, kind, grid, frame_numbers.front());  // fields unknown to Request fail now
    std::vector<std::optional<std::pair<Plan, Rendered>>> rendered(frame_numbers.size());
    const MineralCatalog& minerals = catalog();
    with_progress(progress, [&](const ProgressCallback& callback) {
        std::vector<std::size_t> slots(frame_numbers.size());
        std::iota(slots.begin(), slots.end(), std::size_t{0});
        run_sweep_frames(slots, jobs, [&](std::size_t slot, const ProgressCallback& frame_progress) {
            const std::size_t frame = frame_numbers[slot];
            try {
                Plan planned = plan(frame_request(base, kind, grid, frame), minerals);
                Rendered image = render(planned, frame_progress);
                rendered[slot].emplace(std::move(planned), std::move(image));
            } catch (const InputError& error) {
                throw InputError("frame " + std::to_string(frame) + " (" + grid.label(frame) + "): " + error.what());
            }
        }, callback);
        return 0;
    });
    std::vector<Result> results;
    for (const auto& frame : rendered) results.push_back(result(frame->first, frame->second));
    return results;
}

template <class Request, class PlanFunction, class RenderFunction, class ResultFunction>
void def_sweep(py::module_& module, std::string_view kind, PlanFunction plan, RenderFunction render, ResultFunction result) {
    module.def(
        "_sweep",
        [=](const Request& base, const Axes& axes, const std::optional<std::vector<std::int64_t>>& frames, int jobs, const py::object& progress) {
            return sweep(base, kind, axes, frames, jobs, progress, plan, render, result);
        },
        py::arg("request"), py::arg("axes"), py::arg("frames"), py::arg("jobs"), py::arg("progress"));
}

}  // namespace

void bind_sweep(py::module_& module) {
    def_sweep<ConoscopeRequest>(module, "conoscope", &plan_conoscope, &render_conoscope_figure, &conoscope_result);
    def_sweep<OrthoscopeRequest>(module, "orthoscope", &plan_orthoscope, &render_orthoscope_image, &orthoscope_result);
    def_sweep<ConicalRequest>(module, "conical", &plan_conical, &render_conical_screen, &conical_result);
    module.def("_sweep_fields", [](const std::string& kind) {
        std::vector<std::string> names;
        const auto add = [&](auto fields) {
            for (const auto& field : fields) names.emplace_back(field.name);
        };
        if (kind == "conoscope") add(sweep_fields<ConoscopeRequest>());
        if (kind == "orthoscope") add(sweep_fields<OrthoscopeRequest>());
        if (kind == "conical") add(sweep_fields<ConicalRequest>());
        return names;
    });
}

}  // namespace petroscope::python
