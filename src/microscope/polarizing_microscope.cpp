#include "petroscope/microscope/polarizing_microscope.hpp"

#include "petroscope/core/angles.hpp"
#include "petroscope/core/error.hpp"
#include "petroscope/core/text.hpp"
#include "petroscope/optics/orientation.hpp"
#include "petroscope/optics/slab.hpp"

#include <cmath>
#include <numbers>

namespace petroscope {
namespace {

/// The lab-frame vectors of the (s, p) basis of a direction: columns ŝ and ρ̂ (layer_stack.hpp).
Eigen::Matrix2d sp_to_lab(const TangentialWavevector& direction) {
    Eigen::Matrix2d basis;
    basis << direction.azimuthal, direction.radial;
    return basis;
}

}  // namespace

Eigen::Matrix3d DispersiveMedium::chirality(double wavelength_nm) const {
    if (!gyration) return Eigen::Matrix3d::Zero();
    return chirality_tensor(turned_gyration(gyration(wavelength_nm), axes));
}

GyrationFunction mineral_gyration(const Mineral& mineral, Handedness handedness) {
    if (!mineral.optically_active()) return {};
    return [&mineral, handedness](double wavelength_nm) {
        return gyration_tensor(mineral.principal_rotatory_power(wavelength_nm), Eigen::Matrix3d::Identity(), wavelength_nm, handedness);
    };
}

DispersiveMedium DispersiveMedium::of(const Mineral& mineral, const Eigen::Matrix3d& axes) {
    DispersiveMedium medium;
    medium.principal_n = [&mineral](double wavelength_nm) { return mineral.principal_n(wavelength_nm); };
    if (mineral.absorbing()) {
        medium.principal_kappa = [&mineral](double wavelength_nm) { return mineral.principal_kappa(wavelength_nm); };
    }
    medium.axes = axes;
    return medium;
}

OpticalMedium DispersiveMedium::at(double wavelength_nm) const {
    const Eigen::Vector3d kappa = principal_kappa ? principal_kappa(wavelength_nm) : Eigen::Vector3d::Zero();
    return OpticalMedium::from_n_kappa(principal_n(wavelength_nm), kappa, axes);
}

std::vector<IlluminationSample> condenser_samples(double condenser_na, int rings) {
    if (!(condenser_na >= 0.0 && condenser_na < 1.0)) {
        throw InputError("condenser NA " + format_number(condenser_na) + " is out of range (expected 0 <= NA < 1)");
    }
    if (condenser_na == 0.0 || rings == 0) return {IlluminationSample{}};
    if (rings < 0 || rings > 64) throw InputError("condenser rings must be 1 to 64");
    // Ring k (k = 1 … rings) at radius k·h carries the annulus ((k − ½)h, (k + ½)h) split into 6k equal cells
    // of area πh²/3; the axis carries the disc of radius h/2 (area πh²/4), h = NA/(rings + ½).
    const double h = condenser_na / (rings + 0.5);
    std::vector<IlluminationSample> samples{{Eigen::Vector2d::Zero(), 0.25}};
    for (int k = 1; k <= rings; ++k) {
        for (int j = 0; j < 6 * k; ++j) {
            const double azimuth = 2.0 * std::numbers::pi * (j + 0.5 * (k % 2)) / (6 * k);
            samples.push_back({k * h * Eigen::Vector2d(std::cos(azimuth), std::sin(azimuth)), 1.0 / 3.0});
        }
    }
    double total = 0.0;
    for (const IlluminationSample& sample : samples) total += sample.weight;
    for (IlluminationSample& sample : samples) sample.weight /= total;
    return samples;
}

int default_condenser_rings(double condenser_na) { return static_cast<int>(std::ceil(condenser_na / 0.05)); }

Eigen::Matrix2cd plate_jones_lab(const AccessoryPlate& plate, double wavelength_nm, bool exact) {
    // The plate is crossed at normal incidence, where (s, p) = (ŷ, x̂): its lab Jones matrix is S·J·Sᵀ.
    const Eigen::Matrix2d normal_basis = sp_to_lab(TangentialWavevector::from_xi(Eigen::Vector2d::Zero()));
    const std::vector<OpticalLayer> layers{{plate.medium.permittivity(wavelength_nm), plate.thickness_um}};
    const Eigen::Matrix2cd jones = exact ? coherent_jones(layers, wavelength_nm, Eigen::Vector2d::Zero())
                                         : single_pass_jones(layers, 0, wavelength_nm, Eigen::Vector2d::Zero()).at(plate.thickness_um);
    return normal_basis * jones * normal_basis.transpose();
}

MicroscopeOptics::MicroscopeOptics(const MicroscopeSettings& settings, const SectionMounting& mounting)
    : MicroscopeOptics(settings, mounting,
                       condenser_samples(settings.condenser_na, settings.condenser_rings > 0 ? settings.condenser_rings
                                                                                             : default_condenser_rings(settings.condenser_na))) {}

MicroscopeOptics::MicroscopeOptics(const MicroscopeSettings& settings, const SectionMounting& mounting,
                                   std::vector<IlluminationSample> directions)
    : settings_(settings), mounting_(mounting), directions_(std::move(directions)) {
    for (const double wavelength_nm : settings.wavelengths_nm) {
        plate_jones_lab_.push_back(settings.plate ? plate_jones_lab(*settings.plate, wavelength_nm, settings.exact)
                                                  : Eigen::Matrix2cd::Identity());
        mounting_epsilon_.push_back({mounting.slide.permittivity(wavelength_nm), mounting.cement.permittivity(wavelength_nm),
                                     mounting.cover.permittivity(wavelength_nm)});
    }
    build_paths();
}

MicroscopeOptics MicroscopeOptics::for_directions(std::vector<IlluminationSample> directions) const {
    MicroscopeOptics optics(*this, std::move(directions));
    optics.build_paths();
    return optics;
}

MicroscopeOptics::MicroscopeOptics(const MicroscopeOptics& common, std::vector<IlluminationSample> directions)
    : settings_(common.settings_),
      mounting_(common.mounting_),
      directions_(std::move(directions)),
      plate_jones_lab_(common.plate_jones_lab_),
      mounting_epsilon_(common.mounting_epsilon_) {}

void MicroscopeOptics::build_paths() {
    if (settings_.exact) return;
    paths_.clear();
    paths_.reserve(settings_.wavelengths_nm.size() * directions_.size());
    for (std::size_t w = 0; w < settings_.wavelengths_nm.size(); ++w) {
        const double k0 = wavenumber_per_um(settings_.wavelengths_nm[w]);
        const MountingPermittivity& epsilon = mounting_epsilon_[w];
        for (const IlluminationSample& direction : directions_) {
            const MediumWaves air = berreman_modes(Eigen::Matrix3cd::Identity(), direction.xi);
            const MediumWaves slide = berreman_modes(epsilon.slide, direction.xi);
            const MediumWaves cover = berreman_modes(epsilon.cover, direction.xi);
            Path path;
            path.cement = berreman_modes(epsilon.cement, direction.xi);
            path.k0_per_um = k0;
            path.into_crystal = forward_propagation(path.cement, k0, mounting_.lower_cement_um) *
                                forward_transmission(slide, path.cement) * forward_propagation(slide, k0, mounting_.slide_um) *
                                forward_transmission(air, slide) * incident(direction.xi);
            path.to_eye = after_section(w, direction.xi) * forward_transmission(cover, air) *
                          forward_propagation(cover, k0, mounting_.cover_um) * forward_transmission(path.cement, cover) *
                          forward_propagation(path.cement, k0, mounting_.upper_cement_um);
            paths_.push_back(path);
        }
    }
}

Eigen::Vector2cd MicroscopeOptics::incident(const Eigen::Vector2d& xi) const {
    // An aplanatic condenser keeps the s and p amplitudes of each ray (Richards & Wolf 1959): the polarizer's
    // field P splits as (P·ŝ, P·ρ̂).
    return (sp_to_lab(TangentialWavevector::from_xi(xi)).transpose() * unit_at(settings_.polars.polarizer_deg)).cast<std::complex<double>>();
}

Eigen::Matrix2cd MicroscopeOptics::after_section(std::size_t wavelength, const Eigen::Vector2d& xi) const {
    // The objective keeps s and p too: the field behind it is a_s·ŝ + a_p·ρ̂ in the lab frame.
    Eigen::Matrix2cd after = plate_jones_lab_[wavelength] * sp_to_lab(TangentialWavevector::from_xi(xi)).cast<std::complex<double>>();
    if (settings_.polars.analyzer_in) {
        const Eigen::RowVector2cd analyzed = unit_at(settings_.polars.analyzer_deg).cast<std::complex<double>>().transpose() * after;
        after.row(0) = analyzed;
        after.row(1).setZero();
    }
    return after;
}

double MicroscopeOptics::analyzed_intensity(const Eigen::Matrix2cd& section_jones_sp, std::size_t wavelength,
                                            std::size_t direction) const {
    const Eigen::Vector2d& xi = directions_[direction].xi;
    return (after_section(wavelength, xi) * section_jones_sp * incident(xi)).squaredNorm();
}

std::vector<OpticalLayer> MicroscopeOptics::section_layers(std::size_t wavelength, const Eigen::Matrix3cd& crystal,
                                                           const Eigen::Matrix3d& crystal_chirality, double crystal_thickness_um) const {
    const MountingPermittivity& epsilon = mounting_epsilon_[wavelength];
    return {{epsilon.slide, mounting_.slide_um},
            {epsilon.cement, mounting_.lower_cement_um},
            {crystal, crystal_thickness_um, crystal_chirality},
            {epsilon.cement, mounting_.upper_cement_um},
            {epsilon.cover, mounting_.cover_um}};
}

GrainResponse::GrainResponse(const MicroscopeOptics& optics, const DispersiveMedium& crystal)
    : optics_(optics), crystal_(crystal) {
    const MicroscopeSettings& settings = optics.settings();
    crystal_.axes = rotation_z_deg(settings.stage_deg) * crystal.axes;
    if (settings.exact) return;
    const std::vector<IlluminationSample>& directions = optics.directions();
    samples_.reserve(settings.wavelengths_nm.size() * directions.size());
    for (std::size_t w = 0; w < settings.wavelengths_nm.size(); ++w) {
        const Eigen::Matrix3cd epsilon = crystal_.permittivity(settings.wavelengths_nm[w]);
        const Eigen::Matrix3d chirality = crystal_.chirality(settings.wavelengths_nm[w]);
        const bool active = !chirality.isZero(0.0);
        for (std::size_t k = 0; k < directions.size(); ++k) {
            const MicroscopeOptics::Path& path = optics.path(w, k);
            // An active crystal's modes are elliptical, split even at normal incidence: the general solver serves it.
            const MediumWaves waves = directions[k].xi.isZero() && !active ? normal_incidence_waves(epsilon)
                                                                            : berreman_modes(epsilon, chirality, directions[k].xi);
            const Eigen::Vector2cd entry = forward_transmission(path.cement, waves) * path.into_crystal;
            const Eigen::Matrix2cd exit = path.to_eye * forward_transmission(waves, path.cement);
            Sample sample;
            for (int m = 0; m < 2; ++m) {
                sample.amplitude[m] = exit.col(m) * entry[m];
                sample.phase_per_um[m] = path.k0_per_um * waves[m].q;
            }
            sample.weight = directions[k].weight;
            sample.propagating = !waves[0].evanescent && !waves[1].evanescent;
            samples_.push_back(sample);
        }
    }
}

void GrainResponse::transmission(double thickness_um, std::vector<double>& out) const {
    const MicroscopeSettings& settings = optics_.settings();
    const std::size_t wavelength_count = settings.wavelengths_nm.size();
    const std::vector<IlluminationSample>& directions = optics_.directions();
    out.assign(wavelength_count, 0.0);
    if (settings.exact) {
        for (std::size_t w = 0; w < wavelength_count; ++w) {
            const double wavelength_nm = settings.wavelengths_nm[w];
            const std::vector<OpticalLayer> layers =
                optics_.section_layers(w, crystal_.permittivity(wavelength_nm), crystal_.chirality(wavelength_nm), thickness_um);
            for (std::size_t k = 0; k < directions.size(); ++k) {
                const Eigen::Matrix2cd jones = coherent_jones(layers, wavelength_nm, directions[k].xi);
                out[w] += directions[k].weight * optics_.analyzed_intensity(jones, w, k);
            }
        }
        return;
    }
    const std::complex<double> i(0.0, 1.0);
    for (std::size_t w = 0; w < wavelength_count; ++w) {
        double sum = 0.0;
        for (std::size_t k = 0; k < directions.size(); ++k) {
            const Sample& sample = samples_[w * directions.size() + k];
            if (!sample.propagating) continue;
            const Eigen::Vector2cd field = sample.amplitude[0] * std::exp(i * sample.phase_per_um[0] * thickness_um) +
                                           sample.amplitude[1] * std::exp(i * sample.phase_per_um[1] * thickness_um);
            sum += sample.weight * field.squaredNorm();
        }
        out[w] = sum;
    }
}

}  // namespace petroscope
