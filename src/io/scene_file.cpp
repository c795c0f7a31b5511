#include "petroscope/io/scene_file.hpp"

#include "petroscope/core/error.hpp"
#include "petroscope/io/data_files.hpp"
#include "petroscope/io/image_writer.hpp"
#include "petroscope/io/json_reader.hpp"
#include "petroscope/optics/orientation.hpp"
#include "petroscope/spectral/color.hpp"

#include <Eigen/Geometry>

#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <numbers>

namespace petroscope {
namespace {

constexpr std::array<const char*, kWallCount> kWallNames{"left", "right", "front", "back", "bottom", "top"};
// Textures up to 8192² texels: 256 MiB of palette indices.
constexpr int kMaxTexturePx = 8192;

/// Sigmoid spectra of sRGB-encoded colours, fitted once per 8-bit colour.
class SpectrumPalette {
public:
    explicit SpectrumPalette(const RenderSpectrum& spectrum) : spectrum_(spectrum), rgb_to_xyz_(spectrum.xyz_to_linear_srgb.inverse()) {}

    /// The palette index of an sRGB-encoded colour (components 0 … 1).
    int index(const Eigen::Vector3d& encoded, const JsonValue& where) {
        std::array<int, 3> key{};
        for (int c = 0; c < 3; ++c) {
            if (!(encoded[c] >= 0.0 && encoded[c] <= 1.0)) throw where.error("colour components must lie in 0 … 1");
            key[static_cast<std::size_t>(c)] = static_cast<int>(std::lround(encoded[c] * 255.0));
        }
        const auto found = indices_.find(key);
        if (found != indices_.end()) return found->second;
        Eigen::Vector3d linear;
        for (int c = 0; c < 3; ++c) linear[c] = decode_srgb(key[static_cast<std::size_t>(c)] / 255.0);
        if (key[0] == key[1] && key[1] == key[2]) {
            // Neutral: the light's own spectrum scaled, ρ constant (white and black included, which the
            // sigmoid reaches only in the limit).
            spectra_.push_back(SigmoidSpectrum::constant(linear[0]));
        } else {
            try {
                spectra_.push_back(fit_sigmoid_spectrum(rgb_to_xyz_ * linear, spectrum_.wavelengths_nm, spectrum_.weights));
            } catch (const InputError& e) {
                throw where.error(e.what());
            }
        }
        return indices_[key] = static_cast<int>(spectra_.size()) - 1;
    }
    std::vector<SigmoidSpectrum> take() { return std::move(spectra_); }

private:
    const RenderSpectrum& spectrum_;
    Eigen::Matrix3d rgb_to_xyz_;
    std::map<std::array<int, 3>, int> indices_;
    std::vector<SigmoidSpectrum> spectra_;
};

Eigen::Vector3d vector3(const JsonValue& value) {
    const std::vector<double> v = value.numbers(3);
    return {v[0], v[1], v[2]};
}

int whole_number(const JsonValue& value, int low, int high) {
    const double number = value.number();
    if (number != std::floor(number) || number < low || number > high) {
        throw value.error("expected a whole number from " + std::to_string(low) + " to " + std::to_string(high));
    }
    return static_cast<int>(number);
}

double positive(const JsonValue& value) {
    const double number = value.number();
    if (!(number > 0.0)) throw value.error("expected a number > 0");
    return number;
}

WallEmission texture_wall(const Image& texture, const JsonValue& where, const RenderSpectrum& spectrum) {
    if (texture.channels < 3) throw where.error("expected a colour (RGB) texture");
    if (texture.width > kMaxTexturePx || texture.height > kMaxTexturePx) {
        throw where.error("the texture is " + std::to_string(texture.width) + " x " + std::to_string(texture.height) + " px; at most " +
                          std::to_string(kMaxTexturePx) + " per side");
    }
    WallEmission wall;
    wall.kind = WallEmission::Kind::texture;
    wall.texture_width = texture.width;
    wall.texture_height = texture.height;
    SpectrumPalette palette(spectrum);
    for (int y = 0; y < texture.height; ++y) {
        for (int x = 0; x < texture.width; ++x) {
            const Eigen::Vector3d colour(texture.at(x, y, 0), texture.at(x, y, 1), texture.at(x, y, 2));
            wall.texel_palette_index.push_back(palette.index(colour, where));
        }
    }
    wall.palette = palette.take();
    return wall;
}

WallEmission read_wall(const JsonValue& value, const std::filesystem::path& folder, const RenderSpectrum& spectrum) {
    if (value.raw().is_string()) {
        if (value.text() != "off") throw value.error("expected \"off\" or an object with rgb or texture");
        return {};
    }
    value.only_keys({"rgb", "texture", "scale"});
    WallEmission wall;
    if (value.has("rgb") == value.has("texture")) throw value.error("expected exactly one of rgb and texture");
    if (value.has("rgb")) {
        SpectrumPalette palette(spectrum);
        palette.index(vector3(value["rgb"]), value["rgb"]);
        wall.kind = WallEmission::Kind::uniform;
        wall.uniform = palette.take().front();
    } else {
        const JsonValue texture = value["texture"];
        if (texture.raw().is_string()) {
            const std::filesystem::path path = folder / texture.text();
            Image image;
            try {
                image = read_image(path);
            } catch (const InputError& e) {
                throw texture.error(e.what());
            }
            wall = texture_wall(image, texture, spectrum);
        } else {
            texture.only_keys({"colour_grid"});
            const JsonValue grid = texture["colour_grid"];
            grid.only_keys({"cells", "border_cells", "cell_px", "border_grey"});
            const JsonValue cells = grid["cells"];
            if (cells.size() != 2) throw cells.error("expected [columns, rows]");
            const int border = grid.has("border_cells") ? whole_number(grid["border_cells"], 0, 100) : 3;
            const int columns = whole_number(cells.at(0), 2 * border + 1, 1000), rows = whole_number(cells.at(1), 2 * border + 1, 1000);
            const int cell_px = grid.has("cell_px") ? whole_number(grid["cell_px"], 1, 256) : 16;
            if (columns * cell_px > kMaxTexturePx || rows * cell_px > kMaxTexturePx) {
                throw grid.error("the texture would be " + std::to_string(columns * cell_px) + " x " + std::to_string(rows * cell_px) +
                                 " px; at most " + std::to_string(kMaxTexturePx) + " per side");
            }
            const double grey = grid.has("border_grey") ? grid["border_grey"].number() : 0.5;
            if (!(grey >= 0.0 && grey <= 1.0)) throw grid["border_grey"].error("expected a value from 0 to 1");
            wall = texture_wall(colour_grid_texture(columns, rows, border, cell_px, grey), grid, spectrum);
        }
    }
    if (value.has("scale")) wall.scale = positive(value["scale"]);
    return wall;
}

SceneCrystal read_crystal(const JsonValue& value, const MineralCatalog& catalog, const SceneBox& box) {
    value.only_keys({"mineral", "calcite_rhomb", "vertices_mm", "faces", "euler_zyz_deg", "on_bottom"});
    SceneCrystal crystal;
    const JsonValue mineral_name = value["mineral"];
    std::shared_ptr<const Mineral> mineral;
    try {
        mineral = std::make_shared<const Mineral>(catalog.find(mineral_name.text()));
    } catch (const InputError& e) {
        throw mineral_name.error(e.what());
    }
    if (mineral->absorbing()) {
        throw mineral_name.error(mineral->name + " absorbs light; scenes take transparent crystals only (the renderer has no attenuation inside crystals)");
    }
    if (mineral->optically_active()) {
        throw mineral_name.error(mineral->name + " is optically active, which the renderer does not model yet; scenes take inactive crystals only");
    }
    crystal.mineral = mineral->name;
    crystal.principal_n = [mineral](double wavelength_nm) { return mineral->principal_n(wavelength_nm); };
    if (value.has("calcite_rhomb") == value.has("vertices_mm")) throw value.error("expected exactly one of calcite_rhomb and vertices_mm (with faces)");
    Eigen::Vector3d optic_axis = Eigen::Vector3d::UnitZ();
    if (value.has("calcite_rhomb")) {
        const JsonValue rhomb = value["calcite_rhomb"];
        rhomb.only_keys({"edges_mm"});
        const std::vector<double> edges = rhomb["edges_mm"].numbers(3);
        CalciteRhomb shape;
        try {
            shape = calcite_rhomb({edges[0], edges[1], edges[2]});
        } catch (const InputError& e) {
            throw rhomb["edges_mm"].error(e.what());
        }
        if (value.has("euler_zyz_deg")) throw value["euler_zyz_deg"].error("a calcite rhomb's optic axis follows from its shape; remove euler_zyz_deg");
        if (!value.has("on_bottom")) throw value.error("a calcite_rhomb needs on_bottom (where it lies on the bottom wall)");
        const JsonValue place = value["on_bottom"];
        place.only_keys({"center_mm", "azimuth_deg", "gap_mm"});
        const std::vector<double> center = place["center_mm"].numbers(2);
        const double azimuth = place.has("azimuth_deg") ? place["azimuth_deg"].number() : 0.0;
        // Lying on face 0: its outward normal turned to −z, then the azimuth about z.
        const Eigen::Matrix3d turn = (Eigen::AngleAxisd(azimuth * std::numbers::pi / 180.0, Eigen::Vector3d::UnitZ()) *
                                      Eigen::Quaterniond::FromTwoVectors(shape.polyhedron.face_normals[0], -Eigen::Vector3d::UnitZ()))
                                         .toRotationMatrix();
        std::vector<Eigen::Vector3d> vertices;
        Eigen::Vector3d lower = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity()), upper = -lower;
        for (const auto& v : shape.polyhedron.vertices) {
            vertices.push_back(turn * v);
            lower = lower.cwiseMin(vertices.back());
            upper = upper.cwiseMax(vertices.back());
        }
        // The smallest safe gap: well above the rounding of the intersection points (1e-10 of the scene).
        const double gap = place.has("gap_mm") ? positive(place["gap_mm"]) : 1e-8 * (box.upper_mm - box.lower_mm).norm();
        const Eigen::Vector3d middle = 0.5 * (lower + upper);
        const Eigen::Vector3d shift(center[0] - middle.x(), center[1] - middle.y(), box.lower_mm.z() + gap - lower.z());
        for (auto& v : vertices) v += shift;
        crystal.shape = make_convex_polyhedron(vertices, shape.polyhedron.faces);
        optic_axis = turn * shape.optic_axis;
        const Eigen::Vector3d x = optic_axis.unitOrthogonal();
        crystal.axes << x, optic_axis.cross(x), optic_axis;
        return crystal;
    }
    if (value.has("on_bottom")) throw value["on_bottom"].error("on_bottom places a calcite_rhomb; give the vertices in scene coordinates instead");
    const JsonValue vertex_list = value["vertices_mm"];
    std::vector<Eigen::Vector3d> vertices;
    for (std::size_t i = 0; i < vertex_list.size(); ++i) vertices.push_back(vector3(vertex_list.at(i)));
    const JsonValue face_list = value["faces"];
    std::vector<std::vector<int>> faces;
    for (std::size_t f = 0; f < face_list.size(); ++f) {
        const JsonValue face = face_list.at(f);
        std::vector<int> indices;
        for (std::size_t i = 0; i < face.size(); ++i) indices.push_back(whole_number(face.at(i), 0, 1 << 20));
        faces.push_back(indices);
    }
    try {
        crystal.shape = make_convex_polyhedron(vertices, faces);
    } catch (const InputError& e) {
        throw value.error(e.what());
    }
    const std::vector<double> euler = value.has("euler_zyz_deg") ? value["euler_zyz_deg"].numbers(3) : std::vector<double>{0.0, 0.0, 0.0};
    crystal.axes = euler_zyz_deg(euler[0], euler[1], euler[2]);
    return crystal;
}

}  // namespace

