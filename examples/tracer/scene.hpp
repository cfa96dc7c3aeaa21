#pragma once
// The reference tracer's scene: spheres, planes and triangle meshes, each with a material
// (any shade::shader, type-erased), lit by any of shade's lights, with shadow rays.

#include <algorithm>
#include <cmath>
#include <concepts>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <type_traits>
#include <utility>
#include <variant>
#include <vector>

#include <glm/geometric.hpp>

#include <shade/brdf/any_brdf.hpp>
#include <shade/brdf/lambert.hpp>
#include <shade/brdf/microfacet/ggx.hpp>
#include <shade/bsdf/bsdf.hpp>
#include <shade/bsdf/compensated_rough_dielectric.hpp>
#include <shade/bsdf/rough_dielectric.hpp>
#include <shade/bsdf/smooth_dielectric.hpp>
#include <shade/bsdf/thin_dielectric.hpp>
#include <shade/core/random.hpp>
#include <shade/core/surface_point.hpp>
#include <shade/geometry/aabb.hpp>
#include <shade/geometry/bvh.hpp>
#include <shade/geometry/camera.hpp>
#include <shade/geometry/plane.hpp>
#include <shade/geometry/spawn.hpp>
#include <shade/geometry/sphere.hpp>
#include <shade/geometry/triangle.hpp>
#include <shade/geometry/triangle_bvh.hpp>
#include <shade/light/any_light.hpp>
#include <shade/light/environment_map.hpp>
#include <shade/material/openpbr_parameters.hpp>
#include <shade/material/openpbr_surface.hpp>
#include <shade/shading/shader.hpp>
#include <shade/shading/sum_over_lights.hpp>

#include "mesh.hpp"

namespace tracer {

using rgb = shade::rgb<real>;
using vec2 = shade::vec2<real>;
using surface_point = shade::surface_point<real>;
using light_sample = shade::light_sample<real>;

struct scene;
struct lighting_options;

/// A surface point to light: what a material needs to sum the scene's lights there.
struct lighting_query {
    const scene& lit_scene;
    const surface_point& at;
    const vec3& geometric_n;    ///< unit geometric normal (shadow rays start off it)
    const vec3& p_error;        ///< the rounding bound of at.p (shade::hit::p_error)
    const vec3& v;              ///< unit direction toward the viewer
    shade::rng& random;         ///< jitters the area lights' strata
    const lighting_options& options;
    bool shadows;               ///< trace shadow rays
};

/// The radiance shader s reflects at q.at toward q.v from all the scene's lights (defined
/// below the scene).
template <class S>
rgb light_with(const S& s, const lighting_query& q);

/// A material: any shade::shader<double> (or BRDF), stored behind a std::function so that
/// one scene can mix shader types. It is called once per shaded point and sums the lights
/// itself (light_with), so the loop over the light samples runs on the concrete shader
/// type, without an indirect call per sample.
using material = std::function<rgb(const lighting_query&)>;

/// Wraps a shade shader (or a BRDF, lifted with shade::lit) as a material.
template <class S>
material make_material(S s) {
    if constexpr (shade::shader<S>) {
        return [s](const lighting_query& q) { return light_with(s, q); };
    } else {
        return make_material(shade::lit<S>{s, rgb(0)});
    }
}

/// How a mesh's normals are used.
///   flat:    the triangle's geometric normal everywhere (facets show);
///   gouraud: lighting evaluated at the three vertices, colours interpolated (Gouraud 1971);
///   phong:   vertex normals interpolated, lighting per hit point (Phong 1975).
enum class mesh_shading { flat, gouraud, phong };

/// Where a camera or shadow ray met the scene.
struct scene_hit {
    real t = 0;
    vec3 p{0};
    vec3 p_error{0};           ///< bound on p's rounding (shade::hit::p_error), for spawned rays
    vec3 geometric_n{0, 0, 1}; ///< unit geometric normal, flipped toward the ray origin
    vec3 outward_n{0, 0, 1};   ///< the surface's own unit normal (outward for closed shapes), not flipped
    vec3 shading_n{0, 0, 1};   ///< unit shading normal, same side as geometric_n
    std::size_t object = 0;    ///< index into scene::objects
    std::uint32_t triangle = 0;///< triangle index for meshes
    vec3 barycentric{1, 0, 0}; ///< for meshes
};

/// Which BSDF a rough glass object has (both over GGX microfacets).
enum class rough_glass_model {
    single_scattering, ///< shade::rough_dielectric: loses the light scattered between microfacets
    compensated        ///< shade::compensated_rough_dielectric: gives that light back (R + T = 1)
};

/// The BSDF of a rough glass object: shade::rough_dielectric<shade::ggx<real>> or
/// shade::compensated_rough_dielectric<real>, chosen at run time. A shade::bsdf_sampler
/// whose f, pdf and sample forward to the model it holds (same units: f in 1/sr without
/// the cosine, pdf in 1/sr over the sphere of directions).
class rough_glass_bsdf {
public:
    using scalar_type = real;
    using single_scattering_type = shade::rough_dielectric<shade::ggx<real>>;
    using compensated_type = shade::compensated_rough_dielectric<real>;

