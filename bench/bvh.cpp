// Bounding-volume hierarchies: shade::triangle_bvh<float> against Embree 3 in the same
// binary, single thread: build time, closest-hit throughput for primary (coherent) and
// random (incoherent) rays, any-hit throughput for shadow rays (triangle_bvh::any against
// rtcOccluded1), and the memory of the built hierarchy, on icospheres of 20k / 82k / 328k
// triangles and on the reference tracer's mesh scene. Embree is used only here
// (bench/CMakeLists.txt builds this file only when find_package(embree 3) finds it); the
// library never depends on it.
//
// Names (bench/support.hpp): bvh/<rays>/<scene>/<shade|embree> with rays = build,
// primary, incoherent or shadow; ops_per_iter is the number of rays (or 1 build), so the
// time per operation is ns per ray. Counters: hit_rate (shade's; for shadow rays the
// fraction occluded), agreement: the fraction of rays on which shade and Embree agree on
// hit or miss (computed once, before timing); on the build rows, bytes_per_triangle: for
// shade, triangle_bvh::memory_bytes() (nodes and leaf data) over the triangles; for Embree,
// the bytes its device memory monitor (rtcSetDeviceMemoryMonitorFunction) counts as
// allocated and not freed across rtcCommitScene (the hierarchy and its leaf triangles,
// as its allocator holds them; the geometry's vertex and index buffers, allocated before,
// are not counted), and peak_bytes_per_triangle, the most held during the commit.
// bvh/build/<scene>/shade_parallel: shade's build through support::thread_executor on all
// hardware threads (counter build_threads; bench/report.py times it by the wall clock).
// bvh/<primary|incoherent>/<scene>/shade_lean: triangle_bvh::find_closest, the nearest hit
// without the record's point, normal and error bound (closer to what rtcIntersect1 returns).

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <embree3/rtcore.h>

#include <benchmark/benchmark.h>

#include <shade/core/random.hpp>
#include <shade/geometry/camera.hpp>
#include <shade/geometry/triangle_bvh.hpp>

#include "support.hpp"
#include "support/thread_executor.hpp"
#include "tracer/mesh.hpp"
#include "tracer/scenes.hpp"

