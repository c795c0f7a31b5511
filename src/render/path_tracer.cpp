#include "petroscope/render/path_tracer.hpp"

#include "face_transfer.hpp"

#include "petroscope/core/error.hpp"
#include "petroscope/spectral/color.hpp"
#include "petroscope/spectral/wavelength_grid.hpp"

#include <Eigen/Geometry>

#include <atomic>
#include <exception>
#include <chrono>
#include <cmath>
#include <limits>
#include <numbers>
#include <unordered_map>

namespace petroscope {
namespace {

using detail::Branch;

/// SplitMix64 (Steele, Lea & Flood, "Fast splittable pseudorandom number generators", OOPSLA 2014):
/// one stream per pixel, seeded from the pixel index, so that images do not depend on the thread count.
class Random {
public:
    /// Stream `stream` of seed `seed`: the state starts at a mix of both, so that neighbouring streams are
    /// not shifted copies of each other (SplitMix64 steps its state by a constant).
    Random(std::uint64_t seed, std::uint64_t stream) : state_(mix(mix(seed) + stream)) {}
    std::uint64_t next() { return mix(state_ += 0x9e3779b97f4a7c15ULL); }
    double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }

private:
    static std::uint64_t mix(std::uint64_t z) {
        z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
        z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
        return z ^ (z >> 31);
    }
    std::uint64_t state_;
};

/// The random numbers of one pixel's samples; each is uniform on [0, 1) by itself, so every estimate stays
/// unbiased, while the pixel's samples together cover [0, 1) evenly:
/// - the wavelength coordinate of sample i lies in stratum i of spp, at offset o for even i and 1 − o for
///   odd i, one random o per pixel: an antithetic pair of strata is symmetric about its middle, so the
///   error of a smooth spectral integrand loses its first-order term (O(1/spp²) instead of O(1/spp));
/// - the first kStratifiedDecisions (4) decisions along each path (branch choices and roulette, in the
///   order a path meets them) are Latin-hypercube stratified (McKay, Beckman & Conover 1979): decision j
///   of sample i draws from stratum π_j(i) of spp, π_j a random permutation. Later decisions draw
///   independently.
/// Not `stratified`: every number is drawn independently (plain Monte Carlo).
class PixelSampler {
public:
    static constexpr std::size_t kStratifiedDecisions = 4;

