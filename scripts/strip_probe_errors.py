#!/usr/bin/env python3
"""Drops "probe_errors" from every samples/<item>.json under the folders given, keeping the
timings: a suite run's samples hold every probe point's signed error per class (57 MB a run of
the accuracy suite), which only findings on probe-error columns read. Committed protocol runs
keep their samples without them (results/suites/README.md says which), so that the A/A controls
and the timing intervals rebuild from the folder; a finding on a probe-error column then reads
"not comparable (no probe samples ...)". Prints the bytes before and after.
Usage: scripts/strip_probe_errors.py FOLDER..."""
import json
import pathlib
import sys


def strip(folder):
    before = after = 0
    for path in sorted(pathlib.Path(folder).rglob("samples/*.json")):
        text = path.read_text()
        before += len(text)
        samples = json.loads(text)
        if "probe_errors" in samples:
            del samples["probe_errors"]
            text = json.dumps(samples) + "\n"
            path.write_text(text)
        after += len(text)
    return before, after


def main(folders):
    if not folders:
        print(__doc__.strip().splitlines()[-1], file=sys.stderr)
        return 2
    for folder in folders:
        before, after = strip(folder)
        print("%s: samples %d -> %d bytes" % (folder, before, after))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
