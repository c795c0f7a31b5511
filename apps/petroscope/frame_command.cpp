#include "frame_command.hpp"

#include "cli_common.hpp"

#include "petroscope/io/data_files.hpp"

#include <chrono>
#include <iostream>

namespace petroscope::cli {

nlohmann::json measurements_json(const Measurements& measurements) {
    nlohmann::json json = nlohmann::json::object();
    for (const Measurement& measurement : measurements) json[measurement.name] = measurement.value ? nlohmann::json(*measurement.value) : nlohmann::json(nullptr);
    return json;
}

const MineralCatalog& FrameContext::catalog() {
    if (!catalog_) catalog_ = load_mineral_catalog(minerals_directory(minerals_dir_));
    return *catalog_;
}

const ThinSection& FrameContext::section(const std::string& description_or_dir) {
    auto found = sections_.find(description_or_dir);
    if (found == sections_.end()) found = sections_.emplace(description_or_dir, read_thin_section(description_or_dir, catalog())).first;
    return found->second;
}

const std::vector<std::pair<std::string, std::function<std::unique_ptr<FrameOptions>()>>>& frame_commands() {
    static const std::vector<std::pair<std::string, std::function<std::unique_ptr<FrameOptions>()>>> commands{
        {"conoscope", make_conoscope_options}, {"orthoscope", make_orthoscope_options}, {"conical", make_conical_options}};
    return commands;
}

void add_frame_command(CLI::App& app, std::unique_ptr<FrameOptions> options_in, const std::string& minerals_dir,
                       const std::string& command_line) {
    const std::shared_ptr<FrameOptions> options(std::move(options_in));
    CLI::App* command = app.add_subcommand(options->command(), options->description());
    options->add_options(command);
    const auto output = std::make_shared<std::string>();
    command->add_option("-o,--output", *output,
                        "Output image: .png (sRGB, for viewing), .exr or .tif (float); a JSON sidecar <output>.json is written beside it")
        ->required();
    command->callback([options, output, &minerals_dir, command_line] {
        const auto started = std::chrono::steady_clock::now();
        ImageResult result(*output);  // fails now, before rendering, if the output cannot be written
        FrameContext context(minerals_dir);
        const PreparedFrame prepared = options->prepare(context);
        for (const std::string& note : prepared.notes) std::cerr << "petroscope: " << note << '\n';
        RenderedFrame frame = prepared.render([](double fraction) { show_progress("rendering", fraction); return true; });
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
        frame.sidecar["command_line"] = command_line;
        frame.sidecar["seconds"] = seconds;
        result.write(frame.linear_rgb, frame.sidecar);
        std::cerr << "petroscope: wrote " << *output << " and " << *output << ".json (" << frame.summary << ", " << seconds << " s)\n";
    });
}

}  // namespace petroscope::cli
