#!/usr/bin/env python3
"""Plots of a suite result folder (deepvox report runs it), drawn from rows.csv (with several runs
rows_over_runs.csv, every value the median over the runs) into plots/ with
a caption each in plots/plots.json (the report prints them in that order). Per experiment:

- its "plots" of suite.json, plots/<experiment>_<nn>.png: {"type": "scatter"|"bar"|"line",
  "x": ..., "y": ..., "logx": bool, "logy": bool, "pareto": bool, "title": str}. Columns are
  "metric[:stat]". A scatter joins the items that differ only in the first swept parameter (one
  line and colour per configuration, the parameter's value beside each point); "pareto" adds the
  front of the points no other beats in both x and y (smaller is better). A bar plot takes "y"
  ("logx" puts its value axis on a log scale): with a sweep, one panel per strategy entry
  (strategy and its fixed parameters) and grouped bars (groups: the first varying sweep key or the
  scene, colours: the others). A line plot takes "x": "scene" (the number in the scene's file
  name, e.g. a cup count) or a column, and "y" (a column or an array: one panel each), one line
  per configuration; "fit": "power" writes each line's fitted exponent k of y = c x^k beside it
  and, with the fixed-plus-marginal fit y = a + b x over the same points and both fits' relative
  residuals (suite_fits.py), in the caption and in the plot's "fits" in plots.json, which the
  report prints as a table.
- with "pareto": {"error": [...], "cost": [...]}: plots/<experiment>_pareto_<nn>.png per scene
  and (error, cost) pair (every item coloured by method family, the front joined and labelled)
  and, when a cost is frame_ms, plots/<experiment>_headline.png: error against frame time, one
  panel per scene, the exact oracle's time as a dashed line (the headline chart of the report).

A/A control copies (items whose params say aa=copy) repeat an item's work and are left out of
every plot. Whiskers run from the min to the max of the repetitions where rows.csv has them
(frame_ms, the median generation plus the median render, from the sum of their minima to the sum
of their maxima). The strategies' families, colours and markers come from `deepvox list --json`
(load_catalog: `plot_suite.py DIR [--catalog FILE | --deepvox PATH]`). Exit 3 when matplotlib
is missing, 4 when there is no catalog."""
import csv
import json
import math
import os
import re
import shutil
import subprocess
import sys

try:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.lines import Line2D
    from matplotlib.patches import Patch
except ImportError:
    sys.exit(3)

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))  # its modules beside this file
from plot_labels import place_labels  # noqa: E402
from suite_fits import describe, fits as fit_points  # noqa: E402

# Every registered strategy with its plot family, the family's colour and its marker, as
# `deepvox list --json` prints them (load_catalog); a strategy the binary does not know (an older
# run) is plotted as OTHER. A member (marker) is the strategy, or the strategy its member_param
# names (dsm: its storage).
CATALOG = {}
OTHER = ("other", "#8c564b")
ORACLE = "exact oracle"  # the family of the `reference` method and the `exact` voxelizer
SPARE_MARKERS = ["P", "h", "<", ">", "p", "8"]
SERIES_MARKERS = ["o", "s", "^", "D", "v", "P", "X", "h"]
# Time columns that are sums of timed columns (shadow_driver.cpp): their whiskers add up.
SUMS = {"frame_ms": ("generate_ms", "render_ms")}
# Headline error, the first present column that ranks (see headline_error).
HEADLINE_ERRORS = ["image_rmse", "probe_error_all:p90", "probe_error_all:mean"]


def split_column(spec):
    metric, _, stat = spec.partition(":")
    return metric, stat


def metric_value(rows, spec):
    metric, stat = split_column(spec)
    for wanted in ([stat] if stat else ["value", "median"]):
        for r in rows:
            if r["metric"] == metric and r["stat"] == wanted:
                return float(r["value"]), r["unit"]
    return None, ""


def value_range(rows, spec):
    """(value, min, max) of a column: min and max of the repetitions when rows.csv has them for a
    median (or a sum of medians, SUMS), else the value itself (no whisker)."""
    v, _ = metric_value(rows, spec)
    metric, stat = split_column(spec)
    if v is None or stat not in ("", "median", "value"):
        return v, v, v
    lo, _ = metric_value(rows, metric + ":min")
    hi, _ = metric_value(rows, metric + ":max")
    if lo is None or hi is None:
        parts = [(metric_value(rows, m + ":min")[0], metric_value(rows, m + ":max")[0])
                 for m in SUMS.get(metric, ())]
        if not parts or any(a is None or b is None for a, b in parts):
            return v, v, v
        lo, hi = sum(a for a, _ in parts), sum(b for _, b in parts)
    return v, min(lo, v), max(hi, v)


