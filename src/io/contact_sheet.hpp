#pragma once
// The labelled contact sheet of a sweep: every frame as a thumbnail with its swept values beneath it.
#include "petroscope/io/sweep_plan.hpp"

#include <opencv2/core.hpp>

#include <filesystem>

namespace petroscope {

class ContactSheet {
public:
    /// Lays out the plan's frames (frame_width × frame_height each) row by row; the sheet is kept within
    /// 8192 px a side by shrinking the thumbnails.
    ContactSheet(const SweepPlan& plan, int frame_width, int frame_height);
    /// Places `frame` (8-bit BGR) at its cell with its label.
    void add(std::size_t frame, const cv::Mat& image);
    /// Writes the sheet as PNG; throws InputError naming the file.
    void write_png(const std::filesystem::path& path) const;

    int frame_width() const { return frame_width_; }
    int frame_height() const { return frame_height_; }
    int columns() const { return columns_; }
    int thumbnail_width() const { return thumbnail_width_; }

private:
    const SweepPlan& plan_;
    int frame_width_, frame_height_;
    int columns_, rows_;
    int thumbnail_width_, thumbnail_height_, label_height_;
    cv::Mat sheet_;
};

}  // namespace petroscope
