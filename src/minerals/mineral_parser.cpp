#include "petroscope/minerals/mineral_parser.hpp"

#include "petroscope/core/error.hpp"
#include "petroscope/core/text.hpp"
#include "petroscope/optics/gyration.hpp"
#include "petroscope/optics/indicatrix.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numbers>
#include <set>
#include <sstream>

namespace petroscope {
namespace {

struct Entry {
    std::string value;
    int line = 0;
};

constexpr std::array<std::string_view, 8> kPlainKeys{"name", "aliases", "formula", "system", "class",
                                                    "indicatrix", "reference_wavelength_nm", "source"};
constexpr std::array<std::string_view, 8> kSystems{"cubic", "tetragonal", "hexagonal", "trigonal",
                                                  "orthorhombic", "monoclinic", "triclinic", "amorphous"};

std::vector<std::string> axis_suffixes(OpticalClass optical_class) {
    switch (optical_class) {
        case OpticalClass::isotropic: return {""};
        case OpticalClass::uniaxial: return {"_o", "_e"};
        case OpticalClass::biaxial: return {"_alpha", "_beta", "_gamma"};
    }
    return {};
}

// Removes a comment: '#' at the start of the line or after a space or tab.
std::string_view strip_comment(std::string_view line) {
    for (std::size_t i = 0; i < line.size(); ++i) {
        if (line[i] == '#' && (i == 0 || line[i - 1] == ' ' || line[i - 1] == '\t')) return line.substr(0, i);
    }
    return line;
}

class RecordReader {
public:
    RecordReader(std::string_view text, std::string file_name) : file_(std::move(file_name)) {
        for_each_line(text, [&](int line_number, std::string_view raw) {
            last_line_ = line_number;
            const std::string_view line = trim(strip_comment(raw));
            if (line.empty()) return;
            const std::size_t colon = line.find(':');
            if (colon == std::string_view::npos) {
                throw located_error(file_, line_number, "expected 'key: value', found " + quote_input(line));
            }
            const std::string key(trim(line.substr(0, colon)));
            const std::string value(trim(line.substr(colon + 1)));
            if (key.empty()) throw located_error(file_, line_number, "missing key before ':'");
            if (value.empty()) throw located_error(file_, line_number, "key " + quote_input(key) + " has no value");
            if (const auto previous = entries_.find(key); previous != entries_.end()) {
                throw located_error(file_, line_number,
                                    "key " + quote_input(key) + " appears twice (first on line " + std::to_string(previous->second.line) + ")");
            }
            entries_[key] = Entry{value, line_number};
        });
    }

    const Entry* find(const std::string& key) {
        used_.insert(key);
        const auto it = entries_.find(key);
        return it == entries_.end() ? nullptr : &it->second;
    }
    const Entry& require(const std::string& key, const std::string& what) {
        if (const Entry* entry = find(key)) return *entry;
        throw located_error(file_, last_line_, "missing key " + quote_input(key) + " (" + what + ")");
    }
    InputError error(const Entry& entry, const std::string& what) const { return located_error(file_, entry.line, what); }
    InputError error_at_end(const std::string& what) const { return located_error(file_, last_line_, what); }