    /// Holds the single-scattering model (implicit: an object's rough_glass may be assigned one).
    rough_glass_bsdf(const single_scattering_type& model) : model_(model) {}
    /// Holds the compensated model (implicit, as above).
    rough_glass_bsdf(const compensated_type& model) : model_(model) {}

    /// Which model this is.
    [[nodiscard]] rough_glass_model model() const noexcept {
        return std::holds_alternative<compensated_type>(model_) ? rough_glass_model::compensated
                                                                : rough_glass_model::single_scattering;
    }
    /// The model's f(l, v, at): 1/sr without the cosine, radiance mode, l and v on either side.
    [[nodiscard]] rgb f(const vec3& l, const vec3& v, const shade::surface_point<real>& at) const noexcept {
        if (const auto* c = std::get_if<compensated_type>(&model_)) return c->f(l, v, at);
        return std::get<single_scattering_type>(model_).f(l, v, at);
    }
    /// The model's pdf(l, v, at): the density (1/sr, over the sphere) with which sample draws l.
    [[nodiscard]] real pdf(const vec3& l, const vec3& v, const shade::surface_point<real>& at) const noexcept {
        if (const auto* c = std::get_if<compensated_type>(&model_)) return c->pdf(l, v, at);
        return std::get<single_scattering_type>(model_).pdf(l, v, at);
    }
    /// The model's sample(v, uc, u, at, mode).
    [[nodiscard]] std::optional<shade::bsdf_sample<real>> sample(const vec3& v, real uc, const vec2& u,
                                                                 const shade::surface_point<real>& at,
                                                                 shade::transport_mode mode) const noexcept {
        if (const auto* c = std::get_if<compensated_type>(&model_)) return c->sample(v, uc, u, at, mode);
        return std::get<single_scattering_type>(model_).sample(v, uc, u, at, mode);
    }

private:
    std::variant<single_scattering_type, compensated_type> model_;
};

static_assert(shade::bsdf_sampler<rough_glass_bsdf>);

/// Rough glass over shade::ggx(alpha) of relative index eta (n_inside / n_outside) in the
/// given model. Throws shade::invalid_parameter as ggx and rough_dielectric do.
inline rough_glass_bsdf make_rough_glass(real alpha, real eta, rough_glass_model model) {
    const shade::ggx<real> distribution(alpha);
    if (model == rough_glass_model::compensated) return shade::compensated_rough_dielectric<real>(distribution, eta);
    return shade::rough_dielectric<shade::ggx<real>>(distribution, eta);
}

/// One object of the scene.
struct object {
    enum class kind { sphere, plane, mesh } shape = kind::sphere;
    std::optional<shade::sphere<real>> sphere;
    std::optional<shade::plane<real>> plane;
    std::shared_ptr<const tracer::mesh> mesh;
    /// The mesh's hierarchy, with the watertight triangle test (no ray slips between
    /// neighbouring triangles).
    std::shared_ptr<const shade::triangle_bvh<real, shade::watertight>> mesh_bvh;
    mesh_shading shading = mesh_shading::phong;
    material surface;
    std::optional<shade::any_brdf<real>> brdf; ///< physical material (path integrator); none: black
    /// A delta dielectric instead (path integrator): a smooth interface, the object then a
    /// closed shape whose outward normal points to the outside of the medium, or a thin
    /// slab (a pane: any surface, either side).
    std::optional<std::variant<shade::smooth_dielectric<real>, shade::thin_dielectric<real>>> glass;
    /// Rough glass instead (path integrator): a rough dielectric interface over GGX
    /// microfacets (single scattering or compensated, see rough_glass_bsdf), the object a
    /// closed shape whose outward normal points to the outside of the medium. Unlike
    /// `glass` it has a density over the whole sphere, so the path integrator samples
    /// lights on both sides of it.
    std::optional<rough_glass_bsdf> rough_glass;
    /// An OpenPBR Surface instead (path integrator; the classic integrator draws it black),
    /// evaluated with the surface's own (outward) normal, so that the side of v says whether
    /// the path is inside: its lobes, its emission (counted where a ray hits it) and its
    /// interior medium (openpbr_absorption).
    std::shared_ptr<const shade::openpbr_surface<real>> openpbr;
    /// Whether light can pass through the OpenPBR surface (transmission, geometry_opacity
    /// below 1 or a thin wall): then lights are sampled and paths continue on both sides of
    /// it; otherwise only on the side it is seen from.
    bool openpbr_two_sided = false;
    /// The absorption coefficient (1 / scene length, per channel) a path inside the OpenPBR
    /// object's interior medium is attenuated by: the medium's sigma_t (1 - albedo), its
    /// scattering ignored (openpbr_surface::interior()); 0 without a medium or for a thin wall.
    rgb openpbr_absorption{0};
    int emitter = -1; ///< index into scene::lights of the light this object is the geometry of
    /// For a mesh: each triangle k is a light of its own, scene::lights[emitter + k]
    /// (add_emissive_mesh); otherwise the whole object is scene::lights[emitter].
    bool emitter_per_triangle = false;

