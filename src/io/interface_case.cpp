#include "petroscope/io/interface_case.hpp"

#include "petroscope/core/text.hpp"
#include "petroscope/io/data_files.hpp"
#include "petroscope/io/json_reader.hpp"
#include "petroscope/optics/gyration.hpp"
#include "petroscope/optics/orientation.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace petroscope {
namespace {

using complex = std::complex<double>;

Eigen::Vector3d vector3(const JsonValue& value) {
    const std::vector<double> v = value.numbers(3);
    const Eigen::Vector3d vector(v[0], v[1], v[2]);
    if (vector.norm() == 0.0) throw value.error("expected a non-zero vector");
    return vector;
}

Eigen::Matrix3d orientation_of(const JsonValue& medium) {
    if (!medium.has("euler_zyz_deg")) return Eigen::Matrix3d::Identity();
    const std::vector<double> angles = medium["euler_zyz_deg"].numbers(3);
    return euler_zyz_deg(angles[0], angles[1], angles[2]);
}

void check_index(const JsonValue& where, complex n) {
    if (!(n.real() > 0.0) || n.imag() < 0.0) throw where.error("expected a refractive index with n > 0 (and κ >= 0)");
}

// Optical activity of a medium given by its indices: "rotatory_power_deg_per_mm": [ρX, ρY, ρZ] (°/mm,
// positive dextrorotatory, along the indicatrix axes; docs/conventions.md), as gᵢᵢ = λρᵢ/π.
Eigen::Matrix3d gyration_of(const JsonValue& medium, double wavelength_nm) {
    if (!medium.has("rotatory_power_deg_per_mm")) return Eigen::Matrix3d::Zero();
    const JsonValue value = medium["rotatory_power_deg_per_mm"];
    const std::vector<double> rho = value.numbers(3);
    const Eigen::Vector3d rho_deg_per_mm(rho[0], rho[1], rho[2]);
    if (!(rho_deg_per_mm.cwiseAbs().maxCoeff() <= kMaxRotatoryPowerDegPerMm)) {
        throw value.error("expected rotatory powers within ±" + format_number(kMaxRotatoryPowerDegPerMm) + " °/mm");
    }
    return gyration_tensor(rho_deg_per_mm * (std::numbers::pi / 180.0 * 1e-3), Eigen::Matrix3d::Identity(), wavelength_nm, Handedness::right);
}

// {"n": 1.5} | {"n": [1.5, 0.01]} | {"principal_n": [n1, n2, n3], "euler_zyz_deg": [a, b, c]} (either with
// "rotatory_power_deg_per_mm") | {"mineral": "quartz", "euler_zyz_deg": [a, b, c], "handedness": "left"}
OpticalMedium parse_medium(const JsonValue& medium, double wavelength_nm, const MineralCatalog& catalog) {
    if (!medium.raw().is_object()) throw medium.error("expected an object with \"n\", \"principal_n\" or \"mineral\"");
    const int forms = medium.has("n") + medium.has("principal_n") + medium.has("mineral");
    if (forms != 1) throw medium.error("expected exactly one of \"n\", \"principal_n\" or \"mineral\"");
    if (medium.has("mineral") && medium.has("rotatory_power_deg_per_mm")) {
        throw medium["rotatory_power_deg_per_mm"].error("a mineral's optical activity comes from its record (choose its form with \"handedness\")");
    }
    if (!medium.has("mineral") && medium.has("handedness")) {
        throw medium["handedness"].error("\"handedness\" chooses the form of an optically active mineral; give \"rotatory_power_deg_per_mm\" here");
    }
    if (medium.has("n")) {
        const complex n = medium["n"].complex_number();
        check_index(medium["n"], n);
        OpticalMedium isotropic = OpticalMedium::isotropic(n);
        isotropic.gyration = gyration_of(medium, wavelength_nm);
        return isotropic;
    }
    OpticalMedium result;
    result.axes = orientation_of(medium);
    result.gyration = gyration_of(medium, wavelength_nm);
    if (medium.has("principal_n")) {
        const JsonValue list = medium["principal_n"];
        if (!list.raw().is_array() || list.raw().size() != 3) throw list.error("expected an array of 3 indices (numbers or [re, im])");
        for (std::size_t i = 0; i < 3; ++i) {
            result.principal_n[static_cast<Eigen::Index>(i)] = list.at(i).complex_number();
            check_index(list.at(i), result.principal_n[static_cast<Eigen::Index>(i)]);
        }
        return result;
    }
    const JsonValue name = medium["mineral"];
    const Mineral* mineral = nullptr;
    try {
        mineral = &catalog.find(name.text());
    } catch (const InputError& e) {
        throw name.error(e.what());
    }
    const Eigen::Vector3d n = mineral->principal_n(wavelength_nm);
    if (!n.allFinite() || n.minCoeff() < 1.0) throw name.error(mineral->name + " has no physical index at this wavelength");
    OpticalMedium crystal = OpticalMedium::from_n_kappa(n, mineral->principal_kappa(wavelength_nm), result.axes);
    if (!mineral->optically_active()) {
        if (medium.has("handedness")) throw medium["handedness"].error(mineral->name + " is not optically active: it has no handedness");
        return crystal;
    }
    // The right-handed form unless the case says otherwise, as on the command line.
    Handedness handedness = Handedness::right;
    if (medium.has("handedness")) {
        const JsonValue hand = medium["handedness"];
        try {
            handedness = parse_handedness(hand.text());
        } catch (const InputError& e) {
            throw hand.error(e.what());
        }
    }
    crystal.gyration = mineral->gyration(wavelength_nm, handedness);
    return crystal;
}

constexpr const char* kIncidentModeExpected =
    "medium 1 is anisotropic or optically active: expected the name of the incident mode (\"fast\", \"slow\", \"ordinary\", \"extraordinary\")";

// Polarization of the incident wave (docs/interface.md).
void parse_polarization(const JsonValue& value, bool anisotropic_medium, InterfaceIncidence& incidence) {
    const double root_half = std::sqrt(0.5);
    if (value.raw().is_string()) {
        const std::string text = value.text();
        if (anisotropic_medium) {
            incidence.mode = parse_wave_mode(text);
            if (incidence.mode && *incidence.mode != InterfaceMode::isotropic) return;
            throw value.error(std::string(kIncidentModeExpected) + ", not " + quote_input(text));
        }
        if (text == "unpolarized") {
            incidence.coherency = CoherencyMatrix::Identity() * 0.5;
            return;
        }
        if (text == "s" || text == "p") {
            incidence.jones = text == "s" ? JonesVector(1.0, 0.0) : JonesVector(0.0, 1.0);
        } else {
            throw value.error("expected \"unpolarized\", \"s\", \"p\" or an object ({\"linear_deg\": a}, {\"jones_sp\": …}, {\"stokes\": …}, {\"circular\": \"left\"|\"right\"})");
        }
    } else if (anisotropic_medium) {
        throw value.error(kIncidentModeExpected);
    } else if (value.has("linear_deg")) {
        const double angle = value["linear_deg"].number() * std::numbers::pi / 180.0;
        incidence.jones = JonesVector(std::cos(angle), std::sin(angle));
    } else if (value.has("jones_sp")) {
        const JsonValue pair = value["jones_sp"];
        if (!pair.raw().is_array() || pair.raw().size() != 2) throw pair.error("expected [[re, im], [re, im]]");
        incidence.jones = JonesVector(pair.at(0).complex_number(), pair.at(1).complex_number());
        if (incidence.jones->norm() == 0.0) throw pair.error("expected a non-zero Jones vector");
    } else if (value.has("circular")) {
        const std::string hand = value["circular"].text();
        if (hand != "left" && hand != "right") throw value["circular"].error("expected \"left\" or \"right\"");
        incidence.jones = JonesVector(root_half, complex(0.0, hand == "right" ? root_half : -root_half));
    } else if (value.has("stokes")) {
        const std::vector<double> s = value["stokes"].numbers(4);
        const Eigen::Vector4d stokes(s[0], s[1], s[2], s[3]);
        if (!is_physical_stokes(stokes)) throw value["stokes"].error("expected S0 > 0 and S1² + S2² + S3² <= S0²");
        incidence.coherency = coherency_from_stokes(stokes);
        return;
    } else {
        throw value.error("expected a polarization: \"unpolarized\", \"s\", \"p\", {\"linear_deg\": a}, {\"jones_sp\": …}, {\"stokes\": …} or {\"circular\": …}");
    }
    incidence.coherency = coherency_from_jones(*incidence.jones / incidence.jones->norm());
}

nlohmann::json vector_json(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }
nlohmann::json complex_json(complex z) { return {z.real(), z.imag()}; }

}  // namespace

