#pragma once
// What a sweep renders: a subcommand, its options, and one or two of its numeric options stepped over a
// range (a grid). The plan is stored as DIR/sweep.json (docs/sweep.md) so that an interrupted sweep, its
// shards and the merge all agree on the frames.
#include <nlohmann/json.hpp>

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace petroscope {

/// One swept option: its name without the dashes ("azimuth-deg") and its values as option text, with the
/// unit when the range had one ("10um").
struct SweepParameter {
    std::string name;
    std::vector<std::string> values;
};

/// Parses NAME=START:END:STEP (END included when the steps reach it) or NAME=V1,V2,…; the numbers may carry
/// a unit, the same for all ("thickness=10um:60um:10um", or once at the end: "thickness=10:60:10um").
/// Values are printed with as many decimals as START and STEP have, so 0:1:0.1 gives 0.3, not
/// 0.30000000000000004. Throws InputError naming the text and what was expected; at most `max_values`.
SweepParameter parse_sweep_parameter(std::string_view text, std::size_t max_values = 1000000);

/// A part K/N of the frames (1 ≤ K ≤ N): frames [⌊(K−1)F/N⌋, ⌊KF/N⌋), contiguous.
struct SweepShard {
    int index = 1, count = 1;
    std::size_t begin(std::size_t frames) const { return frames * static_cast<std::size_t>(index - 1) / static_cast<std::size_t>(count); }
    std::size_t end(std::size_t frames) const { return frames * static_cast<std::size_t>(index) / static_cast<std::size_t>(count); }
};
SweepShard parse_sweep_shard(std::string_view text);  // "2/8"; throws InputError

struct SweepPlan {
    std::string command;                     // conoscope, orthoscope, conical
    std::vector<std::string> arguments;      // the subcommand's own options, as given (without -o)
    std::vector<SweepParameter> parameters;  // 1 or 2; frames run through the last fastest
    int columns = 0;                         // contact sheet columns; 0: one per value of the second parameter, or ⌈√frames⌉
    int thumbnail_px = 256;                  // contact sheet: width of each frame
    std::string animation = "gif";           // gif, mp4 or none
    double fps = 8.0;

    std::size_t frame_count() const;
    /// The value of each parameter in `frame` (row-major over the grid).
    std::vector<std::string> values_of(std::size_t frame) const;
    /// "azimuth-deg 30, tilt-deg 10".
    std::string label(std::size_t frame) const;
    /// "frame_0030.png": at least 4 digits, enough for every frame.
    std::string frame_name(std::size_t frame) const;
    /// The arguments that render `frame` alone: the options, then each swept option with its value.
    std::vector<std::string> frame_arguments(std::size_t frame) const;
    int sheet_columns() const;

    nlohmann::json to_json() const;
    /// Reads what to_json wrote; throws InputError naming `file` and the entry.
    static SweepPlan from_json(const nlohmann::json& document, const std::string& file);
};

}  // namespace petroscope