namespace {

using v3 = shade::vec3<float>;

/// An indexed float mesh (Embree's input) and the same triangles as a list (shade's).
struct scene_data {
    std::string name;
    std::vector<float> positions; // x y z per vertex
    std::vector<std::uint32_t> indices;
    std::vector<shade::triangle<float>> triangles;
    std::vector<shade::ray<float>> primary, incoherent, shadow;
};

void add_mesh(scene_data& s, const tracer::mesh& m) {
    const auto base = static_cast<std::uint32_t>(s.positions.size() / 3);
    for (const auto& p : m.positions)
        for (int k = 0; k < 3; ++k) s.positions.push_back(static_cast<float>(p[k]));
    for (const std::uint32_t i : m.indices) s.indices.push_back(base + i);
}

void finish_triangles(scene_data& s) {
    const auto at = [&](std::uint32_t i) {
        return v3(s.positions[3 * i], s.positions[3 * i + 1], s.positions[3 * i + 2]);
    };
    for (std::size_t t = 0; t + 2 < s.indices.size(); t += 3)
        s.triangles.push_back({at(s.indices[t]), at(s.indices[t + 1]), at(s.indices[t + 2])});
}

constexpr int image_side = 256; // primary rays: 256 x 256 per iteration
constexpr std::size_t incoherent_count = 65536;

/// Primary rays of a pinhole camera, one per pixel centre of an image_side^2 image.
std::vector<shade::ray<float>> camera_rays(const shade::pinhole_camera<double>& cam) {
    std::vector<shade::ray<float>> rays;
    for (int y = 0; y < image_side; ++y)
        for (int x = 0; x < image_side; ++x) {
            const auto r = cam.ray_for_raster(x + 0.5, y + 0.5, image_side, image_side);
            rays.push_back({v3(r.origin), v3(r.direction)});
        }
    return rays;
}

/// Random rays: origins uniform in the box [-extent, extent]^3 around the centre, unit
/// directions uniform on the sphere (so successive rays share no path).
std::vector<shade::ray<float>> random_rays(const v3& centre, float extent, std::uint64_t seed) {
    shade::rng g(seed);
    std::vector<shade::ray<float>> rays;
    while (rays.size() < incoherent_count) {
        const v3 o = centre + extent * v3(2 * g.uniform<float>() - 1, 2 * g.uniform<float>() - 1,
                                          2 * g.uniform<float>() - 1);
        const v3 d(2 * g.uniform<float>() - 1, 2 * g.uniform<float>() - 1, 2 * g.uniform<float>() - 1);
        const float len = glm::length(d);
        if (len > 0.1f && len <= 1.0f) rays.push_back({o, d / len});
    }
    return rays;
}

/// Shadow rays: origins as for random_rays, each toward a point near a random triangle
/// (uniform barycentrics) moved off its plane along the unit normal by a distance of
/// either sign and magnitude in [0.001, 0.01] x extent, the segment t in [0, 1] (the
/// direction is the unnormalised difference): the end point lies in front of or behind
/// the surface, never on it, so the rounding of either test does not decide whether the
/// segment is blocked; some are (the mesh lies between), some are not.
std::vector<shade::ray<float>> shadow_rays(const scene_data& s, const v3& centre, float extent, std::uint64_t seed) {
    shade::rng g(seed);
    std::vector<shade::ray<float>> rays;
    while (rays.size() < incoherent_count) {
        const v3 o = centre + extent * v3(2 * g.uniform<float>() - 1, 2 * g.uniform<float>() - 1,
                                          2 * g.uniform<float>() - 1);
        const auto i = static_cast<std::size_t>(g.uniform<float>() * float(s.triangles.size())) % s.triangles.size();
        const shade::triangle<float>& tri = s.triangles[i];
        const v3 n = glm::cross(tri.v1 - tri.v0, tri.v2 - tri.v0);
        const float n_len = glm::length(n);
        if (!(n_len > 0.0f)) continue;
        float u = g.uniform<float>(), w = g.uniform<float>();
        if (u + w > 1.0f) u = 1.0f - u, w = 1.0f - w;
        const float offset = extent * (0.001f + 0.009f * g.uniform<float>()) * (g.uniform<float>() < 0.5f ? -1.0f : 1.0f);
        const v3 target = tri.v0 + u * (tri.v1 - tri.v0) + w * (tri.v2 - tri.v0) + (offset / n_len) * n;
        const v3 d = target - o;
        if (glm::length(d) < 0.01f * extent) continue;
        rays.push_back({o, d, 0.0f, 1.0f});
    }
    return rays;
}

scene_data icosphere(int levels, const char* name) {
    scene_data s;
    s.name = name;
    add_mesh(s, tracer::make_icosphere(tracer::vec3(0), 1.0, levels));
    finish_triangles(s);
    // A camera at distance 3 looking at the sphere, which fills most of the image.
    const shade::pinhole_camera<double> cam({0.3, 0.4, 3}, {0, 0, 0}, {0, 1, 0}, 50 * shade::pi<double> / 180, 1.0);
    s.primary = camera_rays(cam);
    s.incoherent = random_rays(v3(0), 1.5f, 99);
    s.shadow = shadow_rays(s, v3(0), 1.5f, 97);
    return s;
}

scene_data mesh_scene() {
    scene_data s;
    s.name = "mesh_scene";
    const tracer::scene sc = tracer::make_mesh_scene(1.0);
    for (const auto& o : sc.objects)
        if (o.mesh) add_mesh(s, *o.mesh);
    finish_triangles(s);
    s.primary = camera_rays(*sc.camera);
    s.incoherent = random_rays(v3(0, 0.35f, 0), 3.5f, 98);
    s.shadow = shadow_rays(s, v3(0, 0.35f, 0), 3.5f, 96);
    return s;
}

// ---- Embree ---------------------------------------------------------------------------

/// What Embree's device memory monitor reports: bytes held now and the most held since
/// the last reset (single thread: no synchronisation needed).
struct embree_memory {
    long long held = 0;
    long long peak = 0;
    void reset() { peak = held; }
};
embree_memory embree_bytes;

bool monitor(void* user, ssize_t bytes, bool) {
    auto* m = static_cast<embree_memory*>(user);
    m->held += bytes; // positive on allocation, negative on release
    if (m->held > m->peak) m->peak = m->held;
    return true;
}

/// Embree's device configuration: "threads=1", or SHADE_BENCH_EMBREE_CONFIG when set (for
/// experiments such as "threads=1,isa=avx2", which keeps Embree off its AVX-512 kernels).
const char* embree_config() {
    const char* config = std::getenv("SHADE_BENCH_EMBREE_CONFIG");
    return config != nullptr ? config : "threads=1";
}

struct embree_device {
    RTCDevice device = [] {
        RTCDevice d = rtcNewDevice(embree_config());
        rtcSetDeviceMemoryMonitorFunction(d, monitor, &embree_bytes);
        return d;
    }();
    ~embree_device() { rtcReleaseDevice(device); }
};

RTCDevice device() {
    static embree_device d;
    return d.device;
}

/// Embree's scene over s's mesh (default build quality, one thread), not yet committed.
RTCScene embree_scene(const scene_data& s) {
    RTCScene scene = rtcNewScene(device());
    RTCGeometry geom = rtcNewGeometry(device(), RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* vb = static_cast<float*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                           3 * sizeof(float), s.positions.size() / 3));
    std::copy(s.positions.begin(), s.positions.end(), vb);
    auto* ib = static_cast<std::uint32_t*>(rtcSetNewGeometryBuffer(
        geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(std::uint32_t), s.indices.size() / 3));
    std::copy(s.indices.begin(), s.indices.end(), ib);
    rtcCommitGeometry(geom);
    rtcAttachGeometry(scene, geom);
    rtcReleaseGeometry(geom);
    return scene;
}

