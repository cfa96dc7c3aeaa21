#!/usr/bin/env python3
"""Turn Google Benchmark JSON output (and optional callgrind dumps) into docs/benchmarks.md.

Called by script/bench; python3 standard library only.

Benchmark names are "<family>/<type>[/<subgroup>]/<variant>" (bench/support.hpp). All
variants of one group ran on the same data in the same binary run, so every ratio below
divides two numbers from the same run of the same binary.
"""

import argparse
import glob
import json
import os
import re
import sys

# The baseline variant of each family: ratios are time(variant) / time(baseline).
BASELINES = {
    "triangle": "glm",
    "triangle_batch": "glm",
    "sphere": "glm",
    "plane": "glm",
    "brdf": "lambert",
    "bvh": "embree",
    "brdf_sampling": "f",
    "bsdf": "ggx_conductor",
    "openpbr": "lambert",
}

# Row (variant) and column (subgroup) order of a family's tables, where the order of first
# appearance in the JSON (random, with interleaved runs) would not do; others keep it.
VARIANT_ORDER = {
    "bsdf": ["ggx_conductor", "ggx_conductor_exact_fresnel", "smooth_conductor", "smooth_dielectric",
             "thin_dielectric", "rough_dielectric_ggx", "rough_dielectric_beckmann",
             "compensated_dielectric_anisotropic_tables", "compensated_dielectric_anisotropic_grid"],
}
OPENPBR_MATERIALS = ["default_material", "metal", "rough_glass", "coated_plastic"]
VARIANT_ORDER["openpbr"] = ["lambert"] + [v for m in OPENPBR_MATERIALS for v in (
    m, f"{m}.coat", f"{m}.metal", f"{m}.specular", f"{m}.transmission", f"{m}.diffuse")]
SUBGROUP_ORDER = {
    "bsdf": ["f_reflection", "f_transmission", "pdf_reflection", "pdf_transmission", "sample_outside",
             "sample_inside"],
    "openpbr": ["f", "pdf", "sample"],
}

FAMILY_TITLES = {
    "triangle": "Ray/triangle, scalar (random pairs: 512 in float, 256 in double, per hit rate)",
    "triangle_batch": "Ray/triangle, batched: one ray against 8 or 16 triangles (SoA), per test",
    "sphere": "Ray/sphere",
    "plane": "Ray/plane",
    "brdf": "BRDF evaluation (f(l, v), 512 direction pairs above the surface)",
    "bvh": "BVH against Embree 3 (ns per ray, or per build)",
    "brdf_sampling": "BRDF sampling per model: sample(v, uc, u) and pdf(l, v) against f(l, v), and f before the sampling redesign (legacy_f, bench/legacy/)",
    "openpbr": "OpenPBR Surface and its lobes (bench/openpbr.cpp: 512 random inputs visited in a random order; v above, l above for the opaque materials and over the sphere for rough glass; <material>.<lobe> is one lobe of the material alone; ratios to lambert)",
    "bsdf": "BSDFs, the dielectrics next to the conductors (bench/bsdf.cpp: 512 random inputs visited in a random order; f and pdf with l above (reflection) or below (transmission) for v above; sample_bsdf from above and from below; ratios to the rough conductor ggx_conductor)",
}


def strip_name(name):
    """Benchmark name without Google Benchmark's suffixes (/iterations:N, _median, ...)."""
    name = re.sub(r"/iterations:\d+", "", name)
    name = re.sub(r"_(mean|median|stddev|cv)$", "", name)
    return name


