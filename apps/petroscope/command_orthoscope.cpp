// petroscope orthoscope: a thin section under plane-polarized light or between crossed polars.
#include "cli_common.hpp"
#include "cli_light.hpp"
#include "frame_command.hpp"

#include "petroscope/core/error.hpp"
#include "petroscope/core/text.hpp"
#include "petroscope/io/data_files.hpp"
#include "petroscope/io/thin_section_file.hpp"
#include "petroscope/microscope/frame_measurements.hpp"
#include "petroscope/microscope/orthoscope.hpp"

#include <algorithm>
#include <map>
#include <memory>

namespace petroscope::cli {
namespace {

class OrthoscopeOptions final : public FrameOptions {
public:
    std::string command() const override { return "orthoscope"; }
    std::string description() const override {
        return "Render a thin section as seen through the eyepieces: plane-polarized light (--ppl: absorption,\n"
               "pleochroism) or crossed polars (--xpl, the default: interference colours, extinction), with the stage\n"
               "turned and an accessory plate. Frames and angle senses: docs/conventions.md; the model: docs/orthoscope.md.";
    }
    void add_options(CLI::App* command) override;
    PreparedFrame prepare(FrameContext& context) const override;

private:
    std::string section_;
    bool ppl_ = false;
    bool xpl_ = false;
    double stage_deg_ = 0.0;
    PlateOptions plate_;
    double condenser_na_ = 0.0;
    int condenser_rings_ = 0;
    std::string thickness_;
    bool exact_ = false;
    LightOptions light_;
    double polarizer_deg_ = 0.0;
    double analyzer_deg_ = 90.0;
};

nlohmann::json section_summary(const ThinSection& section) {
    std::map<std::string, int> grains_per_mineral;
    for (const ThinSectionGrain& grain : section.grains) ++grains_per_mineral[grain.mineral];
    nlohmann::json thickness;
    switch (section.thickness_kind) {
        case ThicknessKind::uniform: thickness = {{"kind", "uniform"}, {"thickness_um", section.thickness_um}}; break;
        case ThicknessKind::wedge:
            thickness = {{"kind", "wedge"}, {"start_um", section.wedge_start_um}, {"end_um", section.wedge_end_um},
                         {"along", section.wedge_along_x ? "x" : "y"}};
            break;
        case ThicknessKind::map: thickness = {{"kind", "map"}}; break;
    }
    return {{"name", section.name}, {"size_px", {section.width_px, section.height_px}},
            {"pixel_size_um", section.pixel_size_um}, {"grains", section.grains.size()},
            {"grains_per_mineral", grains_per_mineral}, {"thickness", thickness}};
}

PreparedFrame OrthoscopeOptions::prepare(FrameContext& context) const {
    OrthoscopeSettings settings;
    MicroscopeSettings& microscope = settings.microscope;
    microscope.stage_deg = stage_deg_;
    microscope.polars = {polarizer_deg_, analyzer_deg_, !ppl_};
    microscope.condenser_na = condenser_na_;
    microscope.condenser_rings = condenser_rings_;
    microscope.exact = exact_;
    if (condenser_rings_ < 0 || condenser_rings_ > 64) throw InputError("--condenser-rings must be 0 (automatic) to 64");

    const ResolvedLight light_used = resolve_light(light_);
    microscope.wavelengths_nm = light_used.wavelengths_nm;
    const MineralCatalog& catalog = context.catalog();
    settings.mounting = standard_mounting(catalog);
    microscope.plate = make_plate(plate_, catalog);
    settings.validate();
    ThinSection section = context.section(section_);
    if (!thickness_.empty()) {
        section.thickness_kind = ThicknessKind::uniform;
        section.thickness_um = positive_length_um("--thickness", thickness_);
    }

    PreparedFrame prepared;
    std::vector<std::string> warned;
    for (const ThinSectionGrain& grain : section.grains) {
        if (std::find(warned.begin(), warned.end(), grain.mineral) != warned.end()) continue;
        warned.push_back(grain.mineral);
        for (const auto& warning : catalog.find(grain.mineral).range_warnings(microscope.wavelengths_nm)) {
            prepared.notes.push_back("warning: " + warning);
        }
    }
    const SectionMounting& mounting = settings.mounting;
    const nlohmann::json sidecar{
        {"program", "petroscope 0.1.0"},
        {"command", "orthoscope"},
        {"section", section_summary(section)},
        {"section_file", thin_section_description_path(section_).string()},
        {"view", ppl_ ? "plane-polarized light (analyzer out)" : "crossed polars"},
        {"stage_deg", microscope.stage_deg},
        {"polarizer_deg", microscope.polars.polarizer_deg},
        {"analyzer_deg", ppl_ ? nlohmann::json(nullptr) : nlohmann::json(microscope.polars.analyzer_deg)},
        {"plate", plate_json(microscope.plate)},
        {"condenser_na", microscope.condenser_na},
        {"condenser_directions", condenser_samples(microscope.condenser_na, microscope.condenser_rings > 0 ? microscope.condenser_rings
                                                                                                         : default_condenser_rings(microscope.condenser_na)).size()},
        {"mounting", {{"slide", "crown glass"}, {"slide_um", mounting.slide_um}, {"cement", "canada balsam"},
                      {"lower_cement_um", mounting.lower_cement_um}, {"upper_cement_um", mounting.upper_cement_um},
                      {"cover", "crown glass"}, {"cover_um", mounting.cover_um}}},
        {"model", microscope.exact ? "exact coherent 4x4 transfer matrix (Berreman) per element: section, plate"
                                   : "single-pass Jones from the exact eigenmodes of every layer, Fresnel at every interface, no multiple reflections"},
        {"exposure", light_.exposure},
        {"image_frame", "x to the East (right), y to the North (up); the stage turns the section counter-clockwise about the image centre"},
    };
    const LightOptions light_options = light_;
    prepared.render = [settings, section, light_options, light_used, &catalog, sidecar](const ProgressCallback& progress) {
        RenderedFrame frame;
        frame.sidecar = sidecar;
        frame.linear_rgb = render_in_light(
            light_options, light_used,
            [&](const SpectralIntegrator* integrator) { return render_orthoscope(section, catalog, settings, integrator, progress); },
            "the light after the polarizer", frame.sidecar["light"]);
        // Whole-field means: between crossed polars a grain at extinction darkens the field.
        const MeanColour mean = mean_colour(frame.linear_rgb, false);
        frame.sidecar["measurements"] = {{"mean_r", mean.r}, {"mean_g", mean.g}, {"mean_b", mean.b}, {"mean_luminance", mean.luminance}};
        const std::size_t count = settings.microscope.wavelengths_nm.size();
        frame.summary = std::to_string(section.width_px) + "x" + std::to_string(section.height_px) + ", " + std::to_string(section.grains.size()) +
                        " grains, " + std::to_string(count) + " wavelength" + (count == 1 ? "" : "s");
        return frame;
    };
    return prepared;
}

void OrthoscopeOptions::add_options(CLI::App* command) {
    command->add_option("--section", section_, "Thin section: its folder or description file (thin_sections/README.md)")->required();
    auto* ppl = command->add_flag("--ppl", ppl_, "Plane-polarized light: analyzer out");
    command->add_flag("--xpl", xpl_, "Crossed polars (default)")->excludes(ppl);
    command->add_option("--stage-deg", stage_deg_, "Stage rotation (counter-clockwise seen from the observer)")->capture_default_str();
    add_plate_options(command, plate_);
    command->add_option("--condenser-na", condenser_na_, "Condenser cone (Koehler), 0 = parallel light")->capture_default_str();
    command->add_option("--condenser-rings", condenser_rings_, "Rings of directions sampling the cone (0: automatic, NA/0.05)")->capture_default_str();
    command->add_option("--thickness", thickness_, "Override the section's thickness with a uniform one: 30um, …")->type_name(length_type);
    command->add_flag("--exact", exact_, "Coherent 4x4 transfer matrix (every multiple reflection) instead of single-pass Jones");
    add_light_options(command, light_);
    command->add_option("--polarizer-deg", polarizer_deg_, "Polarizer direction, degrees from E toward N")->capture_default_str();
    command->add_option("--analyzer-deg", analyzer_deg_, "Analyzer direction, degrees from E toward N")->capture_default_str();
}

}  // namespace

std::unique_ptr<FrameOptions> make_orthoscope_options() { return std::make_unique<OrthoscopeOptions>(); }

}  // namespace petroscope::cli