InterfaceCase parse_interface_case(const nlohmann::json& document, const std::string& file, const MineralCatalog& catalog) {
    const JsonValue root(document, file, "");
    if (!document.is_object()) throw root.error("expected a JSON object");
    InterfaceCase result;
    result.file = file;
    result.document = document;
    if (root.has("name")) result.name = root["name"].text();
    if (root.has("statement")) result.statement = root["statement"].text();
    result.wavelength_nm = root["wavelength_nm"].number();
    if (!(result.wavelength_nm > 0.0)) throw root["wavelength_nm"].error("expected a positive wavelength in nm");
    result.normal = vector3(root["normal"]);
    result.medium1 = parse_medium(root["medium1"], result.wavelength_nm, catalog);
    result.medium2 = parse_medium(root["medium2"], result.wavelength_nm, catalog);
    const JsonValue incident = root["incident"];
    result.incidence.direction = vector3(incident["direction"]);
    if (!(result.incidence.direction.dot(result.normal) > 0.0)) {
        throw incident["direction"].error("the incident wave must travel from medium 1 into medium 2 (positive component along \"normal\")");
    }
    parse_polarization(incident["polarization"], !result.medium1.has_s_and_p_waves(), result.incidence);
    const bool named_by_axis = result.medium1.is_uniaxial() && !result.medium1.is_active();
    if (!named_by_axis && (result.incidence.mode == InterfaceMode::ordinary || result.incidence.mode == InterfaceMode::extraordinary)) {
        throw incident["polarization"].error(std::string(result.medium1.is_active() ? "medium 1 is optically active" : "medium 1 is biaxial") +
                                             ": expected \"fast\" or \"slow\" (\"ordinary\" and \"extraordinary\" name the waves of an inactive uniaxial crystal)");
    }
    return result;
}