    /// The index into scene::lights of the light at this object's triangle `triangle` (any value
    /// for objects that are not meshes), or -1 when the object does not emit.
    [[nodiscard]] int light_at(std::uint32_t triangle) const noexcept {
        if (emitter < 0) return -1;
        return emitter_per_triangle ? emitter + int(triangle) : emitter;
    }
};

/// Settings of the direct-lighting integrator.
struct lighting_options {
    int area_samples_per_side = 4; ///< n: each area light is sampled n x n times per hit
};

/// A scene: objects, lights, camera and background. Add objects with add_sphere, add_plane
/// and add_mesh, which keep a hierarchy over the bounded ones (spheres and meshes) so that
/// a ray tests only the objects whose boxes it enters; planes are tested one by one.
struct scene {
    std::string name;
    std::vector<object> objects;
    std::vector<shade::any_light<real>> lights;
    /// An image-based environment (trace --envmap), seen by rays that leave the scene and
    /// sampled as one more light by the path integrator (the direct integrator ignores it).
    std::shared_ptr<const shade::environment_map_light<real>> environment_map;
    std::optional<shade::pinhole_camera<real>> camera;
    rgb background{0.02, 0.02, 0.03};

    void add_sphere(const shade::sphere<real>& s, material m) {
        object o;
        o.shape = object::kind::sphere;
        o.sphere = s;
        o.surface = std::move(m);
        objects.push_back(std::move(o));
        index_objects();
    }
    void add_plane(const shade::plane<real>& p, material m) {
        object o;
        o.shape = object::kind::plane;
        o.plane = p;
        o.surface = std::move(m);
        objects.push_back(std::move(o));
        index_objects();
    }
    /// A sphere with a physical material (lit with the classic mode by the direct
    /// integrator).
    void add_physical_sphere(const shade::sphere<real>& s, const shade::any_brdf<real>& b) {
        add_sphere(s, make_material(b));
        objects.back().brdf = b;
    }
    /// A mesh with a physical material.
    void add_physical_mesh(tracer::mesh m, const shade::any_brdf<real>& b) {
        add_mesh(std::move(m), mesh_shading::flat, make_material(b));
        objects.back().brdf = b;
    }
    /// A sphere light that is also visible geometry, with an optional material for the
    /// light it reflects (none: it absorbs).
    void add_emitting_sphere(const shade::sphere_light<real>& light, const std::optional<shade::any_brdf<real>>& b) {
        lights.emplace_back(light);
        add_sphere(light.shape(), make_material(b ? *b : shade::any_brdf<real>(shade::lambert<real>(rgb(0)))));
        objects.back().brdf = b;
        objects.back().emitter = int(lights.size()) - 1;
    }
    /// A quad light that is also visible geometry (two triangles; the whole quad is the
    /// one light), with an optional material for the light it reflects (none: it absorbs).
    void add_emitting_quad(const shade::area_light<real>& light, const std::optional<shade::any_brdf<real>>& b) {
        lights.emplace_back(light);
        tracer::mesh m;
        const vec3 c = light.corner(), u = light.edge_u(), v = light.edge_v();
        m.positions = {c, c + u, c + u + v, c + v}; // wound so that the normal is the light's
        m.normals.assign(4, light.normal());
        m.indices = {0, 1, 2, 0, 2, 3};
        add_mesh(std::move(m), mesh_shading::flat,
                 make_material(b ? *b : shade::any_brdf<real>(shade::lambert<real>(rgb(0)))));
        objects.back().brdf = b;
        objects.back().emitter = int(lights.size()) - 1;
    }
    /// A mesh whose every triangle emits `radiance` in W/(m^2 sr) toward the side its
    /// winding faces (one shade::triangle_light per triangle), with an optional material
    /// (none: black).
    void add_emissive_mesh(tracer::mesh m, const rgb& radiance, const std::optional<shade::any_brdf<real>>& b) {
        const int first = int(lights.size());
        for (std::size_t k = 0; k < m.triangle_count(); ++k) {
            const auto t = m.triangle(k);
            lights.emplace_back(shade::triangle_light<real>::from_radiance(t.v0, t.v1, t.v2, radiance));
        }
        add_mesh(std::move(m), mesh_shading::flat,
                 make_material(b ? *b : shade::any_brdf<real>(shade::lambert<real>(rgb(0)))));
        objects.back().brdf = b;
        objects.back().emitter = first;
        objects.back().emitter_per_triangle = true;
    }
    /// A sphere of glass (a smooth dielectric of relative index eta inside; path
    /// integrator only, which the classic integrator draws black).
    void add_glass_sphere(const shade::sphere<real>& sphere, real eta) {
        add_sphere(sphere, make_material(shade::any_brdf<real>(shade::lambert<real>(rgb(0)))));
        objects.back().glass = shade::smooth_dielectric<real>(eta);
    }
    /// A pane of thin glass (shade::thin_dielectric of index eta) over the mesh's triangles.
    void add_glass_pane(tracer::mesh m, real eta) {
        add_mesh(std::move(m), mesh_shading::flat, make_material(shade::any_brdf<real>(shade::lambert<real>(rgb(0)))));
        objects.back().glass = shade::thin_dielectric<real>(eta);
    }
    /// A sphere of rough glass: shade::rough_dielectric over shade::ggx(alpha) of relative
    /// index eta inside, or with `model` compensated, shade::compensated_rough_dielectric
    /// (path integrator only; the classic integrator draws it black). Throws
    /// shade::invalid_parameter as ggx and rough_dielectric do (alpha in [1e-4, 1e4]; eta
    /// in [1e-4, 1e4], not 1).
    void add_rough_glass_sphere(const shade::sphere<real>& sphere, real alpha, real eta,
                                rough_glass_model model = rough_glass_model::single_scattering) {
        const rough_glass_bsdf glass = make_rough_glass(alpha, eta, model);
        add_sphere(sphere, make_material(shade::any_brdf<real>(shade::lambert<real>(rgb(0)))));
        objects.back().rough_glass = glass;
    }
    /// A closed mesh of rough glass (its triangles wound counter-clockwise seen from
    /// outside, so that their normals point out of the medium), as add_rough_glass_sphere.
    void add_rough_glass_mesh(tracer::mesh m, real alpha, real eta,
                              rough_glass_model model = rough_glass_model::single_scattering) {
        const rough_glass_bsdf glass = make_rough_glass(alpha, eta, model);
        add_mesh(std::move(m), mesh_shading::flat, make_material(shade::any_brdf<real>(shade::lambert<real>(rgb(0)))));
        objects.back().rough_glass = glass;
    }
    /// A sphere of an OpenPBR Surface material (path integrator only; the classic
    /// integrator draws it black). Throws shade::invalid_parameter as openpbr_surface's
    /// constructor does.
    void add_openpbr_sphere(const shade::sphere<real>& sphere, const shade::openpbr_parameters<real>& parameters) {
        auto surface = std::make_shared<const shade::openpbr_surface<real>>(parameters);
        add_sphere(sphere, make_material(shade::any_brdf<real>(shade::lambert<real>(rgb(0)))));
        object& o = objects.back();
        // openpbr_surface transmits through its translucent base (not a pure metal), the
        // pass-through of opacity below 1 and, thin-walled, through the sheet; its
        // subsurface is a diffuse reflection of the surface (the medium is only reported).
        o.openpbr_two_sided = (parameters.transmission_weight > 0 && parameters.base_metalness < 1) ||
                              parameters.geometry_opacity < 1 || parameters.geometry_thin_walled;
        const auto medium = surface->interior();
        if (medium.present && !surface->thin_walled()) o.openpbr_absorption = medium.sigma_t * (rgb(1) - medium.albedo);
        o.openpbr = std::move(surface);
    }
    void add_mesh(tracer::mesh m, mesh_shading shading, material mat) {
        object o;
        o.shape = object::kind::mesh;
        auto shared = std::make_shared<const tracer::mesh>(std::move(m));
        o.mesh_bvh = std::make_shared<const shade::triangle_bvh<real, shade::watertight>>(shared->triangles());
        o.mesh = std::move(shared);
        o.shading = shading;
        o.surface = std::move(mat);
        objects.push_back(std::move(o));
        index_objects();
    }

