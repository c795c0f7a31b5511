// The cost the conoscope fit hands to Ceres, anywhere in the box the fit keeps its parameters in: every
// residual and Jacobian entry it returns is finite, and it refuses no point. (It refuses a point whose
// answer would not be finite, so that Ceres rejects the step instead of printing "non-finite value" and
// failing the solve: without the model's dark pixels beyond grazing it refused 11 of 129 points, with 100
// random points instead of these 40.)
#include "photo_cost.hpp"
#include "synthetic_photo.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

namespace petroscope {
namespace {

struct Evaluation {
    bool accepted = false;
    bool finite = true;
};

Evaluation evaluate(const detail::PhotoCost& cost, const PhotoParameters& values) {
    const auto rows = static_cast<std::size_t>(cost.num_residuals());
    std::vector<double> residuals(rows), jacobian(rows * kPhotoParameterCount);
    const double* parameters = values.data();
    double* jacobian_block = jacobian.data();
    Evaluation result;
    result.accepted = cost.Evaluate(&parameters, residuals.data(), &jacobian_block);
    for (const double value : residuals) result.finite = result.finite && std::isfinite(value);
    for (const double value : jacobian) result.finite = result.finite && std::isfinite(value);
    return result;
}

TEST(PhotoCost, EveryAnswerInsideTheBoundsIsFinite) {
    constexpr int kSize = 48;
    const ConoscopePhotoModel model = testing::photo_model(testing::fit_minerals().find("muscovite"), Cut::acute_bisectrix);
    // A photo of noise: the cost must stay finite whatever it is compared with.
    std::mt19937_64 rng(8);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    Image photo(kSize, kSize, 3);
    for (float& value : photo.pixels) value = static_cast<float>(unit(rng));
    const PhotoParameters start = default_photo_parameters(kSize, kSize);
    const Eigen::Vector2d centre(at(start, PhotoParameter::center_x_px), at(start, PhotoParameter::center_y_px));
    const detail::PhotoLevel level(model, detail::sample_lattice(centre, 20.0, 3, kSize, kSize), photo, 0.0, 2.2, 0.995);
    PhotoParameterFlags free{};
    free.fill(true);
    const detail::PhotoCost cost(level, free, 0.05);
    const detail::PhotoBounds bounds = detail::photo_parameter_bounds(5.0, 5000.0, kSize, kSize);

    // The start, each parameter alone at either bound, every parameter at one bound, and random points.
    std::vector<PhotoParameters> points{start, bounds.lower, bounds.upper};
    for (std::size_t j = 0; j < kPhotoParameterCount; ++j) {
        for (const PhotoParameters* bound : {&bounds.lower, &bounds.upper}) {
            PhotoParameters point = start;
            point[j] = (*bound)[j];
            points.push_back(point);
        }
    }
    for (int i = 0; i < 40; ++i) {
        PhotoParameters point;
        for (std::size_t j = 0; j < kPhotoParameterCount; ++j) point[j] = bounds.lower[j] + unit(rng) * (bounds.upper[j] - bounds.lower[j]);
        points.push_back(point);
    }
    int refused = 0, non_finite = 0;
    for (const PhotoParameters& point : points) {
        const Evaluation result = evaluate(cost, point);
        refused += result.accepted ? 0 : 1;
        non_finite += result.accepted && !result.finite ? 1 : 0;
    }
    std::printf("%zu points: %d refused, %d answered with a non-finite value\n", points.size(), refused, non_finite);
    EXPECT_EQ(non_finite, 0);
    EXPECT_EQ(refused, 0);
}

}  // namespace
}  // namespace petroscope
