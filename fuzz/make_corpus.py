#!/usr/bin/env python3
"""Writes the seed corpora fuzz/corpus/<target>/<name>.bin for every fuzz target.

Each seed is a small, meaningful scene in the byte format of fuzz/input.hpp (a selector
byte per scalar: 0 special value, 1 fixed point int16/256, ...) and of each target's own
layout (see the comment at the top of each fuzz_<target>.cpp). The fuzzer mutates from
these; committing them makes the bounded CI run start from useful inputs.
Re-run after changing a target's layout:  python3 fuzz/make_corpus.py
"""
import os
import struct

HERE = os.path.dirname(os.path.abspath(__file__))

# Indices into special_values() in input.hpp.
ZERO, NEG_ZERO, ONE, MINUS_ONE, HALF, TWO, INF, NEG_INF, NAN, DENORM_MIN, NORM_MIN, MAX, \
    NEG_MAX, EPSILON, ONE_MINUS_HALF_EPS, TINY = range(16)


def sp(i):
    """A special value (selector 0)."""
    return bytes([0, i])


def fx(x):
    """A fixed-point value x, a multiple of 1/256 within +-128 (selector 1)."""
    n = int(round(x * 256))
    assert -32768 <= n <= 32767 and n / 256 == x, x
    return bytes([1]) + struct.pack('<h', n)


def vec(*xs):
    return b''.join(x if isinstance(x, bytes) else fx(x) for x in xs)


def byte(*bs):
    return bytes(bs)


def write(target, name, data):
    d = os.path.join(HERE, 'corpus', target)
    os.makedirs(d, exist_ok=True)
    with open(os.path.join(d, name + '.bin'), 'wb') as f:
        f.write(data)


UNIT_TRI = vec(0, 0, 0) + vec(1, 0, 0) + vec(0, 1, 0)
INTERVAL = sp(ZERO) + sp(INF)


def triangles():
    for algo in ('moller_trumbore', 'plane_then_areas', 'watertight'):
        t = 'triangle_' + algo
        for scalar, head in (('float', 0), ('double', 1)):
            write(t, f'hit_centre_{scalar}', byte(head, 0) + UNIT_TRI + vec(0.25, 0.25, 1) +
                  vec(0, 0, -1) + INTERVAL)
            write(t, f'back_face_culled_{scalar}', byte(head | 2, 0) + UNIT_TRI +
                  vec(0.25, 0.25, -1) + vec(0, 0, 1) + INTERVAL)
            write(t, f'aimed_edge_{scalar}', byte(head, 1) + UNIT_TRI + vec(0.5, 0.5, 2) +
                  vec(0.5, 0.5, 1) + INTERVAL)
            write(t, f'aimed_vertex_{scalar}', byte(head, 1) + UNIT_TRI + vec(-1, 2, 3) +
                  vec(1, 0, 1) + INTERVAL)
            write(t, f'parallel_{scalar}', byte(head, 0) + UNIT_TRI + vec(0, 0, 1) +
                  vec(1, 0, 0) + INTERVAL)
            write(t, f'interval_excludes_{scalar}', byte(head, 0) + UNIT_TRI +
                  vec(0.25, 0.25, 1) + vec(0, 0, -1) + vec(2) + vec(3))
            write(t, f'nan_direction_{scalar}', byte(head, 0) + UNIT_TRI + vec(0.25, 0.25, 1) +
                  vec(0, sp(NAN), -1) + INTERVAL)
            # Closed tetrahedron (0,0,0), (8,0,0), (0,8,0), (0,0,8), ray through an edge
            # midpoint direction and through a vertex direction.
            tet = bytes([0, 0, 0, 8, 0, 0, 0, 8, 0, 0, 0, 8]) + bytes([20])  # k = 0
            write(t, f'closed_edge_{scalar}', byte(head, 2) + tet + vec(1, 1, -1))
            write(t, f'closed_vertex_{scalar}', byte(head, 2) + tet + vec(-1, -1, 3))


