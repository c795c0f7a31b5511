#include "petroscope/render/polyhedron.hpp"

#include "petroscope/core/error.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <string>

namespace petroscope {

Eigen::Vector3d ConvexPolyhedron::lower() const {
    Eigen::Vector3d low = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
    for (const auto& v : vertices) low = low.cwiseMin(v);
    return low;
}

Eigen::Vector3d ConvexPolyhedron::upper() const {
    Eigen::Vector3d high = Eigen::Vector3d::Constant(-std::numeric_limits<double>::infinity());
    for (const auto& v : vertices) high = high.cwiseMax(v);
    return high;
}

bool ConvexPolyhedron::contains(const Eigen::Vector3d& point, double tolerance) const {
    for (std::size_t f = 0; f < faces.size(); ++f) {
        if (face_normals[f].dot(point) - face_offsets[f] > tolerance) return false;
    }
    return true;
}

ConvexPolyhedron make_convex_polyhedron(std::vector<Eigen::Vector3d> vertices, std::vector<std::vector<int>> faces) {
    if (vertices.size() < 4) throw InputError("a polyhedron needs at least 4 vertices, got " + std::to_string(vertices.size()));
    if (faces.size() < 4) throw InputError("a polyhedron needs at least 4 faces, got " + std::to_string(faces.size()));
    ConvexPolyhedron p;
    p.vertices = std::move(vertices);
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
    for (const auto& v : p.vertices) {
        if (!v.allFinite()) throw InputError("a vertex is not finite");
        centroid += v;
    }
    centroid /= static_cast<double>(p.vertices.size());
    const double size = (p.upper() - p.lower()).norm();
    if (!(size > 0.0)) throw InputError("the polyhedron's vertices all coincide");
    const double tolerance = 1e-9 * size;
    std::map<std::pair<int, int>, int> edge_uses;
    for (std::size_t f = 0; f < faces.size(); ++f) {
        const std::string name = "face " + std::to_string(f);
        std::vector<int>& face = faces[f];
        if (face.size() < 3) throw InputError(name + " has " + std::to_string(face.size()) + " vertices (at least 3)");
        for (const int index : face) {
            if (index < 0 || index >= static_cast<int>(p.vertices.size())) {
                throw InputError(name + " names vertex " + std::to_string(index) + ", but there are " + std::to_string(p.vertices.size()));
            }
        }
        // Newell's method: the normal of a planar polygon from all its edges (robust to collinear corners).
        Eigen::Vector3d normal = Eigen::Vector3d::Zero();
        for (std::size_t i = 0; i < face.size(); ++i) normal += p.vertices[face[i]].cross(p.vertices[face[(i + 1) % face.size()]]);
        if (!(normal.norm() > tolerance * size)) throw InputError(name + " has no area");
        normal.normalize();
        double offset = normal.dot(p.vertices[face[0]]);
        if (offset - normal.dot(centroid) < 0.0) {
            std::reverse(face.begin(), face.end());
            normal = -normal;
            offset = -offset;
        }
        for (const int index : face) {
            if (std::abs(normal.dot(p.vertices[index]) - offset) > 1e-6 * size) throw InputError(name + " is not planar");
        }
        for (std::size_t v = 0; v < p.vertices.size(); ++v) {
            if (normal.dot(p.vertices[v]) - offset > tolerance) {
                throw InputError("the polyhedron is not convex: vertex " + std::to_string(v) + " lies outside the plane of " + name);
            }
        }
        for (std::size_t i = 0; i < face.size(); ++i) {
            const int a = face[i], b = face[(i + 1) % face.size()];
            if (a == b) throw InputError(name + " repeats vertex " + std::to_string(a));
            ++edge_uses[{std::min(a, b), std::max(a, b)}];
        }
        p.face_normals.push_back(normal);
        p.face_offsets.push_back(offset);
    }
    for (const auto& [edge, uses] : edge_uses) {
        if (uses != 2) {
            throw InputError("the polyhedron is not closed: edge " + std::to_string(edge.first) + "-" + std::to_string(edge.second) + " belongs to " +
                             std::to_string(uses) + " face" + (uses == 1 ? "" : "s") + " (every edge must join exactly two)");
        }
    }
    p.faces = std::move(faces);
    return p;
}

CalciteRhomb calcite_rhomb(const std::array<double, 3>& edges_mm) {
    for (const double edge : edges_mm) {
        if (!(edge > 0.0) || !std::isfinite(edge)) throw InputError("a calcite rhomb's edges must be positive lengths");
    }
    // Three unit edges symmetric about c: e_i = cos α c + sin α u_i (u_i 120° apart), with
    // e_i·e_j = (3cos²α − 1)/2 = cos 101.92°.
    const double obtuse = (101.0 + 55.0 / 60.0) * std::numbers::pi / 180.0;
    const double cos_alpha = std::sqrt((1.0 + 2.0 * std::cos(obtuse)) / 3.0), sin_alpha = std::sqrt(1.0 - cos_alpha * cos_alpha);
    std::array<Eigen::Vector3d, 3> e;
    for (int i = 0; i < 3; ++i) {
        const double phi = 2.0 * std::numbers::pi * i / 3.0;
        e[static_cast<std::size_t>(i)] = edges_mm[static_cast<std::size_t>(i)] *
                                         Eigen::Vector3d(sin_alpha * std::cos(phi), sin_alpha * std::sin(phi), cos_alpha);
    }
    std::vector<Eigen::Vector3d> vertices;
    for (int k = 0; k < 8; ++k) vertices.push_back((k & 1 ? e[0] : Eigen::Vector3d::Zero()) + (k & 2 ? e[1] : Eigen::Vector3d::Zero()) +
                                                   (k & 4 ? e[2] : Eigen::Vector3d::Zero()));
    // Vertex k has bit i set when edge i is taken; faces hold one bit fixed.
    std::vector<std::vector<int>> faces{{0, 1, 3, 2}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 3, 7, 6}, {0, 2, 6, 4}, {1, 3, 7, 5}};
    return {make_convex_polyhedron(std::move(vertices), std::move(faces)), Eigen::Vector3d::UnitZ()};
}