def load_json(path):
    """{name: {"ns_per_iter", "ops", "hit_rate", "agreement", "node_width", "iterations"}}
    from one JSON file: the fastest repetition when the file holds each repetition (the
    binary ran without --benchmark_report_aggregates_only), else the median when
    repetitions were run, else the single run."""
    with open(path) as f:
        data = json.load(f)
    runs, medians, fastest = {}, {}, {}
    for b in data.get("benchmarks", []):
        name = strip_name(b.get("run_name", b["name"]))
        scale = {"ns": 1.0, "us": 1e3, "ms": 1e6, "s": 1e9}[b.get("time_unit", "ns")]
        # CPU time of the benchmark's thread, except for work it shares out to other
        # threads (counter "build_threads", the parallel builds), timed by the wall clock.
        entry = {
            "ns_per_iter": float(b["real_time" if b.get("build_threads") else "cpu_time"]) * scale,
            "ops": float(b.get("ops_per_iter", 1.0)),
            "hit_rate": b.get("hit_rate"),
            "agreement": b.get("agreement"),
            "node_width": b.get("node_width"),
            "bytes_per_triangle": b.get("bytes_per_triangle"),
            "peak_bytes_per_triangle": b.get("peak_bytes_per_triangle"),
            "build_threads": b.get("build_threads"),
            "real_ns_per_iter": float(b["real_time"]) * scale,
            "iterations": int(b.get("iterations", 0)),
        }
        if b.get("run_type") == "aggregate":
            if b.get("aggregate_name") == "median":
                medians[name] = entry
        else:
            runs.setdefault(name, entry)
            if b.get("repetitions", 1) > 1 and (name not in fastest or
                                                entry["ns_per_iter"] < fastest[name]["ns_per_iter"]):
                fastest[name] = entry
    runs.update(medians)
    runs.update(fastest)
    # The fastest wall-clock time of each, whichever repetition it came from (for the
    # parallel build's speedup, wall clock against wall clock).
    for b in data.get("benchmarks", []):
        name = strip_name(b.get("run_name", b["name"]))
        scale = {"ns": 1.0, "us": 1e3, "ms": 1e6, "s": 1e9}[b.get("time_unit", "ns")]
        if name in fastest and b.get("run_type") != "aggregate":
            runs[name]["real_ns_per_iter"] = min(runs[name]["real_ns_per_iter"], float(b["real_time"]) * scale)
    return data.get("context", {}), runs


def load_callgrind(directory, runs):
    """{name: instructions per operation} from callgrind dumps made with
    CALLGRIND_DUMP_STATS_AT(name) right after each benchmark's loop."""
    result = {}
    def dump_order(path):  # callgrind.out.<pid>.<n>: by pid, then dump number
        return [int(x) if x.isdigit() else x for x in os.path.basename(path).split(".")[2:]]

    # Oldest file first, so that a benchmark dumped again by a later partial run
    # (script/bench --only) keeps its newest count.
    for path in sorted(glob.glob(os.path.join(directory, "callgrind.out.*")),
                       key=lambda p: (os.path.getmtime(p), dump_order(p))):
        desc, total = None, None
        with open(path, errors="replace") as f:
            for line in f:
                if line.startswith("desc: Trigger: Client Request: "):
                    desc = line[len("desc: Trigger: Client Request: "):].strip()
                elif line.startswith("totals:") or (line.startswith("summary:") and total is None):
                    total = int(line.split()[1])
        if desc and total is not None and desc in runs:
            r = runs[desc]
            if r["iterations"] > 0:
                result[desc] = total / (r["iterations"] * r["ops"])
    return result


def split(name):
    parts = name.split("/")
    family, variant = parts[0], parts[-1]
    typ = parts[1] if len(parts) > 2 else ""
    sub = "/".join(parts[2:-1])
    return family, typ, sub, variant


def fmt_ratio(x):
    return "–" if x is None else f"{x:.2f}×"


def tables(values, unit, hit_rates=None):
    """Markdown tables, one per (family, type): rows = variants, a column pair per
    subgroup (value per operation, ratio to the family's baseline)."""
    out = []
    families = {}
    for name, value in values.items():
        family, typ, sub, variant = split(name)
        families.setdefault((family, typ), {}).setdefault(sub, {})[variant] = (value, name)
    order = list(BASELINES)
    for (family, typ) in sorted(families, key=lambda k: (order.index(k[0]) if k[0] in order else 99, k[1] != "float", k[1])):
        subs = families[(family, typ)]
        sub_names = sorted(subs, key=lambda s: (len(s), s))
        if family in SUBGROUP_ORDER:
            known = SUBGROUP_ORDER[family]
            sub_names = sorted(subs, key=lambda s: (known.index(s) if s in known else len(known), s))
        variants = []
        for s in sub_names:
            for v in subs[s]:
                if v not in variants:
                    variants.append(v)
        if family in VARIANT_ORDER:
            known = VARIANT_ORDER[family]
            variants.sort(key=lambda v: (known.index(v) if v in known else len(known), v))
        baseline = BASELINES.get(family)
        title = FAMILY_TITLES.get(family, family)
        show_hits = hit_rates is not None and any(
            subs[s][v][1] in hit_rates for s in sub_names for v in subs[s])
        out.append(f"#### {title}: {typ}\n")
        header = "| variant |"
        rule = "|---|"
        for s in sub_names:
            label = s if s else "value"
            header += f" {label}: {unit} | ratio |"
            rule += "---:|---:|"
            if show_hits:
                header += " hits |"
                rule += "---:|"
        out.append(header)
        out.append(rule)
        for v in variants:
            row = f"| {v}{' (baseline)' if v == baseline else ''} |"
            for s in sub_names:
                cell = subs[s].get(v)
                base = subs[s].get(baseline)
                if cell is None:
                    row += " | |" + (" |" if show_hits else "")
                    continue
                value, name = cell
                ratio = value / base[0] if base else None
                row += f" {value:.2f} | {fmt_ratio(ratio)} |"
                if show_hits:
                    h = hit_rates.get(name)
                    row += f" {h * 100:.1f} % |" if h is not None else " |"
            out.append(row)
        out.append("")
    return out


