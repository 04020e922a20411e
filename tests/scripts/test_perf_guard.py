#!/usr/bin/env python3
"""Tests of the performance regression guard on the CPU, with synthetic Google Benchmark JSON
files: scripts/perf_guard.py's comparison (baseline / now / ratio, exit 1 above the threshold
or for a benchmark not run, exit 2 on bad input or another GPU), its update of the baseline,
the values it reads (a round's median aggregate, else the median of its iterations; the median
over rounds; counters; unit conversion), and scripts/ab-bench.sh end to end in both modes with
stand-in benchmark programs that write such JSON."""
import json
import os
import shutil
import stat
import subprocess
import sys
import tempfile
import textwrap
import unittest

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
GUARD = os.path.join(ROOT, "scripts", "perf_guard.py")
AB_BENCH = os.path.join(ROOT, "scripts", "ab-bench.sh")
sys.path.insert(0, os.path.join(ROOT, "scripts"))
import bench_summary  # noqa: E402

GPU = "NVIDIA H200"


def row(name, real_time, unit="ms", label=GPU, aggregate=None, **counters):
    """One row of --benchmark_out JSON: an iteration, or an aggregate (median, mean, ...)."""
    r = {"name": name + (f"_{aggregate}" if aggregate else ""), "run_name": name,
         "run_type": "aggregate" if aggregate else "iteration", "repetitions": 3, "threads": 1,
         "iterations": 10, "real_time": real_time, "cpu_time": real_time / 2, "time_unit": unit,
         "label": label}
    if aggregate:
        r["aggregate_name"] = aggregate
    r.update(counters)
    return r


def write_json(path, rows, date="2026-12-06T04:00:00+00:00"):
    with open(path, "w") as f:
        json.dump({"context": {"date": date, "executable": path}, "benchmarks": rows}, f)


def baseline(path, threshold=0.05, gpu=GPU):
    """A baseline of three benchmarks: two real_time (ms), one counter (with_clear_ms)."""
    base = {"format": "deepvox-perf-baseline", "version": 1, "gpu": gpu, "commit": "abc1234",
            "date": "2026-12-04", "threshold": threshold, "command": "made by hand",
            "binaries": {"bench_alpha": {"args": ["--benchmark_repetitions=3"]},
                         "bench_beta": {"args": []}},
            "benchmarks": [
                {"binary": "bench_alpha", "name": "frame/none_cuda/manual_time",
                 "metric": "real_time", "unit": "ms", "median": 1.0},
                {"binary": "bench_alpha", "name": "generate/chunked:alloc=thesis/cuda/1024/manual_time",
                 "metric": "real_time", "unit": "ms", "median": 2.0},
                {"binary": "bench_beta", "name": "sat/bunny2_512/manual_time",
                 "metric": "with_clear_ms", "unit": "ms", "median": 0.1}]}
    with open(path, "w") as f:
        json.dump(base, f)
    return base


def guard(*args):
    return subprocess.run([sys.executable, GUARD, *args], capture_output=True, text=True)


class Fixture(unittest.TestCase):
    def setUp(self):
        self.dir = tempfile.mkdtemp(prefix="perf-guard-test-")
        self.base = os.path.join(self.dir, "baseline.json")
        baseline(self.base)
        self.run_dir = os.path.join(self.dir, "run")
        os.mkdir(self.run_dir)

    def tearDown(self):
        shutil.rmtree(self.dir)

    def write_round(self, r, frame=1.0, generate=2.0, sat=0.1, label=GPU, skip=()):
        """Round r of both binaries, as ab-bench.sh names them; medians as aggregates."""
        alpha = []
        if "frame" not in skip:
            alpha += [row("frame/none_cuda/manual_time", frame * 1.3, label=label),
                      row("frame/none_cuda/manual_time", frame, label=label, aggregate="median"),
                      row("frame/none_cuda/manual_time", frame * 0.9, label=label, aggregate="min")]
        alpha.append(row("generate/chunked:alloc=thesis/cuda/1024/manual_time", generate,
                         label=label, aggregate="median"))
        alpha.append(row("not/listed/manual_time", 50.0, label=label, aggregate="median"))
        write_json(os.path.join(self.run_dir, f"new-bench_alpha-r{r}.json"), alpha)
        beta = [row("sat/bunny2_512/manual_time", 0.5, label=label, aggregate="median",
                    with_clear_ms=sat)]
        write_json(os.path.join(self.run_dir, f"new-bench_beta-r{r}.json"), beta)

    def check(self, *extra):
        return guard("check", self.base, self.run_dir, *extra)


