#include "petroscope/api/grain_optics.hpp"

#include "petroscope/optics/eigenmodes.hpp"

#include <cmath>
#include <numbers>

namespace petroscope {
namespace {

/// Below this index difference the two waves along the axis are taken as one (no extinction position).
constexpr double kNoBirefringence = 1e-9;

double degrees_in_half_turn(double radians) {
    const double degrees = radians * 180.0 / std::numbers::pi;
    const double folded = std::fmod(degrees, 180.0);
    return folded < 0.0 ? folded + 180.0 : folded;
}

}  // namespace

GrainOptics grain_optics(const Mineral& mineral, const Eigen::Matrix3d& crystal_axes, double thickness_um, double wavelength_nm) {
    GrainOptics optics;
    optics.wavelength_nm = wavelength_nm;
    optics.mineral = optical_summary(mineral, wavelength_nm);  // checks the data at this wavelength
    const BinormalFrame frame(Indicatrix{mineral.principal_n(wavelength_nm), crystal_axes});
    const ModePair modes = eigenmodes(frame, Eigen::Vector3d::UnitZ());
    optics.n_fast = modes.fast.n;
    optics.n_slow = modes.slow.n;
    optics.birefringence_in_section = modes.slow.n - modes.fast.n;
    optics.retardation_nm = optics.birefringence_in_section * thickness_um * 1e3;
    if (optics.birefringence_in_section > kNoBirefringence) {
        const Eigen::Vector3d& d = modes.slow.d_hat;  // ⟂ z: in the plane of the section
        optics.slow_azimuth_deg = degrees_in_half_turn(std::atan2(d.y(), d.x()));
        // Turning the stage by φ turns the slow direction to azimuth + φ; extinction where that is a
        // multiple of 90°.
        optics.extinction_stage_deg = std::fmod(180.0 - *optics.slow_azimuth_deg, 90.0);
    }
    return optics;
}

}  // namespace petroscope