def plane():
    for scalar, head in (('float', 0), ('double', 1)):
        write('plane', f'hit_{scalar}', byte(head) + vec(0, 0, 0) + vec(0, 0, 2) +
              vec(1, 1, 5) + vec(0, 0, -1) + INTERVAL)
        write('plane', f'culled_back_{scalar}', byte(head | 2) + vec(0, 0, 0) + vec(0, 0, 1) +
              vec(1, 1, -5) + vec(0, 0, 1) + INTERVAL)
        write('plane', f'grazing_{scalar}', byte(head) + vec(0, 0, 0) + vec(0, 0, 1) +
              vec(0, 0, 1) + vec(1, 0, sp(TINY)) + sp(ZERO) + sp(MAX))
        write('plane', f'zero_normal_{scalar}', byte(head) + vec(0, 0, 0) + vec(0, 0, 0) +
              vec(0, 0, 1) + vec(0, 0, -1) + INTERVAL)


def sphere():
    for scalar, head in (('float', 0), ('double', 1)):
        write('sphere', f'hit_{scalar}', byte(head) + vec(0, 0, -5) + fx(2) + vec(0, 0, 0) +
              vec(0, 0, -1) + INTERVAL)
        write('sphere', f'inside_{scalar}', byte(head) + vec(0, 0, 0) + fx(1) +
              vec(0.25, 0, 0) + vec(0, 1, 0) + INTERVAL)
        write('sphere', f'aimed_tangent_{scalar}', byte(head | 2) + vec(0, 0, 0) + fx(1) +
              vec(-4, 0, 0) + vec(0, 1, 0) + fx(1) + INTERVAL)
        write('sphere', f'far_{scalar}', byte(head) + vec(100, 100, 100) + fx(0.5) +
              vec(0, 0, 0) + vec(1, 1, 1) + INTERVAL)
        write('sphere', f'bad_radius_{scalar}', byte(head) + vec(0, 0, 0) + sp(NAN) +
              vec(0, 0, 5) + vec(0, 0, -1) + INTERVAL)


def color():
    for scalar, head in (('float', 0), ('double', 1)):
        weights = vec(1, 1, 1)
        d50_xyz = vec(0.96875, 1, 0.82421875)
        write('color', f'ordinary_{scalar}', byte(head) + vec(0.5, 0.25, 0.75) +
              vec(0.203125, 0.40625, 0.59375) + vec(50, 10, -20) + vec(60, -5, 30) + byte(10, 128, 255) +
              vec(0.3125, 0.328125) + d50_xyz + byte(1) + weights)
        write('color', f'd50_xyz_{scalar}', byte(head) + vec(0, 1, 0.0078125) +
              vec(1, 1, 1) + vec(100, 0, 0) + vec(0, 0, 0) + byte(0, 0, 0) +
              vec(0.3125, 0.328125) + d50_xyz + byte(0) + vec(2, 1, 1))
        write('color', f'nan_and_inf_{scalar}', byte(head) + vec(sp(NAN), sp(INF), sp(NEG_INF)) +
              vec(sp(MAX), -1, 0) + vec(sp(NAN), 0, 0) + vec(50, 0, 0) + byte(1, 2, 3) +
              vec(sp(TINY), sp(DENORM_MIN)) + vec(sp(MAX), 0.5, 1) + byte(0) + weights)
        write('color', f'opposite_hues_{scalar}', byte(head) + vec(0.125, 0.125, 0.125) +
              vec(0.5, 0.5, 0.5) + vec(50, 2.5, 0) + vec(50, -2.5, 0) + byte(255, 255, 255) +
              vec(0.3125, 0.328125) + d50_xyz + byte(1) + weights)


def situation(how, n=(0, 0, 1), t=(1, 0, 0), a=(0.5, 0.25, 1), b=(-0.25, 0.5, 1), u=(0.5, 0.25, 0.75)):
    """n, t, how l and v are made, two vectors, then sample()'s uc, u_x, u_y."""
    return vec(*n) + vec(*t) + byte(how) + vec(*a) + vec(*b) + vec(*u)


