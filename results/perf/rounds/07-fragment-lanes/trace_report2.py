# Per-warp timeline of one fragment pass trace of the lanes build (records: start, end ns;
# samples, crossings, sm, lanes of the pixel's group; threads that returned at once are zero).
import struct, sys
def report(path):
    data = open(path, 'rb').read()
    n = len(data) // 32
    rec = [struct.unpack_from('<QQIIII', data, 32 * i) for i in range(n)]
    live = [r for r in rec if r[0]]
    t0 = min(r[0] for r in live); t1 = max(r[1] for r in live)
    warps = []
    for w in range(n // 32):
        rs = [r for r in rec[32 * w:32 * w + 32] if r[0]]
        if not rs: continue
        s = min(r[0] for r in rs) - t0; e = max(r[1] for r in rs) - t0
        warps.append((s, e, e - s, max(r[2] for r in rs), sum(r[2] for r in rs), rs[0][5], w))
    durs = sorted(w[2] for w in warps)
    pct = lambda p: durs[min(len(durs) - 1, int(p * len(durs)))] / 1e3
    print(f'{path}: span {(t1 - t0) / 1e3:.1f} us, live warps {len(warps)} ({sum(1 for w in warps if w[5] > 1)} with lanes), samples (sum over lanes) {sum(w[4] for w in warps)}')
    print(f'  warp us: p50 {pct(.5):.1f} p90 {pct(.9):.1f} p99 {pct(.99):.1f} max {durs[-1] / 1e3:.1f}')
    print(f'  warp-sum / (span * 132 SMs) = {sum(durs) / ((t1 - t0) * 132):.2f} warps per SM on average')
    for w in sorted(warps, key=lambda w: -w[2])[:6]:
        print(f'  warp {w[6]} lanes {w[5]} start {w[0] / 1e3:.1f} end {w[1] / 1e3:.1f} dur {w[2] / 1e3:.1f} us; pixel samples max {w[3]}')
    B = 25; span = t1 - t0; line = []
    for b in range(B):
        a = span * b / B; c = span * (b + 1) / B
        line.append('%.0f' % (sum(min(w[1], c) - max(w[0], a) for w in warps if w[1] > a and w[0] < c) / (c - a)))
    print('  active warps over 25 time bins:', ' '.join(line))
for p in sys.argv[1:]: report(p)
