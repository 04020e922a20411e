#!/usr/bin/env python3
"""Tests of experiments/harness/plot_suite.py's strategy families on the CPU: the families,
colours and markers come from a catalog in the form of `deepvox list --json` (here a synthetic
one with a storage the script has never heard of), dsm is plotted as its storage (the registered
default when the row leaves it out), and a strategy the catalog lacks is "other"; the headline
shades the region the exact oracle dominates; a lossy item (a loss count above 0) is marked.
Skipped when the interpreter has no matplotlib (the script needs it to load)."""
import importlib.util
import json
import os
import subprocess
import sys
import tempfile
import unittest

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
SCRIPT = os.path.join(ROOT, "experiments", "harness", "plot_suite.py")


def entry(registry, name, family, colour, marker="", member_param="", params=()):
    return {"registry": registry, "name": name, "description": "", "family": family,
            "colour": colour, "marker": marker, "member_param": member_param, "size_key": "",
            "sizes": [], "not_advised": "", "params": list(params)}


CATALOG = {"strategies": [
    entry("shadow method", "dsm", "DSM", "#ff7f0e", "o", "storage",
          [{"key": "storage", "type": "name", "default": "compact", "range": "",
            "description": ""},
           {"key": "storage", "type": "nested", "default": "", "range": "", "description": ""}]),
    entry("shadow method", "reference", "exact oracle", "black", "*"),
    entry("storage", "compact", "DSM, node lists", "#ff7f0e", "o"),
    entry("storage", "brand-new", "DSM, new records", "#123456", "h"),
]}


def load_plot_suite():
    """plot_suite.py as a module (it is a script, not on the path)."""
    spec = importlib.util.spec_from_file_location("plot_suite", SCRIPT)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def rows(strategy, params=""):
    return [{"strategy": strategy, "params": params}]


@unittest.skipIf(importlib.util.find_spec("matplotlib") is None, "no matplotlib here")
class PlotFamilies(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.plot = load_plot_suite()
        cls.tmp = tempfile.TemporaryDirectory()
        path = os.path.join(cls.tmp.name, "catalog.json")
        with open(path, "w") as f:
            json.dump(CATALOG, f)
        cls.assertTrue(cls, cls.plot.load_catalog(["plot_suite.py", "DIR", "--catalog", path]))

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def test_dsm_is_plotted_as_its_storage(self):
        self.assertEqual(self.plot.family(rows("dsm", "res=64 storage=brand-new")),
                         ("DSM, new records", "#123456", "brand-new"))
        self.assertEqual(self.plot.family(rows("dsm", "res=64")),
                         ("DSM, node lists", "#ff7f0e", "compact"))
        self.assertEqual(self.plot.Markers()("brand-new"), "h")

    def test_unknown_strategies_are_other(self):
        self.assertEqual(self.plot.family(rows("gone")), ("other", "#8c564b", "gone"))
        self.assertEqual(self.plot.family(rows("dsm", "storage=gone"))[0], "other")

    def test_the_families_keep_the_catalog_order(self):
        self.assertEqual([f for f, _ in self.plot.family_order()],
                         ["DSM", "exact oracle", "DSM, node lists", "DSM, new records", "other"])

    def test_without_a_catalog_the_script_says_so(self):
        env = dict(os.environ, PATH="/nonexistent", DEEPVOX="/nonexistent/deepvox")
        out = subprocess.run([sys.executable, SCRIPT, self.tmp.name, "--deepvox", "/nonexistent"],
                             capture_output=True, text=True, env=env)
        self.assertEqual(out.returncode, 4, out.stderr)
        self.assertIn("--catalog", out.stderr)



@unittest.skipIf(importlib.util.find_spec("matplotlib") is None, "no matplotlib here")
class OracleDominatedRegion(unittest.TestCase):
    def test_the_region_beyond_the_oracles_time_is_shaded(self):
        plot = load_plot_suite()
        fig, ax = plot.plt.subplots()
        ax.set_xscale("log")
        ax.set_xlim(0.5, 20.0)
        oracle = {"a.json": (4.2, 4.0, 4.4), "far.json": (50.0, 50.0, 50.0)}
        self.assertTrue(plot.shade_dominated(ax, oracle, "a.json"))
        self.assertEqual(len(ax.patches), 1)
        xs = [x for x, _ in ax.patches[0].get_xy()]
        self.assertAlmostEqual(min(xs), 4.2)
        self.assertAlmostEqual(max(xs), 20.0)
        self.assertEqual(ax.get_xlim(), (0.5, 20.0))
        self.assertFalse(plot.shade_dominated(ax, oracle, "far.json"), "beyond the axis")
        self.assertFalse(plot.shade_dominated(ax, oracle, "none.json"), "no oracle item")
        self.assertEqual(len(ax.patches), 1)
        plot.plt.close(fig)


@unittest.skipIf(importlib.util.find_spec("matplotlib") is None, "no matplotlib here")
class LossyMark(unittest.TestCase):
    def test_a_lossy_item_is_marked_and_a_whole_one_is_not(self):
        plot = load_plot_suite()

        def item(metric, value):
            return [{"strategy": "dsm", "params": "res=512 storage=avsm storage.nodes=4",
                     "metric": metric, "stat": "value", "value": str(value)}]

        lossy = item("stats.storage.overflowed_texels", 11380)
        whole = item("stats.storage.overflowed_texels", 0)
        dropped = item("generate.dropped_tiles", 2)
        self.assertTrue(plot.is_lossy(lossy))
        self.assertTrue(plot.is_lossy(dropped))
        self.assertFalse(plot.is_lossy(whole))
        self.assertFalse(plot.is_lossy(item("probe_error_all", 0.5)))
        self.assertEqual(plot.label(lossy), "dsm res=512 storage=avsm storage.nodes=4 \u2020")
        self.assertEqual(plot.label(whole), "dsm res=512 storage=avsm storage.nodes=4")
        self.assertEqual(plot.short_label(lossy, {"dsm": {"res": "512"}}), "avsm nodes=4 \u2020")
        self.assertEqual(plot.short_label(whole, {"dsm": {"res": "512"}}), "avsm nodes=4")


if __name__ == "__main__":
    unittest.main()
