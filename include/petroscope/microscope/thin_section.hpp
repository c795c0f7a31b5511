#pragma once
// A thin section: a map of grain labels, the mineral and orientation of each grain, and the thickness.
// The file format is thin_sections/README.md (io/thin_section_file.hpp); frames: docs/conventions.md.
#include "petroscope/optics/gyration.hpp"

#include <Eigen/Core>

#include <cstdint>
#include <optional>
#include <random>
#include <string>
#include <vector>

namespace petroscope {

class MineralCatalog;

struct ThinSectionGrain {
    int label = 0;                          // value in the grain map, 0 … 65535
    std::string mineral;                    // canonical name in the mineral catalog
    Eigen::Matrix3d crystal_axes = Eigen::Matrix3d::Identity();  // indicatrix X, Y, Z (columns, lab frame) at stage 0
    std::optional<double> thickness_um;     // the grain's own thickness, overriding the section's
    int line = 0;                           // line of the description that defined it (0: not from a file)
    /// The form of an optically active mineral (quartz); none: right-handed, as on the command line. Only
    /// optically active minerals have one (thin_sections/README.md).
    std::optional<Handedness> handedness;
};

enum class ThicknessKind { uniform, wedge, map };

struct ThinSection {
    std::string name;
    std::string note;                        // free text (e.g. the command that generated the section)
    int width_px = 0, height_px = 0;
    double pixel_size_um = 1.0;              // edge of a square pixel on the specimen
    std::vector<std::uint16_t> labels;       // row-major, top row (North) first, width*height
    /// Every label used in the map has exactly one entry; entries for labels absent from the map are
    /// allowed and ignored (thin_sections/README.md).
    std::vector<ThinSectionGrain> grains;
    ThicknessKind thickness_kind = ThicknessKind::uniform;
    double thickness_um = 30.0;              // uniform thickness
    /// Wedge: the thickness varies linearly from wedge_start_um at the left image edge (x = 0, West) to
    /// wedge_end_um at the right edge (x = width), each pixel taking the value at its centre x + ½; with
    /// wedge_along_x false, from the top edge (row 0, North) to the bottom edge in the same way.
    double wedge_start_um = 0.0, wedge_end_um = 0.0;
    bool wedge_along_x = true;
    std::vector<float> thickness_map_um;     // map: per pixel, µm, row-major like `labels`

    /// Thickness at pixel (x, y) for `grain`: the grain's own thickness if set, else the section's
    /// (uniform, wedge or map).
    double thickness_at(int x, int y, const ThinSectionGrain& grain) const;
    /// The section's own thickness at pixel (x, y), ignoring grain overrides.
    double section_thickness_at(int x, int y) const;

    /// Index into `grains` for each label value 0 … 65535 (or −1), built by index_grains().
    std::vector<int> grain_index_of_label;
    /// Builds grain_index_of_label; throws InputError when a label is outside 0 … 65535 or appears twice.
    void index_grains();
    /// The grain of the pixel (x, y); index_grains() must have been called and the label must have a grain.
    const ThinSectionGrain& grain_at(int x, int y) const;