def per_op(runs):
    return {n: r["ns_per_iter"] / r["ops"] for n, r in runs.items()}


def hit_rates_of(runs):
    return {n: r["hit_rate"] for n, r in runs.items() if r.get("hit_rate") is not None}


def target_rows(values, label_unit):
    """The performance targets (goal column) against the measured ratios, per type and
    hit rate."""
    rows = []

    def get(name):
        return values.get(name)

    for typ in ("float", "double"):
        for rate in ("hit0", "hit50", "hit100"):
            g = f"triangle/{typ}/{rate}/"
            mt, glm, area = get(g + "moller_trumbore"), get(g + "glm"), get(g + "plane_then_areas")
            if mt and glm:
                r = mt / glm
                rows.append((f"default scalar test (Möller-Trumbore find_intersection) / GLM, {typ} {rate}", r, "≤ 1.00", r <= 1.0))
            if mt and area:
                r = mt / area
                rows.append((f"Möller-Trumbore / area baseline (plane_then_areas), {typ} {rate}", r, "≤ 0.68", r <= 0.68))
    for typ in ("float", "double"):
        for rate in ("hit0", "hit50", "hit100"):
            g = f"triangle_batch/{typ}/{rate}/"
            b8, glm = get(g + "batch8"), get(g + "glm")
            if b8 and glm:
                r = glm / b8
                rows.append((f"GLM / batch 1×8 per test (throughput gain), {typ} {rate}", r, "≥ 5", r >= 5.0))
    for typ in ("float", "double"):
        trig, free = get(f"brdf/{typ}/oren_nayar_trig"), get(f"brdf/{typ}/oren_nayar_trig_free")
        if trig and free:
            r = trig / free
            rows.append((f"Oren-Nayar trig / trig-free (speed-up), {typ}", r, "≥ 2", r >= 2.0))
    for typ in ("float", "double"):
        models = sorted({n.split("/")[2] for n in values if n.startswith(f"brdf_sampling/{typ}/")})
        for m in models:
            g = f"brdf_sampling/{typ}/{m}/"
            f, sample, legacy = get(g + "f"), get(g + "sample"), get(g + "legacy_f")
            if f and sample:
                r = sample / f
                rows.append((f"sample / f, {m}, {typ}", r, "≤ 2", r <= 2.0))
            if f and legacy:
                # Goal: no slower, within 5 %, the spread of this ratio between runs.
                r = f / legacy
                rows.append((f"f / f before the sampling redesign, {m}, {typ}", r, "≤ 1.05", r <= 1.05))
    out = [f"| target ({label_unit}) | measured | goal | reached |", "|---|---:|---:|:---:|"]
    for label, r, goal, ok in rows:
        out.append(f"| {label} | {r:.2f} | {goal} | {'yes' if ok else '**no**'} |")
    out.append("")
    return out


def hit_rate_range(runs, subgroup):
    """"lo-hi %" of the measured hit rates of the benchmarks in a subgroup (e.g. hit50)."""
    rates = [r["hit_rate"] * 100 for n, r in runs.items()
             if r.get("hit_rate") is not None and f"/{subgroup}/" in n]
    if not rates:
        return "?"
    return f"{min(rates):.0f}-{max(rates):.0f} %"


def l1d_size():
    """This machine's level-1 data cache size as the kernel reports it (e.g. "48K")."""
    base = "/sys/devices/system/cpu/cpu0/cache"
    for index in sorted(glob.glob(os.path.join(base, "index*"))):
        try:
            with open(os.path.join(index, "level")) as f:
                level = f.read().strip()
            with open(os.path.join(index, "type")) as f:
                kind = f.read().strip()
            if level == "1" and kind == "Data":
                with open(os.path.join(index, "size")) as f:
                    return f.read().strip().replace("K", " KiB")
        except OSError:
            continue
    return "(size unknown)"