SITUATIONS = {
    'generic': situation(0),
    'l_equals_v': situation(1),
    'l_opposite_v': situation(2),
    'mirror_h_is_n': situation(3),
    'l_is_n': situation(4),
    'v_is_n': situation(5),
    'grazing': situation(6),
    'below_horizon': situation(0, b=(0.25, 0.5, -1)),
    'raw_unnormalised': situation(7, a=(8, 0, 8), b=(0, sp(NAN), 1)),
    'tilted_normal': situation(0, n=(1, 2, 3), t=(0, 1, 0)),
    'sample_u_zero': situation(0, u=(0, 0, 0)),
    'sample_u_below_one': situation(0, u=(sp(ONE_MINUS_HALF_EPS), sp(ONE_MINUS_HALF_EPS),
                                          sp(ONE_MINUS_HALF_EPS))),
    'sample_grazing_view': situation(0, b=(1, 0, 0.0078125), u=(0.75, 0.5, 0.5)),
}


def brdfs():
    params = {
        'lambert': [('', vec(0.5, 0.25, 0.75))],
        'phong': [(f'form{f}_', byte(f) + vec(0.25, 0.25, 0.25) + vec(0.5, 0.5, 0.5) + s)
                  for f in range(3) for s in (fx(32),)] +
                 [('shininess0_', byte(2) + vec(0.25, 0.25, 0.25) + vec(0.5, 0.5, 0.5) + sp(ZERO)),
                  ('shininess1e4_', byte(0) + vec(0.25, 0.25, 0.25) + vec(0.5, 0.5, 0.5) +
                   bytes([2]) + struct.pack('<h', 20000) + bytes([14]))],  # 0.61 * 2^14
        'blinn_phong': [(f'form{f}_', byte(f) + vec(0.25, 0.25, 0.25) + vec(0.5, 0.5, 0.5) + fx(64))
                        for f in range(4)] +
                       [('shininess0_', byte(3) + vec(0.25, 0.25, 0.25) + vec(0.5, 0.5, 0.5) + sp(ZERO))],
        'oren_nayar': [('trigfree_', byte(0) + vec(0.5, 0.5, 0.5) + fx(0.5)),
                       ('trig_', byte(1) + vec(0.5, 0.5, 0.5) + fx(1)),
                       ('sigma0_', byte(0) + vec(0.5, 0.5, 0.5) + sp(ZERO))],
        'ashikhmin_shirley': [('iso_', vec(0.5, 0.5, 0.5) + vec(0.25, 0.25, 0.25) + fx(100) + fx(100)),
                              ('aniso_', vec(0.5, 0.5, 0.5) + vec(0.25, 0.25, 0.25) + fx(10) + fx(127)),
                              ('p0_', vec(0.5, 0.5, 0.5) + vec(0.25, 0.25, 0.25) + sp(ZERO) + sp(ZERO))],
        'cook_torrance': [(f'c{c}_', byte(c) + r + vec(0.0390625, 0.0390625, 0.0390625) + fx(1.5) +
                           vec(1, 1, 1) + vec(0.25, 0.25, 0.25))
                          for c in (0, 1, 2, 3, 4, 5, 6, 7, 8, 17)
                          for r in (fx(0.25),)] +
                         [('rough1e-4_', byte(1) + sp(TINY) + vec(0.5, 0.5, 0.5) + fx(1.5) +
                           vec(1, 1, 1) + vec(0, 0, 0)),
                          ('rough1_', byte(6) + sp(ONE) + vec(0.5, 0.5, 0.5) + fx(1.5) +
                           vec(1, 1, 1) + vec(0, 0, 0))],
    }
    for model, variants in params.items():
        for prefix, p in variants:
            for sname, s in SITUATIONS.items():
                for scalar, head in (('float', 0), ('double', 1)):
                    if scalar == 'double' and sname not in ('generic', 'grazing', 'mirror_h_is_n'):
                        continue
                    write('brdf_' + model, f'{prefix}{sname}_{scalar}', byte(head) + p + s)