def is_aa_copy(rows):
    """Whether the item is an A/A control copy (suite field aa_duplicates)."""
    return "aa=copy" in rows[0]["params"].split()


def params_of(rows):
    return dict(kv.split("=", 1) for kv in rows[0]["params"].split() if "=" in kv)


# The lossy mark (experiments/harness/lossy.h): an item with a loss count above 0 (a metric
# naming an overflow or a drop) lost data in some run, so its error includes the loss.
LOSSY_MARK = " \u2020"
LOSSY_CAPTION = ("; \u2020 lossy: in at least one run a fixed-size structure overflowed (storage "
                 "nodes merged, recompressed or refused past its capacity, or a walk's buffer "
                 "full), so the item's error includes that loss")
LOSSY = {"experiments": set()}


def is_lossy(rows):
    return any(("overflow" in r["metric"] or "dropped" in r["metric"]) and float(r["value"]) > 0
               for r in rows)


def label(rows):
    r = rows[0]
    return (r["strategy"] + " " + r["params"]).strip() + (LOSSY_MARK if is_lossy(rows) else "")


def base_params(runs):
    """Per strategy the parameters that more than half of its items share (the base the suite
    sweeps around, e.g. dsm eps=0.05 res=512)."""
    counts, items = {}, {}
    for rows in runs:
        s = rows[0]["strategy"]
        items[s] = items.get(s, 0) + 1
        for k, v in params_of(rows).items():
            c = counts.setdefault(s, {}).setdefault(k, {})
            c[v] = c.get(v, 0) + 1
    return {s: {k: v for k, c in keys.items() for v, n in c.items() if 2 * n > items[s]}
            for s, keys in counts.items()}


def short_label(rows, base):
    """The item's name for a plot: dsm by its storage, parameters at their base value and
    "storage." prefixes left out."""
    s = rows[0]["strategy"].replace("transmittance-slicemap", "slicemap")
    words = []
    for k, v in params_of(rows).items():
        if k == "storage" and s == "dsm":
            s = v
        elif base.get(rows[0]["strategy"], {}).get(k) != v:
            words.append("%s=%s" % (k.replace("storage.", ""), v))
    return " ".join([s] + words) + (LOSSY_MARK if is_lossy(rows) else "")


def load_catalog(argv):
    """CATALOG, (registry, name) -> the strategy's entry, from the output of `deepvox list
    --json`: the file given by --catalog FILE (what `deepvox report` passes), else that of the
    binary given by --deepvox PATH, $DEEPVOX, `deepvox` on PATH or build/bin/deepvox beside the
    script's source tree. False when there is none."""
    if "--catalog" in argv:
        with open(argv[argv.index("--catalog") + 1]) as f:
            text = f.read()
    else:
        here = os.path.dirname(os.path.abspath(__file__))
        candidates = [argv[argv.index("--deepvox") + 1]] if "--deepvox" in argv else [
            os.environ.get("DEEPVOX"), shutil.which("deepvox"),
            os.path.join(here, "..", "..", "build", "bin", "deepvox")]
        deepvox = next((c for c in candidates if c and os.access(c, os.X_OK)), None)
        if deepvox is None:
            return False
        text = subprocess.run([deepvox, "list", "--json"], capture_output=True, text=True,
                              check=True).stdout
    for e in json.loads(text)["strategies"]:
        CATALOG[(e["registry"], e["name"])] = e
    return True


def entry_of(name, registries=("shadow method", "voxelizer")):
    return next((CATALOG[(r, name)] for r in registries if (r, name) in CATALOG), None)


def family(rows):
    """(family, colour, member) of an item: its strategy's, or that of the strategy its
    member_param names (the param's registered default when the item leaves it out)."""
    s, p = rows[0]["strategy"], params_of(rows)
    e = entry_of(s)
    if e is None:
        return OTHER + (s,)
    if e["member_param"]:
        key = e["member_param"]
        default = next((q["default"] for q in e["params"]
                        if q["key"] == key and q["type"] == "name"), "")
        member = p.get(key, default)
        e = entry_of(member, (key,))
        if e is None:
            return OTHER + (member,)
    return e["family"], e["colour"], e["name"]


def family_order():
    """The plot families in the catalog's order, each with its colour."""
    order = {}
    for e in CATALOG.values():
        order.setdefault(e["family"], e["colour"])
    order.setdefault(*OTHER)
    return list(order.items())


def scene_name(scene):
    return os.path.splitext(os.path.basename(scene))[0]


def scene_number(scene):
    numbers = re.findall(r"\d+", scene_name(scene))
    return float(numbers[-1]) if numbers else None


def axis_label(spec, unit):
    return spec + (" (" + unit + ")" if unit and unit != "1" else "")


