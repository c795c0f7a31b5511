#include "petroscope/io/chart_drawing.hpp"

#include "petroscope/core/error.hpp"
#include "petroscope/core/text.hpp"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace petroscope {
namespace {

// Birefringence lines of the chart (Sørensen 2013 draws a similar set).
constexpr double kBirefringences[] = {0.001, 0.002, 0.003, 0.004, 0.005, 0.006, 0.007, 0.008, 0.009, 0.010,
                                      0.012, 0.014, 0.016, 0.018, 0.020, 0.022, 0.025, 0.028, 0.032, 0.036,
                                      0.040, 0.045, 0.050, 0.060, 0.070, 0.080, 0.100, 0.120, 0.150, 0.180};
constexpr double kOrderNm = 550.0;  // the order boundaries are drawn at multiples of 550 nm (first-order red)
constexpr int kLeft = 80, kRight = 90, kTop = 40, kBottom = 60;

std::string fixed(double value, int decimals) {
    char text[32];
    std::snprintf(text, sizeof text, "%.*f", decimals, value);
    return text;
}

}  // namespace

Image draw_michel_levy_chart(const std::vector<MichelLevyStep>& steps, const std::vector<Eigen::Vector3d>& linear_srgb,
                             const MichelLevyChartLayout& layout) {
    if (steps.size() < 2 || steps.size() != linear_srgb.size()) throw InputError("the chart needs at least two colours, one per step");
    if (!(layout.max_thickness_um > 0.0) || layout.plot_width_px < 200 || layout.plot_height_px < 100) {
        throw InputError("chart layout out of range (thickness > 0, plot at least 200 x 100 px)");
    }
    const int width = kLeft + layout.plot_width_px + kRight, height = kTop + layout.plot_height_px + kBottom;
    cv::Mat canvas(height, width, CV_32FC3, cv::Scalar(1.0, 1.0, 1.0));
    const double max_retardation = steps.back().retardation_nm;
    const auto x_of = [&](double retardation_nm) { return kLeft + retardation_nm / max_retardation * layout.plot_width_px; };
    const auto y_of = [&](double thickness_um) { return kTop + (1.0 - thickness_um / layout.max_thickness_um) * layout.plot_height_px; };

    for (int column = 0; column < layout.plot_width_px; ++column) {
        const double position = (column + 0.5) / layout.plot_width_px * static_cast<double>(steps.size() - 1);
        const auto below = std::min(static_cast<std::size_t>(position), steps.size() - 2);
        const double fraction = position - static_cast<double>(below);
        const Eigen::Vector3d colour = ((1.0 - fraction) * linear_srgb[below] + fraction * linear_srgb[below + 1]).cwiseMax(0.0);
        cv::line(canvas, {kLeft + column, kTop}, {kLeft + column, kTop + layout.plot_height_px - 1},
                 cv::Scalar(colour[0], colour[1], colour[2]), 1);
    }
    const cv::Scalar black(0.0, 0.0, 0.0), white(1.0, 1.0, 1.0);
    const auto text = [&](const std::string& label, cv::Point at, double scale, const cv::Scalar& colour) {
        cv::putText(canvas, label, at, cv::FONT_HERSHEY_SIMPLEX, scale, colour, 1, cv::LINE_AA);
    };
    // Birefringence lines from the origin, labelled where they leave the plot.
    for (const double birefringence : kBirefringences) {
        const double top_retardation = birefringence * layout.max_thickness_um * 1e3;
        cv::Point end;
        if (top_retardation <= max_retardation) {
            end = {static_cast<int>(std::lround(x_of(top_retardation))), kTop};
            text(fixed(birefringence, 3), {end.x - 14, kTop - 6}, 0.35, black);
        } else {
            const double thickness = max_retardation / (birefringence * 1e3);
            end = {kLeft + layout.plot_width_px, static_cast<int>(std::lround(y_of(thickness)))};
            text(fixed(birefringence, 3), {end.x + 4, end.y + 4}, 0.35, black);
        }
        cv::line(canvas, {kLeft, kTop + layout.plot_height_px}, end, black, 1, cv::LINE_AA);
    }
    // Order boundaries and the standard section thickness, dashed.
    const auto dashed = [&](cv::Point from, cv::Point to) {
        const double length = std::hypot(to.x - from.x, to.y - from.y);
        for (double s = 0.0; s < length; s += 12.0) {
            const double e = std::min(s + 6.0, length);
            cv::line(canvas, from + (to - from) * (s / length), from + (to - from) * (e / length), white, 1, cv::LINE_AA);
        }
    };
    for (int order = 1; order * kOrderNm < max_retardation; ++order) {
        const int x = static_cast<int>(std::lround(x_of(order * kOrderNm)));
        dashed({x, kTop}, {x, kTop + layout.plot_height_px});
    }
    for (int order = 0; order * kOrderNm < max_retardation; ++order) {
        const double middle = std::min((order + 0.5) * kOrderNm, 0.5 * (order * kOrderNm + max_retardation));
        text(std::to_string(order + 1) + (order == 0 ? "st" : order == 1 ? "nd" : order == 2 ? "rd" : "th") + " order",
             {static_cast<int>(x_of(middle)) - 30, kTop + layout.plot_height_px - 8}, 0.45, black);
    }
    if (layout.section_thickness_um < layout.max_thickness_um) {
        const int y = static_cast<int>(std::lround(y_of(layout.section_thickness_um)));
        dashed({kLeft, y}, {kLeft + layout.plot_width_px, y});
    }
    // Axes, ticks and their labels.
    cv::rectangle(canvas, {kLeft, kTop}, {kLeft + layout.plot_width_px, kTop + layout.plot_height_px}, black, 1);
    for (double retardation = 0.0; retardation <= max_retardation + 1e-9; retardation += 200.0) {
        const int x = static_cast<int>(std::lround(x_of(retardation)));
        cv::line(canvas, {x, kTop + layout.plot_height_px}, {x, kTop + layout.plot_height_px + 6}, black, 1);
        text(fixed(retardation, 0), {x - 14, kTop + layout.plot_height_px + 22}, 0.4, black);
    }
    text("retardation (nm)", {kLeft + layout.plot_width_px / 2 - 60, height - 12}, 0.5, black);
    for (double thickness = 0.0; thickness <= layout.max_thickness_um + 1e-9; thickness += 10.0) {
        const int y = static_cast<int>(std::lround(y_of(thickness)));
        cv::line(canvas, {kLeft - 6, y}, {kLeft, y}, black, 1);
        text(fixed(thickness, 0), {kLeft - 30, y + 4}, 0.4, black);
    }
    text("thickness (um)", {8, kTop - 14}, 0.45, black);
    text("birefringence", {kLeft + layout.plot_width_px + 6, kTop - 14}, 0.4, black);

    Image image(width, height, 3);
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            const cv::Vec3f& pixel = canvas.at<cv::Vec3f>(y, x);
            for (int c = 0; c < 3; ++c) image.at(x, y, c) = pixel[c];
        }
    }
    return image;
}

}  // namespace petroscope
