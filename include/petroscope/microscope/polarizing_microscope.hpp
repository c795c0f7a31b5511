#pragma once
// The polarizing microscope's optical train as one object, for orthoscopy (and the Michel-Lévy chart):
// polarizer, condenser cone, the section (slide glass, balsam, crystal, balsam, cover glass), an accessory
// plate, analyzer. Each element between air gaps is one layer stack (layer_stack.hpp); the elements are
// incoherent with each other. Frames and angle senses: docs/conventions.md; the model: docs/orthoscope.md.
#include "petroscope/microscope/layer_stack.hpp"
#include "petroscope/minerals/mineral.hpp"
#include "petroscope/optics/gyration.hpp"
#include "petroscope/optics/medium.hpp"

#include <Eigen/Core>

#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace petroscope {

/// Principal indices (or extinction coefficients) along the indicatrix axes X, Y, Z at a wavelength in nm.
using PrincipalIndexFunction = std::function<Eigen::Vector3d(double wavelength_nm)>;
/// A crystal's gyration tensor g in its indicatrix frame (X, Y, Z) at a wavelength in nm (optics/gyration.hpp).
using GyrationFunction = std::function<Eigen::Matrix3d(double wavelength_nm)>;

/// A homogeneous medium over all wavelengths: principal n and κ as functions of λ and the indicatrix axes
/// (columns, lab frame). At one wavelength it is an OpticalMedium (optics/medium.hpp).
struct DispersiveMedium {
    PrincipalIndexFunction principal_n;
    PrincipalIndexFunction principal_kappa;  // empty: transparent
    GyrationFunction gyration;               // empty: optically inactive
    Eigen::Matrix3d axes = Eigen::Matrix3d::Identity();

    /// The mineral's dispersion; the mineral must outlive the medium.
    static DispersiveMedium of(const Mineral& mineral, const Eigen::Matrix3d& axes = Eigen::Matrix3d::Identity());
    /// The same with its optical activity, of its `handedness` form (none for an inactive mineral).
    static DispersiveMedium of(const Mineral& mineral, const Eigen::Matrix3d& axes, Handedness handedness);
    /// n + iκ along the axes at `wavelength_nm` (time dependence exp(−iωt): absorption has Im ε > 0).
    OpticalMedium at(double wavelength_nm) const;
    Eigen::Matrix3cd permittivity(double wavelength_nm) const { return at(wavelength_nm).permittivity(); }
    /// The largest minus the smallest principal index at `wavelength_nm`.
    double birefringence(double wavelength_nm) const;
    /// The gyration tensor turned by the axes, in the lab frame; zero when inactive.
    Eigen::Matrix3d lab_gyration(double wavelength_nm) const;
    /// The chirality tensor κ (optics/gyration.hpp) of lab_gyration.
    Eigen::Matrix3d chirality(double wavelength_nm) const { return chirality_tensor(lab_gyration(wavelength_nm)); }
};

/// The gyration tensor of `mineral`'s `handedness` form in its indicatrix frame (optics/gyration.hpp); empty for
/// an inactive mineral. The mineral must outlive the function.
GyrationFunction mineral_gyration(const Mineral& mineral, Handedness handedness);

/// Glass and cement around the crystal, from the condenser side up (typical thin section: 1 mm slide,
/// a few µm of balsam on each face of the rock slice, a #1.5 cover glass of 170 µm).
struct SectionMounting {
    DispersiveMedium slide, cement, cover;
    double slide_um = 1000.0, lower_cement_um = 5.0, upper_cement_um = 5.0, cover_um = 170.0;
};

enum class PlateKind { gypsum, mica, wedge };
std::string_view plate_name(PlateKind kind);
PlateKind parse_plate(std::string_view name);  // "gypsum", "mica", "wedge"; throws InputError listing them
/// The catalog name of the mineral each plate is cut from: gypsum, muscovite, quartz.
std::string_view plate_mineral_name(PlateKind kind);

/// An accessory plate: a real crystal plate in the tube, in air, crossed at normal incidence (the same
/// retardation over the whole field). Its slow vibration direction lies at `slow_deg` from E toward N.
struct AccessoryPlate {
    PlateKind kind = PlateKind::gypsum;
    DispersiveMedium medium;  // axes already set: slow direction in the plane at slow_deg
    double thickness_um = 0.0;
    double slow_deg = 45.0;
    std::string description;  // e.g. "gypsum (010) cleavage plate, 56.1 µm, Γ = 550 nm at 550 nm"
};