class Markers:
    """A marker per family member, the same in every plot of a run."""

    def __init__(self):
        self.spare = {}

    def __call__(self, member):
        marked = [e["marker"] for (_, name), e in CATALOG.items() if name == member]
        if marked and marked[0]:
            return marked[0]
        if member not in self.spare:
            self.spare[member] = SPARE_MARKERS[len(self.spare) % len(SPARE_MARKERS)]
        return self.spare[member]


def pareto_front(points):
    """The points no other point beats in both coordinates (smaller is better), by x."""
    front, best_y = [], math.inf
    for p in sorted(points):
        if p[1] < best_y:
            front.append(p)
            best_y = p[1]
    return front


def sweep_keys(exp, runs):
    """The swept parameters that vary among the items, in the suite's order."""
    keys = [k for k in exp.get("sweep", {})]
    return [k for k in keys if len({params_of(rows).get(k) for rows in runs}) > 1]


def without(rows, keys, runs):
    """The item's configuration along the given parameters: its strategy (when the items have
    several) and the parameters that vary among the items, except those keys."""
    constant = {k: v for k, v in params_of(runs[0]).items()
                if all(params_of(r).get(k) == v for r in runs)}
    words = ["%s=%s" % (k, v) for k, v in params_of(rows).items()
             if k not in keys and constant.get(k) != v]
    if len({r[0]["strategy"] for r in runs}) > 1 or not words:
        words.insert(0, rows[0]["strategy"])
    return " ".join(words)


# What the whiskers span: one run's repetitions (rows.csv), or with several runs the lowest to the
# highest run median (rows_over_runs.csv, which deepvox report writes then); main sets it.
WHISKERS = {"rows": "rows.csv", "text": None}


def whisker_text(where=""):
    """What the captions say the whiskers span: one run's repetitions (`where`: where rows.csv
    has them), or the run medians' range."""
    return WHISKERS["text"] or "min-max over the repetitions" + where


def save(fig, folder, name, captions, exp, caption, fits=None):
    fig.savefig(os.path.join(folder, "plots", name), bbox_inches="tight",
                metadata={"Software": None})
    plt.close(fig)
    if exp["name"] in LOSSY["experiments"]:
        body, end = (caption[:-1], ".") if caption.endswith(".") else (caption, "")
        caption = body + LOSSY_CAPTION + end
    captions.append({"experiment": exp["name"], "file": name, "caption": caption})
    if fits:
        captions[-1]["fits"] = fits


def whiskers(ax, x, y, colour, xr=None, yr=None):
    xerr = [[x - xr[0]], [xr[1] - x]] if xr and xr[1] > xr[0] else None
    yerr = [[y - yr[0]], [yr[1] - y]] if yr and yr[1] > yr[0] else None
    if xerr or yerr:
        ax.errorbar([x], [y], xerr=xerr, yerr=yerr, fmt="none", ecolor=colour, elinewidth=0.7,
                    capsize=1.5, alpha=0.8, zorder=2)


def scatter_plot(folder, exp, runs, spec, name, captions):
    keys = sweep_keys(exp, runs)
    along = keys[:1]
    series = {}
    for rows in runs:
        x, xlo, xhi = value_range(rows, spec["x"])
        y, ylo, yhi = value_range(rows, spec["y"])
        if x is None or y is None or (spec.get("logx") and x <= 0):
            continue  # a log axis cannot show x <= 0 (e.g. methods keeping no bytes)
        key = without(rows, along, runs)
        if len(exp_scenes(runs)) > 1:
            key += " on " + scene_name(rows[0]["scene"])
        series.setdefault(key, []).append(
            (x, y, (xlo, xhi), (ylo, yhi), params_of(rows).get(along[0], "") if along else ""))
    fig, ax = plt.subplots(figsize=(7.5, 4.2), dpi=110)
    colours = palette(len(series))
    points, labelled = [], []
    for i, ((key, pts), colour) in enumerate(zip(series.items(), colours)):
        xs, ys = [p[0] for p in pts], [p[1] for p in pts]
        # hollow markers of different shapes keep series with the same values visible
        ax.plot(xs, ys, "-" if along else "", marker=SERIES_MARKERS[i % len(SERIES_MARKERS)],
                color=colour, markerfacecolor="none", markersize=5, linewidth=0.8, label=key)
        for x, y, xr, yr, value in pts:
            whiskers(ax, x, y, colour, xr, yr)
            points.append((x, y))
            if value:
                labelled.append((x, y, value))
    if spec.get("pareto") and points:
        front = pareto_front(points)
        ax.step([p[0] for p in front], [p[1] for p in front], where="post", color="black",
                linewidth=0.8, label="Pareto front")
    if spec.get("logx"):
        ax.set_xscale("log")
    if spec.get("logy"):
        ax.set_yscale("symlog", linthresh=1e-4)
    unit_x, unit_y = unit_of(runs, spec["x"]), unit_of(runs, spec["y"])
    ax.set_xlabel(axis_label(spec["x"], unit_x), fontsize=8)
    ax.set_ylabel(axis_label(spec["y"], unit_y), fontsize=8)
    ax.set_title(spec.get("title", exp["name"]), fontsize=9)
    ax.tick_params(which="both", labelsize=7)
    ax.legend(fontsize=6, loc="upper left", bbox_to_anchor=(1.01, 1.0), frameon=False)
    ax.autoscale_view()  # the limits the labels are placed in
    place_labels(ax, labelled, fontsize=5)
    caption = ("%s: %s against %s, one point per item of `%s` (%d)" %
               (spec.get("title", exp["name"]), spec["y"], spec["x"], exp["name"], len(points)))
    if along:
        caption += ("; a line and colour per configuration joins its values of %s (the number "
                    "beside each point)" % along[0])
    caption += "; whiskers: " + whisker_text(" where rows.csv has them")
    if spec.get("pareto"):
        caption += "; black step: the Pareto front (smaller is better in both)"
    save(fig, folder, name, captions, exp, caption + ".")