    PixelSampler(Random& random, int samples, bool stratified)
        : random_(random), samples_(samples), stratified_(stratified), offset_(random.uniform()), permutations_(stratified ? kStratifiedDecisions : 0) {
        for (std::vector<int>& permutation : permutations_) {
            permutation.resize(static_cast<std::size_t>(samples));
            for (int i = 0; i < samples; ++i) permutation[static_cast<std::size_t>(i)] = i;
            // Fisher–Yates.
            for (int i = samples - 1; i > 0; --i) {
                const auto j = static_cast<int>(random.next() % static_cast<std::uint64_t>(i + 1));
                std::swap(permutation[static_cast<std::size_t>(i)], permutation[static_cast<std::size_t>(j)]);
            }
        }
    }
    void start_sample(int sample) { sample_ = sample; }
    double wavelength_coordinate() {
        if (!stratified_) return random_.uniform();
        return (sample_ + (sample_ % 2 == 1 ? 1.0 - offset_ : offset_)) / samples_;
    }
    /// Decision `decision` (0, 1, … along the path) of the current sample.
    double decision(int decision) {
        if (decision >= static_cast<int>(permutations_.size())) return random_.uniform();
        const int stratum = permutations_[static_cast<std::size_t>(decision)][static_cast<std::size_t>(sample_)];
        return (stratum + random_.uniform()) / samples_;
    }
private:
    Random& random_;
    int samples_;
    bool stratified_;
    double offset_;
    int sample_ = 0;
    std::vector<std::vector<int>> permutations_;
};

struct CameraFrame {
    Eigen::Vector3d forward, right, up;
};

CameraFrame camera_frame(const SceneCamera& camera) {
    CameraFrame frame;
    frame.forward = (camera.target_mm - camera.position_mm).normalized();
    frame.right = frame.forward.cross(camera.up).normalized();
    frame.up = frame.right.cross(frame.forward);
    return frame;
}

/// Where a ray from inside the box (or entering it) leaves it: the distance and the wall.
std::pair<double, Wall> box_exit(const SceneBox& box, const Eigen::Vector3d& origin, const Eigen::Vector3d& direction) {
    double best = std::numeric_limits<double>::infinity();
    Wall wall = Wall::bottom;
    static constexpr std::array<Wall, 3> lower_walls{Wall::left, Wall::front, Wall::bottom}, upper_walls{Wall::right, Wall::back, Wall::top};
    for (int axis = 0; axis < 3; ++axis) {
        if (direction[axis] == 0.0) continue;
        const bool up = direction[axis] > 0.0;
        const double t = ((up ? box.upper_mm[axis] : box.lower_mm[axis]) - origin[axis]) / direction[axis];
        if (t < best) {
            best = t;
            wall = up ? upper_walls[static_cast<std::size_t>(axis)] : lower_walls[static_cast<std::size_t>(axis)];
        }
    }
    return {best, wall};
}

/// The distance along the ray to where it enters the box (0 when it starts inside); nullopt if it misses.
std::optional<double> box_entry(const SceneBox& box, const Eigen::Vector3d& origin, const Eigen::Vector3d& direction) {
    double enter = 0.0, leave = std::numeric_limits<double>::infinity();
    for (int axis = 0; axis < 3; ++axis) {
        if (direction[axis] == 0.0) {
            if (origin[axis] < box.lower_mm[axis] || origin[axis] > box.upper_mm[axis]) return std::nullopt;
            continue;
        }
        double t0 = (box.lower_mm[axis] - origin[axis]) / direction[axis], t1 = (box.upper_mm[axis] - origin[axis]) / direction[axis];
        if (t0 > t1) std::swap(t0, t1);
        enter = std::max(enter, t0);
        leave = std::min(leave, t1);
    }
    if (enter >= leave) return std::nullopt;
    return enter;
}

/// The emitting point of a wall: its spectrum (nullptr when off) and the wall's scale.
std::pair<const SigmoidSpectrum*, double> wall_spectrum(const SceneBox& box, Wall wall, const Eigen::Vector3d& point) {
    const WallEmission& emission = box.walls[static_cast<std::size_t>(wall)];
    if (emission.kind == WallEmission::Kind::off) return {nullptr, 0.0};
    const auto [u_axis, v_axis] = wall_texture_axes(wall);
    const Eigen::Vector3d relative = (point - box.lower_mm).cwiseQuotient(box.upper_mm - box.lower_mm);  // 0 … 1 per axis
    const auto coordinate = [&](const Eigen::Vector3d& axis) {
        int a = 0;
        axis.cwiseAbs().maxCoeff(&a);
        return axis[a] > 0.0 ? relative[a] : 1.0 - relative[a];
    };
    return {emission.spectrum_at(coordinate(u_axis), coordinate(v_axis)), emission.scale};
}

/// Picks one branch with probability ∝ power; returns its index and probability.
std::pair<std::size_t, double> choose(const std::vector<Branch>& branches, double random) {
    double total = 0.0;
    for (const Branch& b : branches) total += b.power;
    double target = random * total;
    for (std::size_t k = 0; k < branches.size(); ++k) {
        target -= branches[k].power;
        if (target < 0.0 || k + 1 == branches.size()) return {k, branches[k].power / total};
    }
    return {0, 0.0};
}

using Contribution = Eigen::Matrix<double, 4, 3>;  // rows S0 … S3, columns X, Y, Z

class PathTracer {
public:
    PathTracer(const Scene& scene, const RenderSpectrum& spectrum, const RenderSettings& settings)
        : scene_(scene), spectrum_(spectrum), settings_(settings) {
        const double size = (scene.box.upper_mm - scene.box.lower_mm).norm();
        epsilon_mm_ = 1e-10 * size;
        // Wavelengths drawn ∝ x̄ + ȳ + z̄ weights (importance sampling; every weight is positive on the grid).
        double total = 0.0;
        for (const Eigen::Vector3d& w : spectrum.weights) {
            total += w.sum();
            cdf_.push_back(total);
        }
        for (double& c : cdf_) c /= total;
        for (const Eigen::Vector3d& w : spectrum.weights) probability_.push_back(w.sum() / total);
        // The exact colour of every wall spectrum, for paths whose geometry does not depend on wavelength.
        for (const WallEmission& wall : scene.box.walls) {
            const auto add = [&](const SigmoidSpectrum& s) {
                Eigen::Vector3d xyz = Eigen::Vector3d::Zero();
                for (std::size_t i = 0; i < spectrum.weights.size(); ++i) xyz += s(spectrum.wavelengths_nm[i]) * spectrum.weights[i];
                colour_[&s] = xyz;
            };
            add(wall.uniform);
            for (const SigmoidSpectrum& s : wall.palette) add(s);
        }
    }

