#pragma once
// Indexed triangle meshes for the reference tracer, and procedural generators for smooth
// objects whose exact normals are known (so per-vertex normals are exact, not averaged).

#include <cmath>
#include <algorithm>
#include <cstdint>
#include <map>
#include <vector>

#include <glm/geometric.hpp>

#include <shade/core/math.hpp>
#include <shade/geometry/aabb.hpp>
#include <shade/geometry/triangle.hpp>

namespace tracer {

using real = double;
using vec3 = shade::vec3<real>;

/// A triangle mesh: shared vertex positions and unit vertex normals, three indices per
/// triangle (counter-clockwise seen from outside).
struct mesh {
    std::vector<vec3> positions;
    std::vector<vec3> normals;
    std::vector<std::uint32_t> indices;
    /// Per-vertex texture coordinates (one per position), or empty when the mesh has none.
    std::vector<shade::vec2<real>> uvs;

    [[nodiscard]] std::size_t triangle_count() const { return indices.size() / 3; }

    /// Triangle i (its three vertices).
    [[nodiscard]] shade::triangle<real> triangle(std::size_t i) const {
        return {positions[indices[3 * i]], positions[indices[3 * i + 1]], positions[indices[3 * i + 2]]};
    }

    /// Every triangle, in index order (for building a shade::triangle_bvh).
    [[nodiscard]] std::vector<shade::triangle<real>> triangles() const {
        std::vector<shade::triangle<real>> out;
        out.reserve(triangle_count());
        for (std::size_t i = 0; i < triangle_count(); ++i) out.push_back(triangle(i));
        return out;
    }

    /// The box of all vertices.
    [[nodiscard]] shade::aabb<real> bounds() const {
        shade::aabb<real> box;
        for (const vec3& p : positions) box.grow(p);
        return box;
    }
};

/// A torus around the y axis through `centre`: major radius R (centre of the tube to the
/// axis), minor radius r (the tube), `rings` segments around the axis and `sides` around
/// the tube. Point(u, w) = centre + (R + r cos w)(cos u, 0, sin u) + r sin w (0, 1, 0);
/// its outward normal is (cos w cos u, sin w, cos w sin u), exact at every vertex.
inline mesh make_torus(const vec3& centre, real R, real r, int rings, int sides) {
    mesh m;
    for (int i = 0; i < rings; ++i) {
        const real u = 2 * shade::pi<real> * real(i) / real(rings);
        for (int j = 0; j < sides; ++j) {
            const real w = 2 * shade::pi<real> * real(j) / real(sides);
            const vec3 n(std::cos(w) * std::cos(u), std::sin(w), std::cos(w) * std::sin(u));
            const vec3 ring(std::cos(u), 0, std::sin(u));
            m.positions.push_back(centre + (R + r * std::cos(w)) * ring + r * std::sin(w) * vec3(0, 1, 0));
            m.normals.push_back(n);
        }
    }
    const auto at = [&](int i, int j) {
        return static_cast<std::uint32_t>(((i + rings) % rings) * sides + (j + sides) % sides);
    };
    for (int i = 0; i < rings; ++i) {
        for (int j = 0; j < sides; ++j) {
            // Winding chosen so that cross(v1 - v0, v2 - v0) points out of the tube.
            const std::uint32_t a = at(i, j), b = at(i + 1, j), c = at(i + 1, j + 1), d = at(i, j + 1);
            m.indices.insert(m.indices.end(), {a, c, b, a, d, c});
        }
    }
    return m;
}

/// A sphere tessellated by subdividing an icosahedron `levels` times and projecting every
/// vertex onto the sphere; vertices are shared exactly between neighbouring triangles.
inline mesh make_icosphere(const vec3& centre, real radius, int levels) {
    const real g = (1 + std::sqrt(real(5))) / 2; // golden ratio: icosahedron vertex coordinates
    std::vector<vec3> unit = {{-1, g, 0}, {1, g, 0}, {-1, -g, 0}, {1, -g, 0}, {0, -1, g}, {0, 1, g},
                              {0, -1, -g}, {0, 1, -g}, {g, 0, -1}, {g, 0, 1}, {-g, 0, -1}, {-g, 0, 1}};
    for (auto& p : unit) p = glm::normalize(p);
    std::vector<std::uint32_t> tris = {0, 11, 5, 0, 5, 1, 0, 1, 7, 0, 7, 10, 0, 10, 11,
                                       1, 5, 9, 5, 11, 4, 11, 10, 2, 10, 7, 6, 7, 1, 8,
                                       3, 9, 4, 3, 4, 2, 3, 2, 6, 3, 6, 8, 3, 8, 9,
                                       4, 9, 5, 2, 4, 11, 6, 2, 10, 8, 6, 7, 9, 8, 1};
    for (int level = 0; level < levels; ++level) {
        std::vector<std::uint32_t> next;
        std::map<std::uint64_t, std::uint32_t> midpoints; // edge (min, max) -> new vertex
        const auto midpoint = [&](std::uint32_t a, std::uint32_t b) {
            const std::uint64_t key = (std::uint64_t(std::min(a, b)) << 32) | std::max(a, b);
            if (const auto found = midpoints.find(key); found != midpoints.end()) return found->second;
            unit.push_back(glm::normalize(unit[a] + unit[b]));
            const auto idx = static_cast<std::uint32_t>(unit.size() - 1);
            midpoints.emplace(key, idx);
            return idx;
        };
        for (std::size_t t = 0; t < tris.size(); t += 3) {
            const std::uint32_t a = tris[t], b = tris[t + 1], c = tris[t + 2];
            const std::uint32_t ab = midpoint(a, b), bc = midpoint(b, c), ca = midpoint(c, a);
            next.insert(next.end(), {a, ab, ca, b, bc, ab, c, ca, bc, ab, bc, ca});
        }
        tris = std::move(next);
    }
    mesh m;
    for (const auto& p : unit) {
        m.positions.push_back(centre + radius * p);
        m.normals.push_back(p);
    }
    m.indices = std::move(tris);
    return m;
}

} // namespace tracer