def exp_scenes(runs):
    scenes = []
    for rows in runs:
        if rows[0]["scene"] not in scenes:
            scenes.append(rows[0]["scene"])
    return scenes


def palette(n):
    cmap = plt.get_cmap("tab10" if n <= 10 else "tab20")
    return [cmap(i % cmap.N) for i in range(n)]


def scale_by_spread(ax, pts, plain_bytes=False):
    """Log axes where the values span more than a factor of 5 (all positive), else linear; log
    ticks at 1, 2, 5 x 10^n (bytes keep matplotlib's 10^n)."""
    for name, axis in (("x", ax.xaxis), ("y", ax.yaxis)):
        values = [p[name] for p in pts]
        if values and min(values) > 0 and max(values) > 5 * min(values):
            getattr(ax, "set_%sscale" % name)("log")
            if not (plain_bytes and name == "x"):
                readable_log(axis)


def readable_log(axis):
    """A log axis ticked at 1, 2 and 5 times the powers of ten, written as plain numbers."""
    axis.set_major_locator(matplotlib.ticker.LogLocator(subs=(1.0, 2.0, 5.0)))
    axis.set_major_formatter(matplotlib.ticker.FormatStrFormatter("%g"))
    axis.set_minor_formatter(matplotlib.ticker.NullFormatter())


def grid(n, width=3.6, height=2.6, cols=2, sharey=False):
    cols = min(cols, n)
    rows = (n + cols - 1) // cols
    fig, axes = plt.subplots(rows, cols, figsize=(width * cols, height * rows), dpi=110,
                             squeeze=False, constrained_layout=True, sharey=sharey)
    for ax in axes.flat[n:]:
        ax.set_visible(False)
    return fig, list(axes.flat[:n])


