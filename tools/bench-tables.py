#!/usr/bin/env python3
"""The Markdown tables of docs/benchmarks.md's current results, from a `make bench` run.

usage: tools/bench-tables.py [RESULTS_DIR]   (default: results)

Reads the CSV files and kernels.json that `make bench` writes and prints one table per
section, so the figures in the docs are the ones the run measured.
"""
import csv
import json
import os
import sys


def rows(results, name):
    with open(os.path.join(results, name + ".csv"), newline="") as f:
        return list(csv.DictReader(f))


def f(x, digits=2):
    return f"{float(x):.{digits}f}"


def table(header, body):
    print("| " + " | ".join(header) + " |")
    print("|" + "---|" * len(header))
    for r in body:
        print("| " + " | ".join(str(c) for c in r) + " |")
    print()


def engines(results):
    body = []
    for r in rows(results, "engines"):
        body.append([
            r["scene"], r["threads"], f(r["megakernel_mpaths"]), f(r["wavefront_mpaths"]),
            f(r["megakernel_embree_mpaths"]), f(r["wavefront_embree_mpaths"]),
            f(r["megakernel_ours_over_embree"]),
            f"**{f(r['ratio_median'])}** [{f(r['ratio_min'])}, {f(r['ratio_max'])}]",
            f(r["wavefront_over_megakernel_embree"]), f"{float(r['rel_mse_between']):.1e}",
            f"{f(r['megakernel_peak_mib'], 1)} / {f(r['wavefront_peak_mib'], 1)}"])
    table(["scene", "threads", "megakernel Mpaths/s", "wavefront Mpaths/s",
           "megakernel on Embree", "wavefront on Embree", "megakernel ours / Embree",
           "**wavefront / megakernel**", "wavefront / megakernel on Embree",
           "rel. MSE between", "peak MiB (mk / wf)"], body)


def schedules(results):
    body = []
    for r in rows(results, "engines"):
        body.append([r["scene"], r["threads"], f(r["megakernel_mpaths"]),
                     f(r["wavefront_mpaths"]), f(r["stage_mpaths"]),
                     f"**{f(r['ratio_median'])}**", f"**{f(r['stage_over_megakernel'])}**",
                     f(r["stage_over_resident"])])
    table(["scene", "threads", "megakernel Mpaths/s", "resident Mpaths/s", "stage Mpaths/s",
           "resident / megakernel", "stage / megakernel", "stage / resident"], body)


def bvh(results):
    by = {}
    for r in rows(results, "bvh"):
        by.setdefault((r["scene"], r["batch"]), {})[r["threads"]] = r
    body, packets = [], []
    for (scene, batch), t in by.items():
        one, two = t.get("1"), t.get("2")
        line = [scene, batch, f(one["ours_mrays"], 1), f(one["embree_mrays"], 1),
                f"**{f(one['ours_over_embree'])}**"]
        if two:
            line += [f(two["ours_mrays"], 1), f(two["embree_mrays"], 1),
                     f"**{f(two['ours_over_embree'])}**"]
        body.append(line)
        if batch == "primary" and float(one["ours_packet_mrays"]) > 0:
            p = [scene, f(one["ours_mrays"], 1), f(one["ours_packet_mrays"], 1),
                 f(one["embree_packet8_mrays"], 1), f(one["embree_packet16_mrays"], 1),
                 f"**{f(one['ours_packet_over_embree_packet16'])}**"]
            if two:
                p += [f(two["ours_packet_mrays"], 1), f(two["embree_packet16_mrays"], 1),
                      f"**{f(two['ours_packet_over_embree_packet16'])}**"]
            packets.append(p)
    table(["scene", "batch", "ours, 1 thread (Mrays/s)", "Embree, 1 thread", "ours / Embree",
           "ours, 2 threads", "Embree, 2 threads", "ours / Embree"], body)
    table(["scene", "ours, single rays, 1 thread", "ours, packets, 1 thread", "Embree 8-wide",
           "Embree 16-wide", "ours / Embree 16", "ours, packets, 2 threads",
           "Embree 16-wide, 2 threads", "ours / Embree 16"], packets)
    table(["scene", "primitives", "ours (ms)", "Embree medium (ms)", "Embree high (ms)"],
          [[r["scene"], r["primitives"], f(r["ours_ms"], 3), f(r["embree_medium_ms"], 3),
            f(r["embree_high_ms"], 3)] for r in rows(results, "bvh_build")])


