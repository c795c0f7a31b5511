// Interface solves per second: random isotropic → biaxial and biaxial → biaxial cases (random indices,
// orientations, incidence 0–89°, unpolarized light or the fast mode), one core; in long double (the
// default) and in double (InterfaceArithmetic::double_precision, the renderer's).
#include "petroscope/optics/interface.hpp"

#include <benchmark/benchmark.h>

#include <Eigen/Geometry>

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

namespace petroscope {
namespace {

struct Case {
    OpticalMedium medium1, medium2;
    InterfaceIncidence incidence;
};

std::vector<Case> random_cases(int count, bool biaxial_medium1) {
    std::mt19937_64 rng(1);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    std::normal_distribution<double> normal;
    std::vector<Case> cases;
    for (int i = 0; i < count; ++i) {
        const auto random_biaxial = [&] {
            const double n_alpha = 1.4 + unit(rng), n_gamma = n_alpha + 0.01 + 0.2 * unit(rng);
            const Eigen::Quaterniond q(normal(rng), normal(rng), normal(rng), normal(rng));
            return OpticalMedium{Eigen::Vector3cd(n_alpha, n_alpha + (0.1 + 0.8 * unit(rng)) * (n_gamma - n_alpha), n_gamma),
                                 q.normalized().toRotationMatrix()};
        };
        Case c;
        c.medium1 = biaxial_medium1 ? random_biaxial() : OpticalMedium::isotropic(1.0 + 0.6 * unit(rng));
        c.medium2 = random_biaxial();
        const double theta = 89.0 * std::numbers::pi / 180.0 * unit(rng), phi = 2.0 * std::numbers::pi * unit(rng);
        c.incidence.direction = {std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)};
        c.incidence.mode = InterfaceMode::fast;
        cases.push_back(c);
    }
    return cases;
}

void solve_cases(benchmark::State& state, bool biaxial_medium1, InterfaceArithmetic arithmetic) {
    std::vector<Case> cases = random_cases(1000, biaxial_medium1);
    for (Case& c : cases) c.incidence.arithmetic = arithmetic;
    std::size_t i = 0;
    for (auto _ : state) {
        const Case& c = cases[i++ % cases.size()];
        InterfaceResult result = solve_interface({0, 0, 1}, c.incidence, c.medium1, c.medium2);
        benchmark::DoNotOptimize(result.waves.data());
    }
    state.counters["solves_per_second"] = benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}

void IsotropicToBiaxial(benchmark::State& state) { solve_cases(state, false, InterfaceArithmetic::long_double); }
void BiaxialToBiaxial(benchmark::State& state) { solve_cases(state, true, InterfaceArithmetic::long_double); }
void IsotropicToBiaxialDouble(benchmark::State& state) { solve_cases(state, false, InterfaceArithmetic::double_precision); }
void BiaxialToBiaxialDouble(benchmark::State& state) { solve_cases(state, true, InterfaceArithmetic::double_precision); }
BENCHMARK(IsotropicToBiaxial)->Unit(benchmark::kMicrosecond);
BENCHMARK(BiaxialToBiaxial)->Unit(benchmark::kMicrosecond);
BENCHMARK(IsotropicToBiaxialDouble)->Unit(benchmark::kMicrosecond);
BENCHMARK(BiaxialToBiaxialDouble)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace petroscope

BENCHMARK_MAIN();
