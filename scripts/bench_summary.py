#!/usr/bin/env python3
"""Google Benchmark JSON files (--benchmark_out) read one way for every benchmark script: one
file is one round, and a benchmark's value in a round is its `median` aggregate where
repetitions made one, else the median of its iterations (rows with an error left out). Every
metric of a row is read: real_time (in the row's time_unit) and each numeric counter (with_clear_ms,
fragment_ms, ...). scripts/ab-bench.sh prints its A/B table with this module (`bench_summary.py
OUT`: OUT's old-*-rN.json and new-*-rN.json files), and scripts/perf_guard.py compares a run
with the accepted baseline through it."""
import glob
import json
import os
import re
import statistics
import sys

# Row fields of Google Benchmark's JSON that are bookkeeping, not a measured metric.
NOT_METRICS = {"family_index", "per_family_instance_index", "repetitions", "repetition_index",
               "threads", "iterations", "cpu_time"}
TIME_UNITS_IN_MS = {"ns": 1e-6, "us": 1e-3, "ms": 1.0, "s": 1e3}


class BenchJsonError(Exception):
    """A file that is no readable JSON, or no Google Benchmark JSON output."""


def unit_of(metric, time_unit):
    """The unit of a metric: the row's time_unit for real_time, ms for a *_ms counter."""
    if metric == "real_time":
        return time_unit
    return "ms" if metric.endswith("_ms") else ""


def to_ms(value, unit):
    """A time in ms (values of other units are returned as they are)."""
    return value * TIME_UNITS_IN_MS.get(unit, 1.0)


class Round:
    """One file's benchmarks: values {name: {metric: value}}, units {name: time_unit}, labels
    {name: label} (deepvox's benchmarks label each row with the GPU's name) and the run's date."""

    def __init__(self, values, units, labels, date):
        self.values, self.units, self.labels, self.date = values, units, labels, date


def read_json(path, what):
    """The JSON document in path; BenchJsonError naming the file and what it should be."""
    try:
        with open(path) as f:
            return json.load(f)
    except (OSError, ValueError) as e:
        raise BenchJsonError(f"{path}: unreadable {what} ({e})") from e


def round_values(path):
    """The Round that the Google Benchmark JSON file at path holds."""
    data = read_json(path, "Google Benchmark JSON")
    if not isinstance(data, dict) or not isinstance(data.get("benchmarks"), list):
        raise BenchJsonError(f"{path}: no 'benchmarks' list (not --benchmark_out JSON)")
    medians, iterations, units, labels = {}, {}, {}, {}
    for row in data["benchmarks"]:
        name = row.get("run_name", row.get("name"))
        if name is None or row.get("error_occurred"):
            continue
        units[name] = row.get("time_unit", "ns")
        if row.get("label"):
            labels[name] = row["label"]
        metrics = {k: v for k, v in row.items() if k not in NOT_METRICS and
                   isinstance(v, (int, float)) and not isinstance(v, bool)}
        if row.get("run_type") == "aggregate":
            if row.get("aggregate_name") == "median":
                medians[name] = metrics
        else:
            for k, v in metrics.items():
                iterations.setdefault(name, {}).setdefault(k, []).append(v)
    values = {}
    for name in set(medians) | set(iterations):
        if name in medians:
            values[name] = medians[name]
        else:
            values[name] = {k: statistics.median(vs) for k, vs in iterations[name].items()}
    return Round(values, units, labels, str(data.get("context", {}).get("date", "")))


def cell(vs):
    """A value over rounds: median (min-max, n)."""
    if not vs:
        return "-"
    return f"{statistics.median(vs):.4g} ({min(vs):.4g}-{max(vs):.4g}, n={len(vs)})"


def ab_table(out):
    """scripts/ab-bench.sh's summary of OUT: per benchmark and side the real_time over rounds."""
    values = {}  # (bench binary, benchmark name) -> side -> [value per round]
    units = {}
    lines = []
    for path in sorted(glob.glob(os.path.join(out, "*-r*.json"))):
        m = re.match(r"(old|new)-(.+)-r(\d+)\.json$", os.path.basename(path))
        if not m:
            continue
        side, binary = m.group(1), m.group(2)
        try:
            one = round_values(path)
        except BenchJsonError as e:
            lines.append(f"# {e}")
            continue
        for name, metrics in one.values.items():
            if "real_time" not in metrics:
                continue
            units[(binary, name)] = one.units[name]
            values.setdefault((binary, name), {}).setdefault(side, []).append(metrics["real_time"])
    lines.append("| binary | benchmark | unit | old: median (min-max over rounds) | new | new/old |")
    lines.append("| --- | --- | --- | --- | --- | --- |")
    for key in sorted(values):
        sides = values[key]
        old, new = sides.get("old", []), sides.get("new", [])
        ratio = "-"
        if old and new and statistics.median(old):
            ratio = f"{statistics.median(new) / statistics.median(old):.3f}"
        lines.append(f"| {key[0]} | {key[1]} | {units[key]} | {cell(old)} | {cell(new)} | {ratio} |")
    return lines


def main(argv):
    if len(argv) != 2 or not os.path.isdir(argv[1]):
        print("usage: bench_summary.py OUT (a folder of ab-bench.sh's old-/new-*-rN.json files)",
              file=sys.stderr)
        return 2
    print("\n".join(ab_table(argv[1])))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
