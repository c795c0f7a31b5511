// petroscope orthoscope: a thin section under plane-polarized light or between crossed polars.
#include "cli_common.hpp"
#include "cli_light.hpp"
#include "frame_command.hpp"

#include "petroscope/api/orthoscope_image.hpp"
#include "petroscope/core/error.hpp"
#include "petroscope/io/thin_section_file.hpp"

#include <map>
#include <memory>
#include <string>

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
    OrthoscopeRequest plain_;  // the options bound as they are (numbers); defaults: the library's
    std::string section_;
    bool ppl_ = false;
    bool xpl_ = false;
    PlateOptions plate_;
    std::string thickness_;
    LightOptions light_;
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
    if (plain_.condenser_rings < 0 || plain_.condenser_rings > kMaxCondenserRings) {
        throw InputError("--condenser-rings must be 0 (automatic) to " + std::to_string(kMaxCondenserRings));
    }
    OrthoscopeRequest request = plain_;
    request.analyzer_in = !ppl_;
    request.plate = plate_request(plate_);
    if (!thickness_.empty()) request.thickness_um = positive_length_um("--thickness", thickness_);
    request.light = light_from_options(light_);
    request.section = context.section(section_);
    const auto plan = std::make_shared<const OrthoscopePlan>(plan_orthoscope(std::move(request), context.catalog()));

    PreparedFrame prepared;
    prepared.notes = plan->notes;
    const MicroscopeSettings& microscope = plan->settings.microscope;
    const nlohmann::json sidecar{
        {"program", "petroscope 0.1.0"},
        {"command", "orthoscope"},
        {"section", section_summary(plan->section)},
        {"section_file", thin_section_description_path(section_).string()},
        {"view", ppl_ ? "plane-polarized light (analyzer out)" : "crossed polars"},
        {"stage_deg", microscope.stage_deg},
        {"polarizer_deg", microscope.polars.polarizer_deg},
        {"analyzer_deg", ppl_ ? nlohmann::json(nullptr) : nlohmann::json(microscope.polars.analyzer_deg)},
        {"plate", plate_json(microscope.plate)},
        {"condenser_na", microscope.condenser_na},
        {"condenser_rings", microscope.condenser_rings},
        {"condenser_directions", condenser_samples(microscope.condenser_na, microscope.condenser_rings).size()},
        {"mounting", mounting_json(plan->settings.mounting)},
        {"model", microscope.exact ? "exact coherent 4x4 transfer matrix (Berreman) per element: section, plate"
                                   : "single-pass Jones from the exact eigenmodes of every layer, Fresnel at every interface, no multiple reflections"},
        {"exposure", plan->light.exposure},
        {"image_frame", "x to the East (right), y to the North (up); the stage turns the section counter-clockwise about the image centre"},
    };
    prepared.render = [plan, sidecar](const ProgressCallback& progress) {
        const OrthoscopeImage rendered = render_orthoscope_image(*plan, progress);
        RenderedFrame frame{rendered.image.linear_rgb, sidecar, ""};
        frame.sidecar["light"] = light_json(plan->light, rendered.image, "the light after the polarizer");
        frame.sidecar["measurements"] = measurements_json(rendered.measurements);
        const ThinSection& section = plan->section;
        const std::size_t count = plan->settings.microscope.wavelengths_nm.size();
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
    command->add_option("--stage-deg", plain_.stage_deg, "Stage rotation (counter-clockwise seen from the observer)")->capture_default_str();
    add_plate_options(command, plate_);
    command->add_option("--condenser-na", plain_.condenser_na, "Condenser cone (Koehler), 0 = parallel light")->capture_default_str();
    command->add_option("--condenser-rings", plain_.condenser_rings, "Rings of the cone's cubature, 4*rings+2 directions each plus the axis (0: automatic, from the thickest and most birefringent grain)")->capture_default_str();
    command->add_option("--thickness", thickness_, "Override the section's thickness with a uniform one: 30um, …")->type_name(length_type);
    command->add_flag("--exact", plain_.exact, "Coherent 4x4 transfer matrix (every multiple reflection) instead of single-pass Jones");
    add_light_options(command, light_);
    command->add_option("--polarizer-deg", plain_.polarizer_deg, "Polarizer direction, degrees from E toward N")->capture_default_str();
    command->add_option("--analyzer-deg", plain_.analyzer_deg, "Analyzer direction, degrees from E toward N")->capture_default_str();
}

}  // namespace

std::unique_ptr<FrameOptions> make_orthoscope_options() { return std::make_unique<OrthoscopeOptions>(); }

}  // namespace petroscope::cli