Image colour_grid_texture(int cells_x, int cells_y, int border_cells, int cell_px, double border_grey) {
    Image texture(cells_x * cell_px, cells_y * cell_px, 3);
    int k = 0;
    for (int cy = 0; cy < cells_y; ++cy) {
        for (int cx = 0; cx < cells_x; ++cx) {
            Eigen::Vector3d rgb = Eigen::Vector3d::Constant(border_grey);
            const bool border = cx < border_cells || cy < border_cells || cx >= cells_x - border_cells || cy >= cells_y - border_cells;
            if (!border) {
                // Hues spread by the golden ratio; two saturations and two values alternate (HSV, sRGB-encoded).
                const double hue = std::fmod(0.61803398875 * k, 1.0) * 6.0, saturation = k % 2 ? 0.55 : 0.85, value = (k / 2) % 2 ? 0.7 : 0.95;
                ++k;
                const int sector = static_cast<int>(hue) % 6;
                const double f = hue - std::floor(hue), p = value * (1 - saturation), q = value * (1 - saturation * f), t = value * (1 - saturation * (1 - f));
                const std::array<Eigen::Vector3d, 6> sectors{Eigen::Vector3d(value, t, p), Eigen::Vector3d(q, value, p), Eigen::Vector3d(p, value, t),
                                                             Eigen::Vector3d(p, q, value), Eigen::Vector3d(t, p, value), Eigen::Vector3d(value, p, q)};
                rgb = sectors[static_cast<std::size_t>(sector)];
            }
            for (int y = 0; y < cell_px; ++y) {
                for (int x = 0; x < cell_px; ++x) {
                    for (int c = 0; c < 3; ++c) texture.at(cx * cell_px + x, cy * cell_px + y, c) = static_cast<float>(rgb[c]);
                }
            }
        }
    }
    return texture;
}

