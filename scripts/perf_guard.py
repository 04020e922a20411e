#!/usr/bin/env python3
"""The performance regression guard: compares a run of the headline benchmarks with the last
accepted medians (results/perf/baseline.json: per benchmark its binary, Google Benchmark name,
metric, unit and median, with the GPU, commit, date and command they came from), and rewrites
that list from a run when a change is accepted. scripts/ab-bench.sh --guard runs the
benchmarks on the device and calls it; the values of a run are read as ab-bench.sh reads them
(scripts/bench_summary.py: one JSON file a round, a round's median, the median over rounds).

  perf_guard.py plan BASELINE
      per binary one line, tab-separated: the binary, then its arguments (the baseline's
      `args` and a --benchmark_filter naming exactly its benchmarks)
  perf_guard.py check BASELINE PATH... [--any-gpu]
      prints per benchmark baseline / now / now/baseline; exit 1 when one is more than the
      baseline's threshold (5 %) slower or was not run, 0 otherwise
  perf_guard.py update BASELINE PATH... --commit SHA [--date YYYY-MM-DD] [--command TEXT]
                 [--any-gpu]
      rewrites the medians, GPU, commit, date and command of BASELINE from the run (a run on
      the baseline's GPU kind; --any-gpu moves the whole list to the run's)

PATH is a Google Benchmark JSON file (--benchmark_out) or a folder of them (its old-* files,
the base side of an A/B, left out); a file's binary is the baseline binary that its name holds
(new-bench_dsm-r1.json, bench_dsm.json). The run's GPU is the label its rows carry. Exit 2 on
bad input: an unreadable baseline or JSON file, no value for any benchmark of the list, a run
on another GPU than the baseline's (without --any-gpu), or an update that lacks a benchmark or
names no commit."""
import argparse
import datetime
import json
import os
import re
import statistics
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from bench_summary import (TIME_UNITS_IN_MS, BenchJsonError, read_json, round_values,  # noqa: E402
                           unit_of)

FORMAT = "deepvox-perf-baseline"
COMMIT = re.compile(r"^[0-9a-f]{7,40}$")
REGEX_SPECIAL = re.compile(r"([.^$|()\[\]{}*+?\\])")


class GuardError(Exception):
    """Bad input: the message names the file and the problem (exit 2)."""


def load_baseline(path):
    try:
        base = read_json(path, "baseline")
    except BenchJsonError as e:
        raise GuardError(str(e)) from e
    if not isinstance(base, dict) or base.get("format") != FORMAT:
        raise GuardError(f"{path}: not a baseline file (its \"format\" must be \"{FORMAT}\")")
    binaries = base.get("binaries")
    entries = base.get("benchmarks")
    if not isinstance(binaries, dict) or not binaries or not isinstance(entries, list) or not entries:
        raise GuardError(f"{path}: needs a non-empty \"binaries\" object and \"benchmarks\" list")
    if not isinstance(base.get("threshold"), (int, float)) or not 0 < base["threshold"] < 1:
        raise GuardError(f"{path}: \"threshold\" must be a fraction such as 0.05")
    seen = set()
    for i, e in enumerate(entries):
        if not isinstance(e, dict) or not all(isinstance(e.get(k), str) and e[k]
                                              for k in ("binary", "name", "metric", "unit")):
            raise GuardError(f"{path}: benchmark {i} needs \"binary\", \"name\", \"metric\" and "
                             "\"unit\" strings")
        if e["binary"] not in binaries:
            raise GuardError(f"{path}: benchmark {e['name']} names binary {e['binary']}, which "
                             "\"binaries\" does not list")
        if e.get("median") is not None and (not isinstance(e["median"], (int, float)) or
                                            e["median"] <= 0):
            raise GuardError(f"{path}: benchmark {e['name']} has a median that is no positive number")
        if (e["binary"], e["name"], e["metric"]) in seen:
            raise GuardError(f"{path}: benchmark {e['name']} ({e['metric']}) is listed twice")
        seen.add((e["binary"], e["name"], e["metric"]))
    return base


def binary_of(path, binaries):
    """The baseline binary whose name the file's name holds (the longest), or None."""
    base = os.path.basename(path)
    found = [b for b in binaries if re.search(r"(?:^|-)" + re.escape(b) + r"(?:-|\.json$)", base)]
    return max(found, key=len) if found else None