def bsdfs():
    """fuzz_bsdf_dielectric: head, model byte (0-6), alpha_x, alpha_y, eta, the conductor's
    eta and kappa, a situation. fuzz_bsdf_openpbr: head, thin-walled byte, a situation, then
    edits of the default parameters: parameter byte (index into kParameters), a channel byte
    for a colour (3: all three), the value. fuzz_brdf_lobes: head, model byte (0-4), a colour,
    a roughness, alpha_x, alpha_y, a situation."""
    sits = {k: SITUATIONS[k] for k in ('generic', 'below_horizon', 'grazing', 'mirror_h_is_n', 'v_is_n',
                                      'sample_grazing_view', 'raw_unnormalised')}
    sits['inside_view'] = situation(0, a=(0.5, 0.25, -1), b=(-0.25, 0.5, -1))
    for model in range(7):
        for sname, st in sits.items():
            for scalar, head in (('float', 0), ('double', 1)):
                if scalar == 'double' and sname not in ('generic', 'inside_view'):
                    continue
                write('bsdf_dielectric', f'model{model}_{sname}_{scalar}',
                      byte(head, model) + fx(0.25) + fx(0.125) + fx(1.5) + vec(0.25, 0.875, 1.125) +
                      vec(3.875, 2.375, 2.25) + st)
    for model in range(5):
        for roughness in (0, 0.5, 1):
            for sname, st in sits.items():
                if sname == 'inside_view':
                    continue
                for scalar, head in (('float', 0), ('double', 1)):
                    if scalar == 'double' and sname != 'generic':
                        continue
                    write('brdf_lobes', f'model{model}_r{roughness}_{sname}_{scalar}',
                          byte(head, model) + vec(0.75, 0.5, 0.25) + fx(roughness) + fx(0.25) + fx(0.125) + st)

    def edit(index, value, colour=False):
        return byte(index) + (byte(3) if colour else b'') + (value if isinstance(value, bytes) else fx(value))
    materials = {
        'default': b'',
        'metal': edit(3, 1),
        'glass': edit(9, 1),
        'smooth_glass': edit(9, 1) + edit(6, 0),
        'coated_plastic': edit(21, 1) + edit(23, 0.125),
        'fuzz': edit(27, 1) + edit(29, 0.5),
        'thin_film': edit(30, 1) + edit(31, 0.5),
        'subsurface': edit(16, 1),
        'opacity': edit(35, 0.5),
        'anisotropic_metal': edit(3, 1) + edit(7, 0.875),
        'emission': edit(33, 1) + edit(21, 1),
    }
    for name, edits in materials.items():
        for thin in (0, 1):
            if thin and name not in ('glass', 'smooth_glass', 'thin_film', 'subsurface'):
                continue
            for sname, st in sits.items():
                for scalar, head in (('float', 0), ('double', 1)):
                    if scalar == 'double' and sname not in ('generic', 'inside_view'):
                        continue
                    write('bsdf_openpbr', f'{name}{"_thin" if thin else ""}_{sname}_{scalar}',
                          byte(head, thin) + st + edits)