def bar_plot(folder, exp, runs, spec, name, captions):
    unit = unit_of(runs, spec["y"])
    pts = [(rows, value_range(rows, spec["y"])) for rows in runs]
    pts = [(rows, v) for rows, v in pts if v[0] is not None and math.isfinite(v[0])
           and (v[0] > 0 or not spec.get("logx"))]
    keys = sweep_keys(exp, runs)
    scenes = exp_scenes(runs)
    axes_of = (["scene"] if len(scenes) > 1 else []) + keys
    title = spec.get("title", exp["name"])
    if not axes_of:  # nothing swept: one bar per item
        fig, ax = plt.subplots(figsize=(6.4, 0.6 + 0.22 * len(pts)), dpi=110)
        shadow = exp.get("kind") == "shadow"  # the families are shadow methods
        for i, (rows, (v, lo, hi)) in enumerate(pts):
            colour = family(rows)[1] if shadow else "C0"
            ax.barh([i], [v], color=colour)
            if hi > lo:
                ax.errorbar([v], [i], xerr=[[v - lo], [hi - v]], fmt="none", ecolor="black",
                            elinewidth=0.7, capsize=2)
        ax.set_yticks(range(len(pts)), [label(rows) for rows, _ in pts], fontsize=7)
        ax.invert_yaxis()
        ax.set_xlabel(axis_label(spec["y"], unit), fontsize=8)
        if spec.get("logx"):
            ax.set_xscale("log")
        ax.set_title(title, fontsize=9)
        ax.tick_params(which="both", labelsize=7)
        save(fig, folder, name, captions, exp,
             "%s: %s per item of `%s`%s; whiskers: %s." %
             (title, spec["y"], exp["name"], ", coloured by method family" if shadow else "",
              whisker_text(" where rows.csv has them")))
        return

    def coordinate(rows, key):
        return scene_name(rows[0]["scene"]) if key == "scene" else params_of(rows).get(key, "")

    group_key, series_keys = axes_of[0], axes_of[1:]
    panels, groups, all_series = {}, [], []
    for rows, v in pts:
        group = coordinate(rows, group_key)
        series = " ".join("%s=%s" % (k, coordinate(rows, k)) for k in series_keys)
        panels.setdefault(without(rows, keys, runs), {}).setdefault(group, {})[series] = v
        if group not in groups:
            groups.append(group)
        if series not in all_series:
            all_series.append(series)
    colours = palette(len(all_series))
    fig, axes = grid(len(panels), sharey=True)  # one scale: the panels compare
    width = 0.8 / max(1, len(all_series))
    for ax, (panel, by_group) in zip(axes, panels.items()):
        for j, (s, colour) in enumerate(zip(all_series, colours)):
            xs, vs, errs = [], [], [[], []]
            for i, g in enumerate(groups):
                if s in by_group.get(g, {}):
                    v, lo, hi = by_group[g][s]
                    xs.append(i - 0.4 + width * (j + 0.5))
                    vs.append(v)
                    errs[0].append(v - lo)
                    errs[1].append(hi - v)
            ax.bar(xs, vs, width=width, color=colour, label=s or panel)
            if any(errs[0]) or any(errs[1]):
                ax.errorbar(xs, vs, yerr=errs, fmt="none", ecolor="black", elinewidth=0.6,
                            capsize=1.5)
        ax.set_xticks(range(len(groups)), groups, fontsize=7)
        ax.set_xlabel(group_key, fontsize=7)
        ax.set_ylabel(axis_label(spec["y"], unit), fontsize=7)
        ax.yaxis.set_tick_params(labelleft=True)
        if len(panels) > 1:
            ax.set_title(panel, fontsize=8)
        ax.tick_params(which="both", labelsize=7)
    if spec.get("logx") and pts:  # log bars start at 0: the shared scale from the data
        for ax in axes:
            ax.set_yscale("log")
            readable_log(ax.yaxis)
        axes[0].set_ylim(min(v[1] for _, v in pts) / 1.5, max(v[2] for _, v in pts) * 1.3)
    if series_keys:
        legend_below(fig, axes, 4)
    fig.suptitle(title, fontsize=9)
    save(fig, folder, name, captions, exp,
         "%s: %s of `%s`, a panel per strategy entry (%d, one scale), bars grouped by %s%s; "
         "whiskers: %s%s." %
         (title, spec["y"], exp["name"], len(panels), group_key,
          ", a colour per " + " and ".join(series_keys) if series_keys else "",
          whisker_text(" where rows.csv has them"), ", log scale" if spec.get("logx") else ""))


def unit_of(runs, spec):
    return next((u for u in (metric_value(r, spec)[1] for r in runs) if u), "")


def line_plot(folder, exp, runs, spec, name, captions):
    ys = [spec["y"]] if isinstance(spec["y"], str) else list(spec["y"])
    title = spec.get("title", exp["name"])
    fig, axes = grid(len(ys), width=3.6, height=3.0, cols=3)
    keys = [] if spec["x"] == "scene" else sweep_keys(exp, runs)[:1]
    configs = sorted({without(rows, keys, runs) for rows in runs})
    colours = dict(zip(configs, palette(len(configs))))
    fits = []
    x_label = spec.get("xlabel", "number in the scene name" if spec["x"] == "scene" else spec["x"])
    for ax, y_spec in zip(axes, ys):
        series = {}
        for rows in runs:
            x = (scene_number(rows[0]["scene"]) if spec["x"] == "scene"
                 else metric_value(rows, spec["x"])[0])
            y, lo, hi = value_range(rows, y_spec)
            if x is not None and y is not None:
                series.setdefault(without(rows, keys, runs), []).append((x, y, lo, hi))
        for key, pts in sorted(series.items()):
            pts.sort()
            ax.errorbar([p[0] for p in pts], [p[1] for p in pts],
                        yerr=[[p[1] - p[2] for p in pts], [p[3] - p[1] for p in pts]],
                        color=colours[key], marker="o", markersize=3, linewidth=1,
                        elinewidth=0.6, capsize=1.5)
            fit = fit_points(pts) if spec.get("fit") == "power" else None
            if fit is not None:
                fits.append(dict(fit, y=y_spec, line=key or "all",
                                 unit=unit_of(runs, y_spec), x=x_label))
                ax.annotate("^%.2f" % fit["power"]["k"], (pts[-1][0], pts[-1][1]), fontsize=6,
                            color=colours[key], xytext=(3, 0), textcoords="offset points",
                            va="center")
        ax.set_ylabel(axis_label(y_spec, unit_of(runs, y_spec)), fontsize=7)
        ax.set_xlabel(x_label, fontsize=7)
        if spec.get("logx"):
            ax.set_xscale("log")
        if spec.get("logy"):
            ax.set_yscale("log")
        ax.tick_params(which="both", labelsize=7)
        ax.grid(True, linewidth=0.3, alpha=0.5)
    fig.legend(handles=[Line2D([], [], color=colours[c], marker="o", markersize=3, label=c)
                        for c in configs], loc="upper center", bbox_to_anchor=(0.5, 0.0),
               ncol=2, fontsize=7, frameon=False)
    fig.suptitle(title, fontsize=9)
    save(fig, folder, name, captions, exp,
         "%s: %s against %s, a line and colour per configuration of `%s` (the same in every "
         "panel; a panel lacks the configurations without that column); whiskers: %s.%s" %
         (title, ", ".join(ys), spec.get("xlabel", spec["x"]), exp["name"], whisker_text(),
                                 " Fits over each line's points with both x and y positive (at "
                                 "least three): the exponent k of y = c x^k (least squares on "
                                 "log y against log x; written beside the line's last point) and "
                                 "the fixed cost a and marginal cost b per unit of x of y = a + b "
                                 "x (least squares on y), each with its relative residual (root "
                                 "mean square of (y - fit) / y): " +
                                 "; ".join("%s of %s: %s" % (f["y"], f["line"], describe(f))
                                           for f in fits) + "." if fits else ""),
         fits)