InterfaceCase load_interface_case(const std::filesystem::path& path, const MineralCatalog& catalog) {
    return parse_interface_case(parse_json_text(read_text_file(path), path.string()), path.string(), catalog);
}

nlohmann::json interface_result_json(const InterfaceResult& result) {
    nlohmann::json waves = nlohmann::json::array();
    for (const InterfaceWave& wave : result.waves) {
        nlohmann::json entry{
            {"kind", wave.kind == InterfaceWave::Kind::reflected ? "reflected" : "transmitted"},
            {"mode", wave_mode_name(wave.mode)},
            {"direction", vector_json(wave.direction)},
            {"ray_direction", vector_json(wave.ray_direction)},
            {"n", wave.n.imag() == 0.0 ? nlohmann::json(wave.n.real()) : complex_json(wave.n)},
            {"power", wave.power},
            {"stokes", {wave.stokes[0], wave.stokes[1], wave.stokes[2], wave.stokes[3]}},
            {"evanescent", wave.evanescent},
        };
        // The polarization ellipse: b/a = tan|χ| with sin 2χ = S3/S0; right-handed when S3 > 0.
        if (wave.stokes[0] > 0.0) {
            const double s3 = std::clamp(wave.stokes[3] / wave.stokes[0], -1.0, 1.0);
            entry["ellipticity"] = std::tan(0.5 * std::abs(std::asin(s3)));
            entry["handedness"] = s3 > 1e-12 ? "right" : s3 < -1e-12 ? "left" : "linear";
        }
        if (wave.jones) entry["jones_sp"] = {complex_json(wave.jones->x()), complex_json(wave.jones->y())};
        if (wave.amplitude) entry["amplitude"] = complex_json(*wave.amplitude);
        waves.push_back(entry);
    }
    return {{"waves", waves},
            {"incident", {{"n", result.incident_n.real()}, {"ray_direction", vector_json(result.incident_ray_direction)}}}};
}

}  // namespace petroscope
