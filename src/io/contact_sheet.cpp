#include "contact_sheet.hpp"

#include "petroscope/core/error.hpp"

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <fstream>

namespace petroscope {
namespace {

constexpr int max_sheet_px = 8192;
constexpr int gap_px = 4;
const cv::Scalar background(32, 32, 32);
const cv::Scalar ink(235, 235, 235);

}  // namespace

ContactSheet::ContactSheet(const SweepPlan& plan, int frame_width, int frame_height)
    : plan_(plan), frame_width_(frame_width), frame_height_(frame_height) {
    const int frames = static_cast<int>(plan.frame_count());
    columns_ = std::max(1, std::min(plan.sheet_columns(), frames));
    rows_ = (frames + columns_ - 1) / columns_;
    thumbnail_width_ = std::min({plan.thumbnail_px, frame_width, max_sheet_px / columns_ - gap_px});
    thumbnail_width_ = std::max(thumbnail_width_, 8);
    thumbnail_height_ = std::max(1, frame_height * thumbnail_width_ / frame_width);
    label_height_ = std::max(12, thumbnail_width_ / 8);
    const int cell_height = thumbnail_height_ + label_height_ + gap_px;
    if (rows_ * cell_height > 4 * max_sheet_px) {
        throw InputError("the contact sheet of " + std::to_string(frames) + " frames would be " + std::to_string(rows_ * cell_height) +
                         " px tall; give more --columns");
    }
    sheet_ = cv::Mat(rows_ * cell_height + gap_px, columns_ * (thumbnail_width_ + gap_px) + gap_px, CV_8UC3, background);
}

void ContactSheet::add(std::size_t frame, const cv::Mat& image) {
    const int column = static_cast<int>(frame) % columns_, row = static_cast<int>(frame) / columns_;
    const int x = gap_px + column * (thumbnail_width_ + gap_px);
    const int y = gap_px + row * (thumbnail_height_ + label_height_ + gap_px);
    cv::Mat thumbnail;
    cv::resize(image, thumbnail, cv::Size(thumbnail_width_, thumbnail_height_), 0, 0, cv::INTER_AREA);
    thumbnail.copyTo(sheet_(cv::Rect(x, y, thumbnail_width_, thumbnail_height_)));
    // The label, shrunk until it fits under the thumbnail.
    const std::string label = plan_.label(frame);
    double scale = label_height_ / 30.0;
    int baseline = 0;
    cv::Size text = cv::getTextSize(label, cv::FONT_HERSHEY_SIMPLEX, scale, 1, &baseline);
    while (text.width > thumbnail_width_ && scale > 0.2) {
        scale *= 0.9;
        text = cv::getTextSize(label, cv::FONT_HERSHEY_SIMPLEX, scale, 1, &baseline);
    }
    cv::putText(sheet_, label, cv::Point(x, y + thumbnail_height_ + (label_height_ + text.height) / 2), cv::FONT_HERSHEY_SIMPLEX, scale,
                ink, 1, cv::LINE_AA);
}

void ContactSheet::write_png(const std::filesystem::path& path) const {
    std::vector<unsigned char> bytes;
    if (!cv::imencode(".png", sheet_, bytes)) throw InputError("cannot encode the contact sheet as PNG");
    std::ofstream file(path, std::ios::binary);
    file.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
    if (!file) throw InputError("cannot write the contact sheet " + path.string());
}

}  // namespace petroscope