def run_files(paths, binaries):
    """[(binary, file)] of the PATH arguments."""
    files = []
    for p in paths:
        if os.path.isdir(p):
            for name in sorted(os.listdir(p)):
                if name.endswith(".json") and not name.startswith("old-"):
                    b = binary_of(name, binaries)
                    if b:
                        files.append((b, os.path.join(p, name)))
        elif os.path.isfile(p):
            b = binary_of(p, binaries)
            if not b:
                raise GuardError(f"{p}: its name holds none of the baseline's binaries "
                                 f"({', '.join(sorted(binaries))}), so which one wrote it is unknown")
            files.append((b, p))
        else:
            raise GuardError(f"{p}: no such file or folder")
    if not files:
        raise GuardError(f"no Google Benchmark JSON file of {', '.join(sorted(binaries))} in "
                         f"{' '.join(paths)}")
    return files


class Run:
    """Values over rounds per (binary, name, metric), their units, GPU labels and dates."""

    def __init__(self, files):
        self.values, self.units, self.labels, self.dates = {}, {}, set(), []
        for binary, path in files:
            try:
                one = round_values(path)
            except BenchJsonError as e:
                raise GuardError(str(e)) from e
            if one.date:
                self.dates.append(one.date)
            for name, metrics in one.values.items():
                for metric, v in metrics.items():
                    key = (binary, name, metric)
                    self.values.setdefault(key, []).append(v)
                    self.units[key] = unit_of(metric, one.units[name])
                if name in one.labels:
                    self.labels.add((binary, name, one.labels[name]))

    def gpu_of(self, entries):
        """The one label of the listed benchmarks' rows (deepvox labels a CUDA case with its GPU)."""
        keys = {(e["binary"], e["name"]) for e in entries}
        names = {label for b, n, label in self.labels if (b, n) in keys}
        if len(names) > 1:
            raise GuardError(f"the run's benchmarks carry several GPU labels: {sorted(names)}")
        return names.pop() if names else None


def in_unit(value, unit, wanted):
    """value (in unit) in the unit wanted; None when the two cannot be converted."""
    if unit == wanted:
        return value
    if unit in TIME_UNITS_IN_MS and wanted in TIME_UNITS_IN_MS:
        return value * TIME_UNITS_IN_MS[unit] / TIME_UNITS_IN_MS[wanted]
    return None


def now_values(run, e):
    """The run's values of entry e over rounds, in e's unit ([] when not run)."""
    key = (e["binary"], e["name"], e["metric"])
    vs = run.values.get(key, [])
    converted = [in_unit(v, run.units[key], e["unit"]) for v in vs]
    if any(v is None for v in converted):
        raise GuardError(f"{e['name']}: the run's {e['metric']} is in {run.units[key]}, the "
                         f"baseline's in {e['unit']}")
    return converted


def exact_filter(names):
    """A --benchmark_filter matching exactly these benchmark names."""
    return "^(" + "|".join(REGEX_SPECIAL.sub(r"\\\1", n) for n in sorted(set(names))) + ")$"


def cmd_plan(args):
    base = load_baseline(args.baseline)
    for binary, spec in base["binaries"].items():
        names = [e["name"] for e in base["benchmarks"] if e["binary"] == binary]
        if not names:
            continue
        extra = spec.get("args", []) if isinstance(spec, dict) else []
        print("\t".join([binary] + list(extra) + ["--benchmark_filter=" + exact_filter(names)]))
    return 0


def fmt(v):
    return f"{v:.4g}"


