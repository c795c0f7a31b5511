#include "petroscope/verification/interface_cases.hpp"

#include "petroscope/core/error.hpp"
#include "petroscope/core/text.hpp"
#include "petroscope/io/json_reader.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace petroscope {
namespace {

using complex = std::complex<double>;
using json = nlohmann::json;

Eigen::Vector3d vector_of(const json& value) { return {value.at(0).get<double>(), value.at(1).get<double>(), value.at(2).get<double>()}; }
complex complex_of(const json& value) { return {value.at(0).get<double>(), value.at(1).get<double>()}; }

double tolerance_of(const json& wave, const std::string& key, double fallback) {
    return wave.contains("tolerance") && wave["tolerance"].contains(key) ? wave["tolerance"][key].get<double>() : fallback;
}

std::string kind_name(InterfaceWave::Kind kind) { return kind == InterfaceWave::Kind::reflected ? "reflected" : "transmitted"; }

// An expected wave's "mode": a mode's name, or "total" (nothing: every wave of its kind).
std::optional<InterfaceMode> expected_mode(const JsonValue& value) {
    const std::string text = value.text();
    if (text == "total") return std::nullopt;
    if (const std::optional<InterfaceMode> mode = parse_wave_mode(text)) return mode;
    throw value.error("expected \"total\", \"s+p\", \"fast\", \"slow\", \"ordinary\" or \"extraordinary\", not " + quote_input(text));
}

// The polarization ellipse's b/a, tan|χ| with sin 2χ = S3/S0.
double ellipticity(const Eigen::Vector4d& stokes) {
    return std::tan(0.5 * std::abs(std::asin(std::clamp(stokes[3] / stokes[0], -1.0, 1.0))));
}

}  // namespace