    /// The closest hit along r, if any.
    [[nodiscard]] std::optional<scene_hit> intersect(shade::ray<real> r) const {
        std::optional<scene_hit> best;
        for (const std::size_t i : unbounded_) {
            if (auto h = intersect_object(i, r)) {
                r.t_max = h->t;
                best = h;
            }
        }
        if (auto h = bounded_.closest(r, [&](std::uint32_t k, const shade::ray<real>& rr) {
                return intersect_object(bounded_objects_[k], rr);
            }))
            best = h->hit;
        return best;
    }

    /// True when something blocks r within its interval (shadow rays).
    [[nodiscard]] bool occluded(const shade::ray<real>& r) const {
        // Only whether something is hit: no scene_hit is built.
        for (const std::size_t i : unbounded_)
            if (shade::intersect(r, *objects[i].plane)) return true;
        return bounded_.any(r, [&](std::uint32_t k, const shade::ray<real>& rr) {
            const object& o = objects[bounded_objects_[k]];
            if (o.shape == object::kind::mesh) return o.mesh_bvh->any(rr);
            return shade::find_intersection(rr, *o.sphere).has_value();
        });
    }

    /// Direct lighting at hit h seen from direction v (unit, toward the viewer): the sum over
    /// lights of the object's material, with shadow rays. `random` jitters area-light strata.
    [[nodiscard]] rgb shade_hit(const scene_hit& h, const vec3& v, shade::rng& random,
                                const lighting_options& options = {}) const {
        const object& o = objects[h.object];
        if (o.shape == object::kind::mesh && o.shading == mesh_shading::gouraud) {
            // Gouraud: light the three vertices (with their own normals and view
            // directions, without shadows, as the 1971 method does) and interpolate.
            rgb c(0);
            const vec3 eye = h.p + v * h.t;
            for (int k = 0; k < 3; ++k) {
                const std::uint32_t vi = o.mesh->indices[3 * std::size_t(h.triangle) + std::size_t(k)];
                const vec3 pk = o.mesh->positions[vi];
                const vec3 vk = glm::normalize(eye - pk);
                const auto at = surface_point::at(pk, o.mesh->normals[vi]);
                c += h.barycentric[k] * light_point(o, at, h.geometric_n, h.p_error, vk, random, options, false);
            }
            return c;
        }
        const auto at = surface_point::at(h.p, h.shading_n);
        return light_point(o, at, h.geometric_n, h.p_error, v, random, options, true);
    }

private:
    shade::bvh<real> bounded_;                   ///< over the objects with a box
    std::vector<std::size_t> bounded_objects_;   ///< bounded_'s primitive k is objects[bounded_objects_[k]]
    std::vector<std::size_t> unbounded_;         ///< the planes

