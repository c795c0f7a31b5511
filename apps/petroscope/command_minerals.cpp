// petroscope minerals [show NAME [--wavelength 589nm] [--json]]
#include "cli_common.hpp"

#include "petroscope/core/error.hpp"
#include "petroscope/core/text.hpp"
#include "petroscope/core/units.hpp"
#include "petroscope/io/data_files.hpp"
#include "petroscope/minerals/mineral.hpp"

#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>

namespace petroscope::cli {
namespace {

struct MineralShowOptions {
    std::string name;
    std::string wavelength = "589.3nm";
    bool json = false;
};

nlohmann::json summary_json(const Mineral& mineral, const OpticalSummary& summary) {
    nlohmann::json document;
    document["name"] = mineral.name;
    document["formula"] = mineral.formula;
    document["system"] = mineral.system;
    document["class"] = std::string(optical_class_name(mineral.optical_class));
    document["wavelength_nm"] = summary.wavelength_nm;
    document["n_alpha"] = summary.n_alpha;
    document["n_beta"] = summary.n_beta;
    document["n_gamma"] = summary.n_gamma;
    document["birefringence"] = summary.birefringence;
    document["two_v_deg"] = summary.two_v_deg ? nlohmann::json(*summary.two_v_deg) : nlohmann::json(nullptr);
    document["sign"] = summary.sign.empty() ? nlohmann::json(nullptr) : nlohmann::json(summary.sign);
    document["absorbing"] = mineral.absorbing();
    nlohmann::json axes = nlohmann::json::array();
    for (const PrincipalAxis& axis : mineral.axes) {
        nlohmann::json entry{{"key", axis.key}, {"model", axis.n.describe()}, {"source", axis.n_source}};
        if (axis.kappa) {
            entry["kappa_model"] = axis.kappa->describe();
            entry["kappa_source"] = axis.kappa_source;
        }
        axes.push_back(entry);
    }
    document["axes"] = axes;
    nlohmann::json activity = nlohmann::json::array();
    for (const RotatoryPower& power : mineral.rotatory_powers) {
        activity.push_back({{"key", power.key}, {"model", power.deg_per_mm.describe()}, {"source", power.source},
                            {"deg_per_mm_right_handed", power.deg_per_mm(summary.wavelength_nm)}});
    }
    document["optical_activity"] = mineral.optically_active() ? activity : nlohmann::json(nullptr);
    document["indicatrix"] = mineral.indicatrix;
    document["file"] = mineral.file;
    return document;
}

void print_summary(const Mineral& mineral, const OpticalSummary& summary) {
    std::printf("%s", mineral.name.c_str());
    if (!mineral.formula.empty()) std::printf("  %s", mineral.formula.c_str());
    std::printf("\n  %s, %s", mineral.system.c_str(), std::string(optical_class_name(mineral.optical_class)).c_str());
    if (!summary.sign.empty()) std::printf(" (%s)", summary.sign.c_str());
    std::printf("\n  at %.1f nm:", summary.wavelength_nm);
    if (mineral.optical_class == OpticalClass::isotropic) {
        std::printf(" n = %.5f\n", summary.n_alpha);
    } else {
        std::printf(" n_alpha = %.5f  n_beta = %.5f  n_gamma = %.5f\n", summary.n_alpha, summary.n_beta, summary.n_gamma);
        std::printf("  maximum birefringence %.5f", summary.birefringence);
        if (summary.two_v_deg) std::printf(", 2V = %.2f deg (computed from the indices)", *summary.two_v_deg);
        std::printf("\n");
    }
    if (!mineral.indicatrix.empty()) std::printf("  indicatrix: %s\n", mineral.indicatrix.c_str());
    for (const PrincipalAxis& axis : mineral.axes) {
        std::printf("  %s: %s\n      source: %s\n", axis.key.c_str(), axis.n.describe().c_str(), axis.n_source.c_str());
        if (axis.kappa) std::printf("  kappa: %s\n      source: %s\n", axis.kappa->describe().c_str(), axis.kappa_source.c_str());
    }
    for (const RotatoryPower& power : mineral.rotatory_powers) {
        std::printf("  %s: %s (%.3f deg/mm here, right-handed form)\n      source: %s\n", power.key.c_str(), power.deg_per_mm.describe().c_str(),
                    power.deg_per_mm(summary.wavelength_nm), power.source.c_str());
    }
    if (!mineral.note.empty()) std::printf("  note: %s\n", mineral.note.c_str());
    std::printf("  file: %s\n", mineral.file.c_str());
}

}  // namespace

void add_minerals_command(CLI::App& app, std::string& minerals_dir) {
    CLI::App* minerals = app.add_subcommand("minerals", "List the minerals petroscope knows, or show one");
    minerals->callback([minerals, &minerals_dir] {
        if (!minerals->get_subcommands().empty()) return;
        const MineralCatalog catalog = load_mineral_catalog(minerals_directory(minerals_dir));
        std::printf("%-14s %-13s %-10s %4s %9s %9s %8s  %s\n", "name", "system", "class", "sign", "n_alpha", "n_gamma", "2V(deg)", "aliases");
        for (const Mineral& mineral : catalog.minerals()) {
            const OpticalSummary summary = optical_summary(mineral, mineral.reference_wavelength_nm);
            std::string aliases;
            for (const auto& alias : mineral.aliases) aliases += (aliases.empty() ? "" : ", ") + alias;
            const std::string two_v = summary.two_v_deg ? std::to_string(static_cast<int>(std::lround(*summary.two_v_deg))) : "-";
            std::printf("%-14s %-13s %-10s %4s %9.4f %9.4f %8s  %s\n", mineral.name.c_str(), mineral.system.c_str(),
                        std::string(optical_class_name(mineral.optical_class)).c_str(),
                        summary.sign.empty() ? "-" : summary.sign.c_str(), summary.n_alpha, summary.n_gamma,
                        two_v.c_str(), aliases.c_str());
        }
    });

    auto options = std::make_shared<MineralShowOptions>();
    CLI::App* show = minerals->add_subcommand("show", "Principal indices, optic sign, 2V and birefringence of one mineral");
    show->add_option("name", options->name, "Mineral name or alias (case-insensitive)")->required();
    show->add_option("--wavelength", options->wavelength, "Wavelength, e.g. 589nm or 0.55um (default 589.3nm)");
    show->add_flag("--json", options->json, "Print JSON (keys n_alpha, n_beta, n_gamma, two_v_deg, sign, birefringence, …)");
    show->callback([options, &minerals_dir] {
        const double wavelength_nm = with_option("--wavelength", [&] { return parse_wavelength_nm(options->wavelength); });
        if (!(wavelength_nm > 0.0)) throw InputError("--wavelength must be positive, got " + quote_input(options->wavelength));
        const MineralCatalog catalog = load_mineral_catalog(minerals_directory(minerals_dir));
        const Mineral& mineral = catalog.find(options->name);
        for (const auto& warning : mineral.range_warnings({wavelength_nm})) std::cerr << "petroscope: warning: " << warning << '\n';
        const OpticalSummary summary = optical_summary(mineral, wavelength_nm);
        if (options->json) {
            std::cout << summary_json(mineral, summary).dump(2) << '\n';
        } else {
            print_summary(mineral, summary);
        }
    });
}

}  // namespace petroscope::cli
