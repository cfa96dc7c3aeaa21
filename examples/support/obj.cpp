// tracer::load_obj (examples/tracer/obj.hpp) through tinyobjloader.

#include "tracer/obj.hpp"

#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <map>
#include <stdexcept>
#include <utility>

#include <tiny_obj_loader.h>

namespace tracer {

namespace {

[[noreturn]] void fail(const std::string& path, const std::string& what) {
    throw std::runtime_error("cannot load OBJ '" + path + "': " + what);
}

} // namespace

mesh load_obj(const std::string& path) {
    {
        std::ifstream probe(path);
        if (!probe) fail(path, std::strerror(errno));
    }
    tinyobj::ObjReaderConfig config;
    config.triangulate = true;
    config.vertex_color = false;
    config.mtl_search_path = "";
    tinyobj::ObjReader reader;
    if (!reader.ParseFromFile(path, config)) {
        std::string message = reader.Error();
        while (!message.empty() && (message.back() == '\n' || message.back() == '\r')) message.pop_back();
        fail(path, message.empty() ? std::string("parse error") : message);
    }
    const tinyobj::attrib_t& attrib = reader.GetAttrib();
    const std::size_t position_count = attrib.vertices.size() / 3;
    const std::size_t uv_count = attrib.texcoords.size() / 2;

    // Texture coordinates are kept only when every corner of every face names one.
    bool with_uvs = true;
    std::size_t corners = 0;
    for (const tinyobj::shape_t& shape : reader.GetShapes()) {
        for (const tinyobj::index_t& corner : shape.mesh.indices) {
            ++corners;
            if (corner.texcoord_index < 0) with_uvs = false;
        }
    }
    if (corners == 0) fail(path, "no triangles");

    mesh m;
    std::map<std::pair<int, int>, std::uint32_t> vertex_of;
    for (const tinyobj::shape_t& shape : reader.GetShapes()) {
        const std::vector<unsigned char>& face_sizes = shape.mesh.num_face_vertices;
        for (std::size_t f = 0; f < face_sizes.size(); ++f) {
            if (face_sizes[f] != 3) fail(path, "face " + std::to_string(f + 1) + " did not triangulate");
        }
        for (const tinyobj::index_t& corner : shape.mesh.indices) {
            if (corner.vertex_index < 0 || static_cast<std::size_t>(corner.vertex_index) >= position_count) {
                fail(path, "face index " + std::to_string(corner.vertex_index + 1) + " is outside its " +
                               std::to_string(position_count) + " vertices");
            }
            const int uv_index = with_uvs ? corner.texcoord_index : -1;
            if (with_uvs && static_cast<std::size_t>(uv_index) >= uv_count) {
                fail(path, "texture coordinate index " + std::to_string(uv_index + 1) + " is outside its " +
                               std::to_string(uv_count) + " texture coordinates");
            }
            const auto key = std::make_pair(corner.vertex_index, uv_index);
            auto found = vertex_of.find(key);
            if (found == vertex_of.end()) {
                const auto p = static_cast<std::size_t>(corner.vertex_index);
                const vec3 position(attrib.vertices[3 * p], attrib.vertices[3 * p + 1], attrib.vertices[3 * p + 2]);
                if (!shade::is_finite(position)) {
                    fail(path, "vertex " + std::to_string(p + 1) + " is not finite");
                }
                m.positions.push_back(position);
                if (with_uvs) {
                    const auto t = static_cast<std::size_t>(uv_index);
                    const shade::vec2<real> uv(attrib.texcoords[2 * t], attrib.texcoords[2 * t + 1]);
                    if (!shade::is_finite(uv)) {
                        fail(path, "texture coordinate " + std::to_string(t + 1) + " is not finite");
                    }
                    m.uvs.push_back(uv);
                }
                found = vertex_of.emplace(key, static_cast<std::uint32_t>(m.positions.size() - 1)).first;
            }
            m.indices.push_back(found->second);
        }
    }

    // Area-weighted vertex normals: |cross(v1 - v0, v2 - v0)| is twice the triangle's area.
    m.normals.assign(m.positions.size(), vec3(0));
    for (std::size_t i = 0; i < m.triangle_count(); ++i) {
        const shade::triangle<real> t = m.triangle(i);
        const vec3 n = glm::cross(t.v1 - t.v0, t.v2 - t.v0);
        for (std::size_t k = 0; k < 3; ++k) m.normals[m.indices[3 * i + k]] += n;
    }
    for (std::size_t v = 0; v < m.normals.size(); ++v) {
        const real length = glm::length(m.normals[v]);
        if (!(length > 0) || !std::isfinite(length)) {
            fail(path, "mesh vertex " + std::to_string(v + 1) + " belongs only to degenerate triangles");
        }
        m.normals[v] /= length;
    }
    return m;
}

} // namespace tracer