/// Embree's scene over s's mesh, committed (built).
RTCScene embree_build(const scene_data& s) {
    RTCScene scene = embree_scene(s);
    rtcCommitScene(scene);
    return scene;
}

/// The bytes Embree's scene over s holds after its commit beyond what it held before
/// (the hierarchy and its leaves), and the most it held beyond that during the commit.
std::pair<double, double> embree_memory_of(const scene_data& s) {
    // The monitor read around the commit.
    RTCScene scene = embree_scene(s);
    const long long before = embree_bytes.held;
    embree_bytes.reset();
    rtcCommitScene(scene);
    const auto retained = double(embree_bytes.held - before), peak = double(embree_bytes.peak - before);
    rtcReleaseScene(scene);
    return {retained, peak};
}

/// Embree's closest hit of r: t, or +infinity on a miss.
float embree_closest(RTCScene scene, const shade::ray<float>& r) {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRayHit rh{};
    rh.ray.org_x = r.origin.x;
    rh.ray.org_y = r.origin.y;
    rh.ray.org_z = r.origin.z;
    rh.ray.dir_x = r.direction.x;
    rh.ray.dir_y = r.direction.y;
    rh.ray.dir_z = r.direction.z;
    rh.ray.tnear = r.t_min;
    rh.ray.tfar = r.t_max;
    rh.ray.mask = ~0u;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(scene, &context, &rh);
    return rh.hit.geomID == RTC_INVALID_GEOMETRY_ID ? std::numeric_limits<float>::infinity() : rh.ray.tfar;
}

/// Embree's occlusion test of r (the segment [t_min, t_max]): true when blocked.
bool embree_occluded(RTCScene scene, const shade::ray<float>& r) {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRay ray{};
    ray.org_x = r.origin.x;
    ray.org_y = r.origin.y;
    ray.org_z = r.origin.z;
    ray.dir_x = r.direction.x;
    ray.dir_y = r.direction.y;
    ray.dir_z = r.direction.z;
    ray.tnear = r.t_min;
    ray.tfar = r.t_max;
    ray.mask = ~0u;
    rtcOccluded1(scene, &context, &ray);
    return ray.tfar < 0.0f; // set to -infinity when occluded
}

struct built {
    scene_data data;
    shade::triangle_bvh<float> shade_bvh;      // the default width: 8 children where the CPU has AVX
    shade::triangle_bvh<float> shade_bvh_four; // 4 children, for comparison
    RTCScene embree = nullptr;
};

