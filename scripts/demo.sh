#!/usr/bin/env bash
# The main job: builds deepvox if needed, renders scenes/demo.json with exact (reference)
# shadows on the default backend (CUDA when a GPU is present, else CPU) and probes the oracle
# at a few points. Results: out/demo.png (look at it), out/demo-stats.json, out/demo-probe.csv.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh --target deepvox
mkdir -p out
./build/bin/deepvox render scenes/demo.json --shadows reference --out out/demo.png --stats out/demo-stats.json
./build/bin/deepvox probe scenes/demo.json --points scenes/demo-points.csv --out out/demo-probe.csv
echo "deepvox: wrote out/demo.png, out/demo-stats.json and out/demo-probe.csv"
