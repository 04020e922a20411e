#!/usr/bin/env bash
# probe_compare.sh OLD NEW BACKEND OUTDIR: the exact oracle's probe answers (--shadows reference) of two
# builds at .gpu/points/*.csv for every committed scene, then the max |difference| per scene.
set -u
old=$1 new=$2 backend=$3 out=$4; mkdir -p $out
for p in .gpu/points/*.csv; do
  n=$(basename $p .csv); s=$(echo $n | sed 's|^experiments_scenes_||; s|_|/|'); s=experiments/scenes/$s.json
  [ -f $s ] || s=experiments/scenes/$(echo $n | sed 's|^experiments_scenes_||').json
  for side in old new; do b=$old; [ $side = new ] && b=$new
    timeout 120 $b probe $PWD/$s --points $p --shadows reference --backend $backend --out $out/$side-$n.csv > $out/$side-$n.log 2>&1 || echo "$side $n rc=$?"
  done
done
python3 - "$out" <<'PY'
import csv, glob, os, sys
out = sys.argv[1]; worst = 0.0; rows = 0; n = 0
for f in sorted(glob.glob(os.path.join(out, "new-*.csv"))):
    g = f.replace("/new-", "/old-")
    if not os.path.exists(g): print("missing", g); continue
    a = list(csv.reader(open(f))); b = list(csv.reader(open(g)))
    if a[0] != b[0] or len(a) != len(b): print("shape differs", f); continue
    d = max((abs(float(x) - float(y)) for ra, rb in zip(a[1:], b[1:]) for x, y in zip(ra[3:], rb[3:])), default=0.0)
    worst = max(worst, d); rows += len(a) - 1; n += 1
    print(f"{os.path.basename(f)[4:-4]} points={len(a)-1} values={(len(a)-1)*(len(a[0])-3)} max_abs_diff={d:.3g}")
print(f"SUMMARY scenes={n} points={rows} max_abs_diff={worst:.3g}")
PY
