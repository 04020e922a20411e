#!/usr/bin/env python3
"""The check of `deepvox advise` and `--shadows auto --error-budget`, run by
scripts/advise-check.sh: per scene (small-shadows, whose shadows cover under 5 % of the view;
two glTF scenes; the built-in ones and the held-out ones the error model never saw) the
exhaustive sweep once (`advise --exhaustive`), then per error bound E: `advise` (timed;
its pick verified at fresh points) and `advise --auto-budget` (what auto --error-budget picks,
measured at the same fresh points). The error is advise's: p95 |T' - T| in every stratum of the
probe points (lit, umbra, partial, media); the per-stratum p95 of every pick and of auto's
choice at fresh points is reported. The sweep's cheapest meets E and the sweep's image bound
(the default configuration's edge error, as advise applies it). Writes OUT/summary.json and
OUT/summary.md with pass/fail per criterion: the pick's verified p95 <= E; its frame time within 1.25x of the sweep's
cheapest configuration meeting E, the two timed alternately in one process (`advise --time`,
--rounds interleaved rounds, medians: one measurement of a ~1 ms frame varies by 10-30 %
between measurements, so the sweep's own times cannot decide a 1.25x bound); the pick's image
edge error <= the default configuration's; auto's p95 <= E;
advise on knecht-fig56 within 60 s (cuda) or 300 s (cpu)."""
import argparse
import json
import os
import platform
import subprocess
import sys
import time

BUILTIN = ["experiments/scenes/knecht-fig56.json", "experiments/scenes/knecht-quick.json",
           "experiments/scenes/ct-phantom.json", "experiments/scenes/smoke-translucent-boxes.json",
           "experiments/scenes/translucent-boxes.json"]
HELDOUT = ["experiments/scenes/heldout/smoke-ring.json",
           "experiments/scenes/heldout/glass-stack.json",
           "experiments/scenes/heldout/opaque-bunnies.json"]
SMALL_SHADOWS = ["experiments/scenes/small-shadows.json"]
# glTF scenes as a user brings them (their own floor, spot light and camera): a thin red glass
# slab, and an alpha-MASK quad whose cut-outs cast hard-edged shadows (GlassBrokenWindow-like).
GLTF = ["experiments/assets/gltf/red-glass-slab.gltf",
        "experiments/assets/gltf/alpha-mask-quad.gltf"]
BOUNDS = [0.005, 0.02, 0.05]
STRATA = ["lit", "umbra", "partial", "media"]
TIME_RATIO = 1.25
CONFIG_FORMAT = {"format": "deepvox-shadow-config", "version": 1}


def fmt(v):
    return "-" if v is None else f"{v:.3f}"


def fmt4(v):
    return "-" if v is None else f"{v:.4f}"


def ratio(row):
    """The pick's time over the sweep's cheapest's (1 when the pick is that configuration)."""
    if row.get("timed") == "the same configuration":
        return 1.0
    if row.get("pick_ms") is None or not row.get("cheapest_ms"):
        return None
    return row["pick_ms"] / row["cheapest_ms"]


def run(deepvox, args, log):
    start = time.monotonic()
    proc = subprocess.run([deepvox] + args, capture_output=True, text=True)
    seconds = time.monotonic() - start
    with open(log, "w") as f:
        f.write("$ deepvox " + " ".join(args) + "\n" + proc.stdout + proc.stderr)
    return proc.returncode, seconds


def timed_pair(a, scene, cheapest, pick, out, log, common):
    """The sweep's cheapest and the pick timed alternately (`advise --time`): their medians."""
    if cheapest == pick:
        return {"timed": "the same configuration"}
    os.makedirs(out, exist_ok=True)
    files = []
    for label, shadows in (("cheapest", cheapest), ("pick", pick)):
        files.append(os.path.join(out, label + ".json"))
        json.dump(dict(CONFIG_FORMAT, shadows=shadows), open(files[-1], "w"), indent=1)
    rc, _ = run(a.deepvox, ["advise", scene, "--time"] + files +
                ["--rounds", str(a.rounds), "--out", out] + common, log)
    if rc != 0:
        return {"timed": f"advise --time failed (exit {rc}, {log})"}
    configs = json.load(open(os.path.join(out, "timing.json")))["configs"]
    return {"cheapest_ms": configs[0]["median_ms"], "pick_ms": configs[1]["median_ms"],
            "timed": f"{a.rounds} interleaved rounds, medians"}