def family_legend(where, used, markers, extra=()):
    """Right of the panels (where: the figure or the one axes): the extra handles, then an entry
    per family member used, in the families' order (colour = family, marker = member)."""
    handles = list(extra)
    for fam, colour in family_order():
        for m in sorted(m for f, m in used if f == fam):
            handles.append(Line2D([], [], color=colour, marker=markers(m), linestyle="",
                                  markersize=5, label="%s: %s" % (fam.split(" (")[0], m)))
    where.legend(handles=handles, loc="upper left", bbox_to_anchor=(1.0, 1.0), fontsize=6,
                 frameon=False)


def legend_below(fig, axes, ncol):
    handles, labels = axes[0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="upper center", bbox_to_anchor=(0.5, 0.0),
               ncol=min(ncol, len(labels)), fontsize=7, frameon=False)


def draw_items(ax, pts, markers):
    """Every item: family colour, member marker, whiskers (one collection per member)."""
    groups = {}
    for p in pts:
        groups.setdefault((p["colour"], p["member"]), []).append(p)
    for (colour, member), group in sorted(groups.items()):
        xs, ys = [p["x"] for p in group], [p["y"] for p in group]
        xerr = [[p["x"] - p["xr"][0] for p in group], [p["xr"][1] - p["x"] for p in group]]
        yerr = [[p["y"] - p["yr"][0] for p in group], [p["yr"][1] - p["y"] for p in group]]
        ax.errorbar(xs, ys, xerr=xerr, yerr=yerr,
                    fmt="none", ecolor=colour, elinewidth=0.7, capsize=1.5, alpha=0.8, zorder=2)
        ax.scatter(xs, ys, color=colour, marker=markers(member), s=18, zorder=3,
                   edgecolors="white", linewidths=0.3)


def points_of(runs, scene, err, cost):
    pts, base = [], base_params(runs)
    for rows in runs:
        if rows[0]["scene"] != scene:
            continue
        x, xlo, xhi = value_range(rows, cost)
        y, ylo, yhi = value_range(rows, err)
        if x is None or y is None or x <= 0 or not math.isfinite(y):
            continue
        fam, colour, member = family(rows)
        pts.append({"x": x, "y": y, "xr": (xlo, xhi), "yr": (ylo, yhi),
                    "label": short_label(rows, base), "family": fam, "colour": colour,
                    "member": member})
    return pts


def columns(v):
    return [v] if isinstance(v, str) else list(v)