    /// The labels that occur in the map, ascending, with their pixel counts.
    std::vector<std::pair<std::uint16_t, std::size_t>> label_counts() const;
    /// Checks sizes, pixel size, thicknesses (finite, ≥ 0; uniform and own thicknesses > 0), that the
    /// crystal axes are rotations, and that every label in the map has a grain; throws InputError.
    /// Calls index_grains().
    void validate();
};

/// A uniform number in [0, 1) from the top 53 bits of one draw: the same on every platform (unlike
/// std::uniform_real_distribution, whose algorithm is implementation-defined).
double uniform_unit_interval(std::mt19937_64& rng);

/// The rotation of a uniformly random unit quaternion built from three uniform numbers in [0, 1):
/// K. Shoemake, "Uniform random rotations", Graphics Gems III (Academic Press 1992), pp. 124–132:
/// q = (√(1−u₁) sin 2πu₂, √(1−u₁) cos 2πu₂, √u₁ sin 2πu₃, √u₁ cos 2πu₃). Uniform in the Haar measure on SO(3).
Eigen::Matrix3d shoemake_rotation(double u1, double u2, double u3);

/// ZYZ Euler angles (degrees) of a rotation, the inverse of euler_zyz_deg: β ∈ [0°, 180°]; α and γ in
/// (−180°, 180°]; when β is 0 or 180° (gimbal lock) α is 0. euler_zyz_deg of the result reproduces
/// `rotation` to rounding.
Eigen::Vector3d euler_zyz_deg_of(const Eigen::Matrix3d& rotation);

struct VoronoiSectionSettings {
    std::vector<std::string> minerals;      // names as they will appear in the section (canonical)
    std::vector<double> weights;            // relative frequency of each mineral among the seeds; empty: equal
    /// Relative grain size g of each mineral; empty or all equal: an ordinary Voronoi tessellation.
    /// Otherwise a power diagram (Laguerre tessellation; F. Aurenhammer, "Power diagrams: properties,
    /// algorithms and applications", SIAM J. Comput. 16, 78–96, 1987): a pixel belongs to the seed s
    /// minimising |p − s|² − w_s, with w_s = L²·(g_s − g_min)/ḡ, L = size_px/√grain_count the mean seed
    /// spacing and ḡ the expected g of a seed (by `weights`). Between neighbours a distance ≈ L apart
    /// the boundary moves by (w_a − w_b)/(2L), so to first order a cell's diameter grows by L(g − ḡ)/ḡ:
    /// diameters come out roughly proportional to g. Cells stay convex; small cells beside large ones are
    /// squeezed, some to nothing, so area fractions differ from `weights` (grain counts).
    std::vector<double> grain_sizes;
    int grain_count = 100;                  // seeds, 1 … min(size², 65535)
    int size_px = 512;                      // square map, 16 … 8192
    double pixel_size_um = 2.0;
    double thickness_um = 30.0;             // uniform
    std::uint64_t seed = 1;
    std::string name = "voronoi";

    /// Throws InputError naming the setting and its accepted range.
    void validate() const;
};

/// A random section. `grain_count` seeds are placed uniformly in the square (continuous coordinates in
/// pixels, 0 … size_px); each pixel belongs to the cell whose seed is nearest to the pixel centre (the
/// power distance with grain sizes; ties go to the seed drawn first). Per seed, in order, six numbers are
/// drawn from std::mt19937_64(seed) with uniform_unit_interval: x, y, the mineral (by cumulative weight),
/// then u₁, u₂, u₃ for shoemake_rotation. So without grain sizes the cells and orientations depend only on
/// the seed and the count (the weights choose the minerals only). The draws are the same on every
/// platform; the results are bit-identical for one build and agree elsewhere up to the last bit of sin/cos
/// (orientations) and, for a pixel centre equidistant from two seeds to rounding, its owner. Cells that
/// contain no pixel centre are dropped; labels are 1 … N in the order the seeds were drawn.
ThinSection random_voronoi_section(const VoronoiSectionSettings& settings);

/// The same with plain Voronoi cells (all grain sizes equal).
ThinSection random_voronoi_section(const std::vector<std::string>& minerals, const std::vector<double>& weights,
                                   int grain_count, int size_px, double pixel_size_um, double thickness_um,
                                   std::uint64_t seed);

/// Gives every grain of an optically active mineral (quartz) a handedness, right or left with probability ½
/// each, as they occur in rocks: one uniform_unit_interval draw per such grain, in the order of `grains`, from
/// std::mt19937_64(seed) (a stream of its own, so the tessellation does not change). Other grains keep none.
void draw_handedness(ThinSection& section, const MineralCatalog& catalog, std::uint64_t seed);

}  // namespace petroscope