VerificationTest check_interface_case(const InterfaceCase& interface_case) {
    VerificationTest test;
    test.name = interface_case.name.empty() ? interface_case.file : interface_case.name;
    test.statement = interface_case.statement;
    test.source = interface_case.document.value("source", interface_case.file);
    const InterfaceResult result =
        solve_interface(interface_case.normal, interface_case.incidence, interface_case.medium1, interface_case.medium2);
    const json& expected = interface_case.document.at("expected");
    std::vector<bool> matched(result.waves.size(), false);
    double smallest_power_tolerance = std::numeric_limits<double>::infinity();
    const JsonValue expected_waves = JsonValue(interface_case.document, interface_case.file, "")["expected"]["waves"];
    for (std::size_t w = 0; w < expected_waves.size(); ++w) {
        const JsonValue entry = expected_waves.at(w);
        const json& wave = entry.raw();
        const std::string kind = wave.at("kind").get<std::string>();
        const std::optional<InterfaceMode> mode = expected_mode(entry["mode"]);
        const std::string label = kind + " " + entry["mode"].text();
        const double power_tolerance = tolerance_of(wave, "power", 1e-12);
        smallest_power_tolerance = std::min(smallest_power_tolerance, power_tolerance);
        // Candidates: the same kind, and the same mode unless the expected wave is the "total" of its kind.
        std::vector<std::size_t> candidates;
        for (std::size_t i = 0; i < result.waves.size(); ++i) {
            if (kind_name(result.waves[i].kind) == kind && (!mode || result.waves[i].mode == *mode)) candidates.push_back(i);
        }
        if (!mode) {
            double total = 0.0;
            for (const std::size_t i : candidates) {
                total += result.waves[i].power;
                matched[i] = true;
                if (wave.contains("direction")) test.check("direction error of " + label, (result.waves[i].direction - vector_of(wave["direction"])).norm(), 0.0, tolerance_of(wave, "direction", 1e-12));
                if (wave.contains("n")) test.check("n of " + label, result.waves[i].n.real(), wave["n"].get<double>(), tolerance_of(wave, "n", 1e-12));
            }
            if (wave.contains("power")) test.check("power of " + label, total, wave["power"].get<double>(), power_tolerance);
            continue;
        }
        if (candidates.empty()) {
            // A wave expected with power 0 may be absent (rule 4).
            const bool zero = wave.value("power", 0.0) == 0.0 || wave.value("evanescent", false);
            test.check("presence of " + label, zero ? 0.0 : 1.0, 0.0, 0.0);
            continue;
        }
        // Several candidates: the nearest in direction (rule 1).
        std::size_t best = candidates.front();
        if (wave.contains("direction")) {
            const Eigen::Vector3d direction = vector_of(wave["direction"]);
            for (const std::size_t i : candidates) {
                if ((result.waves[i].direction - direction).norm() < (result.waves[best].direction - direction).norm()) best = i;
            }
        }
        matched[best] = true;
        const InterfaceWave& found = result.waves[best];
        if (wave.contains("power")) test.check("power of " + label, found.power, wave["power"].get<double>(), power_tolerance);
        if (wave.value("evanescent", false)) test.check("power of evanescent " + label, found.power, 0.0, power_tolerance);
        if (wave.contains("direction")) test.check("direction error of " + label, (found.direction - vector_of(wave["direction"])).norm(), 0.0, tolerance_of(wave, "direction", 1e-12));
        if (wave.contains("n")) test.check("n of " + label, found.n.real(), wave["n"].get<double>(), tolerance_of(wave, "n", 1e-12));
        if (wave.contains("ray_direction")) {
            test.check("ray direction error of " + label, (found.ray_direction - vector_of(wave["ray_direction"])).norm(), 0.0, tolerance_of(wave, "ray_direction", 1e-12));
        }
        if (wave.contains("D_direction")) {
            const Eigen::Vector3d d = vector_of(wave["D_direction"]);
            test.check("D direction error of " + label, std::min((found.d_direction - d).norm(), (found.d_direction + d).norm()), 0.0, tolerance_of(wave, "D_direction", 1e-12));
        }
        const double polarization_tolerance = tolerance_of(wave, "polarization", 1e-12);
        if (wave.contains("stokes")) {
            for (int k = 0; k < 4; ++k) {
                test.check("S" + std::to_string(k) + " of " + label, found.stokes[k], wave["stokes"].at(static_cast<std::size_t>(k)).get<double>(), polarization_tolerance);
            }
        }
        if (wave.contains("jones_sp")) {
            if (!found.jones) {
                test.check("Jones vector of " + label + " reported", 0.0, 1.0, 0.0);
            } else {
                for (int k = 0; k < 2; ++k) {
                    const complex reference = complex_of(wave["jones_sp"].at(static_cast<std::size_t>(k)));
                    test.check(std::string(k == 0 ? "E_s" : "E_p") + " error of " + label, std::abs((*found.jones)[k] - reference), 0.0, polarization_tolerance);
                }
            }
        }
        if (wave.contains("ellipticity")) {
            test.check("ellipticity of " + label, ellipticity(found.stokes), wave["ellipticity"].get<double>(), tolerance_of(wave, "ellipticity", 1e-12));
        }
        if (wave.contains("handedness")) {
            const bool right = found.stokes[3] > 0.0;
            test.check("handedness of " + label + " (1 = as expected)", right == (wave["handedness"].get<std::string>() == "right") ? 1.0 : 0.0, 1.0, 0.0);
        }
    }
    // Rule 5: a reported wave that matches nothing carries no power.
    for (std::size_t i = 0; i < result.waves.size(); ++i) {
        if (!matched[i]) {
            test.check("power of unexpected " + kind_name(result.waves[i].kind) + " " + std::string(wave_mode_name(result.waves[i].mode)), result.waves[i].power, 0.0,
                       std::isfinite(smallest_power_tolerance) ? smallest_power_tolerance : 1e-12);
        }
    }
    if (expected.contains("sum_power")) {
        double total = 0.0;
        for (const InterfaceWave& wave : result.waves) total += wave.power;
        test.check("sum of powers", total, expected["sum_power"].get<double>(), tolerance_of(expected, "sum_power", 1e-12));
    }
    return test;
}

VerificationReport check_case_directory(const std::filesystem::path& directory, const MineralCatalog& catalog) {
    std::error_code error;
    if (!std::filesystem::is_directory(directory, error)) throw InputError("case folder " + directory.string() + " does not exist");
    std::vector<std::filesystem::path> files;
    for (const auto& entry : std::filesystem::directory_iterator(directory)) {
        if (entry.is_regular_file() && entry.path().extension() == ".json") files.push_back(entry.path());
    }
    std::sort(files.begin(), files.end());
    VerificationReport report;
    for (const auto& file : files) {
        const InterfaceCase interface_case = load_interface_case(file, catalog);
        if (!interface_case.document.contains("expected")) throw InputError(file.string() + ": expected: missing (a verification case needs its expected waves)");
        report.tests.push_back(check_interface_case(interface_case));
    }
    return report;
}

}  // namespace petroscope