def bound_rows(ns):
    """The float batch kernel's time per test against its arithmetic bound on this machine:
    32 vector operations (18 multiplications, 14 additions per lane before the decision) at
    the measured throughput of one vector operation (bench/triangle.cpp, machine/...),
    divided by the lanes per vector: 8 for batches of 8 (AVX), 16 for 16 (AVX-512F)."""
    kernels = [("batch8", "avx", 8), ("batch16", "avx512f", 16)]
    rows = []
    for variant, isa, lanes in kernels:
        op = ns.get(f"machine/float/vector_op/{isa}")
        if not op:
            continue
        bound = 32 * op / lanes
        for sub in ("hit0", "hit50", "hit100", "hit0_shuffled", "hit50_shuffled", "hit100_shuffled", "hit50_memory"):
            t = ns.get(f"triangle_batch/float/{sub}/{variant}")
            if t:
                rows.append(f"| {variant} ({isa}) | {sub} | {t:.3f} | {bound:.3f} | {t / bound:.2f} |")
    if not rows:
        return []
    return ["## The batch kernel against its arithmetic bound (timed run)", "",
            "Bound: 18 multiplications and 14 additions per lane (the work before the hit/miss "
            "decision; no division) at the measured time of one vector multiply or add "
            "(12 independent chains, so throughput-bound) divided by the lanes per vector. "
            "A ratio of 1 would be the kernel running at the machine's arithmetic throughput; "
            "the rest is loads, comparisons, the divisions of hit lanes, the stores of the "
            "result and the call.", "",
            "| kernel | data | ns per test | bound ns | ratio |", "|---|---|---:|---:|---:|"] + rows + [""]


# The production reference of issue 32 (ns per call) and the goal: at most half of it.
OPENPBR_REFERENCE = {"f": (280, 280), "sample": (460, 760)}


def openpbr_rows(values):
    """shade::openpbr_surface (bench/openpbr.cpp) per material: ns per call, the ratio to
    the sum of its own lobes' times (benchmarks named <material>.<lobe>) and to Lambert."""
    ops = ["f", "pdf", "sample"]
    got = {}
    for name, value in values.items():
        family, typ, sub, variant = split(name)
        if family == "openpbr" and typ == "float":
            got[(sub, variant)] = value
    materials = [m for m in OPENPBR_MATERIALS if any((op, m) in got for op in ops)]
    if not materials:
        return []
    lines = ["## OpenPBR Surface against its lobes (timed run)", "",
             "`shade::openpbr_surface<float>` (bench/openpbr.cpp, one thread, "
             "512 random inputs in a random order) for four presets of "
             "`shade/material/openpbr_presets.hpp`: ns per call; × lobes, its time over the sum of the "
             "times of the lobes it evaluates, each timed alone on the same inputs (what the layering, "
             "the albedo lookups and the lobe choice add; 1.00× would be free); × lambert, over "
             "`shade::lambert`'s.", "",
             "| material (its lobes) | f: ns | × lobes | × lambert | pdf: ns | × lobes | × lambert "
             "| sample: ns | × lobes | × lambert |",
             "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|"]
    for m in materials:
        lobes = [v.split(".", 1)[1] for v in VARIANT_ORDER["openpbr"]
                 if v.startswith(m + ".") and any((op, v) in got for op in ops)]
        row = f"| {m} ({', '.join(lobes)}) |"
        for op in ops:
            t = got.get((op, m))
            parts = [got[(op, f"{m}.{lobe}")] for lobe in lobes if (op, f"{m}.{lobe}") in got]
            base = got.get((op, "lambert"))
            if t is None:
                row += " | | |"
                continue
            row += (f" {t:.1f} | {fmt_ratio(t / sum(parts) if parts else None)} |"
                    f" {fmt_ratio(t / base if base else None)} |")
        lines.append(row)
    lines.append("")
    for op, (low, high) in OPENPBR_REFERENCE.items():
        times = [got[(op, m)] for m in materials if (op, m) in got]
        if not times:
            continue
        ref = f"{low}" if low == high else f"{low}–{high}"
        goal = low / 2
        over = sum(t > goal for t in times)
        verdict = "met by every material" if over == 0 else f"exceeded by {over} of the {len(times)} materials"
        lines.append(f"- `{op}`: {min(times):.0f}–{max(times):.0f} ns per call over these materials, against "
                     f"the production reference of ~{ref} ns (issue 32); the goal, at most half of "
                     f"{low} ns ({goal:.0f} ns), is {verdict}.")
    lines.append("")
    return lines


