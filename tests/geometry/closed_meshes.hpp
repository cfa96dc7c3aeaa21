#pragma once
// Closed triangle meshes with exactly shared vertices, for the watertightness tests
// (tests/geometry/test_triangle.cpp and test_triangle_watertight.cpp): a subdivided
// icosahedron, a tessellated cube, and a jittered icosphere with sliver and needle
// triangles; and the points on their shared edges and vertices that rays are aimed at.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <map>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>

#include <shade/geometry/triangle.hpp>

namespace geometry_test {

template <class T>
using v3 = shade::vec3<T>;

template <class T>
struct mesh {
    std::vector<v3<T>> vertices;
    std::vector<std::array<int, 3>> faces; // counter-clockwise seen from outside

    [[nodiscard]] shade::triangle<T> triangle(std::size_t f) const {
        return {vertices[static_cast<std::size_t>(faces[f][0])],
                vertices[static_cast<std::size_t>(faces[f][1])],
                vertices[static_cast<std::size_t>(faces[f][2])]};
    }
    // Unique undirected edges (i < j).
    [[nodiscard]] std::vector<std::pair<int, int>> edges() const {
        std::vector<std::pair<int, int>> e;
        for (const auto& f : faces)
            for (int k = 0; k < 3; ++k) {
                const int a = f[static_cast<std::size_t>(k)];
                const int b = f[static_cast<std::size_t>((k + 1) % 3)];
                e.emplace_back(std::min(a, b), std::max(a, b));
            }
        std::sort(e.begin(), e.end());
        e.erase(std::unique(e.begin(), e.end()), e.end());
        return e;
    }
};

// An icosahedron subdivided `levels` times, every vertex pushed to the unit sphere and
// stored once (faces index the shared vertices, so neighbours use identical coordinates).
template <class T>
mesh<T> icosphere(int levels) {
    const T g = (T(1) + std::sqrt(T(5))) / T(2);
    mesh<T> m;
    m.vertices = {{-1, g, 0}, {1, g, 0}, {-1, -g, 0}, {1, -g, 0}, {0, -1, g}, {0, 1, g},
                  {0, -1, -g}, {0, 1, -g}, {g, 0, -1}, {g, 0, 1}, {-g, 0, -1}, {-g, 0, 1}};
    for (auto& v : m.vertices) v = glm::normalize(v);
    m.faces = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
               {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
               {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
               {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
    for (int level = 0; level < levels; ++level) {
        std::map<std::pair<int, int>, int> midpoint;
        auto mid = [&](int a, int b) {
            const auto key = std::make_pair(std::min(a, b), std::max(a, b));
            const auto it = midpoint.find(key);
            if (it != midpoint.end()) return it->second;
            const v3<T> p = glm::normalize(m.vertices[static_cast<std::size_t>(a)] +
                                           m.vertices[static_cast<std::size_t>(b)]);
            m.vertices.push_back(p);
            const int index = static_cast<int>(m.vertices.size()) - 1;
            midpoint.emplace(key, index);
            return index;
        };
        std::vector<std::array<int, 3>> finer;
        for (const auto& f : m.faces) {
            const int a = mid(f[0], f[1]), b = mid(f[1], f[2]), c = mid(f[2], f[0]);
            finer.push_back({f[0], a, c});
            finer.push_back({f[1], b, a});
            finer.push_back({f[2], c, b});
            finer.push_back({a, b, c});
        }
        m.faces = std::move(finer);
    }
    return m;
}

// The cube [-1,1]^3, each face an n x n grid of squares split along a diagonal, vertices
// shared. All coordinates are multiples of 2/n with n a power of two: exact in binary.
template <class T>
mesh<T> tessellated_cube(int n) {
    mesh<T> m;
    std::map<std::array<int, 3>, int> index; // integer grid coordinates in [0, n]
    auto vertex = [&](std::array<int, 3> g) {
        const auto it = index.find(g);
        if (it != index.end()) return it->second;
        m.vertices.push_back(v3<T>(T(2 * g[0]) / T(n) - 1, T(2 * g[1]) / T(n) - 1,
                                   T(2 * g[2]) / T(n) - 1));
        const int i = static_cast<int>(m.vertices.size()) - 1;
        index.emplace(g, i);
        return i;
    };
    // For each axis and side, a face grid; (a, b) are the two in-face axes ordered so that
    // a x b points outward.
    for (int axis = 0; axis < 3; ++axis)
        for (int side = 0; side < 2; ++side) {
            int a = (axis + 1) % 3, b = (axis + 2) % 3;
            if (side == 0) std::swap(a, b); // outward is -axis: flip the winding
            for (int i = 0; i < n; ++i)
                for (int j = 0; j < n; ++j) {
                    auto grid = [&](int ia, int jb) {
                        std::array<int, 3> g{};
                        g[static_cast<std::size_t>(axis)] = side * n;
                        g[static_cast<std::size_t>(a)] = ia;
                        g[static_cast<std::size_t>(b)] = jb;
                        return vertex(g);
                    };
                    const int p00 = grid(i, j), p10 = grid(i + 1, j), p11 = grid(i + 1, j + 1),
                              p01 = grid(i, j + 1);
                    m.faces.push_back({p00, p10, p11});
                    m.faces.push_back({p00, p11, p01});
                }
        }
    return m;
}

// Points exactly at, or computed on, the mesh's shared edges and vertices.
template <class T>
std::vector<v3<T>> edge_and_vertex_targets(const mesh<T>& m) {
    std::vector<v3<T>> targets(m.vertices.begin(), m.vertices.end());
    for (const auto& [i, j] : m.edges()) {
        const v3<T>& a = m.vertices[static_cast<std::size_t>(i)];
        const v3<T>& b = m.vertices[static_cast<std::size_t>(j)];
        for (const T s : {T(0.5), T(0.125), T(1) / T(3), T(0.71), T(0.9375)})
            targets.push_back(a + s * (b - a));
    }
    return targets;
}

// A deterministic number in [-1, 1) from an integer (SplitMix64's finaliser, Steele,
// Lea, Flood 2014, "Fast Splittable Pseudorandom Number Generators", OOPSLA), so the
// meshes are the same with every compiler and standard library.
inline double jitter_value(std::uint64_t i) {
    std::uint64_t z = i * 0x9e3779b97f4a7c15ULL + 0x632be59bd9b4e5bbULL;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    z ^= z >> 31;
    return double(z >> 11) * 0x1p-52 - 1.0;
}

// The icosphere of `levels` subdivisions with every vertex moved by up to 2 % of the
// radius along and across the radius (so no two neighbours are symmetric and the sheared
// coordinates have full-length mantissas), then with sliver and needle triangles: every
// 5th face (a, b, c) is split into the fan (a, b, p), (b, c, p), (c, a, p) around a point
// p that lies 1e-4 of the way from the midpoint of a b toward c (so (a, b, p) is a
// sliver of almost no area) or, for every 5th face from the 2nd, 1e-3 of the way from a
// toward the centroid (so (a, b, p) and (c, a, p) are needles). Built in double and
// rounded to T once, vertex by vertex, so triangles share exactly equal coordinates.
// The mesh stays closed and, for the test's origins, star-shaped (the test checks).
template <class T>
mesh<T> jittered_icosphere_with_slivers(int levels) {
    const mesh<double> base = icosphere<double>(levels);
    std::vector<v3<double>> vertices;
    std::uint64_t k = 0;
    for (const v3<double>& v : base.vertices) {
        const v3<double> across(jitter_value(k), jitter_value(k + 1), jitter_value(k + 2));
        const double along = 1 + 0.02 * jitter_value(k + 3);
        k += 4;
        vertices.push_back(along * v + 0.01 * across);
    }
    std::vector<std::array<int, 3>> faces;
    for (std::size_t f = 0; f < base.faces.size(); ++f) {
        const auto [ia, ib, ic] = base.faces[f];
        if (f % 5 != 0 && f % 5 != 1) {
            faces.push_back(base.faces[f]);
            continue;
        }
        const v3<double>& a = vertices[std::size_t(ia)];
        const v3<double>& b = vertices[std::size_t(ib)];
        const v3<double>& c = vertices[std::size_t(ic)];
        const v3<double> mid = 0.5 * (a + b);
        const v3<double> p = f % 5 == 0 ? mid + 1e-4 * (c - mid) : a + 1e-3 * ((a + b + c) / 3.0 - a);
        vertices.push_back(p);
        const int ip = int(vertices.size()) - 1;
        faces.push_back({ia, ib, ip});
        faces.push_back({ib, ic, ip});
        faces.push_back({ic, ia, ip});
    }
    mesh<T> m;
    for (const v3<double>& v : vertices) m.vertices.push_back(v3<T>(v));
    m.faces = std::move(faces);
    return m;
}

// True when every face (a, b, c) of m winds counter-clockwise around o, seen from outside:
// (a - o) . ((b - o) x (c - o)) > 0, evaluated in double. For a closed mesh around o this
// means m is star-shaped from o: each ray from o leaves through exactly one point.
template <class T>
bool star_shaped_from(const mesh<T>& m, const v3<T>& o) {
    for (std::size_t f = 0; f < m.faces.size(); ++f) {
        const shade::triangle<T> t = m.triangle(f);
        const v3<double> od(o);
        const v3<double> a = v3<double>(t.v0) - od, b = v3<double>(t.v1) - od, c = v3<double>(t.v2) - od;
        if (!(glm::dot(a, glm::cross(b, c)) > 0)) return false;
    }
    return true;
}

} // namespace geometry_test
