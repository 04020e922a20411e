#!/usr/bin/env python3
# Writes DIR/<name>.csv: 400 seeded uniform points inside each scene's bounds (from `deepvox info`),
# for comparing the exact oracle's probe answers of two builds.
import json, random, subprocess, sys, pathlib, re
binary, outdir, scenes = sys.argv[1], pathlib.Path(sys.argv[2]), sys.argv[3:]
outdir.mkdir(parents=True, exist_ok=True)
for s in scenes:
    info = subprocess.run([binary, "info", s], capture_output=True, text=True).stdout
    m = re.search(r"^bounds\s+(\{.*\})$", info, re.M)
    if not m:
        print("no bounds:", s); continue
    b = json.loads(m.group(1)); lo, hi = b["min"], b["max"]
    rng = random.Random(s)
    name = s.replace("/", "_").replace(".json", "")
    with open(outdir / f"{name}.csv", "w") as f:
        f.write("x,y,z\n")
        for _ in range(400):
            f.write(",".join(f"{rng.uniform(lo[k], hi[k]):.9g}" for k in range(3)) + "\n")
    print(name)
