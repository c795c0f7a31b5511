#pragma once
// The Michel-Lévy chart's arguments as both extension modules take them (michel_levy_colours, and the
// drawn chart of the files module).
#include "convert.hpp"

#include "petroscope/api/michel_levy_chart.hpp"

#include <optional>
#include <string>

namespace petroscope::python {

/// Computes the chart's colours with the GIL released; ValueError for a bad argument.
MichelLevyColours chart_colours(const std::optional<std::string>& mineral, double max_retardation_nm, double step_nm, const py::object& light);

}  // namespace petroscope::python