    /// Rebuilds the hierarchy over the bounded objects (a few dozen at most: cheap).
    void index_objects() {
        std::vector<shade::aabb<real>> boxes;
        bounded_objects_.clear();
        unbounded_.clear();
        for (std::size_t i = 0; i < objects.size(); ++i) {
            const object& o = objects[i];
            if (o.shape == object::kind::plane) {
                unbounded_.push_back(i);
                continue;
            }
            boxes.push_back(o.shape == object::kind::sphere ? shade::bounds(*o.sphere) : o.mesh->bounds());
            bounded_objects_.push_back(i);
        }
        bounded_ = shade::bvh<real>(boxes);
    }

    [[nodiscard]] std::optional<scene_hit> intersect_object(std::size_t i, const shade::ray<real>& r) const {
        const object& o = objects[i];
        scene_hit out;
        out.object = i;
        switch (o.shape) {
        case object::kind::sphere: {
            // The lean test (t, p, n, face): the scene uses no surface parameterisation.
            const auto h = shade::find_intersection(r, *o.sphere);
            if (!h) return std::nullopt;
            out.t = h->t;
            out.p = h->p;
            out.p_error = h->p_error;
            out.geometric_n = out.shading_n = h->facing_normal();
            out.outward_n = h->n;
            return out;
        }
        case object::kind::plane: {
            const auto h = shade::intersect(r, *o.plane);
            if (!h) return std::nullopt;
            out.t = h->t;
            out.p = h->p;
            out.p_error = h->p_error;
            out.geometric_n = out.shading_n = h->facing_normal();
            out.outward_n = h->n;
            return out;
        }
        case object::kind::mesh: {
            const tracer::mesh& m = *o.mesh;
            const auto x = o.mesh_bvh->closest(r);
            if (!x) return std::nullopt;
            out.triangle = x->primitive;
            const shade::triangle_hit<real>& h = x->hit;
            out.t = h.t;
            out.p = h.p;
            out.p_error = h.p_error;
            out.barycentric = h.barycentric;
            out.geometric_n = h.facing_normal();
            out.outward_n = h.n;
            out.shading_n = out.geometric_n;
            if (o.shading != mesh_shading::flat) {
                const std::size_t k = 3 * std::size_t(out.triangle);
                vec3 n = h.barycentric.x * m.normals[m.indices[k]] +
                         h.barycentric.y * m.normals[m.indices[k + 1]] +
                         h.barycentric.z * m.normals[m.indices[k + 2]];
                n = glm::normalize(n);
                // Keep the interpolated normal on the viewer's side of the surface.
                out.shading_n = glm::dot(n, out.geometric_n) < 0 ? -n : n;
            }
            return out;
        }
        }
        return std::nullopt;
    }

public:
    /// Sum over lights for shader s at q.at (shade::sum_over_lights), with shadow rays
    /// when q.shadows; area lights are sampled on a jittered n x n grid.
    template <class S>
    [[nodiscard]] rgb sum_lights(const S& s, const lighting_query& q) const {
        const auto jitter = [&](int, int) { return vec2(q.random.uniform<real>(), q.random.uniform<real>()); };
        // The same origin for every sample: off the surface on the side of the geometric
        // normal (shadow rays toward lights below it are never traced).
        const vec3 origin = shade::offset_ray_origin(q.at.p, q.p_error, q.geometric_n, q.geometric_n);
        // One light at a time, so that each shadow ray knows which light it goes to.
        rgb sum(0);
        for (std::size_t i = 0; i < lights.size(); ++i) {
            const auto unoccluded = [&](const light_sample& ls) {
                return !q.shadows || (glm::dot(ls.l, q.geometric_n) > 0 && light_visible(i, origin, ls.l, ls.distance));
            };
            sum += shade::sum_over_lights(s, q.at, q.v, std::span<const shade::any_light<real>>(&lights[i], 1), unoccluded,
                                          q.options.area_samples_per_side, jitter);
        }
        return sum;
    }