def bvhs():
    """fuzz_bvh: head (bit 0 double, bits 1-2 structure, bit 3 cull), count, primitives,
    then four rays: aimed flag, origin, (target byte + weights | direction), t_min, t_max."""
    # A closed tetrahedron (outward winding) and a far triangle behind it.
    tet = [((0, 0, 0), (1, 0, 0), (0, 1, 0)), ((0, 0, 0), (0, 0, 1), (1, 0, 0)),
           ((0, 0, 0), (0, 1, 0), (0, 0, 1)), ((1, 0, 0), (0, 0, 1), (0, 1, 0))]
    tris = tet + [((-4, -4, -3), (4, -4, -3), (0, 4, -3))]
    tri_bytes = b''.join(vec(*a) + vec(*b) + vec(*c) for a, b, c in tris)
    rays = (byte(1) + vec(0.25, 0.25, 2) + byte(0) + vec(1, 1, 1) + INTERVAL +          # centroid of face 0
            byte(1) + vec(0.125, 0.125, -2) + byte(3) + vec(1, 1, 0) + INTERVAL +       # edge of face 3
            byte(1) + vec(2, 2, 2) + byte(1) + vec(1, 0, 0) + INTERVAL +                # a vertex
            byte(0) + vec(0.25, 0.25, 0.25) + vec(0, 0, -1) + INTERVAL)                 # from inside, down
    spheres = b''.join(vec(*c) + fx(r) for c, r in (((0, 0, 0), 1), ((3, 0, 0), 0.5), ((0, 0, -6), 2),
                                                      ((0.5, 0, 0), 0.25)))
    sphere_rays = (byte(1) + vec(0, 0, 5) + byte(0) + vec(0, 0, 1) + INTERVAL +
                   byte(1) + vec(3, 3, 0) + byte(1) + vec(0, 1, 0) + INTERVAL +
                   byte(0) + vec(-5, 0, 0) + vec(1, 0, 0) + INTERVAL +
                   byte(0) + vec(0, 0, 0) + vec(0, 0, -1) + INTERVAL)
    for scalar, bit in (('float', 0), ('double', 1)):
        for name, structure in (('moller_trumbore', 0), ('watertight', 1)):
            for cull in (0, 8):
                head = bit | (structure << 1) | cull
                write('bvh', f'tetrahedron_{name}{"_culled" if cull else ""}_{scalar}',
                      byte(head, len(tris)) + tri_bytes + rays)
        write('bvh', f'spheres_{scalar}', byte(bit | 4, 4) + spheres + sphere_rays)
        write('bvh', f'empty_{scalar}', byte(bit, 0) + rays)
        write('bvh', f'non_finite_vertex_{scalar}', byte(bit, 1) + vec(0, 0, 0) + vec(1, sp(NAN), 0) +
              vec(0, 1, 0) + rays)


def emission(intensity=1):
    return fx(intensity) + vec(0.125, 0.125, 0.125) + vec(1, 1, 1) + vec(1, 0.5, 0.25)


def sums():
    lights = {
        'directional': byte(0) + emission() + byte(0) + vec(1, 1, 1),
        'point': byte(1) + emission(4) + byte(2) + vec(1, 2, 3),
        'spot': byte(2) + emission(4) + byte(1) + vec(0, 0, 4) + vec(0, 0, -1) + fx(0.25) + fx(0.5),
        'area': byte(3) + emission(2) + byte(0) + vec(-1, -1, 3) + vec(2, 0, 0) + vec(0, 2, 0) + byte(1),
    }
    shader_names = ['lit_lambert', 'lit_blinn_phong', 'toon', 'gooch', 'checker', 'gradient']
    tail = vec(0.25, 0.5, 0) + vec(0, 0, 1) + vec(0.25, 0, 1)  # p, n, v
    for which, sname in enumerate(shader_names):
        shader = (byte(which) + vec(0.5, 0.5, 0.5) + vec(0.25, 0.25, 0.25) + vec(0.125, 0, 0.25) +
                  fx(16) + fx(1) + vec(1, 0, 0) + byte(3))
        for lname, l in lights.items():
            for vis in range(4):
                if vis and lname != 'area':
                    continue
                data = byte(0) + shader + byte(0) + l + tail + byte(vis) + fx(0.5) + byte(1) + byte(2)
                write('sum_over_lights', f'{sname}_{lname}_vis{vis}', data)
        all_lights = byte(2) + lights['directional'] + lights['point'] + lights['area']
        write('sum_over_lights', f'{sname}_three_lights_double',
              byte(1) + shader + all_lights + tail + byte(0) + fx(1) + byte(1) + byte(3))
    # samples_per_side 0 must throw invalid_parameter.
    write('sum_over_lights', 'samples_per_side_zero',
          byte(0) + byte(0) + vec(0.5, 0.5, 0.5) + vec(0.25, 0.25, 0.25) + vec(0, 0, 0) + fx(16) +
          fx(1) + vec(1, 0, 0) + byte(3) + byte(0) + lights['area'] + tail + byte(0) + fx(1) +
          byte(1) + byte(0))