def pareto_plots(folder, exp, runs, oracle, captions, markers):
    """Per scene and (error, cost) pair: every item by family, the front joined and labelled;
    against frame_ms the exact oracle's time dashed."""
    n = 0
    for scene in exp_scenes(runs):
        for err in columns(exp["pareto"]["error"]):
            for cost in columns(exp["pareto"]["cost"]):
                n += 1
                pts = points_of(runs, scene, err, cost)
                if not pts:
                    continue
                left_out = sum(1 for rows in runs if rows[0]["scene"] == scene) - len(pts)
                fig, ax = plt.subplots(figsize=(7.0, 4.4), dpi=110)
                draw_items(ax, pts, markers)
                front = pareto_front([(p["x"], p["y"], i) for i, p in enumerate(pts)])
                ax.step([p[0] for p in front], [p[1] for p in front], where="post",
                        color="black", linewidth=0.8, zorder=2)
                if cost == "frame_ms":
                    mark_oracle(ax, oracle, scene)
                scale_by_spread(ax, pts, plain_bytes=cost == "bytes")
                ax.set_xlabel(axis_label(cost, unit_of(runs, cost)), fontsize=8)
                ax.set_ylabel(err, fontsize=8)
                ax.set_title("%s: %s vs %s" % (scene_name(scene), err, cost), fontsize=9)
                ax.tick_params(which="both", labelsize=7)
                family_legend(ax, {(p["family"], p["member"]) for p in pts}, markers)
                ax.autoscale_view()  # the limits the labels are placed in
                place_labels(ax, [(x, y, pts[i]["label"]) for x, y, i in front], fontsize=5,
                             obstacles=[(p["x"], p["y"]) for p in pts])
                save(fig, folder, "%s_pareto_%02d.png" % (exp["name"], n), captions, exp,
                     "Pareto front %d of `%s` on `%s`: %s against %s (log axes where the values "
                     "span over 5x), %d items%s. "
                     "Colour: method family, marker: storage or strategy (legend); whiskers: "
                     "%s; black step and labels: the front (%d items no "
                     "other beats in both; the table above), labelled without the parameters that "
                     "most items of the strategy share (its base)%s." %
                     (n, exp["name"], scene_name(scene), err, cost, len(pts),
                      " (%d with no %s left out)" % (left_out, cost) if left_out else "",
                      whisker_text(),
                      len(front), "; dashed: the exact oracle's frame time"
                      if cost == "frame_ms" and scene in oracle else ""))


def ranks(runs, spec):
    """A column ranks when it has values and fewer than a third of each scene's items tie at
    that scene's maximum or at its minimum, within 1e-9 (p99 and max columns saturate at 1, a
    camera-visible p90 is 0, i.e. about 1e-14, for most maps)."""
    by_scene = {}
    for rows in runs:
        v, _ = metric_value(rows, spec)
        if v is not None and math.isfinite(v):
            by_scene.setdefault(rows[0]["scene"], []).append(v)
    if not by_scene:
        return False
    return all(sum(1 for v in vs if abs(v - edge) <= 1e-9) < max(2, len(vs) / 3)
               for vs in by_scene.values() for edge in (min(vs), max(vs)))


def headline_error(runs):
    """The headline's error column: a camera-visible probe class (p90, then mean) when the rows
    have one, else HEADLINE_ERRORS; the first that ranks."""
    metrics = sorted({r["metric"] for rows in runs for r in rows})
    camera = [m for m in metrics if m.startswith("probe_error_") and
              ("camera" in m or "visible" in m)]
    candidates = [m + ":" + s for m in camera for s in ("p90", "mean")] + HEADLINE_ERRORS
    return next((c for c in candidates if ranks(runs, c)), None)


def oracle_times(all_runs):
    """Per scene the exact oracle's frame time (a `reference` or `exact` item anywhere)."""
    times = {}
    for rows in all_runs:
        if family(rows)[0] == ORACLE:
            v, lo, hi = value_range(rows, "frame_ms")
            if v is not None:
                times.setdefault(rows[0]["scene"], (v, lo, hi))
    return times


def mark_oracle(ax, oracle, scene):
    """The exact oracle's frame time on the scene: a dashed line (its min-max shaded)."""
    if scene not in oracle:
        return
    t, lo, hi = oracle[scene]
    ax.axvline(t, color="black", linestyle="--", linewidth=0.9)
    if hi > lo:
        ax.axvspan(lo, hi, color="black", alpha=0.08, linewidth=0)
    ax.annotate("exact oracle\n%.3g ms" % t, (t, 0), xycoords=("data", "axes fraction"),
                xytext=(-3, 3), textcoords="offset points", ha="right", va="bottom", fontsize=6)


def shade_dominated(ax, oracle, scene):
    """Grey from the exact oracle's frame time to the axis' end: an item there is slower than
    the oracle, whose error is 0, so the oracle beats it in both."""
    if scene not in oracle:
        return False
    left, right = ax.get_xlim()
    t = oracle[scene][0]
    if t >= right:
        return False
    ax.axvspan(max(t, left), right, color="0.5", alpha=0.15, linewidth=0, zorder=0)
    ax.set_xlim(left, right)
    return True