Scene read_scene(const std::filesystem::path& file, const MineralCatalog& catalog, const RenderSpectrum& spectrum) {
    return parse_scene(read_text_file(file), file, catalog, spectrum);
}

Scene parse_scene(const std::string& text, const std::filesystem::path& file, const MineralCatalog& catalog, const RenderSpectrum& spectrum) {
    const nlohmann::json document = parse_json_text(text, file.string());
    const JsonValue root(document, file.string(), "");
    root.only_keys({"description", "box", "crystals", "camera"});
    Scene scene;
    const JsonValue box = root["box"];
    box.only_keys({"lower_mm", "upper_mm", "walls"});
    scene.box.lower_mm = vector3(box["lower_mm"]);
    scene.box.upper_mm = vector3(box["upper_mm"]);
    if (!((scene.box.upper_mm - scene.box.lower_mm).minCoeff() > 0.0)) throw box.error("upper_mm must exceed lower_mm along x, y and z");
    if (box.has("walls")) {
        const JsonValue walls = box["walls"];
        walls.only_keys({kWallNames.begin(), kWallNames.end()});
        for (std::size_t w = 0; w < kWallNames.size(); ++w) {
            if (walls.has(kWallNames[w])) scene.box.walls[w] = read_wall(walls[kWallNames[w]], file.parent_path(), spectrum);
        }
    }
    if (root.has("crystals")) {
        const JsonValue crystals = root["crystals"];
        for (std::size_t c = 0; c < crystals.size(); ++c) scene.crystals.push_back(read_crystal(crystals.at(c), catalog, scene.box));
    }
    const JsonValue camera = root["camera"];
    camera.only_keys({"position_mm", "target_mm", "up", "sensor_width_mm", "sensor_height_mm", "sensor_distance_mm", "width_px", "height_px",
                      "polarizer_deg"});
    SceneCamera& c = scene.camera;
    c.position_mm = vector3(camera["position_mm"]);
    c.target_mm = vector3(camera["target_mm"]);
    if (camera.has("up")) c.up = vector3(camera["up"]);
    c.sensor_width_mm = positive(camera["sensor_width_mm"]);
    c.sensor_height_mm = positive(camera["sensor_height_mm"]);
    c.sensor_distance_mm = positive(camera["sensor_distance_mm"]);
    c.width_px = whole_number(camera["width_px"], 1, 16384);
    c.height_px = whole_number(camera["height_px"], 1, 16384);
    if (camera.has("polarizer_deg")) {
        c.has_polarizer = true;
        c.polarizer_deg = camera["polarizer_deg"].number();
    }
    try {
        check_scene(scene);
    } catch (const InputError& e) {
        throw InputError(file.string() + ": " + e.what());
    }
    return scene;
}

}  // namespace petroscope
