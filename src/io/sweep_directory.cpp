#include "petroscope/io/sweep_directory.hpp"

#include "animation_writer.hpp"
#include "contact_sheet.hpp"

#include "petroscope/core/error.hpp"
#include "petroscope/io/atomic_file.hpp"
#include "petroscope/io/data_files.hpp"
#include "petroscope/io/json_reader.hpp"
#include "petroscope/io/json_sidecar.hpp"

#include <opencv2/imgcodecs.hpp>

#include <cstdio>
#include <fstream>
#include <set>

namespace petroscope {
namespace {

constexpr const char* plan_file = "sweep.json";

nlohmann::json read_json(const std::filesystem::path& path) { return parse_json_text(read_text_file(path), path.string()); }

std::string csv_number(const nlohmann::json& value) {
    if (!value.is_number()) return "";
    const double number = value.get<double>();
    char text[32];
    std::snprintf(text, sizeof text, "%.10g", number == 0.0 ? 0.0 : number);  // no "-0"
    return text;
}

// Quotes a CSV field when it holds a comma or a quote (RFC 4180).
std::string csv_text(const std::string& text) {
    if (text.find_first_of(",\"\n") == std::string::npos) return text;
    std::string quoted = "\"";
    for (const char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
    return quoted + "\"";
}

}  // namespace

SweepDirectory SweepDirectory::create(const std::filesystem::path& folder, const SweepPlan& plan) {
    std::error_code error;
    const std::filesystem::path plan_path = folder / plan_file;
    if (std::filesystem::exists(plan_path, error)) {
        const SweepPlan existing = SweepPlan::from_json(read_json(plan_path), plan_path.string());
        if (existing.to_json() != plan.to_json()) {
            throw InputError(folder.string() + " holds another sweep (its sweep.json differs: command, options or swept values); "
                             "resume it with the same options or choose a new folder");
        }
    } else {
        if (std::filesystem::exists(folder, error)) {
            if (!std::filesystem::is_directory(folder, error)) throw InputError("-o " + folder.string() + ": it is a file, not a folder");
            if (!std::filesystem::is_empty(folder, error)) {
                throw InputError("-o " + folder.string() + ": the folder is not empty and holds no sweep.json; choose a new or empty folder");
            }
        }
        std::filesystem::create_directories(folder, error);
        if (error) throw InputError("cannot create the sweep folder " + folder.string() + ": " + error.message());
        PendingOutputs pending;
        write_json_file(plan.to_json(), pending.add(plan_path));
        pending.commit();
    }
    std::filesystem::create_directories(folder / "frames", error);
    if (error) throw InputError("cannot create " + (folder / "frames").string() + ": " + error.message());
    return SweepDirectory(folder, plan);
}

SweepDirectory SweepDirectory::open(const std::filesystem::path& folder) {
    const std::filesystem::path plan_path = folder / plan_file;
    std::error_code error;
    if (!std::filesystem::exists(plan_path, error)) {
        throw InputError("--merge " + folder.string() + ": no sweep.json there (not a sweep folder made by 'petroscope sweep')");
    }
    return SweepDirectory(folder, SweepPlan::from_json(read_json(plan_path), plan_path.string()));
}

std::filesystem::path SweepDirectory::frame_path(std::size_t frame) const { return folder_ / "frames" / plan_.frame_name(frame); }

std::optional<nlohmann::json> SweepDirectory::finished_frame_sidecar(std::size_t frame) const {
    const std::filesystem::path image = frame_path(frame);
    std::error_code error;
    if (!std::filesystem::is_regular_file(image, error) || !std::filesystem::is_regular_file(sidecar_path(image), error)) return std::nullopt;
    try {
        nlohmann::json sidecar = read_json(sidecar_path(image));
        if (sidecar.is_object()) return sidecar;
    } catch (const InputError&) {
    }
    return std::nullopt;
}

SweepMerge merge_sweep(const SweepDirectory& directory) {
    const SweepPlan& plan = directory.plan();
    const std::size_t frames = plan.frame_count();
    // Each frame's measurements, from its sidecar, read once; the columns are every name any frame reports,
    // in name order.
    std::vector<nlohmann::json> measurements(frames, nlohmann::json::object());
    std::set<std::string> names;
    std::vector<std::size_t> missing;
    for (std::size_t frame = 0; frame < frames; ++frame) {
        const std::optional<nlohmann::json> sidecar = directory.finished_frame_sidecar(frame);
        if (!sidecar) {
            missing.push_back(frame);
            continue;
        }
        if (sidecar->contains("measurements") && (*sidecar)["measurements"].is_object()) measurements[frame] = (*sidecar)["measurements"];
        for (const auto& item : measurements[frame].items()) names.insert(item.key());
    }
    if (!missing.empty()) {
        std::string list;
        for (std::size_t k = 0; k < std::min<std::size_t>(missing.size(), 5); ++k) list += (k ? ", " : "") + plan.frame_name(missing[k]);
        throw InputError(directory.folder().string() + ": " + std::to_string(missing.size()) + " of " + std::to_string(frames) +
                         " frames are missing (" + list + (missing.size() > 5 ? ", …" : "") +
                         "); render them (run the remaining shards, or the sweep again) before merging");
    }

    PendingOutputs pending;
    SweepMerge merged{directory.folder() / "measurements.csv", directory.folder() / "sheet.png", {}};
    const std::filesystem::path csv_temporary = pending.add(merged.csv);
    const std::filesystem::path sheet_temporary = pending.add(merged.sheet);
    const std::filesystem::path sheet_sidecar_temporary = pending.add(sidecar_path(merged.sheet));
    std::filesystem::path animation_temporary;
    if (plan.animation != "none") {
        merged.animation = directory.folder() / ("animation." + plan.animation);
        animation_temporary = pending.add(merged.animation);
    }

    std::ofstream csv(csv_temporary, std::ios::binary);
    csv << "frame,file";
    for (const SweepParameter& parameter : plan.parameters) csv << ',' << csv_text(parameter.name);
    for (const std::string& name : names) csv << ',' << csv_text(name);
    csv << '\n';
    for (std::size_t frame = 0; frame < frames; ++frame) {
        csv << frame << ',' << "frames/" << plan.frame_name(frame);
        for (const std::string& value : plan.values_of(frame)) csv << ',' << csv_text(value);
        for (const std::string& name : names) csv << ',' << (measurements[frame].contains(name) ? csv_number(measurements[frame][name]) : "");
        csv << '\n';
    }
    csv.close();
    if (!csv) throw InputError("cannot write " + merged.csv.string());

    // The frames in batches: each batch is read and its animation frames encoded in parallel, then placed
    // on the sheet and appended to the animation in order; memory holds one batch.
    std::unique_ptr<ContactSheet> sheet;
    std::unique_ptr<AnimationWriter> animation;
    constexpr std::size_t batch = 16;
    for (std::size_t start = 0; start < frames; start += batch) {
        const std::size_t count = std::min(batch, frames - start);
        std::vector<cv::Mat> images(count);
        std::vector<std::vector<std::uint8_t>> encoded(count);
        if (!sheet) {
            images[0] = cv::imread(directory.frame_path(0).string(), cv::IMREAD_COLOR);
            if (images[0].empty()) throw InputError("cannot read the frame " + directory.frame_path(0).string());
            sheet = std::make_unique<ContactSheet>(plan, images[0].cols, images[0].rows);
            if (!animation_temporary.empty()) {
                animation = std::make_unique<AnimationWriter>(animation_temporary, plan.animation, plan.fps, images[0].cols, images[0].rows);
            }
        }
#pragma omp parallel for schedule(dynamic, 1)
        for (std::size_t k = 0; k < count; ++k) {
            if (images[k].empty()) images[k] = cv::imread(directory.frame_path(start + k).string(), cv::IMREAD_COLOR);
            const bool usable = images[k].cols == sheet->frame_width() && images[k].rows == sheet->frame_height();
            if (usable && animation) encoded[k] = animation->prepare(images[k]);
        }
        for (std::size_t k = 0; k < count; ++k) {
            const std::filesystem::path path = directory.frame_path(start + k);
            if (images[k].empty()) throw InputError("cannot read the frame " + path.string());
            if (images[k].cols != sheet->frame_width() || images[k].rows != sheet->frame_height()) {
                throw InputError(path.string() + ": its size differs from the first frame's; the frames of a sweep share one size");
            }
            sheet->add(start + k, images[k]);
            if (animation) animation->add(images[k], encoded[k]);
        }
    }
    if (animation) animation->finish();
    sheet->write_png(sheet_temporary);
    nlohmann::json sheet_sidecar = plan.to_json();
    sheet_sidecar["sheet_layout"] = {{"columns", sheet->columns()}, {"thumbnail_px", sheet->thumbnail_width()},
                                     {"order", "frames row by row; with two swept options, a row per value of the first"}};
    write_json_file(sheet_sidecar, sheet_sidecar_temporary);
    pending.commit();
    return merged;
}

}  // namespace petroscope