def bvh_rows(runs, flags=None, ctx=None):
    """The BVH section: shade::triangle_bvh<float> against Embree 3 per scene, from the
    bench_bvh groups bvh/<build|primary|incoherent|shadow>/<scene>/<shade|embree>; empty
    when bench_bvh did not run (Embree not installed). flags: the compiler flags of a
    separate build (a section of its own), or None for the timed run of the report; ctx:
    the run's context (its date and load average are printed under the tables)."""
    ns = per_op(runs)
    scenes = []
    for name in ns:
        parts = name.split("/")
        if parts[0] == "bvh" and len(parts) == 4 and parts[2] not in scenes:
            scenes.append(parts[2])
    if not scenes:
        return []
    # Icospheres by size (the number in their name), then the other scenes.
    scenes.sort(key=lambda sc: (0, int(re.sub(r"\D", "", sc) or 0)) if sc.startswith("ico") else (1, sc))
    widths = {runs[k].get("node_width") for k in runs if k.startswith("bvh/") and k.endswith("/shade")}
    width = ", ".join(str(int(w)) for w in sorted(w for w in widths if w is not None)) or "?"
    title = "## Bounding-volume hierarchy against Embree (timed run)" if flags is None else \
        f"### Bounding-volume hierarchy against Embree with `{flags}` (bench_bvh alone, separate build)"
    out = [title, ""]
    if flags is None:
        out += ["`shade::triangle_bvh<float>` (Möller-Trumbore leaves through the batch kernel; nodes of "
                f"{width} children, the default width on this CPU; the column 'nodes of 4' is the same "
                "hierarchy built with `shade::bvh_width::four`; 'find_closest' the same nearest hits through "
                "`triangle_bvh::find_closest`, which returns the triangle, t, barycentrics and front_face "
                "without `closest()`'s record of point, unit normal, dp/du and error bound) against "
                "Embree 3 (`rtcIntersect1` for closest hits, `rtcOccluded1` for shadow rays, default "
                "build quality, device `threads=1`) in the same "
                "binary (bench/bvh.cpp), single thread; the repetitions of the two are "
                "interleaved (`--benchmark_enable_random_interleaving`). Primary rays: one per pixel "
                "of a 256 x 256 pinhole camera; incoherent: 65,536 rays with random origins around "
                "the mesh and random directions; shadow: 65,536 segments (`triangle_bvh::any`) from "
                "random origins around the mesh to points just in front of or behind a random "
                "triangle (hits: the fraction blocked). Agreement: fraction of rays on which both "
                "report the same hit or miss. Memory: shade's `triangle_bvh::memory_bytes()` (nodes "
                "and leaf blocks, which hold all it keeps of the triangles) per triangle; Embree's, "
                "the bytes its device memory monitor (`rtcSetDeviceMemoryMonitorFunction`) counts as "
                "allocated and not released by `rtcCommitScene` (hierarchy and leaf triangles; its "
                "vertex and index buffers, allocated before, not counted), and the most it held "
                "during the commit (peak). Parallel build: the same hierarchy built through "
                "`support::thread_executor` (examples/support/thread_executor.hpp) on all the "
                "machine's hardware threads, timed by the wall clock, and its speedup: the single-thread "
                "build's wall-clock time over it (the other build columns are CPU times of the "
                "benchmark's thread; on a loaded machine the wall clock runs ahead of both). Goals (issue 34): throughput >= 1.0x Embree's for every "
                "kind of ray and scene, build time <= 1.0x Embree's, the parallel build >= 1.7x "
                "faster than shade's single-thread one, memory <= 1.0x at ico82k and "
                "ico328k, agreement >= 99.99 %.", ""]
    out += ["| scene | rays | shade Mrays/s | Embree Mrays/s | shade / Embree | goal | nodes of 4 / Embree | "
            "find_closest / Embree | agreement | hits |",
            "|---|---|---:|---:|---:|---|---:|---:|---:|---:|"]
    for sc in scenes:
        for kind in ("primary", "incoherent", "shadow"):
            a, e = ns.get(f"bvh/{kind}/{sc}/shade"), ns.get(f"bvh/{kind}/{sc}/embree")
            if not (a and e):
                continue
            r = runs[f"bvh/{kind}/{sc}/shade"]
            agree, hit = r.get("agreement"), r.get("hit_rate")
            goal = "≥ 1.0 " + ("yes" if e / a >= 1.0 else "**no**")
            four = ns.get(f"bvh/{kind}/{sc}/shade_four")
            four_ratio = f"{e / four:.2f}×" if four else ""
            lean = ns.get(f"bvh/{kind}/{sc}/shade_lean")
            lean_ratio = f"{e / lean:.2f}×" if lean else ""
            out.append(f"| {sc} | {kind} | {1e3 / a:.2f} | {1e3 / e:.2f} | {e / a:.2f}× | {goal} | {four_ratio} | "
                       f"{lean_ratio} | "
                       f"{'?' if agree is None else f'{agree * 100:.3f} %'} | "
                       f"{'' if hit is None else f'{hit * 100:.1f} %'} |")
    out += ["", "| scene | shade build ms | Embree build ms | shade / Embree | goal | parallel build ms (threads) | "
            "speedup | goal | shade bytes/triangle | Embree bytes/triangle (peak) | shade / Embree | goal |",
            "|---|---:|---:|---:|---|---:|---:|---|---:|---:|---:|---|"]
    for sc in scenes:
        a, e = ns.get(f"bvh/build/{sc}/shade"), ns.get(f"bvh/build/{sc}/embree")
        if a and e:
            goal = "≤ 1.0 " + ("yes" if a / e <= 1.0 else "**no**")
            par, par_run = ns.get(f"bvh/build/{sc}/shade_parallel"), runs.get(f"bvh/build/{sc}/shade_parallel", {})
            parallel = ["", "", ""]
            if par:
                speedup = runs[f"bvh/build/{sc}/shade"]["real_ns_per_iter"] / par
                parallel = [f"{par / 1e6:.2f} ({int(par_run.get('build_threads') or 0)})", f"{speedup:.2f}×",
                            "≥ 1.7 " + ("yes" if speedup >= 1.7 else "**no**")]
            mem_a = runs[f"bvh/build/{sc}/shade"].get("bytes_per_triangle")
            mem_e = runs[f"bvh/build/{sc}/embree"].get("bytes_per_triangle")
            peak_e = runs[f"bvh/build/{sc}/embree"].get("peak_bytes_per_triangle")
            mem = ["", "", "", ""]
            if mem_a and mem_e:
                mem = [f"{mem_a:.1f}", f"{mem_e:.1f} ({peak_e:.1f})" if peak_e else f"{mem_e:.1f}",
                       f"{mem_a / mem_e:.2f}×",
                       ("≤ 1.0 " + ("yes" if mem_a / mem_e <= 1.0 else "**no**")) if sc in ("ico82k", "ico328k")
                       else ""]
            out.append(f"| {sc} | {a / 1e6:.2f} | {e / 1e6:.2f} | {a / e:.2f}× | {goal} | " + " | ".join(parallel + mem) + " |")
    if ctx:
        out += ["", f"bench_bvh run {ctx.get('date', '?')}, load average at start "
                f"{', '.join(f'{x:.2f}' for x in ctx.get('load_avg', [])) or '?'} (on a loaded machine "
                "the ratios of single runs move by several per cent between builds)."]
    out.append("")
    return out