void register_scene(const built& b) {
    const scene_data& s = b.data;
    const std::string build = "bvh/build/" + s.name + "/";
    const double triangles = double(s.triangles.size());
    const auto [embree_retained, embree_peak] = embree_memory_of(s);
    shade_bench::add(
        build + "embree", 1.0,
        [&s] {
            RTCScene scene = embree_build(s);
            benchmark::DoNotOptimize(scene);
            rtcReleaseScene(scene);
        },
        -1.0,
        {{"bytes_per_triangle", embree_retained / triangles}, {"peak_bytes_per_triangle", embree_peak / triangles}});
    // shade's hierarchy at the default width (eight children where the CPU has AVX) and
    // at four, each against Embree on the same rays.
    const std::pair<const char*, shade::bvh_width> widths[] = {{"shade", shade::bvh_width::automatic},
                                                              {"shade_four", shade::bvh_width::four}};
    for (const auto& variant : widths) {
        const shade::triangle_bvh<float>& tree = variant.second == shade::bvh_width::four ? b.shade_bvh_four : b.shade_bvh;
        shade_bench::add(
            build + variant.first, 1.0,
            [&s, width = variant.second] {
                shade::triangle_bvh<float> t(s.triangles, width);
                benchmark::DoNotOptimize(t);
            },
            -1.0, {{"bytes_per_triangle", double(tree.memory_bytes()) / triangles}});
    }
    {
        static const support::thread_executor threads;
        shade_bench::add(
            build + "shade_parallel", 1.0,
            [&s] {
                shade::triangle_bvh<float> t(s.triangles, shade::bvh_width::automatic, threads);
                benchmark::DoNotOptimize(t);
            },
            -1.0, {{"build_threads", double(threads.threads())}});
    }
    {
        // Shadow rays: any-hit against Embree's occlusion test.
        const std::vector<shade::ray<float>>& rays = s.shadow;
        const double n = double(rays.size());
        const std::string group = "bvh/shadow/" + s.name + "/";
        std::size_t embree_blocked = 0;
        for (const auto& r : rays) embree_blocked += embree_occluded(b.embree, r);
        shade_bench::add(
            group + "embree", n,
            [&b, &rays] {
                for (const auto& r : rays) benchmark::DoNotOptimize(embree_occluded(b.embree, r));
            },
            double(embree_blocked) / n);
        for (const auto& [name, width] : widths) {
            const shade::triangle_bvh<float>& tree = width == shade::bvh_width::four ? b.shade_bvh_four : b.shade_bvh;
            std::size_t agree = 0, blocked = 0;
            for (const auto& r : rays) {
                const bool a = tree.any(r);
                agree += a == embree_occluded(b.embree, r);
                blocked += a;
            }
            shade_bench::add(
                group + name, n,
                [&tree, &rays] {
                    for (const auto& r : rays) benchmark::DoNotOptimize(tree.any(r));
                },
                double(blocked) / n,
                {{"agreement", double(agree) / n}, {"node_width", double(tree.node_width())}});
        }
    }
    for (const bool coherent : {true, false}) {
        const std::vector<shade::ray<float>>& rays = coherent ? s.primary : s.incoherent;
        const double n = double(rays.size());
        const std::string group = std::string("bvh/") + (coherent ? "primary/" : "incoherent/") + s.name + "/";
        std::size_t embree_hits = 0;
        for (const auto& r : rays) embree_hits += embree_closest(b.embree, r) < std::numeric_limits<float>::infinity();
        shade_bench::add(
            group + "embree", n,
            [&b, &rays] {
                for (const auto& r : rays) benchmark::DoNotOptimize(embree_closest(b.embree, r));
            },
            double(embree_hits) / n);
        for (const auto& [name, width] : widths) {
            const shade::triangle_bvh<float>& tree = width == shade::bvh_width::four ? b.shade_bvh_four : b.shade_bvh;
            std::size_t agree = 0, hits = 0;
            for (const auto& r : rays) {
                const bool a = tree.closest(r).has_value();
                agree += a == (embree_closest(b.embree, r) < std::numeric_limits<float>::infinity());
                hits += a;
            }
            shade_bench::add(
                group + name, n,
                [&tree, &rays] {
                    for (const auto& r : rays) {
                        const auto h = tree.closest(r);
                        benchmark::DoNotOptimize(h);
                    }
                },
                double(hits) / n,
                {{"agreement", double(agree) / n}, {"node_width", double(tree.node_width())}});
        }
        {
            // find_closest: the nearest hit's triangle, t, barycentrics and front_face, no
            // record (Embree's rtcIntersect1 returns t, u, v, the unnormalised normal and the
            // primitive).
            const shade::triangle_bvh<float>& tree = b.shade_bvh;
            std::size_t agree = 0, hits = 0;
            for (const auto& r : rays) {
                const bool a = tree.find_closest(r).has_value();
                agree += a == (embree_closest(b.embree, r) < std::numeric_limits<float>::infinity());
                hits += a;
            }
            shade_bench::add(
                group + "shade_lean", n,
                [&tree, &rays] {
                    for (const auto& r : rays) {
                        const auto h = tree.find_closest(r);
                        benchmark::DoNotOptimize(h);
                    }
                },
                double(hits) / n,
                {{"agreement", double(agree) / n}, {"node_width", double(tree.node_width())}});
        }
    }
}

const bool registered = [] {
    // Static storage: the benchmarks refer to the data while they run.
    static std::vector<std::unique_ptr<built>> scenes;
    const auto add = [](scene_data s) {
        auto b = std::make_unique<built>();
        b->data = std::move(s);
        b->shade_bvh = shade::triangle_bvh<float>(b->data.triangles);
        b->shade_bvh_four = shade::triangle_bvh<float>(b->data.triangles, shade::bvh_width::four);
        b->embree = embree_build(b->data);
        scenes.push_back(std::move(b));
    };
    add(icosphere(5, "ico20k"));
    add(icosphere(6, "ico82k"));
    add(icosphere(7, "ico328k"));
    add(mesh_scene());
    for (const auto& b : scenes) register_scene(*b);
    return true;
}();

} // namespace