class Check(Fixture):
    def test_within_the_threshold_passes(self):
        for r in (1, 2, 3):
            self.write_round(r, frame=1.049, generate=1.9, sat=0.104)
        out = self.check()
        self.assertEqual(out.returncode, 0, out.stdout + out.stderr)
        self.assertIn("| bench_alpha | frame/none_cuda/manual_time | real_time | ms | 1 | "
                      "1.049 (1.049-1.049, n=3) | 1.049 | ok |", out.stdout)
        self.assertIn("| bench_beta | sat/bunny2_512/manual_time | with_clear_ms | ms | 0.1 | "
                      "0.104 (0.104-0.104, n=3) | 1.040 | ok |", out.stdout)
        self.assertIn("3 benchmarks, 0 more than 5 % slower, 0 not run: pass", out.stdout)
        self.assertNotIn("not/listed", out.stdout)

    def test_one_benchmark_over_the_threshold_fails(self):
        for r in (1, 2, 3):
            self.write_round(r, generate=2.102)
        out = self.check()
        self.assertEqual(out.returncode, 1, out.stdout + out.stderr)
        self.assertIn("| 2 | 2.102 (2.102-2.102, n=3) | 1.051 | SLOWER by 5.1 % |", out.stdout)
        self.assertIn("1 more than 5 % slower, 0 not run: FAIL", out.stdout)

    def test_the_median_over_rounds_decides_not_one_slow_round(self):
        self.write_round(1, frame=1.2)
        self.write_round(2, frame=1.0)
        self.write_round(3, frame=1.01)
        out = self.check()
        self.assertEqual(out.returncode, 0, out.stdout + out.stderr)
        self.assertIn("1.01 (1-1.2, n=3) | 1.010 | ok", out.stdout)

    def test_the_threshold_is_the_baselines(self):
        baseline(self.base, threshold=0.2)
        self.write_round(1, frame=1.15)
        out = self.check()
        self.assertEqual(out.returncode, 0, out.stdout + out.stderr)
        self.assertIn("fails above 1.20x", out.stdout)

    def test_a_benchmark_not_run_fails(self):
        self.write_round(1, skip=("frame",))
        out = self.check()
        self.assertEqual(out.returncode, 1, out.stdout + out.stderr)
        self.assertIn("| frame/none_cuda/manual_time | real_time | ms | 1 | - | - | NOT RUN |",
                      out.stdout)

    def test_a_run_with_an_error_row_counts_as_not_run(self):
        self.write_round(1)
        path = os.path.join(self.run_dir, "new-bench_beta-r1.json")
        failed = row("sat/bunny2_512/manual_time", 0.0, aggregate="median", with_clear_ms=0.0)
        failed.update(error_occurred=True, error_message="no CUDA device")
        write_json(path, [failed])
        out = self.check()
        self.assertEqual(out.returncode, 1, out.stdout + out.stderr)
        self.assertIn("| sat/bunny2_512/manual_time | with_clear_ms | ms | 0.1 | - | - | NOT RUN |",
                      out.stdout)

    def test_no_value_at_all_is_bad_input(self):
        write_json(os.path.join(self.run_dir, "new-bench_alpha-r1.json"),
                   [row("other/manual_time", 1.0, aggregate="median")])
        out = self.check()
        self.assertEqual(out.returncode, 2)
        self.assertIn("holds no value of any benchmark", out.stderr)

    def test_another_gpu_is_refused_unless_asked(self):
        self.write_round(1, label="NVIDIA H100 80GB HBM3")
        out = self.check()
        self.assertEqual(out.returncode, 2)
        self.assertIn("holds medians of a NVIDIA H200, this run is on a NVIDIA H100 80GB HBM3",
                      out.stderr)
        self.assertEqual(self.check("--any-gpu").returncode, 0)

    def test_old_side_files_of_an_ab_folder_are_left_out(self):
        self.write_round(1)
        write_json(os.path.join(self.run_dir, "old-bench_alpha-r1.json"),
                   [row("frame/none_cuda/manual_time", 9.0, aggregate="median")])
        out = self.check()
        self.assertEqual(out.returncode, 0, out.stdout + out.stderr)
        self.assertIn("1 (1-1, n=1) | 1.000 | ok", out.stdout)

    def test_times_in_another_unit_are_converted(self):
        write_json(os.path.join(self.run_dir, "bench_alpha.json"),
                   [row("frame/none_cuda/manual_time", 1100.0, unit="us", aggregate="median"),
                    row("generate/chunked:alloc=thesis/cuda/1024/manual_time", 2e6, unit="ns",
                        aggregate="median")])
        out = self.check()
        self.assertEqual(out.returncode, 1, out.stdout + out.stderr)
        self.assertIn("| 1 | 1.1 (1.1-1.1, n=1) | 1.100 | SLOWER by 10.0 % |", out.stdout)
        self.assertIn("| 2 | 2 (2-2, n=1) | 1.000 | ok |", out.stdout)

    def test_bad_baseline_and_files_exit_2_naming_the_file(self):
        with open(self.base, "w") as f:
            f.write("{not json")
        self.write_round(1)
        out = self.check()
        self.assertEqual(out.returncode, 2)
        self.assertIn(self.base, out.stderr)
        baseline(self.base)
        bad = os.path.join(self.run_dir, "new-bench_beta-r2.json")
        with open(bad, "w") as f:
            f.write("[]")
        out = self.check()
        self.assertEqual(out.returncode, 2)
        self.assertIn(bad + ": no 'benchmarks' list", out.stderr)
        out = guard("check", self.base, os.path.join(self.dir, "mystery.json"))
        self.assertEqual(out.returncode, 2)
        self.assertIn("no such file or folder", out.stderr)
        stray = os.path.join(self.dir, "bench_gamma.json")
        write_json(stray, [])
        out = guard("check", self.base, stray)
        self.assertEqual(out.returncode, 2)
        self.assertIn("its name holds none of the baseline's binaries", out.stderr)