/// The standard plates, cut from the catalog's minerals:
/// - gypsum: a (010) cleavage flake (normal = Y), slow Z, thick enough for Γ = 550 nm at 550 nm (first-order red);
/// - mica: a muscovite (001) cleavage flake (normal ≈ X), slow Z, Γ = λ/4 at 589.3 nm (147.3 nm);
/// - wedge: quartz with c in the plane (slow, quartz is positive), 0 to 4 orders (Γ 0 … 2200 nm at 550 nm)
///   along its length; `wedge_position` ∈ [0, 1] says how far it is pushed in.
/// Throws InputError when a required mineral or a wedge position is out of range.
AccessoryPlate make_accessory_plate(PlateKind kind, const Mineral& plate_mineral, double slow_deg, double wedge_position = 0.5);

/// The plate's Jones matrix at normal incidence in the lab (x, y) frame, single pass or coherent (`exact`).
Eigen::Matrix2cd plate_jones_lab(const AccessoryPlate& plate, double wavelength_nm, bool exact);

/// Polarizer, analyzer and stage.
struct Polars {
    double polarizer_deg = 0.0;  // transmission direction, from E toward N
    double analyzer_deg = 90.0;
    bool analyzer_in = true;
};

/// Directions of the illuminating plane waves: Köhler illumination with the condenser aperture filled
/// uniformly (uniform in ξ over the disc |ξ| ≤ NA), sampled by a polar Gauss–Radau cubature: the axis and
/// `rings` rings of 4·rings + 2 points, exact for polynomials in ξ of degree 4·rings + 1 (7 directions for one
/// ring). NA 0 gives the axial wave alone (parallel light).
struct IlluminationSample {
    Eigen::Vector2d xi = Eigen::Vector2d::Zero();
    double weight = 1.0;  // Σ weights = 1
};
constexpr int kMaxCondenserRings = 64;
std::vector<IlluminationSample> condenser_samples(double condenser_na, int rings);
/// The fewest rings whose cubature degree 4·rings + 1 reaches the phase spread + 2 (at least one ring): the
/// error measured against a 16-ring reference is in docs/orthoscope.md.
int condenser_rings_for(double condenser_na, double phase_spread_rad);

struct MicroscopeSettings {
    Polars polars;
    double stage_deg = 0.0;
    double condenser_na = 0.0;
    int condenser_rings = 0;  // 0: automatic, resolved by the caller from its crystals (condenser_rings_for)
    std::optional<AccessoryPlate> plate;
    bool exact = false;  // coherent 4×4 per element instead of single pass
    std::vector<double> wavelengths_nm{589.3};
};

/// How much the phase difference of the crystal's two waves can change between the condenser cone's axis and
/// its rim at this thickness, in radians: 2π·d·B·NA/(λ·n) at the shortest wavelength, taking |∂(Δn)/∂θ| ≤ B
/// (the birefringence) and the angle NA/n inside the crystal (n its smallest principal index).
double condenser_phase_spread_rad(const MicroscopeSettings& microscope, const DispersiveMedium& crystal, double thickness_um);

/// Everything of the microscope that does not depend on the grain, per wavelength and illumination direction:
/// the light from the polarizer up to the crystal's lower face (as forward waves of the cement), and from the
/// crystal's upper face through cement, cover glass, plate and analyzer to the eye. Built once per render.
class MicroscopeOptics {
public:
    MicroscopeOptics(const MicroscopeSettings& settings, const SectionMounting& mounting);
    /// The same for given directions instead of the condenser's.
    MicroscopeOptics(const MicroscopeSettings& settings, const SectionMounting& mounting,
                     std::vector<IlluminationSample> directions);
    /// These optics for other directions, reusing what depends on the wavelength only (the plate, the
    /// mounting's permittivities): the conoscope builds one per image point.
    MicroscopeOptics for_directions(std::vector<IlluminationSample> directions) const;

    const MicroscopeSettings& settings() const { return settings_; }
    const SectionMounting& mounting() const { return mounting_; }
    const std::vector<IlluminationSample>& directions() const { return directions_; }

