// White light from spectral nodes (issue 22): the figure with the modes solved at 8 wavelengths and
// interpolated to the others against the figure with every wavelength solved, as colour differences
// ΔE₀₀ per pixel, for thin and thick slabs, uniaxial and biaxial crystals with dispersion of the optic
// axes, plates, and polars in any position.
#include "conoscope_evaluator.hpp"
#include "conoscope_fixtures.hpp"
#include "node_colour.hpp"
#include "plate_terms.hpp"

#include "petroscope/microscope/polarizing_microscope.hpp"

#include "petroscope/spectral/color.hpp"
#include "petroscope/spectral/wavelength_grid.hpp"

#include <gtest/gtest.h>

#include <cstdio>

namespace petroscope {
namespace {

struct Difference {
    double worst_delta_e = 0.0;
    int pixels = 0;
    double interpolated_fraction = 0.0;  // of the image points, those whose spectrum came from the nodes
};

/// The share of the figure's points that the evaluator interpolates.
double interpolated_fraction(const ConoscopeSettings& settings, const Mineral& mineral) {
    const detail::ConoscopeEvaluator evaluator(settings, testing::indices_of(mineral));
    detail::SpectralScratch scratch;
    std::vector<double> plus(settings.wavelengths_nm.size()), minus(plus.size());
    int points = 0, interpolated = 0;
    for (int row = 0; row < settings.size_px / 2; ++row) {
        for (int column = 0; column < settings.size_px; ++column) {
            const Eigen::Vector2d xi = conoscope_tangential_wavevector(settings, column, row);
            if (xi.norm() > settings.numerical_aperture) continue;
            evaluator.spectral_pair(xi, scratch, false, plus.data(), minus.data());
            points += 2;
            interpolated += scratch.interpolated ? 2 : 0;
        }
    }
    return static_cast<double>(interpolated) / points;
}

/// The largest ΔE₀₀ over the figure between the interpolated and the exact spectrum, in D65 light with
/// the 81 wavelengths of 380 … 780 nm in steps of 5 nm (the CLI's default).
Difference interpolation_difference(ConoscopeSettings settings, const Mineral& mineral) {
    settings.wavelengths_nm = WavelengthGrid{380.0, 780.0, 5.0}.wavelengths_nm();
    const SpectralIntegrator integrator(settings.wavelengths_nm, load_cie_1931_observer(), load_light_source("D65"));
    settings.spectrum = SpectrumSampling::exact;
    const Image exact = render_conoscope(settings, testing::indices_of(mineral), &integrator);
    settings.spectrum = SpectrumSampling::interpolated;
    const Image interpolated = render_conoscope(settings, testing::indices_of(mineral), &integrator);
    Difference difference;
    for (int row = 0; row < settings.size_px; ++row) {
        for (int column = 0; column < settings.size_px; ++column) {
            if (conoscope_tangential_wavevector(settings, column, row).norm() > settings.numerical_aperture) continue;
            const auto lab = [&](const Image& image) {
                const Eigen::Vector3d xyz(image.at(column, row, 0), image.at(column, row, 1), image.at(column, row, 2));
                return xyz_to_lab(xyz, integrator.white_xyz());
            };
            difference.worst_delta_e = std::max(difference.worst_delta_e, delta_e_2000(lab(exact), lab(interpolated)));
            ++difference.pixels;
        }
    }
    difference.interpolated_fraction = interpolated_fraction(settings, mineral);
    return difference;
}

ConoscopeSettings tilted(const Mineral& mineral, Cut cut, double tilt_deg, double thickness_um) {
    ConoscopeSettings settings = testing::figure_settings(mineral, cut, thickness_um, 128);
    settings.crystal_axes = cut_orientation(cut, mineral.optical_class, mineral.principal_n(mineral.reference_wavelength_nm), 30.0, tilt_deg);
    return settings;
}

void expect_close_to_exact(const ConoscopeSettings& settings, const Mineral& mineral, const std::string& label, double least_interpolated) {
    const Difference difference = interpolation_difference(settings, mineral);
    std::printf("%s: max dE00 %.2g over %d px, %.1f%% interpolated\n", label.c_str(), difference.worst_delta_e, difference.pixels,
                100.0 * difference.interpolated_fraction);
    EXPECT_LE(difference.worst_delta_e, 0.3) << label;
    EXPECT_GE(difference.interpolated_fraction, least_interpolated) << label;
}

std::string thickness_label(const char* name, double thickness_um) { return std::string(name) + ' ' + std::to_string(static_cast<int>(thickness_um)) + " um"; }

TEST(ConoscopeSpectrum, UniaxialFromThinToThickMatchesEveryWavelengthSolved) {
    const MineralCatalog& minerals = testing::repository_minerals();
    for (const char* name : {"calcite", "quartz"}) {
        for (const double thickness_um : {30.0, 300.0, 5000.0}) {
            for (const double tilt_deg : {0.0, 25.0}) {
                const Mineral& mineral = minerals.find(name);
                // A 5 mm calcite slab's phase (up to 2e4 rad) is interpolated to 1e-3 rad only nearer the optic axis.
                const double least = thickness_um > 1000.0 && std::string(name) == "calcite" ? 0.4 : 0.95;
                expect_close_to_exact(tilted(mineral, Cut::optic_axis, tilt_deg, thickness_um), mineral,
                                      thickness_label(name, thickness_um) + ", tilt " + std::to_string(static_cast<int>(tilt_deg)), least);
            }
        }
    }
}

TEST(ConoscopeSpectrum, BiaxialWithDispersedOpticAxesMatchesEveryWavelengthSolved) {
    const MineralCatalog& minerals = testing::repository_minerals();
    for (const char* name : {"muscovite", "augite", "aragonite", "sillimanite"}) {
        for (const double thickness_um : {30.0, 5000.0}) {
            for (const Cut cut : {Cut::acute_bisectrix, Cut::optic_axis}) {
                const Mineral& mineral = minerals.find(name);
                expect_close_to_exact(tilted(mineral, cut, 10.0, thickness_um), mineral,
                                      thickness_label(name, thickness_um) + ", " + std::string(cut_name(cut)), 0.95);
            }
        }
    }
}

// Rutile's indices have a pole at 0.29 µm, KTP's at 0.21 µm and an infrared term: their fields and phases
// need more than 8 nodes over much of the figure, which then solves every wavelength.
TEST(ConoscopeSpectrum, StronglyDispersiveCrystalsFallBackToEveryWavelength) {
    const MineralCatalog& minerals = testing::repository_minerals();
    for (const char* name : {"rutile", "ktp"}) {
        for (const double thickness_um : {30.0, 5000.0}) {
            const Mineral& mineral = minerals.find(name);
            const Cut cut = mineral.optical_class == OpticalClass::biaxial ? Cut::acute_bisectrix : Cut::optic_axis;
            expect_close_to_exact(tilted(mineral, cut, 25.0, thickness_um), mineral, thickness_label(name, thickness_um), 0.0);
        }
    }
}

TEST(ConoscopeSpectrum, PlatesAndPolarsInAnyPositionMatchEveryWavelengthSolved) {
    const MineralCatalog& minerals = testing::repository_minerals();
    struct PlateCase {
        const char* mineral;
        double thickness_um;
        PlateKind plate;
        const char* plate_mineral;
        double polarizer_deg, analyzer_deg;
        bool analyzer_in;
    };
    for (const PlateCase& each : {PlateCase{"quartz", 300.0, PlateKind::gypsum, "gypsum", 0.0, 90.0, true},
                                  PlateCase{"calcite", 30.0, PlateKind::wedge, "quartz", 17.0, 100.0, true},
                                  PlateCase{"muscovite", 30.0, PlateKind::mica, "muscovite", 30.0, 0.0, false},
                                  PlateCase{"augite", 5000.0, PlateKind::gypsum, "gypsum", 45.0, 135.0, true}}) {
        const Mineral& mineral = minerals.find(each.mineral);
        const Cut cut = mineral.optical_class == OpticalClass::biaxial ? Cut::acute_bisectrix : Cut::optic_axis;
        ConoscopeSettings settings = tilted(mineral, cut, 10.0, each.thickness_um);
        settings.plate = make_accessory_plate(each.plate, minerals.find(each.plate_mineral), 45.0, 0.5);
        settings.polarizer_deg = each.polarizer_deg;
        settings.analyzer_deg = each.analyzer_deg;
        settings.analyzer_in = each.analyzer_in;
        expect_close_to_exact(settings, mineral, thickness_label(each.mineral, each.thickness_um) + " with a plate", 0.95);
        settings.plate.reset();
        expect_close_to_exact(settings, mineral, thickness_label(each.mineral, each.thickness_um) + " without a plate", 0.95);
    }
}

TEST(ConoscopeSpectrum, OpticallyActiveQuartzMatchesEveryWavelengthSolved) {
    // The coupled fields and b₀b₁ interpolated with the rest (spectral_nodes.hpp, ActiveNodeFields): basal
    // plates from 300 µm to 5 mm, tilted, both hands, with a λ/4 mica plate, and with the analyzer out.
    const MineralCatalog& minerals = testing::repository_minerals();
    const Mineral& quartz = minerals.find("quartz");
    for (const double thickness_um : {300.0, 1000.0, 5000.0}) {
        for (const double tilt_deg : {0.0, 25.0}) {
            ConoscopeSettings settings = tilted(quartz, Cut::optic_axis, tilt_deg, thickness_um);
            settings.gyration = mineral_gyration(quartz, tilt_deg == 0.0 ? Handedness::right : Handedness::left);
            expect_close_to_exact(settings, quartz, thickness_label("active quartz", thickness_um) + ", tilt " + std::to_string(static_cast<int>(tilt_deg)),
                                  0.95);
        }
    }
    ConoscopeSettings settings = tilted(quartz, Cut::optic_axis, 0.0, 2000.0);
    settings.gyration = mineral_gyration(quartz, Handedness::right);
    settings.plate = make_accessory_plate(PlateKind::mica, minerals.find("muscovite"), 45.0);
    expect_close_to_exact(settings, quartz, "active quartz 2 mm with a quarter-wave plate", 0.95);
    settings.plate.reset();
    settings.analyzer_in = false;
    expect_close_to_exact(settings, quartz, "active quartz 2 mm, analyzer out", 0.95);
}

// The interpolation itself: exact for polynomials of degree 7 in σ, with a tail estimate (the Chebyshev
// coefficients of degrees 6 and 7) that is zero for degree 5 and large for a pole near the visible range.
TEST(ConoscopeSpectrum, NodesInterpolatePolynomialsInWavenumberExactly) {
    const std::vector<double> grid = WavelengthGrid{380.0, 780.0, 5.0}.wavelengths_nm();
    const detail::SpectralNodes nodes(grid);
    const auto polynomial = [](double wavelength_nm) {
        const double x = 1000.0 / wavelength_nm;  // σ in µm⁻¹
        return 1.5 + x * (0.3 + x * (-0.2 + x * (0.05 + x * x * x * x * 0.001)));
    };
    const auto quintic = [](double wavelength_nm) { return std::pow(1000.0 / wavelength_nm - 1.9, 5); };
    const auto pole = [](double wavelength_nm) { return 1.0 / (wavelength_nm / 1000.0 - 0.3); };
    detail::NodeValues polynomial_values{}, quintic_values{}, pole_values{};
    for (std::size_t j = 0; j < detail::kSpectralNodes; ++j) {
        polynomial_values[j] = polynomial(nodes.wavelengths_nm()[j]);
        quintic_values[j] = quintic(nodes.wavelengths_nm()[j]);
        pole_values[j] = pole(nodes.wavelengths_nm()[j]);
    }
    double worst = 0.0;
    for (std::size_t w = 0; w < grid.size(); ++w) {
        double value = 0.0;
        for (std::size_t j = 0; j < detail::kSpectralNodes; ++j) value += nodes.basis()[j * nodes.padded_grid_size() + w] * polynomial_values[j];
        worst = std::max(worst, std::abs(value - polynomial(grid[w])));
    }
    EXPECT_LT(worst, 1e-12);
    EXPECT_LT(nodes.tail(quintic_values), 1e-12);
    EXPECT_GT(nodes.tail(pole_values), 1e-3);
    EXPECT_NEAR(nodes.wavelengths_nm().front(), 380.0, 1e-9);
    EXPECT_NEAR(nodes.wavelengths_nm().back(), 780.0, 1e-9);
}

// The colour straight from the nodes (NodeColour) against the interpolated spectrum integrated wavelength by
// wavelength: the same sum where the amplitudes are cubic in σ, so that their product (degree 6) is interpolated
// exactly, up to the single precision in which NodeColour interpolates the fringe term's amplitude P = Σc₀c₁: the
// node values, the basis and the eight products and sums each rounded to 2⁻²⁴ of at most Σⱼ|ℓⱼPⱼ| < 3·max|P| (the
// Lebesgue constant of 8 Chebyshev–Lobatto points is below 3), some 20 roundings, under 4e-6 for |P| < 1, times P's
// factor 4 in the transmission and the colour weights' sum. A phase of up to 4e3 rad puts hundreds of fringes in
// the spectrum. Amplitudes with a pole near the visible range give a product too rough to interpolate, which is
// refused.
TEST(ConoscopeSpectrum, ColourFromNodesEqualsTheIntegratedInterpolatedSpectrum) {
    const std::vector<double> grid = WavelengthGrid{380.0, 780.0, 5.0}.wavelengths_nm();
    const detail::SpectralNodes nodes(grid);
    const SpectralIntegrator integrator(grid, load_cie_1931_observer(), load_light_source("D65"));
    const detail::NodeColour colour(nodes, integrator.weights());
    const Eigen::Vector3d white = integrator.integrate(std::vector<double>(grid.size(), 1.0));  // Σ_w W(w): a unit amplitude's bound
    std::array<detail::NodeValues, 4> amplitudes{}, poles{};
    detail::NodeValues phase{};
    for (std::size_t j = 0; j < detail::kSpectralNodes; ++j) {
        const double x = 1000.0 / nodes.wavelengths_nm()[j];  // σ in µm⁻¹
        for (std::size_t k = 0; k < 4; ++k) {
            const double shift = 0.3 * static_cast<double>(k);
            amplitudes[k][j] = (k % 2 == 0 ? 0.6 : -0.5) + (0.2 - 0.1 * shift) * x - 0.05 * x * x + 0.01 * shift * x * x * x;
            poles[k][j] = 0.1 / (nodes.wavelengths_nm()[j] / 1000.0 - 0.33);
        }
        phase[j] = 1600.0 * x + 40.0 * x * x;
    }
    std::vector<double> spectrum(grid.size());
    for (const int pairs : {1, 2}) {
        detail::interpolated_transmission(nodes, amplitudes, pairs, phase, spectrum.data());
        const Eigen::Vector3d expected = integrator.integrate(spectrum);
        const std::optional<Eigen::Vector3d> from_nodes = colour.xyz(nodes, amplitudes, pairs, phase, 1.0);
        ASSERT_TRUE(from_nodes.has_value()) << pairs << " pairs";
        EXPECT_LT((*from_nodes - expected).cwiseAbs().maxCoeff(), 4.0 * 4e-6 * white.maxCoeff()) << pairs << " pairs";
        EXPECT_FALSE(colour.xyz(nodes, poles, pairs, phase, 1e-4).has_value()) << pairs << " pairs";
    }
}


// An optically active crystal's colour from the nodes (NodeColour::active_xyz: S + X·cos 2Ω + Y·sin 2Ω with S, X, Y
// and Ω interpolated) against its interpolated spectrum (the fields, δ and b₀b₁ interpolated) integrated wavelength
// by wavelength: the two interpolate different smooth quantities, so they agree to the interpolation's error (its
// estimate is held to 1e-4), for one and two components, a narrow and a wide range of Ω. Without coupling on the
// optic axis (Ω = 0 at a node) the nodes refuse.
TEST(ConoscopeSpectrum, ActiveColourFromNodesMatchesTheIntegratedInterpolatedSpectrum) {
    const std::vector<double> grid = WavelengthGrid{380.0, 780.0, 5.0}.wavelengths_nm();
    const detail::SpectralNodes nodes(grid);
    const SpectralIntegrator integrator(grid, load_cie_1931_observer(), load_light_source("D65"));
    const detail::NodeColour colour(nodes, integrator.weights());
    std::vector<double> spectrum(grid.size());
    for (const double phase_scale : {0.5, 40.0}) {
        for (const int components : {1, 2}) {
            detail::ActiveNodeFields fields;
            fields.components = components;
            detail::NodeValues phase{};
            for (std::size_t j = 0; j < detail::kSpectralNodes; ++j) {
                const double x = 1000.0 / nodes.wavelengths_nm()[j];  // σ in µm⁻¹
                for (std::size_t k = 0; k < 2; ++k) {
                    const double shift = 0.2 * static_cast<double>(k);
                    fields.component[k][0][j] = 0.5 + 0.1 * x - shift * 0.02 * x * x;  // F₀
                    fields.component[k][1][j] = -0.4 + 0.05 * x + shift * 0.1;        // F₁
                    fields.component[k][2][j] = 0.02 * x;                              // G₀
                    fields.component[k][3][j] = -0.03 + 0.01 * shift * x;              // G₁
                }
                fields.coupling_product[j] = 0.01 * x * x;
                phase[j] = phase_scale * x * (1.0 + 0.05 * x);
            }
            detail::interpolated_active_transmission(nodes, fields, phase, nullptr, spectrum.data());
            const Eigen::Vector3d expected = integrator.integrate(spectrum);
            const std::optional<Eigen::Vector3d> from_nodes = colour.active_xyz(nodes, fields, phase);
            ASSERT_TRUE(from_nodes.has_value()) << components << " components, phase scale " << phase_scale;
            EXPECT_LT((*from_nodes - expected).cwiseAbs().maxCoeff(), 2e-4) << components << " components, phase scale " << phase_scale;
            fields.coupling_product.fill(0.0);
            phase[3] = 0.0;
            EXPECT_FALSE(colour.active_xyz(nodes, fields, phase).has_value());
        }
    }
}

// Behind an accessory plate the colour comes from the nodes as S + X cos θ + Y sin θ + cos Γ·(…) − sin Γ·(…)
// (NodeColour::plate_xyz, plate_terms.hpp). Against the interpolated spectrum through the plate (the lab fields, δ and,
// when active, b₀b₁ interpolated, each wavelength through the plate's Jones matrix and the analyzer) integrated wavelength by
// wavelength: the two interpolate different smooth quantities, so they agree to the interpolation's error (held to
// 1e-4). Gypsum and a quartz wedge (Γ up to four orders, far from smooth) at 30° to the lab's x, crossed polars and the
// analyzer out (no cross term), a small and a large δ, with and without optical activity.
TEST(ConoscopeSpectrum, PlateColourFromNodesMatchesTheIntegratedInterpolatedSpectrum) {
    const std::vector<double> grid = WavelengthGrid{380.0, 780.0, 5.0}.wavelengths_nm();
    const detail::SpectralNodes nodes(grid);
    const SpectralIntegrator integrator(grid, load_cie_1931_observer(), load_light_source("D65"));
    std::vector<double> spectrum(grid.size());
    const Eigen::Vector2d analyzer(0.0, 1.0);
    double worst = 0.0;
    for (const PlateKind kind : {PlateKind::gypsum, PlateKind::wedge}) {
        const AccessoryPlate plate = make_accessory_plate(kind, testing::repository_minerals().find(kind == PlateKind::gypsum ? "gypsum" : "quartz"), 30.0, 0.9);
        for (const bool analyzer_in : {true, false}) {
            std::vector<Eigen::Matrix2cd> jones(grid.size());
            for (std::size_t w = 0; w < grid.size(); ++w) jones[w] = plate_jones_lab(plate, grid[w], false);
            const std::optional<detail::PlateFrame> frame = detail::plate_frame(plate, jones, nodes, analyzer, analyzer_in);
            ASSERT_TRUE(frame.has_value());
            EXPECT_EQ(frame->cross, analyzer_in);
            const detail::NodeColour colour(nodes, integrator.weights(), frame->phase_rad);
            // The analyzers after the plate at every grid wavelength, bᵀ = aᵀJ (SampleCrystal::plate_analyzer).
            std::array<std::array<std::vector<double>, 4>, 2> analyzer_parts;
            for (std::size_t w = 0; w < grid.size(); ++w) {
                for (std::size_t k = 0; k < 2; ++k) {
                    const Eigen::Vector2d a = analyzer_in ? analyzer : Eigen::Vector2d::Unit(static_cast<Eigen::Index>(k));
                    const Eigen::RowVector2cd b = a.transpose().cast<std::complex<double>>() * jones[w];
                    const std::array<double, 4> parts{b[0].real(), b[1].real(), b[0].imag(), b[1].imag()};
                    for (std::size_t c = 0; c < 4; ++c) analyzer_parts[k][c].push_back(parts[c]);
                }
            }
            detail::PlateAnalyzers analyzers{analyzer_in ? 1 : 2, {}};
            for (std::size_t k = 0; k < 2; ++k) {
                for (std::size_t c = 0; c < 4; ++c) analyzers.lab[k][c] = analyzer_parts[k][c].data();
            }
            for (const double phase_scale : {0.5, 40.0}) {
                std::array<detail::NodeValues, 4> lab_fields{};
                detail::ActiveNodeFields active;
                active.components = 2;
                detail::NodeValues phase{};
                for (std::size_t j = 0; j < detail::kSpectralNodes; ++j) {
                    const double x = 1000.0 / nodes.wavelengths_nm()[j];  // σ in µm⁻¹
                    lab_fields[0][j] = 0.5 + 0.1 * x;          // x of the fast mode
                    lab_fields[1][j] = 0.4 - 0.02 * x * x;     // x of the slow mode
                    lab_fields[2][j] = -0.3 + 0.05 * x;        // y of the fast mode
                    lab_fields[3][j] = 0.6 + 0.01 * x * x;     // y of the slow mode
                    for (std::size_t k = 0; k < 2; ++k) {
                        const double shift = 0.2 * static_cast<double>(k);
                        active.component[k][0][j] = 0.5 + 0.1 * x - shift * 0.02 * x * x;  // F₀
                        active.component[k][1][j] = -0.4 + 0.05 * x + shift;               // F₁
                        active.component[k][2][j] = 0.02 * x - shift * 0.05;               // G₀
                        active.component[k][3][j] = -0.03 + 0.01 * shift * x;              // G₁
                    }
                    active.coupling_product[j] = 0.01 * x * x;
                    phase[j] = phase_scale * x * (1.0 + 0.05 * x);
                }
                const std::string label = std::string(plate_name(kind)) + (analyzer_in ? ", crossed" : ", analyzer out") + ", phase scale " +
                                          std::to_string(phase_scale);
                detail::interpolated_transmission(nodes, lab_fields, phase, analyzers, spectrum.data());
                const Eigen::Vector3d expected = integrator.integrate(spectrum);
                detail::PlateNodeTerms terms;
                detail::plate_terms(*frame, lab_fields, phase, terms);
                const std::optional<Eigen::Vector3d> from_nodes = colour.plate_xyz(nodes, terms);
                ASSERT_TRUE(from_nodes.has_value()) << label;
                worst = std::max(worst, (*from_nodes - expected).cwiseAbs().maxCoeff());
                EXPECT_LT((*from_nodes - expected).cwiseAbs().maxCoeff(), 2e-4) << label;
                detail::interpolated_active_transmission(nodes, active, phase, &analyzers, spectrum.data());
                const Eigen::Vector3d active_expected = integrator.integrate(spectrum);
                ASSERT_TRUE(detail::active_plate_terms(*frame, active, phase, terms)) << label;
                const std::optional<Eigen::Vector3d> active_from_nodes = colour.plate_xyz(nodes, terms);
                ASSERT_TRUE(active_from_nodes.has_value()) << label << ", active";
                worst = std::max(worst, (*active_from_nodes - active_expected).cwiseAbs().maxCoeff());
                EXPECT_LT((*active_from_nodes - active_expected).cwiseAbs().maxCoeff(), 2e-4) << label << ", active";
            }
        }
    }
    std::printf("plate colour from the nodes against the integrated spectrum: largest XYZ difference %.2g\n", worst);
}

}  // namespace
}  // namespace petroscope
