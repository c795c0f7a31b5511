#pragma once
// Convex polyhedra for the scene renderer: crystals given by their vertices and faces, or a calcite
// cleavage rhomb by its edge lengths; ray–polyhedron intersection.
#include <Eigen/Core>

#include <array>
#include <optional>
#include <vector>

namespace petroscope {

struct ConvexPolyhedron {
    std::vector<Eigen::Vector3d> vertices;
    std::vector<std::vector<int>> faces;        // vertex indices, counter-clockwise seen from outside
    std::vector<Eigen::Vector3d> face_normals;  // unit, outward
    std::vector<double> face_offsets;           // n·x = offset on the face plane

    /// The lowest and highest corner of the bounding box.
    Eigen::Vector3d lower() const;
    Eigen::Vector3d upper() const;
    bool contains(const Eigen::Vector3d& point, double tolerance) const;
};

/// Builds the polyhedron and checks it: at least 4 vertices, faces of ≥ 3 vertices that are planar, every
/// edge shared by exactly two faces (closed), every vertex on or behind every face plane (convex, tolerance
/// 1e-9 of the size). Faces may be listed in either winding; normals are made to point outward. Throws
/// InputError naming the face or edge at fault.
ConvexPolyhedron make_convex_polyhedron(std::vector<Eigen::Vector3d> vertices, std::vector<std::vector<int>> faces);

/// The calcite cleavage rhombohedron {10-14} with edges `edges_mm` along its three edge directions from an
/// obtuse corner (at the origin). The angle between any two edges there is 101.92° (the rhombic faces'
/// obtuse angle, 101°55', Deer, Howie & Zussman, Rock-forming minerals 5B), so each edge makes 63.8° with
/// the three-fold axis c, which is returned as `optic_axis`: for equal edges it joins the two obtuse corners.
/// Faces 0 and 1 are the pair spanned by edges 1 and 2 (face 0 through the origin).
struct CalciteRhomb {
    ConvexPolyhedron polyhedron;
    Eigen::Vector3d optic_axis;
};
CalciteRhomb calcite_rhomb(const std::array<double, 3>& edges_mm);

/// Where a ray o + t·d (t > t_min) enters and leaves a convex polyhedron: the parameters and face indices.
struct PolyhedronHit {
    double t_enter = 0.0, t_exit = 0.0;
    int face_enter = -1, face_exit = -1;
};
std::optional<PolyhedronHit> intersect(const ConvexPolyhedron& polyhedron, const Eigen::Vector3d& origin, const Eigen::Vector3d& direction);

/// The exit of a ray that starts inside (or on the surface of) the polyhedron: the distance to the nearest
/// face plane the ray leaves through, and that face.
std::optional<std::pair<double, int>> exit_from_inside(const ConvexPolyhedron& polyhedron, const Eigen::Vector3d& origin,
                                                       const Eigen::Vector3d& direction);

}  // namespace petroscope
