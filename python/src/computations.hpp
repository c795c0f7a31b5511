#pragma once
// The computations that Python calls one at a time (conoscope(), orthoscope(), conical()) and over a
// sweep (sweep()): how each planned and rendered result becomes a Result.
#include "convert.hpp"

#include "petroscope/api/conical_screen.hpp"
#include "petroscope/api/conoscope_figure.hpp"
#include "petroscope/api/orthoscope_image.hpp"

namespace petroscope::python {

/// Plans and renders `request` with the GIL released (progress as with_progress), then makes its Result.
template <class Request, class PlanFunction, class RenderFunction, class ResultFunction>
Result compute(const Request& request, const py::object& progress, PlanFunction plan, RenderFunction render, ResultFunction result) {
    const auto [planned, rendered] = with_progress(progress, [&](const ProgressCallback& callback) {
        auto plan_made = plan(request, catalog());
        auto image = render(plan_made, callback);
        return std::pair{std::move(plan_made), std::move(image)};
    });
    return result(planned, rendered);
}

/// Hold the GIL to call these: they build Python objects.
Result conoscope_result(const ConoscopePlan& plan, const ConoscopeFigure& figure);
Result orthoscope_result(const OrthoscopePlan& plan, const OrthoscopeImage& image);
Result conical_result(const ConicalPlan& plan, const ConicalScreen& screen);

}  // namespace petroscope::python
