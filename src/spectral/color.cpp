#include "petroscope/spectral/color.hpp"

#include <Eigen/Dense>

#include <cmath>
#include <numbers>

namespace petroscope {

Eigen::Vector3d srgb_white_xyz() { return {0.95047, 1.0, 1.08883}; }

Eigen::Vector3d xyz_to_linear_srgb(const Eigen::Vector3d& xyz) {
    Eigen::Matrix3d m;
    m << 3.2406, -1.5372, -0.4986,
        -0.9689, 1.8758, 0.0415,
         0.0557, -0.2040, 1.0570;
    return m * xyz;
}

double encode_srgb(double linear) {
    if (linear <= 0.0031308) return 12.92 * linear;
    return 1.055 * std::pow(linear, 1.0 / 2.4) - 0.055;
}

double decode_srgb(double encoded) {
    if (encoded <= 0.04045) return encoded / 12.92;
    return std::pow((encoded + 0.055) / 1.055, 2.4);
}

Eigen::Matrix3d bradford_adaptation(const Eigen::Vector3d& source_white_xyz, const Eigen::Vector3d& target_white_xyz) {
    Eigen::Matrix3d bradford;
    bradford << 0.8951, 0.2664, -0.1614,
               -0.7502, 1.7135, 0.0367,
                0.0389, -0.0685, 1.0296;
    const Eigen::Vector3d source_cone = bradford * source_white_xyz;
    const Eigen::Vector3d target_cone = bradford * target_white_xyz;
    const Eigen::Matrix3d scale = (target_cone.array() / source_cone.array()).matrix().asDiagonal();
    return bradford.inverse() * scale * bradford;
}

Eigen::Vector3d xyz_to_lab(const Eigen::Vector3d& xyz, const Eigen::Vector3d& white_xyz) {
    constexpr double epsilon = 216.0 / 24389.0;
    constexpr double kappa = 24389.0 / 27.0;
    const auto f = [&](double t) { return t > epsilon ? std::cbrt(t) : (kappa * t + 16.0) / 116.0; };
    const double fx = f(xyz.x() / white_xyz.x());
    const double fy = f(xyz.y() / white_xyz.y());
    const double fz = f(xyz.z() / white_xyz.z());
    return {116.0 * fy - 16.0, 500.0 * (fx - fy), 200.0 * (fy - fz)};
}

double delta_e_2000(const Eigen::Vector3d& lab1, const Eigen::Vector3d& lab2) {
    using std::atan2, std::cos, std::exp, std::pow, std::sin, std::sqrt;
    constexpr double pi = std::numbers::pi;
    const auto degrees = [](double radians) { return radians * 180.0 / pi; };
    const auto radians = [](double deg) { return deg * pi / 180.0; };
    const double c1 = std::hypot(lab1[1], lab1[2]);
    const double c2 = std::hypot(lab2[1], lab2[2]);
    const double c_mean7 = pow(0.5 * (c1 + c2), 7);
    const double g = 0.5 * (1.0 - sqrt(c_mean7 / (c_mean7 + pow(25.0, 7))));
    const double a1 = (1.0 + g) * lab1[1];
    const double a2 = (1.0 + g) * lab2[1];
    const double c1p = std::hypot(a1, lab1[2]);
    const double c2p = std::hypot(a2, lab2[2]);
    const auto hue = [&](double b, double a) {
        if (a == 0.0 && b == 0.0) return 0.0;
        const double h = degrees(atan2(b, a));
        return h < 0.0 ? h + 360.0 : h;
    };
    const double h1p = hue(lab1[2], a1);
    const double h2p = hue(lab2[2], a2);
    const double delta_l = lab2[0] - lab1[0];
    const double delta_c = c2p - c1p;
    double delta_h_angle = 0.0;
    if (c1p * c2p != 0.0) {
        delta_h_angle = h2p - h1p;
        if (delta_h_angle > 180.0) delta_h_angle -= 360.0;
        if (delta_h_angle < -180.0) delta_h_angle += 360.0;
    }
    const double delta_h = 2.0 * sqrt(c1p * c2p) * sin(radians(delta_h_angle) / 2.0);
    const double l_mean = 0.5 * (lab1[0] + lab2[0]);
    const double c_mean_p = 0.5 * (c1p + c2p);
    double h_mean = h1p + h2p;
    if (c1p * c2p != 0.0) {
        if (std::abs(h1p - h2p) <= 180.0) h_mean *= 0.5;
        else h_mean = (h_mean < 360.0) ? 0.5 * (h_mean + 360.0) : 0.5 * (h_mean - 360.0);
    }
    const double t = 1.0 - 0.17 * cos(radians(h_mean - 30.0)) + 0.24 * cos(radians(2.0 * h_mean)) +
                     0.32 * cos(radians(3.0 * h_mean + 6.0)) - 0.20 * cos(radians(4.0 * h_mean - 63.0));
    const double delta_theta = 30.0 * exp(-pow((h_mean - 275.0) / 25.0, 2));
    const double c_mean_p7 = pow(c_mean_p, 7);
    const double r_c = 2.0 * sqrt(c_mean_p7 / (c_mean_p7 + pow(25.0, 7)));
    const double l_term = pow(l_mean - 50.0, 2);
    const double s_l = 1.0 + 0.015 * l_term / sqrt(20.0 + l_term);
    const double s_c = 1.0 + 0.045 * c_mean_p;
    const double s_h = 1.0 + 0.015 * c_mean_p * t;
    const double r_t = -sin(radians(2.0 * delta_theta)) * r_c;
    const double dl = delta_l / s_l;
    const double dc = delta_c / s_c;
    const double dh = delta_h / s_h;
    return sqrt(dl * dl + dc * dc + dh * dh + r_t * dc * dh);
}

}  // namespace petroscope

namespace petroscope {

Eigen::Matrix3d xyz_to_display_matrix(const Eigen::Vector3d& source_white_xyz, bool white_balance, double exposure) {
    const Eigen::Matrix3d adaptation =
        white_balance ? bradford_adaptation(source_white_xyz, srgb_white_xyz()) : Eigen::Matrix3d::Identity();
    Eigen::Matrix3d to_srgb;
    for (int c = 0; c < 3; ++c) to_srgb.col(c) = xyz_to_linear_srgb(Eigen::Vector3d::Unit(c));
    return exposure * to_srgb * adaptation;
}

Image xyz_image_to_linear_srgb(const Image& xyz, const Eigen::Vector3d& source_white_xyz, bool white_balance,
                               double exposure) {
    const Eigen::Matrix3d display = xyz_to_display_matrix(source_white_xyz, white_balance, exposure);
    Image rgb(xyz.width, xyz.height, 3);
    for (std::size_t i = 0; i < xyz.pixels.size(); i += 3) {
        const Eigen::Vector3d value(xyz.pixels[i], xyz.pixels[i + 1], xyz.pixels[i + 2]);
        const Eigen::Vector3d linear = display * value;
        for (int c = 0; c < 3; ++c) rgb.pixels[i + static_cast<std::size_t>(c)] = static_cast<float>(linear[c]);
    }
    return rgb;
}

Image gray_image_to_rgb(const Image& gray, double exposure) {
    Image rgb(gray.width, gray.height, 3);
    for (std::size_t i = 0; i < gray.pixels.size(); ++i) {
        for (std::size_t c = 0; c < 3; ++c) rgb.pixels[3 * i + c] = static_cast<float>(exposure * gray.pixels[i]);
    }
    return rgb;
}

}  // namespace petroscope