def lights():
    """Seeds of fuzz_light_area, _disk, _sphere and _environment: byte 0 = scalar type,
    the light's parameters, the emission, a sides byte, then p, u.x, u.y, w."""
    def situation(p, u=(0.25, 0.75), w=(0, 0, 1)):
        return vec(*p) + vec(*u) + vec(*w)
    for scalar, head in (('float', 0), ('double', 1)):
        rect = vec(-1, -1, 2) + vec(2, 0, 0) + vec(0, 2, 0) + emission(2)
        write('light_area', f'above_one_sided_{scalar}', byte(head) + rect + byte(0) + situation((0.25, 0, 0), w=(0, 0.125, 1)))
        write('light_area', f'behind_one_sided_{scalar}', byte(head) + rect + byte(0) + situation((0, 0, 4)))
        write('light_area', f'behind_two_sided_{scalar}', byte(head) + rect + byte(1) + situation((0, 0, 4), w=(0, 0, -1)))
        write('light_area', f'on_the_light_{scalar}', byte(head) + rect + byte(0) + situation((0, 0, 2)))
        write('light_area', f'parallel_edges_{scalar}', byte(head) + vec(0, 0, 2) + vec(1, 0, 0) + vec(2, 0, 0) +
              emission() + byte(0) + situation((0, 0, 0)))
        write('light_area', f'invalid_sides_{scalar}', byte(head) + rect + byte(2) + situation((0, 0, 0)))
        disk = vec(0, 0, 2) + vec(0, 0, -1) + fx(0.5) + emission(3)
        write('light_disk', f'facing_{scalar}', byte(head) + disk + byte(0) + situation((0.25, 0.5, 0), w=(0.125, 0, 1)))
        write('light_disk', f'behind_{scalar}', byte(head) + disk + byte(0) + situation((0, 0, 3)))
        write('light_disk', f'two_sided_{scalar}', byte(head) + disk + byte(1) + situation((0, 0, 3), w=(0, 0, -1)))
        write('light_disk', f'zero_radius_{scalar}', byte(head) + vec(0, 0, 2) + vec(0, 0, -1) + fx(0) + emission() +
              byte(0) + situation((0, 0, 0)))
        write('light_disk', f'zero_normal_{scalar}', byte(head) + vec(0, 0, 2) + vec(0, 0, 0) + fx(1) + emission() +
              byte(0) + situation((0, 0, 0)))
        sphere = vec(0, 0, 3) + fx(0.5) + emission(2)
        write('light_sphere', f'outside_{scalar}', byte(head) + sphere + byte(0) + situation((0, 0, 0), w=(0, 0.0625, 1)))
        write('light_sphere', f'far_small_{scalar}', byte(head) + vec(0, 0, 100) + fx(0.0625) + emission() + byte(0) +
              situation((0, 0, 0)))
        write('light_sphere', f'inside_two_sided_{scalar}', byte(head) + vec(0, 0, 0) + fx(4) + emission() + byte(1) +
              situation((0.5, 0.25, 1), w=(1, 0, 0)))
        write('light_sphere', f'inside_one_sided_{scalar}', byte(head) + vec(0, 0, 0) + fx(4) + emission() + byte(0) +
              situation((0.5, 0.25, 1)))
        write('light_sphere', f'on_the_surface_{scalar}', byte(head) + sphere + byte(0) + situation((0, 0, 2.5)))
        write('light_sphere', f'negative_radius_{scalar}', byte(head) + vec(0, 0, 3) + fx(-1) + emission() + byte(0) +
              situation((0, 0, 0)))
        write('light_environment', f'white_{scalar}', byte(head) + emission() + situation((1, 2, 3), w=(0, 1, 0)))
        write('light_environment', f'black_{scalar}', byte(head) + emission(0) + situation((0, 0, 0)))
        write('light_environment', f'negative_{scalar}', byte(head) + emission(-1) + situation((0, 0, 0)))
        write('light_environment', f'huge_{scalar}', byte(head) + sp(MAX) + vec(0, 0, 0) + vec(1, 1, 1) + vec(1, 1, 1) +
              situation((0, 0, 0)))


if __name__ == '__main__':
    triangles()
    plane()
    sphere()
    color()
    brdfs()
    bsdfs()
    bvhs()
    sums()
    lights()