    /// The wavelength index of stratum coordinate `u` ∈ [0, 1) (inverse CDF).
    std::size_t wavelength_index(double u) const {
        return std::min(static_cast<std::size_t>(std::upper_bound(cdf_.begin(), cdf_.end(), u) - cdf_.begin()), cdf_.size() - 1);
    }

    /// The light reaching the camera along `direction`: its Stokes vector (camera frame) times XYZ,
    /// relative to the white. A path that meets no crystal does not depend on wavelength and gets the
    /// exact colour of the wall it sees; one that does is followed at wavelength `index` and weighted by
    /// 1/pdf.
    Contribution trace(const Eigen::Vector3d& camera_position, const Eigen::Vector3d& direction, const Eigen::Vector3d& camera_s,
                       std::size_t index, PixelSampler& sampler, RenderStatistics& statistics) const {
        const std::optional<double> entry = box_entry(scene_.box, camera_position, direction);
        if (!entry) return Contribution::Zero();
        PathState path;
        path.position = camera_position + *entry * direction;
        path.d = direction;
        // The camera's (ŝ, p̂) has p̂ = −up: S2 and S3 change sign to the (right, up) frame.
        path.mueller = Eigen::Vector4d(1, 1, -1, -1).asDiagonal();
        path.s_hat = camera_s;
        return follow(path, index, sampler, statistics);
    }

private:
    /// A path being traced backward. In air: camera Stokes = mueller · S, S in the basis (s_hat,
    /// s_hat × k) of the light travelling along k = −d. In a crystal: camera Stokes = column · P, P the
    /// power of the mode `mode` travelling along −wave_normal.
    struct PathState {
        Eigen::Vector3d position, d;
        Eigen::Matrix4d mueller = Eigen::Matrix4d::Identity();
        Eigen::Vector3d s_hat;
        Eigen::Vector4d column = Eigen::Vector4d::Zero();
        int crystal = -1;
        InterfaceMode mode = InterfaceMode::isotropic;
        Eigen::Vector3d wave_normal = Eigen::Vector3d::Zero();
        int depth = 0;  // crystal-face interactions so far
        int decisions = 0;  // random decisions (branch choices, roulette) so far
        /// The fraction of the camera ray's power that the path carries (the product of its branches'
        /// powers over their probabilities): 1 while it is followed by power alone, less after splits.
        double power = 1.0;
    };