std::optional<PolyhedronHit> intersect(const ConvexPolyhedron& polyhedron, const Eigen::Vector3d& origin, const Eigen::Vector3d& direction) {
    // Slabs of the face planes (Kay & Kajiya 1986; Haines, Graphics Gems II, "Fast ray-convex polyhedron
    // intersection"): the ray is inside where it is behind every plane.
    PolyhedronHit hit{-std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(), -1, -1};
    for (std::size_t f = 0; f < polyhedron.faces.size(); ++f) {
        const double along = polyhedron.face_normals[f].dot(direction);
        const double distance = polyhedron.face_offsets[f] - polyhedron.face_normals[f].dot(origin);  // > 0 behind the plane
        if (along == 0.0) {
            if (distance < 0.0) return std::nullopt;
            continue;
        }
        const double t = distance / along;
        if (along < 0.0) {
            if (t > hit.t_enter) hit = {t, hit.t_exit, static_cast<int>(f), hit.face_exit};
        } else if (t < hit.t_exit) {
            hit = {hit.t_enter, t, hit.face_enter, static_cast<int>(f)};
        }
        if (hit.t_enter > hit.t_exit) return std::nullopt;
    }
    if (hit.face_enter < 0 || hit.face_exit < 0) return std::nullopt;
    return hit;
}

std::optional<std::pair<double, int>> exit_from_inside(const ConvexPolyhedron& polyhedron, const Eigen::Vector3d& origin,
                                                       const Eigen::Vector3d& direction) {
    double best = std::numeric_limits<double>::infinity();
    int face = -1;
    for (std::size_t f = 0; f < polyhedron.faces.size(); ++f) {
        const double along = polyhedron.face_normals[f].dot(direction);
        if (!(along > 0.0)) continue;
        const double t = std::max(polyhedron.face_offsets[f] - polyhedron.face_normals[f].dot(origin), 0.0) / along;
        if (t < best) {
            best = t;
            face = static_cast<int>(f);
        }
    }
    if (face < 0) return std::nullopt;
    return std::pair{best, face};
}

}  // namespace petroscope