def strata_p95(measured):
    """Per stratum holding points its judged p95 (the max where it has too few points)."""
    out = {}
    for name, e in (measured or {}).get("strata", {}).items():
        if e["count"] > 0:
            out[name] = e["max"] if e["few"] else e["p95"]
    return out


def strata_text(strata):
    return " ".join(f"{k} {strata[k]:.4g}" for k in STRATA if k in strata) or "-"


def stem(scene):
    return os.path.splitext(os.path.basename(scene))[0]


def write_summary(a, rows, limit_s):
    """OUT/summary.json and OUT/summary.md of the rows so far (written after every scene, so
    that a run cut short keeps what it measured)."""
    meta = {"backend": a.backend, "host": platform.node(), "cpus": os.cpu_count(),
            "load_average": os.getloadavg(), "command": " ".join(sys.argv),
            "advise_time_limit_s": limit_s}
    json.dump({"meta": meta, "rows": rows}, open(os.path.join(a.out, "summary.json"), "w"),
              indent=1)
    verdict = lambda v: "n/a" if v is None else ("pass" if v else "FAIL")
    with open(os.path.join(a.out, "summary.md"), "w") as f:
        f.write(f"# advise check ({a.backend}, {meta['cpus']} CPUs, load {meta['load_average']})\n\n"
                "| scene | E | pick | verified p95 | verified per stratum | pick ms | "
                "sweep's cheapest ms | pick / cheapest | auto p95 (by) | auto per stratum | "
                "pick edge (default's) | advise s | verified | time | image | auto |\n|" +
                " --- |" * 16 + "\n")
        for r in rows:
            f.write(f"| {stem(r['scene'])}{' (held out)' if r['held_out'] else ''} | {r['E']} | "
                    f"{r.get('pick', '-')} | {r.get('pick_verified_p95', '-')} | "
                    f"{strata_text(r.get('pick_verified_strata', {}))} | "
                    f"{fmt(r.get('pick_ms'))} | {fmt(r.get('cheapest_ms'))} | "
                    f"{fmt(ratio(r))} | "
                    f"{r.get('auto_p95', '-')} ({r.get('auto_by', '-')}) | "
                    f"{strata_text(r.get('auto_verified_strata', {}))} | "
                    f"{fmt4(r.get('pick_image_edge'))} ({fmt4(r.get('image_bound'))}) | "
                    f"{r['advise_s']:.1f} | {verdict(r['pass_verified'])} | "
                    f"{verdict(r['pass_time'])} | {verdict(r['pass_image'])} | "
                    f"{verdict(r['pass_auto'])} |\n")
        f.write("\nn/a: no configuration of the sweep meets E on this scene. pick ms and "
                "sweep's cheapest ms: medians of the two timed alternately in one process "
                f"({a.rounds} interleaved rounds, `advise --time`); ratio 1 where the pick is "
                "the sweep's cheapest. Per stratum: the p95 |T' - T| at fresh points (the max "
                "where a stratum has too few points), strata without points left out.\n")


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--deepvox", default="build/bin/deepvox")
    ap.add_argument("--backend", default="cuda")
    ap.add_argument("--out", default="out/advise-check")
    ap.add_argument("--width", type=int, default=0, help="image width (0: advise's default)")
    ap.add_argument("--probes", type=int, default=2000)
    ap.add_argument("--max-res", type=int, default=0)
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--rounds", type=int, default=9,
                    help="interleaved rounds timing the pick against the sweep's cheapest")
    ap.add_argument("--scenes", nargs="*", default=SMALL_SHADOWS + GLTF + BUILTIN + HELDOUT)
    ap.add_argument("--bounds", nargs="*", type=float, default=BOUNDS)
    a = ap.parse_args()
    os.makedirs(a.out, exist_ok=True)
    common = ["--backend", a.backend, "--probes", str(a.probes), "--repeat", str(a.repeat)]
    if a.width:
        common += ["--width", str(a.width)]
    if a.max_res:
        common += ["--max-res", str(a.max_res)]
    limit_s = 60 if a.backend == "cuda" else 300
    rows = []
    for scene in a.scenes:
        name = stem(scene)
        sweep_dir = os.path.join(a.out, name, "sweep")
        rc, sweep_s = run(a.deepvox, ["advise", scene, "--exhaustive", "--out", sweep_dir] + common,
                          os.path.join(a.out, name + "-sweep.log"))
        sweep = json.load(open(os.path.join(sweep_dir, "advice.json")))
        measured = {r["param_line"]: r["measured"] for r in sweep["results"]}
        shadows = {r["param_line"]: r["shadows"] for r in sweep["results"]}
        image_bound = sweep.get("image_bound")
        print(f"{name}: sweep of {len(measured)} configurations in {sweep_s:.0f} s; strata "
              f"{sweep.get('strata_counts')}", flush=True)
        for bound in a.bounds:
            row = {"scene": scene, "held_out": scene in HELDOUT, "E": bound,
                   "strata_counts": sweep.get("strata_counts"), "image_bound": image_bound}
            meeting = [(m["frame_ms"], line) for line, m in measured.items()
                       if m.get("ok") and m["error_p95"] <= bound and
                       (image_bound is None or m["image_edge"] <= image_bound)]
            row["sweep_cheapest"] = min(meeting)[1] if meeting else None
            row["sweep_cheapest_ms"] = min(meeting)[0] if meeting else None
            advise_dir = os.path.join(a.out, name, f"advise-{bound}")
            rc, seconds = run(a.deepvox, ["advise", scene, "--error", str(bound), "--out",
                                          advise_dir] + common,
                              os.path.join(a.out, f"{name}-advise-{bound}.log"))
            advice = json.load(open(os.path.join(advise_dir, "advice.json")))
            row["advise_s"] = seconds
            row["advise_measured"] = len(advice["results"])
            pick = advice.get("pick")
            if pick is not None:
                line = advice["results"][pick]["param_line"]
                row["pick"] = line
                row["pick_search_p95"] = advice["results"][pick]["measured"]["error_p95"]
                row["pick_verified_p95"] = advice["verified"]["error_p95"]
                row["pick_verified_strata"] = strata_p95(advice["verified"])
                row["pick_worst_stratum"] = advice["verified"].get("worst_stratum")
                row["pick_image_edge"] = advice["results"][pick]["measured"].get("image_edge")
                row["pick_sweep_ms"] = measured.get(line,
                                                    advice["results"][pick]["measured"])["frame_ms"]
                if row["sweep_cheapest"] is not None:
                    row.update(timed_pair(a, scene, shadows[row["sweep_cheapest"]],
                                          advice["results"][pick]["shadows"],
                                          os.path.join(a.out, name, f"time-{bound}"),
                                          os.path.join(a.out, f"{name}-time-{bound}.log"), common))
            auto_dir = os.path.join(a.out, name, f"auto-{bound}")
            rc, _ = run(a.deepvox, ["advise", scene, "--auto-budget", "--error", str(bound),
                                    "--out", auto_dir] + common,
                        os.path.join(a.out, f"{name}-auto-{bound}.log"))
            auto_file = os.path.join(auto_dir, "auto.json")
            if os.path.exists(auto_file):
                auto = json.load(open(auto_file))
                row["auto"] = auto["shadows"]["params"]
                row["auto_p95"] = auto["auto_budget"]["verified"].get("error_p95")
                row["auto_verified_strata"] = strata_p95(auto["auto_budget"]["verified"])
                row["auto_ms"] = auto["auto_budget"]["verified"].get("frame_ms")
                row["auto_by"] = "model" if any(l.startswith("model (") for l in
                                                auto["auto_budget"]["explanation"]) else "measured"
            feasible = row["sweep_cheapest"] is not None
            row["pass_verified"] = (row.get("pick_verified_p95") is not None and
                                    row["pick_verified_p95"] <= bound) if feasible else None
            row["time_ratio"] = ratio(row)
            row["pass_time"] = (row["time_ratio"] is not None and
                                row["time_ratio"] <= TIME_RATIO) if feasible else None
            row["pass_auto"] = (row.get("auto_p95") is not None and row["auto_p95"] <= bound) \
                if feasible else None
            row["pass_image"] = (row["pick_image_edge"] <= image_bound) \
                if row.get("pick_image_edge") is not None and image_bound is not None else None
            if name == "knecht-fig56":
                row["pass_advise_time"] = seconds <= limit_s
            rows.append(row)
            print(json.dumps(row), flush=True)
        write_summary(a, rows, limit_s)
    failed = [r for r in rows for k in ("pass_verified", "pass_time", "pass_image", "pass_auto",
                                        "pass_advise_time") if r.get(k) is False]
    print(f"{len(rows)} rows, {len(failed)} with a failed criterion -> {a.out}/summary.md")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