    /// Follows `path` to a wall. At the first `split_depth` interactions every branch is followed with
    /// its full transfer; later one is chosen by power.
    Contribution follow(PathState path, std::size_t index, PixelSampler& sampler, RenderStatistics& statistics) const {
        const double wavelength_nm = spectrum_.wavelengths_nm[index];
        const OpticalMedium air = OpticalMedium::isotropic(1.0);
        for (;; ++path.depth) {
            if (path.depth >= settings_.max_depth) {
                ++statistics.depth_limited;
                return Contribution::Zero();
            }
            if (path.depth >= settings_.roulette_depth && path.power < settings_.roulette_power) {
                const double survive = path.power / settings_.roulette_power;
                if (sampler.decision(path.decisions++) >= survive) {
                    ++statistics.roulette_killed;
                    return Contribution::Zero();
                }
                path.power = settings_.roulette_power;
                if (path.crystal < 0) path.mueller /= survive; else path.column /= survive;
            }
            std::vector<Branch> branches;
            Eigen::Vector3d outward;
            const bool from_outside = path.crystal < 0;
            int hit_crystal = path.crystal;
            if (from_outside) {
                // Air: the nearest crystal face ahead, or the wall.
                double nearest = std::numeric_limits<double>::infinity();
                int face = -1;
                for (std::size_t c = 0; c < scene_.crystals.size(); ++c) {
                    const std::optional<PolyhedronHit> hit = intersect(scene_.crystals[c].shape, path.position, path.d);
                    if (hit && hit->t_enter > epsilon_mm_ && hit->t_enter < nearest) {
                        nearest = hit->t_enter;
                        face = hit->face_enter;
                        hit_crystal = static_cast<int>(c);
                    }
                }
                const auto [t_wall, wall] = box_exit(scene_.box, path.position, path.d);
                if (hit_crystal < 0 || t_wall < nearest) {
                    const auto [emitter, scale] = wall_spectrum(scene_.box, wall, path.position + t_wall * path.d);
                    if (!emitter) return Contribution::Zero();
                    const Eigen::Vector3d xyz = path.depth > 0 ? Eigen::Vector3d((*emitter)(wavelength_nm) / probability_[index] * spectrum_.weights[index])
                                                               : colour_.at(emitter);
                    return path.mueller.col(0) * (scale * xyz).transpose();
                }
                path.position += nearest * path.d;
                outward = scene_.crystals[static_cast<std::size_t>(hit_crystal)].shape.face_normals[static_cast<std::size_t>(face)];
                branches = detail::branches_from_outside(outward, path.d, air, crystal_medium(hit_crystal, wavelength_nm));
            } else {
                // Inside a crystal: the face the ray leaves through.
                const ConvexPolyhedron& shape = scene_.crystals[static_cast<std::size_t>(path.crystal)].shape;
                const std::optional<std::pair<double, int>> exit = exit_from_inside(shape, path.position, path.d);
                if (!exit) return inconsistent(statistics);
                path.position += exit->first * path.d;
                outward = shape.face_normals[static_cast<std::size_t>(exit->second)];
                if (detail::walks_off(path.wave_normal, outward)) return walked_off(statistics);
                branches = detail::branches_from_inside(outward, path.wave_normal, path.mode, air, crystal_medium(path.crystal, wavelength_nm));
            }
            ++statistics.crystal_interactions;
            if (branches.empty()) return Contribution::Zero();
            if (path.depth < settings_.split_depth) {
                Contribution sum = Contribution::Zero();
                for (const Branch& b : branches) {
                    PathState next = path;
                    take(next, b, 1.0, from_outside, hit_crystal, outward);
                    ++next.depth;
                    sum += follow(next, index, sampler, statistics);
                }
                return sum;
            }
            const auto [chosen, probability] = choose(branches, sampler.decision(path.decisions++));
            take(path, branches[chosen], probability, from_outside, hit_crystal, outward);
        }
    }

