// petroscope sweep: the image of conoscope, orthoscope or conical over a range of one or two of its numeric
// options, as numbered frames with their sidecars, a labelled contact sheet, an animation and a CSV of
// measurements (docs/sweep.md).
#include "cli_common.hpp"
#include "heavy_commands.hpp"
#include "frame_command.hpp"

#include "petroscope/api/sweep.hpp"
#include "petroscope/core/error.hpp"
#include "petroscope/core/text.hpp"
#include "petroscope/io/json_sidecar.hpp"
#include "petroscope/io/sweep_directory.hpp"

#include <algorithm>
#include <chrono>
#include <iostream>
#include <memory>
#include <set>

namespace petroscope::cli {
namespace {

constexpr std::size_t frames_without_yes = 10000;
constexpr std::size_t max_frames = 1000000;

struct SweepOptions {
    std::vector<std::string> vary;
    std::string output;
    std::string shard;
    bool yes = false;
    int jobs = 0;
    std::string animation = "gif";
    double fps = 8.0;
    int columns = 0;
    int thumbnail_px = 256;
};

// The options of the rendering subcommand as they were registered (before the sweep's own).
struct RenderOptionSet {
    std::vector<CLI::Option*> options;

    CLI::Option* find(const std::string& name) const {
        for (CLI::Option* option : options) {
            for (const std::string& long_name : option->get_lnames()) {
                if (long_name == name) return option;
            }
        }
        return nullptr;
    }
    static bool sweepable(const CLI::Option* option) {
        const std::string type = option->get_type_name();
        const bool numeric = type == "FLOAT" || type == "INT" || type == length_type || type == wavelength_type;
        // The frames of a sweep share one size (contact sheet, animation).
        return numeric && option->get_lnames().front() != "size";
    }
    std::string sweepable_names() const {
        std::string names;
        for (const CLI::Option* option : options) {
            if (sweepable(option)) names += (names.empty() ? "" : ", ") + option->get_lnames().front();
        }
        return names;
    }
};

// Checks a swept parameter against the subcommand's options: known, numeric, not also given a fixed value,
// with a unit exactly when the option takes a length or a wavelength.
void check_parameter(const SweepParameter& parameter, const RenderOptionSet& options, const std::string& command) {
    const CLI::Option* option = options.find(parameter.name);
    if (option == nullptr || !RenderOptionSet::sweepable(option)) {
        throw InputError("--vary: " + quote_input(parameter.name) + " is not a numeric option of " + command + "; these can be swept: " +
                         options.sweepable_names());
    }
    if (option->count() > 0) {
        throw InputError("--" + parameter.name + " is given a value and swept by --vary; give one or the other");
    }
    const std::string type = option->get_type_name();
    const std::string& value = parameter.values.front();
    const bool has_unit = !value.empty() && !std::isdigit(static_cast<unsigned char>(value.back()));
    if (type == length_type && !has_unit) {
        throw InputError("--vary " + parameter.name + ": give the unit of the length, e.g. " + parameter.name + "=10um:60um:10um");
    }
    if ((type == "FLOAT" || type == "INT") && has_unit) {
        throw InputError("--vary " + parameter.name + ": this option takes a plain number, without a unit");
    }
}

// The subcommand's options as given on the command line, to repeat for every frame.
std::vector<std::string> given_arguments(const RenderOptionSet& options) {
    std::vector<std::string> arguments;
    for (const CLI::Option* option : options.options) {
        if (option->count() == 0) continue;
        const std::string name = "--" + option->get_lnames().front();
        if (option->get_type_size() == 0) {
            arguments.push_back(name);
            continue;
        }
        for (const std::string& value : option->results()) {
            arguments.push_back(name);
            arguments.push_back(value);
        }
    }
    return arguments;
}

std::string shell_quoted(const std::string& text) {
    if (!text.empty() && text.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789-_.,:/=+") == std::string::npos) {
        return text;
    }
    std::string quoted = "'";
    for (const char c : text) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return quoted + "'";
}

// Parses one frame's arguments into fresh options of the subcommand and prepares it; errors name the frame.
PreparedFrame prepare_frame(const std::function<std::unique_ptr<FrameOptions>()>& make, const SweepPlan& plan, std::size_t frame,
                            FrameContext& context) {
    const auto fail = [&](const std::string& why) {
        return InputError("frame " + std::to_string(frame) + " (" + plan.label(frame) + "): " + why);
    };
    const std::unique_ptr<FrameOptions> options = make();
    CLI::App parser{plan.command};
    options->add_options(&parser);
    std::vector<std::string> arguments = plan.frame_arguments(frame);
    std::reverse(arguments.begin(), arguments.end());  // CLI11 takes a vector of arguments last first
    try {
        parser.parse(arguments);
        return options->prepare(context);
    } catch (const CLI::ParseError& error) {
        throw fail(error.what());
    } catch (const InputError& error) {
        throw fail(error.what());
    }
}

void report_merge(const SweepMerge& merged) {
    std::cerr << "petroscope: wrote " << merged.csv.string() << ", " << merged.sheet.string() << " and its sidecar"
              << (merged.animation.empty() ? std::string() : ", " + merged.animation.string()) << '\n';
}

void run_sweep(const SweepOptions& sweep, const RenderOptionSet& options, const std::string& command,
               const std::function<std::unique_ptr<FrameOptions>()>& make, const std::string& minerals_dir) {
    const auto started = std::chrono::steady_clock::now();
    SweepPlan plan;
    plan.command = command;
    plan.arguments = given_arguments(options);
    if (sweep.vary.empty() || sweep.vary.size() > 2) throw InputError("--vary: sweep one or two options (a grid), e.g. --vary azimuth-deg=0:360:5");
    for (const std::string& text : sweep.vary) {
        SweepParameter parameter = parse_sweep_parameter(text, max_frames);
        check_parameter(parameter, options, command);
        if (!plan.parameters.empty() && plan.parameters.front().name == parameter.name) {
            throw InputError("--vary: " + parameter.name + " is swept twice");
        }
        plan.parameters.push_back(std::move(parameter));
    }
    if (sweep.animation != "gif" && sweep.animation != "mp4" && sweep.animation != "none") {
        throw InputError("--animation " + quote_input(sweep.animation) + ": expected gif, mp4 or none");
    }
    if (!(sweep.fps > 0.0 && sweep.fps <= 100.0)) throw InputError("--fps must be > 0 and <= 100");
    if (sweep.thumbnail_px < 16 || sweep.thumbnail_px > 4096) throw InputError("--thumbnail must be 16 to 4096 px");
    if (sweep.columns < 0 || sweep.columns > 1000) throw InputError("--columns must be 0 (automatic) to 1000");
    if (sweep.jobs < 0 || sweep.jobs > 1024) throw InputError("--jobs must be 0 (every core) to 1024");
    plan.animation = sweep.animation;
    plan.fps = sweep.fps;
    plan.columns = sweep.columns;
    plan.thumbnail_px = sweep.thumbnail_px;
    double frame_product = 1.0;  // checked before the count, which could overflow
    for (const SweepParameter& parameter : plan.parameters) frame_product *= static_cast<double>(parameter.values.size());
    if (frame_product > static_cast<double>(max_frames)) {
        throw InputError("the sweep has " + format_number(frame_product) + " frames; at most " + std::to_string(max_frames) + " can be swept");
    }
    const std::size_t frames = plan.frame_count();
    if (frames > frames_without_yes && !sweep.yes) {
        throw InputError("the sweep has " + std::to_string(frames) + " frames (more than " + std::to_string(frames_without_yes) +
                         "); add --yes to render them all");
    }
    const SweepShard shard = sweep.shard.empty() ? SweepShard{} : parse_sweep_shard(sweep.shard);
    const std::size_t first = shard.begin(frames), last = shard.end(frames);

    // Every frame of the shard is checked before anything is written.
    FrameContext context(minerals_dir);
    std::set<std::string> notes;
    for (std::size_t frame = first; frame < last; ++frame) {
        for (const std::string& note : prepare_frame(make, plan, frame, context).notes) {
            if (notes.insert(note).second) std::cerr << "petroscope: " << note << '\n';
        }
    }
    const SweepDirectory directory = SweepDirectory::create(sweep.output, plan);
    std::vector<std::size_t> todo;
    for (std::size_t frame = first; frame < last; ++frame) {
        if (!directory.frame_finished(frame)) todo.push_back(frame);
    }
    const std::size_t already = (last - first) - todo.size();
    std::cerr << "petroscope: sweep of " << frames << " frame" << (frames == 1 ? "" : "s");
    if (shard.count > 1) std::cerr << ", shard " << shard.index << "/" << shard.count << " (frames " << first << " to " << last - 1 << ")";
    std::cerr << ": " << todo.size() << " to render";
    if (already > 0) std::cerr << ", " << already << " already there";
    std::cerr << '\n';

    // Frames in parallel, each on one thread (run_sweep_frames): the same frame is the same file every time.
    const std::string label = "sweep " + std::to_string(todo.size()) + " frames";
    if (!todo.empty()) show_progress(label, 0.0);
    const auto render_frame = [&](std::size_t frame, const ProgressCallback& frame_progress) {
        // Prepared again rather than kept from the check above: a prepared orthoscope frame holds its own
        // copy of the section, too much to keep for thousands of frames. (The context is not thread-safe.)
        PreparedFrame prepared;
#pragma omp critical(petroscope_sweep_context)
        prepared = prepare_frame(make, plan, frame, context);
        const std::filesystem::path path = directory.frame_path(frame);
        ImageResult result(path);
        RenderedFrame rendered = prepared.render(frame_progress);
        std::string command_line = "petroscope " + plan.command;
        for (const std::string& argument : plan.frame_arguments(frame)) command_line += " " + shell_quoted(argument);
        rendered.sidecar["command_line"] = command_line + " -o " + shell_quoted(path.filename().string());
        const std::vector<std::string> values = plan.values_of(frame);
        nlohmann::json swept = nlohmann::json::object();
        for (std::size_t p = 0; p < plan.parameters.size(); ++p) swept[plan.parameters[p].name] = values[p];
        rendered.sidecar["sweep"] = {{"frame", frame}, {"frames", frames}, {"values", swept}};
        result.write(rendered.linear_rgb, rendered.sidecar);
    };
    run_sweep_frames(todo, sweep.jobs, render_frame, [&](double fraction_done) {
        show_progress(label, fraction_done);
        return true;
    });
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    std::cerr << "petroscope: rendered " << todo.size() << " frame" << (todo.size() == 1 ? "" : "s") << " into "
              << (std::filesystem::path(sweep.output) / "frames").string() << " (" << seconds << " s)\n";
    if (shard.count > 1) {
        std::cerr << "petroscope: shard " << shard.index << "/" << shard.count << " is done; when every shard is, run: petroscope sweep --merge "
                  << shell_quoted(sweep.output) << '\n';
        return;
    }
    report_merge(merge_sweep(directory));
}

}  // namespace

void add_sweep_command(CLI::App& app, const std::string& minerals_dir) {
    CLI::App* sweep = app.add_subcommand(std::string(kSweepCommand.name), std::string(kSweepCommand.description));
    const auto merge_folder = std::make_shared<std::string>();
    sweep->add_option("--merge", *merge_folder, "Build measurements.csv, the contact sheet and the animation of a sweep folder whose shards are all done");
    for (const auto& [name, make] : frame_commands()) {
        const std::shared_ptr<FrameOptions> template_options = make();
        CLI::App* command = sweep->add_subcommand(name, "Sweep '" + name + "': its options (petroscope " + name + " --help), plus these:\n" +
                                                            template_options->description());
        template_options->add_options(command);
        auto options = std::make_shared<RenderOptionSet>();
        for (CLI::Option* option : command->get_options()) {
            if (!option->get_lnames().empty() && option->get_lnames().front() != "help") options->options.push_back(option);
        }
        const auto sweep_options = std::make_shared<SweepOptions>();
        command->add_option("--vary", sweep_options->vary,
                            "NAME=START:END:STEP or NAME=V1,V2,…: an option to sweep, e.g. azimuth-deg=0:360:5, thickness=10um:60um:10um;\n"
                            "twice for a grid (the first varies slowest)")
            ->required()->type_name("NAME=RANGE");
        command->add_option("-o,--output", sweep_options->output, "Folder of the sweep (created; may hold an earlier run of the same sweep)")->required();
        command->add_option("--shard", sweep_options->shard, "Render only part K of N (e.g. 2/8) of the frames; merge with --merge");
        command->add_flag("--yes", sweep_options->yes, "Allow more than 10000 frames");
        command->add_option("--jobs", sweep_options->jobs, "Frames rendered at once (0: one per core)")->capture_default_str();
        command->add_option("--animation", sweep_options->animation, "gif, mp4 or none")->capture_default_str();
        command->add_option("--fps", sweep_options->fps, "Animation frames per second")->capture_default_str();
        command->add_option("--columns", sweep_options->columns, "Contact sheet columns (0: one per value of the second option, or a square)")
            ->capture_default_str();
        command->add_option("--thumbnail", sweep_options->thumbnail_px, "Contact sheet: width of each frame in pixels")->capture_default_str();
        const std::string command_name = name;
        const auto make_options = make;
        // template_options holds the values CLI11 writes; the frames are parsed afresh from the plan.
        command->callback([=, &minerals_dir] {
            (void)template_options;
            if (!merge_folder->empty()) throw InputError("--merge DIR takes no subcommand: petroscope sweep --merge DIR");
            run_sweep(*sweep_options, *options, command_name, make_options, minerals_dir);
        });
    }
    sweep->callback([sweep, merge_folder] {
        if (merge_folder->empty()) {
            if (sweep->get_subcommands().empty()) throw InputError("sweep: name what to sweep (conoscope, orthoscope or conical) or give --merge DIR");
            return;
        }
        report_merge(merge_sweep(SweepDirectory::open(*merge_folder)));
    });
}

}  // namespace petroscope::cli
