#pragma once
// Numbers measured on a rendered image, by name, in the order they were measured.
#include <optional>
#include <string>
#include <vector>

namespace petroscope {

struct Measurement {
    std::string name;              // "mean_luminance", "melatope_1_x", …
    std::optional<double> value;   // none: nothing to measure (e.g. an optic axis outside the field)
};
using Measurements = std::vector<Measurement>;

}  // namespace petroscope