    /// Moves `path` onto branch `b` (taken with `probability`) at the face with `outward` normal of crystal
    /// `crystal`. Every forward transfer onto the traced wave comes from the reversed problem's branch by
    /// reciprocity (face_transfer.hpp): one interface solve per face interaction.
    void take(PathState& path, const Branch& b, double probability, bool from_outside, int crystal, const Eigen::Vector3d& outward) const {
        if (from_outside) {
            if (!b.in_crystal) {
                path.mueller = path.mueller * detail::stokes_frame_change(detail::s_basis(-outward, -path.d), path.s_hat, -path.d) *
                               detail::reflection_mueller(b) / probability;
                path.s_hat = detail::s_basis(-outward, -b.wave_normal);
            } else {
                path.column = path.mueller * detail::stokes_frame_change(detail::s_basis(outward, -path.d), path.s_hat, -path.d) *
                              detail::refraction_out_stokes(b) / probability;
                path.crystal = crystal;
                path.mode = b.mode;
                path.wave_normal = b.wave_normal;
            }
        } else if (b.in_crystal) {
            path.column *= b.power / probability;
            path.mode = b.mode;
            path.wave_normal = b.wave_normal;
        } else {
            path.mueller = path.column * detail::refraction_in_row(b) / probability;
            path.s_hat = detail::s_basis(-outward, -b.wave_normal);
            path.crystal = -1;
        }
        path.d = b.ray;
        path.power *= b.power / probability;
    }

    OpticalMedium crystal_medium(int crystal, double wavelength_nm) const {
        const SceneCrystal& c = scene_.crystals[static_cast<std::size_t>(crystal)];
        return OpticalMedium{c.principal_n(wavelength_nm).cast<std::complex<double>>(), c.axes};
    }
    static Contribution walked_off(RenderStatistics& statistics) {
        ++statistics.walked_off;
        return Contribution::Zero();
    }
    static Contribution inconsistent(RenderStatistics& statistics) {
        ++statistics.inconsistent;
        return Contribution::Zero();
    }

    const Scene& scene_;
    const RenderSpectrum& spectrum_;
    const RenderSettings& settings_;
    std::vector<double> cdf_, probability_;
    std::unordered_map<const SigmoidSpectrum*, Eigen::Vector3d> colour_;
    double epsilon_mm_ = 0.0;
};

}  // namespace

RenderSpectrum render_spectrum(const ColorMatchingFunctions& cmf, const LightSource& light) {
    RenderSpectrum spectrum;
    spectrum.wavelengths_nm = WavelengthGrid{380.0, 780.0, 1.0}.wavelengths_nm();
    const SpectralIntegrator integrator(spectrum.wavelengths_nm, cmf, light);
    spectrum.weights = integrator.weights();
    spectrum.xyz_to_linear_srgb = xyz_to_display_matrix(integrator.white_xyz(), true, 1.0);
    return spectrum;
}

Image RenderResult::camera_xyz(bool polarizer, double polarizer_deg) const {
    Image xyz(stokes_xyz.width, stokes_xyz.height, 3);
    const double angle = 2.0 * polarizer_deg * std::numbers::pi / 180.0;
    const double c1 = polarizer ? 0.5 * std::cos(angle) : 0.0, c2 = polarizer ? 0.5 * std::sin(angle) : 0.0, c0 = polarizer ? 0.5 : 1.0;
    for (int y = 0; y < xyz.height; ++y) {
        for (int x = 0; x < xyz.width; ++x) {
            for (int c = 0; c < 3; ++c) {
                xyz.at(x, y, c) = static_cast<float>(c0 * stokes_xyz.at(x, y, c) + c1 * stokes_xyz.at(x, y, 3 + c) + c2 * stokes_xyz.at(x, y, 6 + c));
            }
        }
    }
    return xyz;
}