    /// Whether light `index` (of `lights`) is visible from `origin` (already off its
    /// surface) in the unit direction l, the light's sample being `distance` away, without
    /// an epsilon at the light's end:
    ///   * at infinity: nothing blocks the ray (origin, l);
    ///   * a light that is scene geometry (object::emitter): the closest hit along
    ///     (origin, l) is that light itself (object::light_at gives its index). A flat or
    ///     convex emitter cannot hide its own sampled point, and asking which surface is hit
    ///     first avoids comparing the light's distance with another routine's rounding of it;
    ///   * any other light (points, spots, lights without geometry): nothing blocks the
    ///     segment up to the light's distance (nothing of the scene is at the light to tie with).
    /// An index past `lights` (the environment map of the path integrator) is at infinity.
    [[nodiscard]] bool light_visible(std::size_t index, const vec3& origin, const vec3& l, real distance) const {
        if (std::isinf(distance)) return !occluded(shade::ray<real>{origin, l, 0, distance});
        const bool is_geometry =
            index < lights.size() && std::any_of(objects.begin(), objects.end(), [&](const object& o) {
                if (o.emitter < 0 || index < std::size_t(o.emitter)) return false;
                const std::size_t count = o.emitter_per_triangle && o.mesh ? o.mesh->triangle_count() : 1;
                return index - std::size_t(o.emitter) < count;
            });
        if (!is_geometry) return !occluded(shade::ray<real>{origin, l, 0, distance});
        const auto h = intersect(shade::ray<real>{origin, l});
        return h && objects[h->object].light_at(h->triangle) == int(index);
    }

private:
    /// Lights `at` with object o's material.
    [[nodiscard]] rgb light_point(const object& o, const surface_point& at, const vec3& geometric_n,
                                  const vec3& p_error, const vec3& v, shade::rng& random,
                                  const lighting_options& options, bool shadows) const {
        return o.surface(lighting_query{*this, at, geometric_n, p_error, v, random, options, shadows});
    }
};

namespace detail {

/// A two-way pattern (shade::checker, shade::checker_2d): the child used at a point is
/// first() where parity(at) is 0, else second().
template <class S>
concept two_way_pattern = requires(const S& s, const surface_point& at) {
    { s.parity(at) } -> std::same_as<int>;
    s.first();
    s.second();
};

template <class S>
inline constexpr bool is_lit = false;
template <class B>
inline constexpr bool is_lit<shade::lit<B>> = true;

/// BRDF b as a BRDF with f only (not a shade::split_brdf), so that shade::lit weights all
/// of it with the light's diffuse colour.
template <class B>
struct unsplit_brdf {
    using scalar_type = real;
    const B* b;
    [[nodiscard]] rgb f(const vec3& l, const vec3& v, const surface_point& at) const { return b->f(l, v, at); }
};

} // namespace detail

/// A pattern's child is the same for every light sample at one point, so it is chosen
/// once per point. The checker shader shades with shade_of(child), so lighting the child
/// computes the same, sample for sample. lit<checker> computes what lit<child> with the
/// same ambient reflectance does, if the checker and the child are both split BRDFs (f_d
/// and f_s weighted by the light's diffuse and specular colours) or both not; a split
/// child of an unsplit checker (a Lambert and a Blinn-Phong cell) is lit through its f.
template <class S>
rgb light_with(const S& s, const lighting_query& q) {
    if constexpr (detail::two_way_pattern<S>) {
        return s.parity(q.at) == 0 ? light_with(s.first(), q) : light_with(s.second(), q);
    } else if constexpr (detail::is_lit<S>) {
        using pattern = std::remove_cvref_t<decltype(s.brdf())>;
        if constexpr (detail::two_way_pattern<pattern>) {
            const auto light_child = [&](const auto& child) {
                using B = std::remove_cvref_t<decltype(child)>;
                if constexpr (shade::split_brdf<pattern> == shade::split_brdf<B>)
                    return light_with(shade::lit(child, s.ambient()), q);
                else
                    return light_with(shade::lit(detail::unsplit_brdf<B>{&child}, s.ambient()), q);
            };
            const pattern& b = s.brdf();
            return b.parity(q.at) == 0 ? light_child(b.first()) : light_child(b.second());
        } else {
            return q.lit_scene.sum_lights(s, q);
        }
    } else {
        return q.lit_scene.sum_lights(s, q);
    }
}

} // namespace tracer