def scene_size(results):
    by = {}
    for r in rows(results, "scene_size"):
        by.setdefault((int(r["triangles"]), r["batch"]), {})[r["threads"]] = r
    body = []
    for (n, batch), t in sorted(by.items(), key=lambda kv: kv[0][0]):
        line = [f"{n:,}", batch]
        for threads in sorted(t, key=int):
            r = t[threads]
            line += [f(r["ours_mrays"], 1), f(r["embree_mrays"], 1),
                     f"**{f(r['ours_over_embree'])}**"]
        if batch == "primary":
            r = t["1"]
            line += [f(r["ours_packet_mrays"], 1), f(r["embree_packet16_mrays"], 1),
                     f"**{f(r['ours_packet_over_embree_packet16'])}**"]
        body.append(line)
    table(["triangles", "batch", "ours, 1 thread (Mrays/s)", "Embree, 1 thread", "ours / Embree",
           "ours, all threads", "Embree, all threads", "ours / Embree",
           "ours, packets, 1 thread", "Embree 16-wide", "ours / Embree 16"], body)
    table(["triangles", "ours build (ms)", "Embree medium (ms)", "Embree high (ms)",
           "ours / Embree high", "ours (B/triangle)", "ours, traversal only", "Embree medium",
           "Embree high", "peak memory (MiB)"],
          [[f"{int(r['triangles']):,}", f(r["ours_ms"], 1), f(r["embree_medium_ms"], 1),
            f(r["embree_high_ms"], 1), f"**{f(r['ours_over_embree_high'])}**",
            f(r["ours_bytes_per_triangle"], 1), f(r["ours_traversal_bytes_per_triangle"], 1),
            f(r["embree_medium_bytes_per_triangle"], 1), f(r["embree_high_bytes_per_triangle"], 1),
            f(r["peak_rss_mib"], 0)] for r in rows(results, "scene_size_build")])
    table(["triangles", "threads", "megakernel (Mpaths/s)", "wavefront", "wavefront / megakernel",
           "megakernel on Embree", "wavefront on Embree", "megakernel: ours / Embree"],
          [[f"{int(r['triangles']):,}", r["threads"], f(r["megakernel_mpaths"], 3),
            f(r["wavefront_mpaths"], 3), f"**{f(r['wavefront_over_megakernel'])}**",
            f(r["megakernel_embree_mpaths"], 3), f(r["wavefront_embree_mpaths"], 3),
            f"**{f(r['megakernel_ours_over_embree'])}**"] for r in rows(results, "scene_size_render")])


def scaling(results):
    body = []
    for r in rows(results, "scaling"):
        body.append([r["scene"], r["engine"], r["threads"], f(r["mpaths"]), f(r["speedup"]),
                     f(r["efficiency"]), f(r["independent_own_speedup"]),
                     f(r["arithmetic_speedup"]), f(r["wavefront_over_megakernel"])])
    table(["scene", "engine", "threads", "Mpaths/s", "speed-up", "efficiency",
           "renders alone: own rates", "arithmetic", "over the megakernel"], body)


def waves(results):
    body = []
    for r in rows(results, "waves"):
        body.append([r["scene"], int(float(r["wave_size"])),
                     f(r["queue_kib_per_thread"], 1), f(r["wavefront_mpaths"]),
                     f(r["megakernel_mpaths"]), f(r["ratio_median"]),
                     int(float(r["effective_wave"]))])
    table(["scene", "wave (paths per thread)", "queues per thread (KiB)", "wavefront Mpaths/s",
           "megakernel Mpaths/s", "wavefront / megakernel", "used"], body)


