#pragma once
// What the fit commands share in their reports and summaries: a fitted value as JSON and as a line.
#include "cli_common.hpp"

#include "petroscope/core/text.hpp"
#include "petroscope/fit/conoscope_fit.hpp"

#include <nlohmann/json.hpp>

#include <functional>
#include <iostream>
#include <string>

namespace petroscope::cli {

/// {"value" (null when not identifiable), "value_at_minimum", "sigma" (null when none), "free", "identifiable"}.
inline nlohmann::json fitted_value_json(const FittedValue& value) {
    return {{"value", value.identifiable ? nlohmann::json(value.value) : nlohmann::json(nullptr)},
            {"value_at_minimum", value.value},
            {"sigma", value.sigma ? nlohmann::json(*value.sigma) : nlohmann::json(nullptr)},
            {"free", value.free},
            {"identifiable", value.identifiable}};
}

/// "39.974 +- 0.048", "2.2 (fixed)" or "not determined (… at the minimum)".
inline std::string fitted_value_text(const FittedValue& value) {
    if (!value.identifiable) return "not determined (" + format_significant(value.value, 6) + " at the minimum)";
    if (value.sigma) return format_with_uncertainty(value.value, *value.sigma);
    return format_significant(value.value, 6) + (value.free ? "" : " (fixed)");
}

/// The options every fit command ends with: the -o folder and --json.
inline void add_fit_output_options(CLI::App* command, std::string& output_dir, bool& json) {
    command->add_option("-o,--output", output_dir, "Folder for the results (must exist)")->required();
    command->add_flag("--json", json, "Print the report as JSON instead of the summary");
}

/// Prints the report (`json`) or the verdict and `summary`'s lines; then, when no fit is acceptable, the
/// verdict as the error and exit code 1.
inline void finish_fit(bool json, const nlohmann::json& report, bool acceptable, const std::string& verdict, const std::function<void()>& summary) {
    if (json) {
        std::cout << report.dump(2) << '\n';
    } else {
        std::cout << (acceptable ? "fit: " : "fit failed: ") << verdict << '\n';
        summary();
    }
    if (!acceptable) {
        std::cerr << "petroscope: error: " << verdict << '\n';
        throw ExitCode{1};
    }
}

}  // namespace petroscope::cli