def headline_plot(folder, exp, runs, all_runs, captions, markers):
    """Error against frame time on every scene: what accuracy costs, at a glance."""
    err = headline_error(runs)
    if err is None or "frame_ms" not in columns(exp["pareto"]["cost"]):
        return
    scenes = exp_scenes(runs)
    oracle = oracle_times(all_runs)
    fig, axes = grid(len(scenes), width=4.0, height=3.0)
    used = set()
    shaded = False
    for ax, scene in zip(axes, scenes):
        pts = [p for p in points_of(runs, scene, err, "frame_ms") if p["family"] != ORACLE]
        draw_items(ax, pts, markers)
        used |= {(p["family"], p["member"]) for p in pts}
        front = pareto_front([(p["x"], p["y"]) for p in pts])
        ax.step([p[0] for p in front], [p[1] for p in front], where="post", color="black",
                linewidth=0.7, zorder=2)
        mark_oracle(ax, oracle, scene)
        scale_by_spread(ax, pts + ([{"x": oracle[scene][0], "y": pts[0]["y"]}]
                                   if scene in oracle and pts else []))
        shaded |= shade_dominated(ax, oracle, scene)
        ax.set_title(scene_name(scene), fontsize=8)
        ax.set_xlabel("frame time (ms, median; whiskers %s)"
                      % ("run medians" if WHISKERS["text"] else "min-max"), fontsize=7)
        ax.set_ylabel(err, fontsize=7)
        ax.tick_params(which="both", labelsize=7)
        ax.grid(True, which="major", linewidth=0.3, alpha=0.5)
    family_legend(fig, used, markers, [
        Line2D([], [], color="black", linestyle="--", label="exact oracle (frame time)"),
        Line2D([], [], color="black", linewidth=0.7, label="Pareto front")] +
        ([Patch(color="0.5", alpha=0.15, label="dominated by the exact oracle")]
         if shaded else []))
    fig.suptitle("What accuracy costs: %s against frame time, per scene" % err, fontsize=9)
    save(fig, folder, "%s_headline.png" % exp["name"], captions, exp,
         "Headline: %s (smaller is better) against frame time (median generation + median "
         "render, ms) for every item of `%s`, one panel per scene, log axes where the values "
         "span over 5x. Colour: method family, marker: storage or strategy; whiskers: %s "
         "(the sum of the passes' minima and maxima); black step: the "
         "Pareto front; dashed line: the exact oracle's frame time on that scene (its error is "
         "0); grey beyond it: the region the oracle dominates (slower and less accurate than "
         "the exact answer). Items with no frame time are left out." %
         (err, exp["name"], whisker_text()))


def main(folder):
    with open(os.path.join(folder, "suite.json")) as f:
        suite = json.load(f)
    items = {}
    over_runs = os.path.join(folder, "rows_over_runs.csv")
    if os.path.exists(over_runs):
        WHISKERS["rows"] = "rows_over_runs.csv"
        WHISKERS["text"] = ("the lowest to the highest run median over the runs "
                            "(rows_over_runs.csv: each value the median over the runs)")
    with open(os.path.join(folder, WHISKERS["rows"]), newline="") as f:
        for r in csv.DictReader(f):
            items.setdefault((r["experiment"], int(r["item"])), []).append(r)
    plots = os.path.join(folder, "plots")
    os.makedirs(plots, exist_ok=True)
    all_runs = [rows for _, rows in sorted(items.items())
                if not any(r["metric"] == "failed" for r in rows) and not is_aa_copy(rows)]
    captions, markers = [], Markers()
    for exp in suite["experiments"]:
        runs = [rows for rows in all_runs if rows[0]["experiment"] == exp["name"]]
        if not runs:
            continue  # not run in this folder (another shard, --only, interrupted)
        if any(is_lossy(rows) for rows in runs):
            LOSSY["experiments"].add(exp["name"])
        drawn = re.compile(re.escape(exp["name"]) + r"_(\d+|headline|pareto_\d+)\.png")
        for old in os.listdir(plots):  # redrawn below (an older script numbered them 1, 2, ...)
            if drawn.fullmatch(old):
                os.remove(os.path.join(plots, old))
        if "pareto" in exp:
            headline_plot(folder, exp, runs, all_runs, captions, markers)
        for n, spec in enumerate(exp.get("plots", [])):
            name = "%s_%02d.png" % (exp["name"], n + 1)
            draw = {"bar": bar_plot, "line": line_plot}.get(spec.get("type"), scatter_plot)
            draw(folder, exp, runs, spec, name, captions)
        if "pareto" in exp:
            pareto_plots(folder, exp, runs, oracle_times(all_runs), captions, markers)
    with open(os.path.join(plots, "plots.json"), "w") as f:
        json.dump(captions, f, indent=1)
        f.write("\n")


if __name__ == "__main__":
    if not load_catalog(sys.argv):
        print("plot_suite.py: no deepvox binary for `deepvox list --json` (give --catalog FILE or"
              " --deepvox PATH)", file=sys.stderr)
        sys.exit(4)
    main(sys.argv[1])