def convergence(results):
    spp = max(int(r["spp"]) for r in rows(results, "convergence"))
    scenes = {}
    for r in rows(results, "convergence"):
        if int(r["spp"]) == spp:
            scenes.setdefault(r["scene"], {})[r["strategy"]] = r
    strategies = ["bsdf", "light", "mixture", "nee", "mis"]
    body = []
    for scene, s in scenes.items():
        body.append([f"{scene}: rMSE"] + [f"{float(s[k]['rel_mse']):.3g}" for k in strategies])
        body.append([f"{scene}: efficiency"] +
                    [f"{float(s[k]['efficiency']):.3g}" for k in strategies])
    print(f"At {spp} spp:\n")
    table(["scene"] + strategies, body)


def error_time(results):
    """Per scene: the time each engine and sampler takes to reach the error the megakernel with
    the independent sampler has at half its most samples (16 spp for the bench scenes, 128 for
    Mitsuba's; from a least-squares line through log rMSE against log seconds from 4 spp), the
    line's slope, and the errors at the most samples."""
    import math
    series = {}
    for r in rows(results, "error_time"):
        key = (r["scene"], r["engine"], r["sampler"])
        series.setdefault(key, []).append(
            (int(r["spp"]), float(r["seconds"]), float(r["rel_mse"]), float(r["rel_mse_2x2"])))
    scenes = list(dict.fromkeys(k[0] for k in series))
    combos = [(e, s) for e in ("megakernel", "wavefront") for s in ("independent", "sobol", "zsobol")]

    def fit(points):
        points = [p for p in points if p[0] >= 4] or points  # --quick runs have 1 and 2
        xs = [math.log(t) for spp, t, e, _ in points]
        ys = [math.log(e) for spp, t, e, _ in points]
        n = len(xs)
        mx, my = sum(xs) / n, sum(ys) / n
        slope = sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sum((x - mx) ** 2 for x in xs)
        return slope, my - slope * mx

    body, errors = [], []
    for scene in scenes:
        baseline = series[(scene, "megakernel", "independent")]
        target = baseline[-2 if len(baseline) > 1 else -1][2]
        cells, times = [], {}
        for c in combos:
            slope, intercept = fit(series[(scene,) + c])
            times[c] = math.exp((math.log(target) - intercept) / slope)
            cells.append(f"{times[c] * 1e3:.0f} ({slope:.2f})")
        base = times[("megakernel", "independent")]
        best = min(times[("wavefront", s)] for s in ("independent", "sobol", "zsobol"))
        body.append([scene, f"{target:.3g}"] + cells + [f"**{base / best:.2f}×**"])
        last = {c: series[(scene,) + c][-1] for c in combos}
        errors.append([scene] + [f"{last[('wavefront', s)][2]:.3g} / {last[('wavefront', s)][3]:.3g}"
                                 for s in ("independent", "sobol", "zsobol")])
    table(["scene", "target rMSE"] + [f"{e}, {s}: ms (slope)" for e, s in combos] +
          ["speed-up to the target, best wavefront over megakernel independent"], body)
    print("Wavefront at the most samples, relative MSE per pixel / over 2 x 2 squares:\n")
    table(["scene", "independent", "sobol", "zsobol"], errors)


def kernels(results):
    with open(os.path.join(results, "kernels.json")) as fh:
        data = json.load(fh)
    body = []
    for b in data["benchmarks"]:
        if "items_per_second" in b:
            body.append([b["name"], f(b["items_per_second"] * 1e-6, 1)])
    table(["benchmark", "M items/s"], body)


def main():
    results = sys.argv[1] if len(sys.argv) > 1 else "results"
    for title, section in [("engines", engines), ("schedules", schedules), ("bvh", bvh), ("scene_size", scene_size),
                           ("scaling", scaling),
                           ("waves", waves), ("convergence", convergence),
                           ("error_time", error_time),
                           ("kernels", kernels)]:
        print(f"<!-- {title} -->\n")
        try:
            section(results)
        except FileNotFoundError as e:  # a run of some sections only (--sections)
            print(f"(not in this run: {os.path.basename(e.filename)})\n")


if __name__ == "__main__":
    main()
