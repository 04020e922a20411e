# Per-warp timeline of one fragment pass trace (records: start, end ns; samples, crossings, sm).
import struct, sys
def report(path, width=720):
    data = open(path, 'rb').read()
    n = len(data) // 32
    rec = [struct.unpack_from('<QQIIII', data, 32 * i) for i in range(n)]
    t0 = min(r[0] for r in rec if r[0]); t1 = max(r[1] for r in rec)
    warps = []
    for w in range(n // 32):
        rs = rec[32 * w:32 * w + 32]
        s = min(r[0] for r in rs) - t0; e = max(r[1] for r in rs) - t0
        warps.append((s, e, e - s, max(r[2] for r in rs), sum(r[2] for r in rs), max(r[3] for r in rs), rs[0][4], w))
    tot = sum(w[4] for w in warps)
    durs = sorted(w[2] for w in warps)
    pct = lambda p: durs[min(len(durs) - 1, int(p * len(durs)))] / 1e3
    print(f'{path}: span {(t1 - t0) / 1e3:.1f} us, warps {len(warps)}, samples {tot}')
    print(f'  warp us: p50 {pct(.5):.1f} p90 {pct(.9):.1f} p99 {pct(.99):.1f} max {durs[-1] / 1e3:.1f}; busy-sum {sum(durs) / 1e3:.0f} us')
    print(f'  warp-sum / (span * 132 SMs) = {sum(durs) / ((t1 - t0) * 132):.2f} warps per SM on average')
    top = sorted(warps, key=lambda w: -w[2])[:12]
    tiles_x = (width + 7) // 8
    for w in top:
        tile = w[7] // 2
        print(f'  warp {w[7]} tile ({tile % tiles_x},{tile // tiles_x}) sm {w[6]} start {w[0] / 1e3:.1f} end {w[1] / 1e3:.1f} dur {w[2] / 1e3:.1f} us; samples max {w[3]} sum {w[4]} crossings max {w[5]}')
    B = 25; span = t1 - t0
    line = []
    for b in range(B):
        a = span * b / B; c = span * (b + 1) / B
        active = sum(min(w[1], c) - max(w[0], a) for w in warps if w[1] > a and w[0] < c) / (c - a)
        line.append(f'{active:.0f}')
    print('  active warps over 25 time bins:', ' '.join(line))
    lat = sorted(w[2] / max(w[3], 1) for w in warps if w[3] > 50)
    if lat: print(f'  ns per sample step along the slowest lane (warps with >50 samples): p50 {lat[len(lat)//2]:.1f} p10 {lat[len(lat)//10]:.1f} p90 {lat[9*len(lat)//10]:.1f}')
for p in sys.argv[1:]: report(p)