    struct Path {  // one wavelength, one direction (single pass)
        MediumWaves cement;                 // the cement's waves on both faces of the crystal
        Eigen::Vector2cd into_crystal;      // the cement's forward-wave amplitudes at the crystal's lower face
        Eigen::Matrix2cd to_eye;            // cement forward waves at the crystal's upper face → analyzed field
        double k0_per_um = 0.0;
    };
    /// Single pass only (empty in exact mode): [wavelength][direction].
    const Path& path(std::size_t wavelength, std::size_t direction) const {
        return paths_[wavelength * directions_.size() + direction];
    }
    /// Exact mode: the analyzed intensity for the section's coherent Jones matrix (s, p bases of the air).
    double analyzed_intensity(const Eigen::Matrix2cd& section_jones_sp, std::size_t wavelength, std::size_t direction) const;
    /// The section's layers at wavelength index `wavelength`, the crystal (index 2) with `crystal` and
    /// `crystal_thickness_um`.
    std::vector<OpticalLayer> section_layers(std::size_t wavelength, const Eigen::Matrix3cd& crystal, const Eigen::Matrix3d& crystal_chirality,
                                             double crystal_thickness_um) const;

private:
    const MicroscopeSettings& settings_;
    const SectionMounting& mounting_;
    std::vector<IlluminationSample> directions_;
    std::vector<Eigen::Matrix2cd> plate_jones_lab_;  // per wavelength, lab (x, y) frame
    struct MountingPermittivity {
        Eigen::Matrix3cd slide, cement, cover;
    };
    std::vector<MountingPermittivity> mounting_epsilon_;  // per wavelength
    std::vector<Path> paths_;

    MicroscopeOptics(const MicroscopeOptics& common, std::vector<IlluminationSample> directions);
    /// The single-pass paths of every wavelength and direction (none in exact mode).
    void build_paths();

    /// Rows taking the transmitted (s, p) amplitudes in the air above the section to what the eye receives:
    /// through the plate, then onto the analyzer (first row; second zero) or both lab components (no analyzer).
    Eigen::Matrix2cd after_section(std::size_t wavelength, const Eigen::Vector2d& xi) const;
    /// The polarizer's field in the (s, p) basis of the direction (an aplanatic condenser keeps s and p).
    Eigen::Vector2cd incident(const Eigen::Vector2d& xi) const;
};

/// The analyzed transmission of one crystal (a grain) in its mounting as a function of its thickness:
/// intensity after the analyzer (or behind the stage without it) relative to the light after the polarizer,
/// per wavelength, averaged over the condenser's directions. The crystal's axes are given at stage 0; the
/// stage turns them. Single pass: the per-wave split is computed once, any thickness is then cheap; exact:
/// the coherent Jones matrix is computed for each thickness asked for. `optics` must outlive the response.
class GrainResponse {
public:
    GrainResponse(const MicroscopeOptics& optics, const DispersiveMedium& crystal);
    /// Transmission per wavelength of the settings, written to `out`.
    void transmission(double thickness_um, std::vector<double>& out) const;
    /// The transmissions at `count` thicknesses first_um + k·step_um, in order: `consume(k, spectrum)`. Single
    /// pass: each term advances by one complex product per step instead of an exponential.
    void transmission_series(double first_um, double step_um, int count,
                             const std::function<void(int, const std::vector<double>&)>& consume) const;

private:
    /// One wavelength's transmission as a function of the thickness d: constant + Σ Re(coefficient·exp(i·rate·d)).
    /// The analyzed field of a direction, a₀e^{iφ₀d} + a₁e^{iφ₁d}, squares to |a₀|²e^{i(φ₀−φ₀*)d} +
    /// |a₁|²e^{i(φ₁−φ₁*)d} + 2Re(a₁ᴴa₀·e^{i(φ₀−φ₁*)d}); terms with a zero rate (no absorption) join the constant.
    struct Term {
        std::complex<double> coefficient, rate_per_um;
    };
    struct Spectrum {
        double constant = 0.0;
        std::vector<Term> terms;
    };
    const MicroscopeOptics& optics_;
    DispersiveMedium crystal_;
    std::vector<Spectrum> single_pass_;  // per wavelength; empty in exact mode
};

}  // namespace petroscope