    // Every key that was never asked for is unknown to the format.
    void reject_unused(const std::vector<std::string>& valid) const {
        for (const auto& [key, entry] : entries_) {
            if (used_.count(key) == 0) {
                std::string list;
                for (const auto& name : valid) list += (list.empty() ? "" : ", ") + name;
                throw located_error(file_, entry.line, "unknown key " + quote_input(key) + " (valid keys here: " + list + ")");
            }
        }
    }

private:
    std::string file_;
    std::map<std::string, Entry> entries_;
    std::set<std::string> used_;
    int last_line_ = 1;  // the last line of the file (1 for an empty file)
};

DispersionModel parse_model(RecordReader& reader, const Entry& entry, const std::string& key) {
    try {
        return DispersionModel::parse(entry.value);
    } catch (const InputError& e) {
        throw reader.error(entry, key + ": " + e.what());
    }
}

PrincipalAxis read_axis(RecordReader& reader, const std::string& suffix, std::vector<std::string>& valid) {
    PrincipalAxis axis;
    axis.key = "n" + suffix;
    const std::string kappa_key = "kappa" + suffix;
    for (const std::string& key : {axis.key, axis.key + ".source", axis.key + ".range_um", kappa_key, kappa_key + ".source"}) {
        valid.push_back(key);
    }
    const Entry& index = reader.require(axis.key, "principal refractive index, e.g. 'cauchy 1.53 0.0042'");
    axis.n = parse_model(reader, index, axis.key);
    axis.n_source = reader.require(axis.key + ".source", "where the numbers of " + axis.key + " come from").value;
    if (const Entry* range = reader.find(axis.key + ".range_um")) {
        const auto words = split_whitespace(range->value);
        const auto low = words.size() == 2 ? parse_double(words[0]) : std::nullopt;
        const auto high = words.size() == 2 ? parse_double(words[1]) : std::nullopt;
        if (!low || !high || *low <= 0.0 || *high <= *low) {
            throw reader.error(*range, axis.key + ".range_um: expected two increasing positive numbers MIN MAX in micrometres");
        }
        axis.range_um = std::array<double, 2>{*low, *high};
    }
    if (const Entry* kappa = reader.find(kappa_key)) {
        axis.kappa = parse_model(reader, *kappa, kappa_key);
        axis.kappa_source = reader.require(kappa_key + ".source", "where the numbers of " + kappa_key + " come from").value;
    } else if (const Entry* orphan = reader.find(kappa_key + ".source")) {
        throw reader.error(*orphan, kappa_key + ".source given without " + kappa_key);
    }
    return axis;
}

// The rotatory power is checked every 5 nm over the CIE 1931 observer's range, 360 … 830 nm.
constexpr double kCheckedFromNm = 360.0, kCheckedToNm = 830.0, kCheckStepNm = 5.0;

// The rotatory power keys of an optical class, in the order of Mineral::rotatory_powers.
std::vector<std::string> rotatory_power_keys(OpticalClass optical_class) {
    switch (optical_class) {
        case OpticalClass::isotropic: return {"rotatory_power"};
        case OpticalClass::uniaxial: return {"rotatory_power_normal", "rotatory_power_axis"};
        case OpticalClass::biaxial: return {"rotatory_power_x", "rotatory_power_y", "rotatory_power_z"};
    }
    return {};
}

// Optical activity: all of the class's rotatory power keys or none, each with its source and within range over
// the visible.
void read_rotatory_powers(RecordReader& reader, Mineral& mineral, std::vector<std::string>& valid) {
    const std::vector<std::string> keys = rotatory_power_keys(mineral.optical_class);
    std::vector<const Entry*> entries;
    for (const std::string& key : keys) {
        valid.push_back(key);
        valid.push_back(key + ".source");
        entries.push_back(reader.find(key));
    }
    const auto given = std::find_if(entries.begin(), entries.end(), [](const Entry* entry) { return entry != nullptr; });
    if (given == entries.end()) return;
    for (std::size_t i = 0; i < keys.size(); ++i) {
        if (entries[i] == nullptr) {
            std::string all_keys = keys.front();
            for (std::size_t k = 1; k < keys.size(); ++k) all_keys += (k + 1 == keys.size() ? " and " : ", ") + keys[k];
            throw reader.error(**given, "optical activity of a " + std::string(optical_class_name(mineral.optical_class)) + " crystal needs " +
                                            all_keys + " (°/mm for waves along its principal directions, minerals/README.md); " + keys[i] +
                                            " is missing");
        }
        RotatoryPower power{keys[i], parse_model(reader, *entries[i], keys[i]),
                            reader.require(keys[i] + ".source", "where the numbers of " + keys[i] + " come from").value};
        for (double wavelength_nm = kCheckedFromNm; wavelength_nm <= kCheckedToNm; wavelength_nm += kCheckStepNm) {
            const double value = power.deg_per_mm(wavelength_nm);
            if (!std::isfinite(value) || std::abs(value) > kMaxRotatoryPowerDegPerMm) {
                std::ostringstream what;
                what << keys[i] << " evaluates to " << value << " deg/mm at " << wavelength_nm << " nm; expected a finite rotatory power within ±"
                     << kMaxRotatoryPowerDegPerMm << " deg/mm from " << kCheckedFromNm << " to " << kCheckedToNm << " nm";
                throw reader.error(*entries[i], what.str());
            }
        }
        mineral.rotatory_powers.push_back(std::move(power));
    }
}

// A record gives the right-handed (dextrorotatory) form: along an optic axis (any direction when isotropic) its
// rotatory power ŝ·ρ·ŝ is positive at the reference wavelength. A biaxial crystal's optic axes (binormals) lie in
// its XZ plane, at V from Z with tan²V = (1/nα² − 1/nβ²)/(1/nβ² − 1/nγ²) (Born & Wolf §15.3.3), where ŝ·ρ·ŝ =
// ρ_x sin²V + ρ_z cos²V. Called once the indices are known to be ordered.
void require_right_handed(RecordReader& reader, const Mineral& mineral) {
    if (!mineral.optically_active()) return;
    const double wavelength_nm = mineral.reference_wavelength_nm;
    const Eigen::Vector3d binormal = BinormalFrame(Indicatrix{mineral.principal_n(wavelength_nm)}).binormal_1;
    const double along_optic_axis_deg_per_mm =
        binormal.dot(mineral.principal_rotatory_power(wavelength_nm).cwiseProduct(binormal)) * 180.0 / std::numbers::pi * 1e3;
    if (along_optic_axis_deg_per_mm > 0.0) return;
    const RotatoryPower& last = mineral.rotatory_powers.back();
    std::ostringstream what;
    what << "the rotatory power along the optic " << (mineral.optical_class == OpticalClass::biaxial ? "axes" : "axis") << " is "
         << along_optic_axis_deg_per_mm << " deg/mm at " << wavelength_nm
         << " nm; it must be positive: a record gives the right-handed (dextrorotatory) form, and --handedness left mirrors it";
    throw reader.error(reader.require(last.key, ""), what.str());
}

}  // namespace

Mineral parse_mineral(std::string_view text, const std::string& file_name) {
    RecordReader reader(text, file_name);
    Mineral mineral;
    mineral.file = file_name;
    std::vector<std::string> valid(kPlainKeys.begin(), kPlainKeys.end());
    valid.emplace_back("note");

    mineral.name = reader.require("name", "the mineral's name").value;
    if (const Entry* aliases = reader.find("aliases")) {
        for (auto& alias : split(aliases->value, ',')) {
            if (alias.empty()) throw reader.error(*aliases, "aliases: expected comma-separated names, found an empty one");
            mineral.aliases.push_back(alias);
        }
    }
    for (const auto& [key, field] : {std::pair{"formula", &mineral.formula}, {"indicatrix", &mineral.indicatrix},
                                     {"source", &mineral.source}, {"note", &mineral.note}}) {
        if (const Entry* entry = reader.find(key)) *field = entry->value;
    }
    const Entry& system = reader.require("system", "crystal system");
    if (std::find(kSystems.begin(), kSystems.end(), system.value) == kSystems.end()) {
        throw reader.error(system, "unknown crystal system " + quote_input(system.value) +
                                       " (expected cubic, tetragonal, hexagonal, trigonal, orthorhombic, monoclinic, triclinic or amorphous)");
    }
    mineral.system = system.value;
    const Entry& optical_class = reader.require("class", "isotropic, uniaxial or biaxial");
    if (optical_class.value == "isotropic") mineral.optical_class = OpticalClass::isotropic;
    else if (optical_class.value == "uniaxial") mineral.optical_class = OpticalClass::uniaxial;
    else if (optical_class.value == "biaxial") mineral.optical_class = OpticalClass::biaxial;
    else throw reader.error(optical_class, "unknown optical class " + quote_input(optical_class.value) + " (expected isotropic, uniaxial or biaxial)");

    if (const Entry* reference = reader.find("reference_wavelength_nm")) {
        const auto value = parse_double(reference->value);
        if (!value || *value <= 0.0) throw reader.error(*reference, "reference_wavelength_nm: expected a positive number of nanometres");
        mineral.reference_wavelength_nm = *value;
    }
    for (const std::string& suffix : axis_suffixes(mineral.optical_class)) {
        mineral.axes.push_back(read_axis(reader, suffix, valid));
    }
    read_rotatory_powers(reader, mineral, valid);
    reader.reject_unused(valid);

    // The indices must be physical at the reference wavelength, and ordered as the labels say.
    std::vector<double> n_reference;
    for (const PrincipalAxis& axis : mineral.axes) {
        const double n = axis.n(mineral.reference_wavelength_nm);
        if (!std::isfinite(n) || n < 1.0) {
            std::ostringstream what;
            what << axis.key << " evaluates to " << n << " at " << mineral.reference_wavelength_nm
                 << " nm; expected a finite index >= 1";
            throw reader.error(reader.require(axis.key, ""), what.str());
        }
        n_reference.push_back(n);
    }
    if (mineral.optical_class == OpticalClass::biaxial &&
        !(n_reference[0] < n_reference[1] && n_reference[1] < n_reference[2])) {
        std::ostringstream what;
        what << "biaxial indices must satisfy n_alpha < n_beta < n_gamma at " << mineral.reference_wavelength_nm
             << " nm; found " << n_reference[0] << ", " << n_reference[1] << ", " << n_reference[2];
        throw reader.error(reader.require("n_beta", ""), what.str());
    }
    if (mineral.optical_class == OpticalClass::uniaxial && n_reference[0] == n_reference[1]) {
        throw reader.error(reader.require("n_e", ""), "uniaxial indices n_o and n_e are equal: use class: isotropic");
    }
    require_right_handed(reader, mineral);
    return mineral;
}

}  // namespace petroscope
