#pragma once
// The computations that Python calls one at a time (conoscope(), orthoscope(), conical()) and over a
// sweep (sweep()): how each planned and rendered result becomes a Result.
#include "convert.hpp"

#include "petroscope/api/conical_screen.hpp"
#include "petroscope/api/conoscope_figure.hpp"
#include "petroscope/api/orthoscope_image.hpp"

namespace petroscope::python {

/// Hold the GIL to call these: they build Python objects.
Result conoscope_result(const ConoscopePlan& plan, const ConoscopeFigure& figure);
Result orthoscope_result(const OrthoscopePlan& plan, const OrthoscopeImage& image);
Result conical_result(const ConicalPlan& plan, const ConicalScreen& screen);

}  // namespace petroscope::python
