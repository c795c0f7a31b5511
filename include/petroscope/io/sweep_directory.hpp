#pragma once
// A sweep's folder (docs/sweep.md): sweep.json (the plan), frames/frame_NNNN.png with its sidecar
// frame_NNNN.png.json (which holds the frame's measurements), and, once every frame is there,
// measurements.csv, sheet.png with its sidecar, and animation.gif or animation.mp4.
#include "petroscope/io/sweep_plan.hpp"

#include <filesystem>
#include <optional>

namespace petroscope {

class SweepDirectory {
public:
    /// Creates `folder` (and frames/) and writes sweep.json, or checks that the sweep.json already there
    /// describes the same sweep (a resumed sweep, another shard). Throws InputError for a folder that holds
    /// other files or another sweep, naming it.
    static SweepDirectory create(const std::filesystem::path& folder, const SweepPlan& plan);
    /// An existing sweep's folder; throws InputError when it holds no readable sweep.json.
    static SweepDirectory open(const std::filesystem::path& folder);

    const SweepPlan& plan() const { return plan_; }
    const std::filesystem::path& folder() const { return folder_; }
    std::filesystem::path frame_path(std::size_t frame) const;
    /// The frame's sidecar when the frame is finished: its image and its sidecar are both in place and the
    /// sidecar reads as a JSON object. (A frame's files are renamed into place image first, sidecar last, so
    /// this never accepts a half-written frame.)
    std::optional<nlohmann::json> finished_frame_sidecar(std::size_t frame) const;
    bool frame_finished(std::size_t frame) const { return finished_frame_sidecar(frame).has_value(); }

private:
    SweepDirectory(std::filesystem::path folder, SweepPlan plan) : folder_(std::move(folder)), plan_(std::move(plan)) {}
    std::filesystem::path folder_;
    SweepPlan plan_;
};

struct SweepMerge {
    std::filesystem::path csv, sheet, animation;  // animation empty when the plan asks for none
};

/// Builds measurements.csv (a row per frame: its number, file, swept values and measurements), the
/// labelled contact sheet and the animation from the frames, in frame order; the same frames give the
/// same bytes however they were rendered (shards, resumed runs). Throws InputError listing missing frames.
SweepMerge merge_sweep(const SweepDirectory& directory);

}  // namespace petroscope