class Update(Fixture):
    def test_update_rewrites_medians_gpu_commit_date_and_command(self):
        for r, frame in ((1, 1.3), (2, 1.1), (3, 1.2)):
            self.write_round(r, frame=frame, sat=0.09)
        out = guard("update", self.base, self.run_dir, "--commit", "0123abcd",
                    "--command", "ab-bench.sh --guard --update bin 3")
        self.assertEqual(out.returncode, 0, out.stdout + out.stderr)
        with open(self.base) as f:
            base = json.load(f)
        self.assertEqual((base["gpu"], base["commit"], base["date"], base["command"]),
                         (GPU, "0123abcd", "2026-12-06", "ab-bench.sh --guard --update bin 3"))
        frame = base["benchmarks"][0]
        self.assertEqual((frame["median"], frame["min"], frame["max"], frame["rounds"]),
                         (1.2, 1.1, 1.3, 3))
        self.assertEqual(base["benchmarks"][2]["median"], 0.09)
        self.assertEqual(base["threshold"], 0.05)
        self.assertEqual(self.check().returncode, 0)

    def test_update_refuses_a_missing_benchmark_no_commit_and_another_gpu(self):
        with open(self.base) as f:
            before = f.read()
        self.write_round(1, skip=("frame",))
        out = guard("update", self.base, self.run_dir, "--commit", "0123abcd")
        self.assertEqual(out.returncode, 2)
        self.assertIn("frame/none_cuda/manual_time (real_time) is not in the run", out.stderr)
        self.write_round(1)
        out = guard("update", self.base, self.run_dir, "--commit", "(no commit file)")
        self.assertEqual(out.returncode, 2)
        self.assertIn("is no commit hash", out.stderr)
        self.write_round(1, label="NVIDIA H100 80GB HBM3")
        out = guard("update", self.base, self.run_dir, "--commit", "0123abcd")
        self.assertEqual(out.returncode, 2)
        with open(self.base) as f:
            self.assertEqual(f.read(), before)
        out = guard("update", self.base, self.run_dir, "--commit", "0123abcd", "--any-gpu")
        self.assertEqual(out.returncode, 0, out.stderr)
        with open(self.base) as f:
            self.assertEqual(json.load(f)["gpu"], "NVIDIA H100 80GB HBM3")


