#!/usr/bin/env python3
"""Plots of a suite result folder (deepvox report runs it): for each experiment of suite.json
with "plots", each plot {"x": "metric[:stat]", "y": "metric[:stat]", "type": "scatter"|"bar",
"logx": bool, "logy": bool, "pareto": bool, "title": str} drawn from rows.csv into
plots/<experiment>_<n>.png. "pareto" adds the front of the scatter's points that no other point
beats in both x and y (smaller is better). A bar plot takes only "y" (one bar per item). An
experiment with "pareto": {"error": [...], "cost": [...]} also gets, per scene and (error, cost)
pair, every point in grey and the front labelled, log x (log y when every error is positive), in plots/<experiment>_pareto_<n>.png
(the report prints the same fronts as tables). Exit 3 when matplotlib is missing."""
import csv
import json
import math
import os
import sys

try:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
except ImportError:
    sys.exit(3)


def metric_value(rows, spec):
    metric, _, stat = spec.partition(":")
    for wanted in ([stat] if stat else ["value", "median"]):
        for r in rows:
            if r["metric"] == metric and r["stat"] == wanted:
                return float(r["value"]), r["unit"]
    return None, ""


def pareto_front(points):
    """The points no other point beats in both coordinates (smaller is better), by x."""
    front, best_y = [], math.inf
    for x, y in sorted(points):
        if y < best_y:
            front.append((x, y))
            best_y = y
    return front


def label(rows):
    r = rows[0]
    return (r["strategy"] + " " + r["params"]).strip()


def main(folder):
    with open(os.path.join(folder, "suite.json")) as f:
        suite = json.load(f)
    items = {}
    with open(os.path.join(folder, "rows.csv"), newline="") as f:
        for r in csv.DictReader(f):
            items.setdefault((r["experiment"], int(r["item"])), []).append(r)
    os.makedirs(os.path.join(folder, "plots"), exist_ok=True)
    for exp in suite["experiments"]:
        runs = [rows for (name, _), rows in sorted(items.items()) if name == exp["name"]]
        runs = [rows for rows in runs if not any(r["metric"] == "failed" for r in rows)]
        if not runs:
            continue  # not run in this folder (another shard, --only, interrupted)
        for n, spec in enumerate(exp.get("plots", [])):
            fig, ax = plt.subplots(figsize=(6.4, 3.6), dpi=110)
            if spec.get("type", "scatter") == "bar":
                pairs = [(label(rows), metric_value(rows, spec["y"])) for rows in runs]
                pairs = [(l, v) for l, (v, _) in pairs if v is not None and math.isfinite(v)
                         and (v > 0 or not spec.get("logx"))]
                ax.barh([l for l, _ in pairs], [v for _, v in pairs])
                unit = next((metric_value(r, spec["y"])[1] for r in runs), "")
                ax.set_xlabel(spec["y"] + (" (" + unit + ")" if unit else ""))
                ax.invert_yaxis()
                if spec.get("logx"):
                    ax.set_xscale("log")
            else:
                points = []
                for rows in runs:
                    x, xu = metric_value(rows, spec["x"])
                    y, yu = metric_value(rows, spec["y"])
                    if x is None or y is None or (spec.get("logx") and x <= 0):
                        continue  # a log axis cannot show x <= 0 (e.g. methods keeping no bytes)
                    ax.scatter([x], [y], label=label(rows))
                    points.append((x, y))
                    ax.set_xlabel(spec["x"] + (" (" + xu + ")" if xu else ""))
                    ax.set_ylabel(spec["y"] + (" (" + yu + ")" if yu else ""))
                if spec.get("pareto") and points:
                    front = pareto_front(points)
                    ax.step([p[0] for p in front], [p[1] for p in front], where="post",
                            color="grey", linewidth=0.8, label="Pareto front")
                if spec.get("logx"):
                    ax.set_xscale("log")
                if spec.get("logy"):
                    ax.set_yscale("symlog", linthresh=1e-4)
                ax.legend(fontsize=6, loc="best")
            ax.set_title(spec.get("title", exp["name"]), fontsize=9)
            ax.tick_params(labelsize=7)
            fig.tight_layout()
            fig.savefig(os.path.join(folder, "plots", "%s_%d.png" % (exp["name"], n + 1)))
            plt.close(fig)
        if "pareto" in exp:
            pareto_plots(folder, exp, runs)


def columns(v):
    return [v] if isinstance(v, str) else list(v)


def pareto_plots(folder, exp, runs):
    """Per scene and (error, cost) pair: all points grey, the front joined and labelled."""
    scenes = []
    for rows in runs:
        if rows[0]["scene"] not in scenes:
            scenes.append(rows[0]["scene"])
    n = 0
    for scene in scenes:
        for err in columns(exp["pareto"]["error"]):
            for cost in columns(exp["pareto"]["cost"]):
                pts = []
                for rows in runs:
                    if rows[0]["scene"] != scene:
                        continue
                    x, _ = metric_value(rows, cost)
                    y, _ = metric_value(rows, err)
                    if x is not None and y is not None and x > 0 and math.isfinite(y):
                        pts.append((x, y, label(rows)))
                n += 1
                if not pts:
                    continue
                fig, ax = plt.subplots(figsize=(6.4, 4.0), dpi=110)
                ax.scatter([p[0] for p in pts], [p[1] for p in pts], color="lightgrey", s=12)
                front = pareto_front([(p[0], p[1]) for p in pts])
                ax.step([p[0] for p in front], [p[1] for p in front], where="post", color="C0",
                        linewidth=1.0)
                for x, y in front:
                    name = next(p[2] for p in pts if p[0] == x and p[1] == y)
                    ax.scatter([x], [y], color="C0", s=16)
                    ax.annotate(name, (x, y), fontsize=5, xytext=(3, 3),
                                textcoords="offset points")
                ax.set_xscale("log")
                if all(p[1] > 0 for p in pts):
                    ax.set_yscale("log")
                ax.set_xlabel(cost)
                ax.set_ylabel(err)
                ax.set_title("%s: %s vs %s" % (os.path.basename(scene), err, cost), fontsize=9)
                ax.tick_params(labelsize=7)
                fig.tight_layout()
                fig.savefig(os.path.join(folder, "plots", "%s_pareto_%d.png" % (exp["name"], n)))
                plt.close(fig)


if __name__ == "__main__":
    main(sys.argv[1])