def cmd_check(args):
    base = load_baseline(args.baseline)
    entries = base["benchmarks"]
    run = Run(run_files(args.paths, base["binaries"]))
    gpu = run.gpu_of(entries)
    if gpu is not None and gpu != base.get("gpu") and not args.any_gpu:
        raise GuardError(f"{args.baseline} holds medians of a {base.get('gpu')}, this run is on "
                         f"a {gpu}: run the guard on that GPU kind (or --any-gpu to compare anyway)")
    limit = 1.0 + base["threshold"]
    rows, slower, missing, measured = [], [], [], 0
    for e in entries:
        vs = now_values(run, e)
        if vs:
            measured += 1
        now = statistics.median(vs) if vs else None
        if not vs:
            verdict = "NOT RUN"
            missing.append(e["name"])
        elif e.get("median") is None:
            verdict = "no baseline yet"
        elif now / e["median"] > limit:
            verdict = f"SLOWER by {100 * (now / e['median'] - 1):.1f} %"
            slower.append(e["name"])
        else:
            verdict = "ok"
        ratio = f"{now / e['median']:.3f}" if vs and e.get("median") else "-"
        span = f"{fmt(now)} ({fmt(min(vs))}-{fmt(max(vs))}, n={len(vs)})" if vs else "-"
        base_cell = fmt(e["median"]) if e.get("median") is not None else "-"
        rows.append(f"| {e['binary']} | {e['name']} | {e['metric']} | {e['unit']} | {base_cell} | "
                    f"{span} | {ratio} | {verdict} |")
    if measured == 0:
        raise GuardError(f"the run holds no value of any benchmark of {args.baseline} "
                         "(no GPU? see the benchmarks' logs)")
    print(f"# baseline {args.baseline}: {base.get('gpu')}, commit {base.get('commit')}, "
          f"{base.get('date')}; fails above {limit:.2f}x")
    print(f"# run: {gpu or '(no GPU label)'}, {' '.join(args.paths)}")
    print("| binary | benchmark | metric | unit | baseline | now: median (min-max over rounds) | "
          "now/baseline | verdict |")
    print("| --- | --- | --- | --- | --- | --- | --- | --- |")
    print("\n".join(rows))
    failed = bool(slower or missing)
    print(f"perf-guard: {len(entries)} benchmarks, {len(slower)} more than "
          f"{100 * base['threshold']:g} % slower, {len(missing)} not run: "
          f"{'FAIL' if failed else 'pass'}")
    return 1 if failed else 0


def cmd_update(args):
    base = load_baseline(args.baseline)
    if not COMMIT.match(args.commit):
        raise GuardError(f"--commit '{args.commit}' is no commit hash: the baseline is updated "
                         "only from a build of a committed tree, whose commit it records")
    run = Run(run_files(args.paths, base["binaries"]))
    gpu = run.gpu_of(base["benchmarks"])
    if gpu is None:
        raise GuardError("the run's rows carry no GPU label: the baseline needs the GPU they ran on")
    if base.get("gpu") and gpu != base["gpu"] and not args.any_gpu:
        raise GuardError(f"{args.baseline} holds medians of a {base['gpu']}, this run is on a "
                         f"{gpu}: update it from a run on that GPU kind (or --any-gpu to move the "
                         "whole list to this one)")
    for e in base["benchmarks"]:
        vs = now_values(run, e)
        if not vs:
            raise GuardError(f"{e['binary']} {e['name']} ({e['metric']}) is not in the run: the "
                             "baseline is rewritten only from a run of every benchmark it lists")
        e["median"] = float(f"{statistics.median(vs):.6g}")
        e["min"], e["max"], e["rounds"] = float(f"{min(vs):.6g}"), float(f"{max(vs):.6g}"), len(vs)
    date = args.date or (min(run.dates)[:10] if run.dates else
                         datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d"))
    base.update(gpu=gpu, commit=args.commit, date=date)
    if args.command:
        base["command"] = args.command
    with open(args.baseline + ".tmp", "w") as f:
        json.dump(base, f, indent=2)
        f.write("\n")
    os.replace(args.baseline + ".tmp", args.baseline)
    print(f"perf-guard: {args.baseline} now holds {len(base['benchmarks'])} medians of a {gpu}, "
          f"commit {args.commit}, {date}")
    return 0


def main(argv):
    parser = argparse.ArgumentParser(prog="perf_guard.py", description=__doc__.split("\n")[0])
    sub = parser.add_subparsers(dest="command_name", required=True)
    p = sub.add_parser("plan")
    p.add_argument("baseline")
    p.set_defaults(run=cmd_plan)
    p = sub.add_parser("check")
    p.add_argument("baseline")
    p.add_argument("paths", nargs="+")
    p.add_argument("--any-gpu", action="store_true", help="compare a run on another GPU anyway")
    p.set_defaults(run=cmd_check)
    p = sub.add_parser("update")
    p.add_argument("baseline")
    p.add_argument("paths", nargs="+")
    p.add_argument("--commit", required=True, help="the commit the run's binaries were built from")
    p.add_argument("--date", help="the run's date (default: the earliest date of its JSON files)")
    p.add_argument("--command", help="the command that made the run, recorded in the baseline")
    p.add_argument("--any-gpu", action="store_true",
                   help="move the list to the run's GPU kind when it is not the baseline's")
    p.set_defaults(run=cmd_update)
    args = parser.parse_args(argv[1:])
    try:
        return args.run(args)
    except GuardError as e:
        print(f"perf_guard.py: error: {e}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main(sys.argv))