class Plan(Fixture):
    def test_plan_names_exactly_the_listed_benchmarks_per_binary(self):
        out = guard("plan", self.base)
        self.assertEqual(out.returncode, 0, out.stderr)
        self.assertEqual(out.stdout.splitlines(), [
            "bench_alpha\t--benchmark_repetitions=3\t--benchmark_filter=^(frame/none_cuda/"
            "manual_time|generate/chunked:alloc=thesis/cuda/1024/manual_time)$",
            "bench_beta\t--benchmark_filter=^(sat/bunny2_512/manual_time)$"])

    def test_the_committed_baseline_is_valid_and_names_the_headline_benchmarks(self):
        path = os.path.join(ROOT, "results", "perf", "baseline.json")
        out = guard("plan", path)
        self.assertEqual(out.returncode, 0, out.stderr)
        with open(path) as f:
            base = json.load(f)
        names = {e["name"]: e for e in base["benchmarks"]}
        self.assertEqual(names["raster_render/fig56_none_cuda/manual_time"]["median"], 0.867893)
        self.assertEqual(names["sat/bunny2_512/manual_time"]["metric"], "with_clear_ms")
        for storage in ("beer", "texture3d", "compact", "blocked", "moments", "avsm", "chunked",
                        "occupancy", "fourier"):
            for kind in ("generate", "render_bilinear"):
                self.assertIn(f"{kind}/{storage}/cuda/1024/manual_time", names)
        self.assertTrue(all(isinstance(e["median"], float) for e in base["benchmarks"]))
        self.assertTrue(base["gpu"] and base["commit"] and base["date"] and base["command"])


class Summary(unittest.TestCase):
    def test_a_round_without_aggregates_is_the_median_of_its_iterations(self):
        with tempfile.TemporaryDirectory() as d:
            path = os.path.join(d, "r.json")
            failed = row("a/manual_time", 100.0)
            failed["error_occurred"] = True
            write_json(path, [row("a/manual_time", 3.0, fragment_ms=1.0),
                              row("a/manual_time", 1.0, fragment_ms=3.0),
                              row("a/manual_time", 2.0, fragment_ms=2.0), failed])
            one = bench_summary.round_values(path)
            self.assertEqual(one.values["a/manual_time"]["real_time"], 2.0)
            self.assertEqual(one.values["a/manual_time"]["fragment_ms"], 2.0)
            self.assertNotIn("iterations", one.values["a/manual_time"])
            self.assertEqual(one.labels["a/manual_time"], GPU)

    def test_the_ab_table_compares_the_two_sides(self):
        with tempfile.TemporaryDirectory() as d:
            for r, old, new in ((1, 2.0, 1.0), (2, 2.2, 1.1), (3, 2.1, 0.9)):
                write_json(os.path.join(d, f"old-bench_x-r{r}.json"),
                           [row("f/manual_time", old, aggregate="median")])
                write_json(os.path.join(d, f"new-bench_x-r{r}.json"),
                           [row("f/manual_time", new, aggregate="median")])
            lines = bench_summary.ab_table(d)
            self.assertEqual(lines[-1], "| bench_x | f/manual_time | ms | 2.1 (2-2.2, n=3) | "
                                        "1 (0.9-1.1, n=3) | 0.476 |")


# A stand-in benchmark program: writes --benchmark_out JSON for the benchmarks of its list that
# match --benchmark_filter, each at its time times $FAKE_SCALE, labelled with $FAKE_GPU.
FAKE_BENCH = textwrap.dedent("""\
    #!/usr/bin/env python3
    import json, os, re, sys
    TIMES = {times}
    args = dict(a[2:].split("=", 1) for a in sys.argv[1:] if "=" in a)
    scale = float(os.environ.get("FAKE_SCALE", "1"))
    rows = []
    for name, (metric, value) in TIMES.items():
        if re.search(args["benchmark_filter"], name):
            r = {{"name": name + "_median", "run_name": name, "run_type": "aggregate",
                  "aggregate_name": "median", "real_time": 1.0, "time_unit": "ms",
                  "label": os.environ.get("FAKE_GPU", "NVIDIA H200")}}
            r[metric] = value * scale
            rows.append(r)
    with open(args["benchmark_out"], "w") as f:
        json.dump({{"context": {{"date": "2026-12-06T05:00:00+00:00"}}, "benchmarks": rows,
                   "argv": sys.argv[1:]}}, f)
    print("ran", len(rows))
""")