RenderResult render_scene(const Scene& scene, const RenderSpectrum& spectrum, const RenderSettings& settings, const ProgressCallback& progress) {
    check_scene(scene);
    if (settings.samples_per_pixel < 1) throw InputError("samples per pixel must be >= 1");
    if (settings.max_depth < 1) throw InputError("the trace depth must be >= 1");
    const auto started = std::chrono::steady_clock::now();
    const SceneCamera& camera = scene.camera;
    const CameraFrame frame = camera_frame(camera);
    const PathTracer tracer(scene, spectrum, settings);
    const int width = camera.width_px, height = camera.height_px, spp = settings.samples_per_pixel;
    RenderResult result;
    result.stokes_xyz = Image(width, height, 12);
    result.standard_error_y = Image(width, height, 4);
    // One pixel: its samples' mean Stokes × XYZ and the standard errors of its Y.
    const auto render_pixel = [&](int column, int row, RenderStatistics& statistics) {
        const std::uint64_t pixel = static_cast<std::uint64_t>(row) * static_cast<std::uint64_t>(width) + static_cast<std::uint64_t>(column);
        Random random(settings.seed, pixel);
        PixelSampler sampler(random, spp, settings.stratified);
        Contribution sum = Contribution::Zero();
        Eigen::Vector4d sum_y2 = Eigen::Vector4d::Zero();
        for (int sample = 0; sample < spp; ++sample) {
            sampler.start_sample(sample);
            // Wavelengths stratified within the pixel (PixelSampler), positions uniform in the pixel.
            const std::size_t index = tracer.wavelength_index(sampler.wavelength_coordinate());
            const double sx = ((column + random.uniform()) / width - 0.5) * camera.sensor_width_mm;
            const double sy = (0.5 - (row + random.uniform()) / height) * camera.sensor_height_mm;
            const Eigen::Vector3d d = (camera.sensor_distance_mm * frame.forward + sx * frame.right + sy * frame.up).normalized();
            const Eigen::Vector3d camera_s = (frame.right - frame.right.dot(d) * d).normalized();
            ++statistics.paths;
            const Contribution contribution = tracer.trace(camera.position_mm, d, camera_s, index, sampler, statistics);
            sum += contribution;
            sum_y2 += contribution.col(1).cwiseAbs2();
        }
        for (int s = 0; s < 4; ++s) {
            for (int c = 0; c < 3; ++c) result.stokes_xyz.at(column, row, 3 * s + c) = static_cast<float>(sum(s, c) / spp);
            const double mean_y = sum(s, 1) / spp;
            const double variance = spp > 1 ? std::max(sum_y2[s] / spp - mean_y * mean_y, 0.0) * spp / (spp - 1) : 0.0;
            result.standard_error_y.at(column, row, s) = static_cast<float>(std::sqrt(variance / spp));
        }
    };
    ProgressRelay relay(progress);
    std::atomic<int> rows_done{0};
    RenderStatistics totals;
    std::exception_ptr failure;
#pragma omp parallel
    {
        RenderStatistics statistics;
#pragma omp for schedule(dynamic, 1)
        for (int row = 0; row < height; ++row) {
            // An exception may not leave an OpenMP region: the first is kept, the other rows skipped.
            bool failed = false;
#pragma omp critical(render_failure)
            failed = static_cast<bool>(failure);
            if (failed || relay.cancelled()) continue;
            try {
                for (int column = 0; column < width; ++column) render_pixel(column, row, statistics);
            } catch (...) {
#pragma omp critical(render_failure)
                if (!failure) failure = std::current_exception();
            }
            relay.count_done(rows_done, height);
        }
#pragma omp critical
        {
            totals.paths += statistics.paths;
            totals.crystal_interactions += statistics.crystal_interactions;
            totals.depth_limited += statistics.depth_limited;
            totals.roulette_killed += statistics.roulette_killed;
            totals.inconsistent += statistics.inconsistent;
            totals.walked_off += statistics.walked_off;
        }
    }
    if (failure) std::rethrow_exception(failure);
    relay.finish();
    totals.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    result.statistics = totals;
    return result;
}

}  // namespace petroscope
