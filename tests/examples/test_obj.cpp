// tracer::load_obj: counts, a known vertex and its normal on a committed pyramid, and the
// errors on files that are missing, unparsable, empty or non-finite.

#include <cmath>
#include <cstdio>
#include <fstream>
#include <stdexcept>
#include <string>

#include <doctest/doctest.h>

#include "tracer/obj.hpp"

namespace {

const std::string pyramid_path = SHADE_EXAMPLES_DATA_DIR "/pyramid.obj";

// Writes `text` to a file named `name` in the working directory and returns its name.
std::string write_file(const std::string& name, const std::string& text) {
    std::ofstream(name) << text;
    return name;
}

// The message load_obj throws for `path`, or "" when it loads.
std::string load_error(const std::string& path) {
    try {
        (void)tracer::load_obj(path);
    } catch (const std::runtime_error& e) {
        return e.what();
    }
    return "";
}

} // namespace

TEST_CASE("load_obj: the pyramid has 5 vertices, 6 triangles and per-vertex uvs") {
    const tracer::mesh m = tracer::load_obj(pyramid_path);
    // The quad base triangulates to 2 triangles, the 4 sides are triangles: 6. Every face
    // corner pairs position i with texture coordinate i, so 5 distinct vertices.
    CHECK(m.triangle_count() == 6);
    CHECK(m.positions.size() == 5);
    CHECK(m.normals.size() == 5);
    REQUIRE(m.uvs.size() == 5);

    // Vertex 5 of the file is the apex (0, 1, 0) with uv (0.5, 0.5).
    bool found_apex = false;
    for (std::size_t i = 0; i < m.positions.size(); ++i) {
        if (m.positions[i] != tracer::vec3(0, 1, 0)) continue;
        found_apex = true;
        CHECK(m.uvs[i].x == 0.5);
        CHECK(m.uvs[i].y == 0.5);
        // The four sides' cross(v1 - v0, v2 - v0) are (0, 0.5, 1), (1, 0.5, 0), (0, 0.5, -1)
        // and (-1, 0.5, 0): their sum (0, 2, 0) normalises to (0, 1, 0).
        CHECK(m.normals[i].x == doctest::Approx(0).epsilon(1e-12));
        CHECK(m.normals[i].y == doctest::Approx(1).epsilon(1e-12));
        CHECK(m.normals[i].z == doctest::Approx(0).epsilon(1e-12));
    }
    CHECK(found_apex);

    // The surface area does not depend on which diagonal splits the base: the base is 1,
    // each side has |cross| / 2 = |(0, 0.5, 1)| / 2 = sqrt(1.25) / 2, so 1 + 2 sqrt(1.25)
    // = 1 + sqrt(5) in all.
    double area = 0;
    for (std::size_t i = 0; i < m.triangle_count(); ++i) {
        const auto t = m.triangle(i);
        area += glm::length(glm::cross(t.v1 - t.v0, t.v2 - t.v0)) / 2;
    }
    CHECK(area == doctest::Approx(1 + std::sqrt(5.0)).epsilon(1e-12));

    // Every triangle faces out: its geometric normal points away from the pyramid's
    // centre (0, 0.25, 0) (a wrong winding, or a lost triangle, would fail here).
    for (std::size_t i = 0; i < m.triangle_count(); ++i) {
        const auto t = m.triangle(i);
        const tracer::vec3 n = glm::cross(t.v1 - t.v0, t.v2 - t.v0);
        const tracer::vec3 centroid = (t.v0 + t.v1 + t.v2) / 3.0;
        CHECK(glm::dot(n, centroid - tracer::vec3(0, 0.25, 0)) > 0);
    }
}

TEST_CASE("load_obj: a file without texture coordinates gives no uvs") {
    const std::string path = write_file("obj_test_no_uv.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    const tracer::mesh m = tracer::load_obj(path);
    CHECK(m.triangle_count() == 1);
    CHECK(m.uvs.empty());
    // cross((1,0,0), (0,1,0)) = (0, 0, 1).
    CHECK(m.normals[0] == tracer::vec3(0, 0, 1));
    std::remove(path.c_str());
}

TEST_CASE("load_obj: bad files fail with a message naming the file") {
    CHECK(load_error("no_such_mesh.obj") == "cannot load OBJ 'no_such_mesh.obj': No such file or directory");

    const std::string empty = write_file("obj_test_empty.obj", "# only vertices\nv 0 0 0\nv 1 0 0\nv 0 1 0\n");
    CHECK(load_error(empty) == "cannot load OBJ 'obj_test_empty.obj': no triangles");

    const std::string infinite = write_file("obj_test_inf.obj", "v 1e999 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    CHECK(load_error(infinite) == "cannot load OBJ 'obj_test_inf.obj': vertex 1 is not finite");

    const std::string outside = write_file("obj_test_index.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n");
    CHECK(load_error(outside) == "cannot load OBJ 'obj_test_index.obj': face index 9 is outside its 3 vertices");

    // tinyobjloader's own parse error, after the file's name.
    const std::string unparsable = write_file("obj_test_parse.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 x\n");
    CHECK(load_error(unparsable).rfind("cannot load OBJ 'obj_test_parse.obj': Failed parse `f' line", 0) == 0);

    const std::string degenerate = write_file("obj_test_line.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n");
    CHECK(load_error(degenerate) == "cannot load OBJ 'obj_test_line.obj': mesh vertex 1 belongs only to degenerate triangles");

    for (const std::string& path : {empty, infinite, outside, unparsable, degenerate}) std::remove(path.c_str());
}