def runs_apart(dates):
    """True when the binaries' start dates (ISO 8601) span more than an hour: results of
    different runs of script/bench (one full run takes minutes)."""
    import datetime
    parsed = []
    for d in dates:
        try:
            parsed.append(datetime.datetime.fromisoformat(d))
        except (TypeError, ValueError):
            return False
    return len(parsed) > 1 and (max(parsed) - min(parsed)).total_seconds() > 3600


def cpu_model():
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return "unknown"


def cpu_flags_of_interest():
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("flags"):
                    flags = set(line.split(":", 1)[1].split())
                    return " ".join(x for x in ("sse4_2", "avx", "avx2", "fma", "avx512f") if x in flags)
    except OSError:
        pass
    return ""


def main():
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--out", required=True)
    ap.add_argument("--time-dir", required=True, help="JSON files of the timed run")
    ap.add_argument("--native-dir", help="JSON files of the -march=native batch run")
    ap.add_argument("--callgrind-dir", help="callgrind dumps and JSON of the fixed-iteration run")
    ap.add_argument("--compiler", default="")
    ap.add_argument("--flags", default="")
    ap.add_argument("--native-flags", default="")
    ap.add_argument("--bvh-build", nargs=2, action="append", default=[], metavar=("FLAGS", "JSON"),
                    help="bench_bvh results of a separate build with these flags (repeatable)")
    ap.add_argument("--command", default="script/bench")
    ap.add_argument("--benchmark-version", default="")
    args = ap.parse_args()

    time_runs, context, run_dates = {}, {}, {}
    for path in sorted(glob.glob(os.path.join(args.time_dir, "*.json"))):
        ctx, runs = load_json(path)
        context = {**ctx, **context}  # keys of every file; the first file's win
        time_runs.update(runs)
        run_dates[os.path.splitext(os.path.basename(path))[0]] = ctx.get("date", "?")
    if not time_runs:
        sys.exit("report.py: no benchmark results in " + args.time_dir)

    lines = ["# Benchmarks", "",
             f"Generated by `{args.command}` (bench/report.py); do not edit by hand.", "",
             "## Machine", "",
             f"- CPU: {cpu_model()} ({os.cpu_count()} logical CPUs; {cpu_flags_of_interest()})",
             f"- Compiler: {args.compiler}",
             f"- Flags: `{args.flags}`",
             f"- Google Benchmark: {args.benchmark_version or context.get('library_version', '?')}"
             f"{' (a debug build of the library, as Debian ships it: it warns, the ratios still hold)' if context.get('library_build_type') == 'debug' else ''}",
             f"- Batch kernel (`shade::triangle_batch_kernel()`): "
             f"{context.get('triangle_batch_kernel', '?')}",
             f"- Run: {context.get('date', '?')}, load average at start "
             f"{', '.join(f'{x:.2f}' for x in context.get('load_avg', [])) or '?'}",
             *([f"- Binaries run at different times (`script/bench --only` reruns one): "
                + ", ".join(f"{b} {d}" for b, d in sorted(run_dates.items()))]
               if runs_apart(run_dates.values()) else []),
             "",
             "## Method", "",
             "- Every benchmark runs one routine over the same precomputed arrays (ray/shape "
             "pairs: 512 in float, 256 in double, at most 35 KiB, so they stay in the "
             f"{l1d_size()} L1 data cache; 512 direction pairs for the BRDFs) and hands each "
             "result to "
             "`benchmark::DoNotOptimize`. Intersection routines "
             "are reduced to the same record (hit, t, two barycentrics or coordinates), so "
             "every routine does the same observable work.",
             "- GLM's `intersectRayTriangle` is given the `t > 0` check it lacks (it reports "
             "hits behind the origin); its epsilon on det stays. Sphere: GLM's position-and-"
             "normal overload (unit directions, as it requires). Plane: GLM's distance plus the "
             "hit point. shade's sphere and plane do more than GLM's, which the ratios "
             "include: the sphere solves the quadratic in the form without cancellation "
             "(Haines, Günther, Akenine-Möller 2019; one division and one square root more), "
             "rescales huge or tiny directions, normalises p - c (GLM divides by R, which is "
             "not unit length once p is rounded) and rejects non-finite t, p or normals; the "
             "plane tests t against [t_min, t_max] and p for finiteness.",
             "- Times are CPU time per operation, the median of 3 repetitions, except the BRDF and BVH benchmarks: the fastest of 9 and of 5 (their goals are ratios, the BRDFs' within a few per cent, and the noise of a shared machine only ever adds time to single-threaded work); a ratio is "
             "time(variant) / time(baseline) of the same group from the same run of the same "
             "binary (below 1: faster than the baseline). On a shared machine (other work "
             "running, see the load average above) single times are noisy; the ratios and "
             "the instruction "
             "counts are the figures to compare.",
             "- Which figures to believe: the groups without a suffix visit their pairs in "
             "storage order, the same sequence every iteration, which the branch predictor "
             "learns, flattering every test that branches on hit or miss (the scalar tests, "
             "GLM's most of all). The `_shuffled` columns visit the same L1-resident pairs in a "
             "random order, and `_memory` a 64 MiB set (twice the last-level cache) in a random "
             "order, as a renderer's incoherent rays meet their primitives. For a renderer, "
             "believe `_shuffled` for the cost of the test itself and `_memory` for a test that "
             "waits for its data; the unsuffixed columns are the best case.",
             "- Hit rates are measured with each routine on its own data and shown next to "
             f"its time (~0 %, ~50 %, ~100 % targeted; the 50 % sets came out at "
             f"{hit_rate_range(time_runs, 'hit50')} in this run).",
             "- Triangle rows `moller_trumbore`, `plane_then_areas`, `watertight` time the lean "
             "test `shade::find_intersection<A>` (t, barycentrics, face: GLM's job); "
             "`moller_trumbore_record` times `shade::intersect`, which also builds the hit "
             "point and the unit normal (a renderer does that once per ray, with `make_hit`).",
             "- The batch (`shade::triangle_batch`, include/shade/geometry/triangle_batch.hpp) "
             "gives bitwise the scalar Möller-Trumbore's results "
             "(tests/geometry/test_triangle_batch.cpp). It uses GNU vector extensions: 4 "
             "floats or 2 doubles per step with the x86-64 baseline (SSE2), 8 or 4 with AVX. "
             "Built for the baseline (the default flags, as here), it also carries a copy "
             "compiled for AVX and selects it at run time when the CPU has AVX, and for "
             "batches of 64 bytes (16 floats, 8 doubles) a copy written with AVX-512F "
             "builtins (16 floats or 8 doubles per step) that it selects when the CPU has "
             "AVX-512F (see \"Batch kernel\" above).",
             ""]

    lines += ["## Targets (timed run)", ""]
    lines += target_rows(per_op(time_runs), "ratio of times")

    lines += ["What each routine does beyond GLM's (the code, not this run):", "",
              "- Default scalar test vs GLM: `find_intersection` does GLM's job with the same "
              "arithmetic on a hit (two cross products, four dot products, one division's "
              "worth of work per output) and leaves most misses before computing the normal, "
              "as GLM leaves them before its second cross product. What it adds is what GLM "
              "gets wrong: exact sign tests on the three barycentric numerators and a finite, "
              "non-zero det in place of GLM's absolute epsilon (which loses small "
              "triangles), the test that t is finite and inside [t_min, t_max] (GLM reports "
              "hits behind the origin: t_min >= 0, t >= t_min, t <= t_max and t < infinity "
              "against GLM's t > 0), an early exit when U and V have opposite signs, the "
              "det <= max test, rejection of degenerate triangles and of NaN or infinite "
              "input, and three correctly rounded divisions where GLM multiplies by one "
              "reciprocal (the batch reproduces those bits). GLM's own extras (two epsilon "
              "tests on det, U <= det and U + V <= det) win some of that back.",
              "- Batch vs GLM: a lane does 18 multiplications and 14 additions (the normal is "
              "stored at packing) before any division, and a vector step holds 8 floats or 4 "
              "doubles with AVX (selected at run time in the default build, compiled in with "
              "-march=native), 4 floats or 2 doubles on a CPU without AVX; on a CPU with "
              "AVX-512F the default build runs batches of 64 bytes (16 floats, 8 doubles) in "
              "16- or 8-lane steps. Where lanes hit, t and the three barycentrics are four "
              "correctly rounded divisions (the scalar code's bits), which one reciprocal and "
              "four multiplications would not give. The default build also pays a function "
              "call per batch (a function compiled for AVX or AVX-512F is not inlined into "
              "code built for the baseline).",
              ""]

    bvh_json = os.path.join(args.time_dir, "bench_bvh.json")
    lines += bvh_rows(time_runs, None, load_json(bvh_json)[0] if os.path.exists(bvh_json) else None)
    for flags, path in args.bvh_build:
        if os.path.exists(path):
            ctx, runs = load_json(path)
            lines += bvh_rows(runs, flags, ctx)
    lines += bound_rows(per_op(time_runs))
    lines += openpbr_rows(per_op(time_runs))

    native_runs, native_context = {}, {}
    if args.native_dir:
        for path in sorted(glob.glob(os.path.join(args.native_dir, "*.json"))):
            ctx, runs = load_json(path)
            native_context = {**ctx, **native_context}
            native_runs.update(runs)
        if native_runs:
            lines += [f"With `{args.native_flags}` (triangle benchmarks only, separate build; "
                      f"batch kernel: {native_context.get('triangle_batch_kernel', '?')}):", ""]
            nat = per_op(native_runs)
            rows = target_rows(nat, "ratio of times")
            lines += [r for r in rows if "Oren-Nayar" not in r]

    lines += ["## Time per operation (ns)", ""]
    lines += tables(per_op(time_runs), "ns", hit_rates_of(time_runs))
    if native_runs:
        lines += [f"### Triangles with `{args.native_flags}`", ""]
        lines += tables(per_op(native_runs), "ns", hit_rates_of(native_runs))

    lines += ["## Instructions per operation (callgrind)", ""]
    if args.callgrind_dir:
        cg_runs, cg_context = {}, {}
        for path in sorted(glob.glob(os.path.join(args.callgrind_dir, "*.json"))):
            ctx, runs = load_json(path)
            cg_context = {**ctx, **cg_context}
            cg_runs.update(runs)
        ir = load_callgrind(args.callgrind_dir, cg_runs)
        iters = sorted({r["iterations"] for r in cg_runs.values()})
        lines += ["Counted by `valgrind --tool=callgrind` over exactly the benchmark loop "
                  f"({', '.join(map(str, iters))} iterations of 256 or 512 operations; counters zeroed "
                  "before the loop and dumped after it), divided by the number of operations. "
                  "Independent of machine noise; includes the loop and `DoNotOptimize` "
                  "overhead, the same for every variant. Same build as the timed run; "
                  "valgrind does not emulate AVX-512, so under it the batch runs this kernel: "
                  f"{cg_context.get('triangle_batch_kernel', '?')}.", ""]
        lines += ["### Targets (instruction counts)", ""]
        lines += target_rows(ir, "ratio of instruction counts")
        lines += tables(ir, "instr")
    else:
        lines += ["Not measured in this run: `script/bench --callgrind` adds them.", ""]

    with open(args.out, "w") as f:
        f.write("\n".join(lines))
    print(f"report.py: wrote {args.out}")


if __name__ == "__main__":
    main()