class AbBench(Fixture):
    def setUp(self):
        super().setUp()
        self.bin = os.path.join(self.dir, "bin")
        os.mkdir(self.bin)
        self.fake("bench_alpha", {"frame/none_cuda/manual_time": ("real_time", 1.0),
                                  "generate/chunked:alloc=thesis/cuda/1024/manual_time":
                                      ("real_time", 2.0),
                                  "frame/none_cuda_extra/manual_time": ("real_time", 9.0)})
        self.fake("bench_beta", {"sat/bunny2_512/manual_time": ("with_clear_ms", 0.1)})
        with open(os.path.join(self.bin, "commit"), "w") as f:
            f.write("fedcba9\n")

    def fake(self, name, times):
        path = os.path.join(self.bin, name)
        with open(path, "w") as f:
            f.write(FAKE_BENCH.format(times=repr(times)))
        os.chmod(path, os.stat(path).st_mode | stat.S_IXUSR)

    def ab(self, *args, scale="1"):
        env = dict(os.environ, FAKE_SCALE=scale, DEEPVOX_SOURCE_DIR=self.dir)
        return subprocess.run(["bash", AB_BENCH, *args], capture_output=True, text=True,
                              env=env, cwd=self.dir)

    def test_guard_passes_a_build_as_fast_as_the_baseline(self):
        out_dir = os.path.join(self.dir, "out")
        out = self.ab("--guard", "--baseline", self.base, self.bin, "2", out_dir, scale="1.03")
        self.assertEqual(out.returncode, 0, out.stdout + out.stderr)
        self.assertIn("3 benchmarks, 0 more than 5 % slower, 0 not run: pass", out.stdout)
        self.assertEqual(sorted(f for f in os.listdir(out_dir) if f.endswith(".json")),
                         ["new-bench_alpha-r1.json", "new-bench_alpha-r2.json",
                          "new-bench_beta-r1.json", "new-bench_beta-r2.json"])
        with open(os.path.join(out_dir, "new-bench_alpha-r1.json")) as f:
            ran = json.load(f)
        self.assertEqual(len(ran["benchmarks"]), 2)  # the exact filter left out the third
        self.assertIn("--benchmark_repetitions=3", ran["argv"])
        with open(os.path.join(out_dir, "meta.txt")) as f:
            meta = f.read()
        self.assertIn("new: " + self.bin + " commit fedcba9", meta)
        self.assertTrue(os.path.exists(os.path.join(out_dir, "guard.txt")))

    def test_guard_fails_a_build_more_than_5_percent_slower(self):
        out = self.ab("--guard", "--baseline", self.base, self.bin, "1",
                      os.path.join(self.dir, "out"), scale="1.06")
        self.assertEqual(out.returncode, 1, out.stdout + out.stderr)
        self.assertIn("3 more than 5 % slower", out.stdout)

    def test_guard_update_rewrites_the_baseline_from_the_run(self):
        out = self.ab("--guard", "--update", "--baseline", self.base, self.bin, "1",
                      os.path.join(self.dir, "out"), scale="1.5")
        self.assertEqual(out.returncode, 0, out.stdout + out.stderr)
        self.assertIn("SLOWER by 50.0 %", out.stdout)
        with open(self.base) as f:
            base = json.load(f)
        self.assertEqual([e["median"] for e in base["benchmarks"]], [1.5, 3.0, 0.15])
        self.assertEqual((base["commit"], base["date"]), ("fedcba9", "2026-12-06"))
        self.assertIn("--guard --update", base["command"])

    def test_guard_without_a_listed_binary_is_a_usage_error(self):
        os.remove(os.path.join(self.bin, "bench_beta"))
        out = self.ab("--guard", "--baseline", self.base, self.bin, "1",
                      os.path.join(self.dir, "out"))
        self.assertEqual(out.returncode, 2)
        self.assertIn("lists bench_beta, which " + self.bin + " does not hold", out.stderr)

    def test_ab_mode_still_compares_two_builds(self):
        old = os.path.join(self.dir, "old")
        shutil.copytree(self.bin, old)
        out_dir = os.path.join(self.dir, "out")
        out = self.ab(old, self.bin, "frame/none_cuda/", "2", out_dir)
        self.assertEqual(out.returncode, 0, out.stdout + out.stderr)
        with open(os.path.join(out_dir, "summary.txt")) as f:
            summary = f.read()
        self.assertIn("| bench_alpha | frame/none_cuda/manual_time | ms | 1 (1-1, n=2) | "
                      "1 (1-1, n=2) | 1.000 |", summary)
        self.assertNotIn("guard", os.listdir(out_dir))


if __name__ == "__main__":
    unittest.main()
