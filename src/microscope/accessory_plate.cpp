#include "petroscope/microscope/polarizing_microscope.hpp"

#include "petroscope/core/angles.hpp"
#include "petroscope/core/error.hpp"
#include "petroscope/core/text.hpp"

#include <cmath>
#include <iomanip>
#include <numbers>
#include <sstream>

namespace petroscope {
namespace {

/// Retardation Γ = (n_slow − n_fast)·d of a plate whose slow and fast principal axes are `slow`, `fast`.
double birefringence(const Mineral& mineral, int slow, int fast, double wavelength_nm) {
    const Eigen::Vector3d n = mineral.principal_n(wavelength_nm);
    return n[slow] - n[fast];
}

}  // namespace

std::string_view plate_name(PlateKind kind) {
    switch (kind) {
        case PlateKind::gypsum: return "gypsum";
        case PlateKind::mica: return "mica";
        case PlateKind::wedge: return "wedge";
    }
    return "";
}

PlateKind parse_plate(std::string_view name) {
    for (const PlateKind kind : {PlateKind::gypsum, PlateKind::mica, PlateKind::wedge}) {
        if (name == plate_name(kind)) return kind;
    }
    throw InputError("unknown accessory plate " + quote_input(name) + " (expected gypsum, mica or wedge)");
}

std::string_view plate_mineral_name(PlateKind kind) {
    switch (kind) {
        case PlateKind::gypsum: return "gypsum";
        case PlateKind::mica: return "muscovite";
        case PlateKind::wedge: return "quartz";
    }
    return "";
}

AccessoryPlate make_accessory_plate(PlateKind kind, const Mineral& plate_mineral, double slow_deg, double wedge_position) {
    if (!std::isfinite(slow_deg)) throw InputError("the plate's slow direction must be a finite angle in degrees");
    if (!(wedge_position >= 0.0 && wedge_position <= 1.0)) {
        throw InputError("wedge position " + format_number(wedge_position) + " is out of range (expected 0 to 1)");
    }
    if (plate_mineral.optical_class == OpticalClass::isotropic) {
        throw InputError("an accessory plate needs a birefringent mineral, not " + plate_mineral.name);
    }
    const Eigen::Vector3d slow(std::cos(slow_deg * kDegree), std::sin(slow_deg * kDegree), 0.0);
    const Eigen::Vector3d fast(-slow.y(), slow.x(), 0.0);
    const Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
    AccessoryPlate plate;
    plate.kind = kind;
    plate.slow_deg = slow_deg;
    Eigen::Matrix3d axes;  // indicatrix X, Y, Z (columns)
    std::ostringstream description;
    switch (kind) {
        case PlateKind::gypsum: {
            // A (010) cleavage flake: Y = b is the normal, X (fast) and Z (slow) lie in the plate (Deer, Howie &
            // Zussman; Nesse). First-order red: Γ = 550 nm at 550 nm.
            axes << fast, normal, slow;
            plate.thickness_um = 0.550 / birefringence(plate_mineral, 2, 0, 550.0);
            description << "gypsum (010) plate, first-order red: Γ = 550 nm at 550 nm";
            break;
        }
        case PlateKind::mica: {
            // A muscovite (001) cleavage flake: X ≈ normal, Y (fast) and Z (slow) in the plate (Deer, Howie &
            // Zussman). Quarter wave at 589.3 nm.
            axes << normal, fast, slow;
            plate.thickness_um = 0.25 * 0.5893 / birefringence(plate_mineral, 2, 1, 589.3);
            description << "muscovite (001) plate, λ/4 at 589.3 nm (Γ = 147.3 nm)";
            break;
        }
        case PlateKind::wedge: {
            // Quartz with c (the slow e vibration of a positive crystal) along the wedge: 0 to 4 orders,
            // Γ = 0 … 2200 nm at 550 nm along its length.
            axes << fast, normal, slow;
            plate.thickness_um = wedge_position * 2.200 / birefringence(plate_mineral, 2, 0, 550.0);
            description << "quartz wedge pushed in to " << format_number(wedge_position) << " of its length (0 to 4 orders)";
            break;
        }
    }
    description << ", " << std::fixed << std::setprecision(1) << plate.thickness_um << std::defaultfloat << " µm of " << plate_mineral.name << ", slow direction at "
                << format_number(slow_deg) << "° from E toward N";
    plate.description = description.str();
    plate.medium = DispersiveMedium::of(plate_mineral, axes);
    return plate;
}

}  // namespace petroscope
