#!/usr/bin/env python3
"""Summary of a soak (scripts/soak.sh): per kind (render frames, suite experiments) and quantity
(host RSS, device memory), whether the memory stays flat within 1 % after the warm-up (the first
tenth of the run, at least the first sample past step 1): every sample after it within 1 % of
the first sample after it. Writes OUT/summary.md and OUT/soak.svg (one panel per kind, plain
SVG: no plotting library needed). Exit 1 when a curve is not flat.
Usage: soak_summary.py SOAK.csv OUT [--title TEXT]"""
import argparse
import csv
import os
import sys

TOLERANCE = 0.01


def read(path):
    series = {}
    with open(path) as f:
        for row in csv.DictReader(f):
            s = series.setdefault(row["kind"], {"step": [], "rss_mib": [], "device_mib": []})
            s["step"].append(int(row["step"]))
            s["rss_mib"].append(int(row["rss_kib"]) / 1024.0)
            s["device_mib"].append(float(row["device_mib"]) if row["device_mib"] else None)
    return series


def verdict(steps, values):
    """(flat, base, worst relative change, samples after warm-up) of one curve."""
    last = max(steps)
    warm = max(last * 0.1, min(s for s in steps if s > 1) if any(s > 1 for s in steps) else 1)
    after = [(s, v) for s, v in zip(steps, values) if s >= warm and v is not None]
    if len(after) < 2:
        return None
    base = after[0][1]
    worst = max(abs(v - base) / base for _, v in after) if base else 0.0
    return worst <= TOLERANCE, base, worst, len(after), after[0][0]


def svg(series, title):
    width, height, pad = 720, 260, 50
    panels = []
    for k, (kind, s) in enumerate(sorted(series.items())):
        x0 = k * width
        curves = [("host RSS", s["rss_mib"], "#1f77b4")]
        if any(v is not None for v in s["device_mib"]):
            curves.append(("device", s["device_mib"], "#d62728"))
        values = [v for _, vs, _ in curves for v in vs if v is not None]
        lo, hi = min(values) * 0.98, max(values) * 1.02
        sx = lambda step: x0 + pad + (width - 2 * pad) * step / max(max(s["step"]), 1)
        sy = lambda v: height - pad - (height - 2 * pad) * (v - lo) / max(hi - lo, 1e-9)
        parts = [f'<text x="{x0 + pad}" y="20" font-size="13">{kind}: MiB against '
                 f'{"frames" if kind == "render" else "experiments"}</text>',
                 f'<line x1="{x0 + pad}" y1="{height - pad}" x2="{x0 + width - pad}" '
                 f'y2="{height - pad}" stroke="black"/>',
                 f'<line x1="{x0 + pad}" y1="{pad}" x2="{x0 + pad}" y2="{height - pad}" '
                 f'stroke="black"/>',
                 f'<text x="{x0 + 4}" y="{sy(hi / 1.02) + 4:.1f}" font-size="10">{hi / 1.02:.1f}'
                 f'</text>',
                 f'<text x="{x0 + 4}" y="{sy(lo / 0.98) + 4:.1f}" font-size="10">{lo / 0.98:.1f}'
                 f'</text>',
                 f'<text x="{x0 + width - pad - 30}" y="{height - pad + 15}" font-size="10">'
                 f'{max(s["step"])}</text>']
        for i, (name, vs, color) in enumerate(curves):
            points = " ".join(f"{sx(st):.1f},{sy(v):.1f}" for st, v in zip(s["step"], vs)
                              if v is not None)
            parts.append(f'<polyline fill="none" stroke="{color}" points="{points}"/>')
            parts.append(f'<text x="{x0 + width - pad - 90}" y="{pad + 14 * i}" font-size="11" '
                         f'fill="{color}">{name}</text>')
        panels.append("\n".join(parts))
    total = width * max(len(panels), 1)
    return (f'<svg xmlns="http://www.w3.org/2000/svg" width="{total}" height="{height + 20}">\n'
            f'<text x="{pad}" y="{height + 12}" font-size="12">{title}</text>\n'
            + "\n".join(panels) + "\n</svg>\n")


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("csv")
    parser.add_argument("out")
    parser.add_argument("--title", default="deepvox soak")
    args = parser.parse_args()
    series = read(args.csv)
    lines = [f"# {args.title}", "",
             f"Flat: every sample after the warm-up within {TOLERANCE:.0%} of the first sample "
             "after it (scripts/soak_summary.py).", "",
             "| kind | quantity | samples | warm-up ends at | base MiB | min MiB | max MiB | "
             "largest change | flat |",
             "| --- | --- | --- | --- | --- | --- | --- | --- | --- |"]
    all_flat = True
    for kind, s in sorted(series.items()):
        for quantity, label in (("rss_mib", "host RSS"), ("device_mib", "device memory")):
            values = s[quantity]
            if all(v is None for v in values):
                continue
            v = verdict(s["step"], values)
            if v is None:
                lines.append(f"| {kind} | {label} | {len(values)} | - | - | - | - | - | "
                             "too few samples |")
                all_flat = False
                continue
            flat, base, worst, count, warm = v
            after = [x for st, x in zip(s["step"], values) if st >= warm and x is not None]
            all_flat &= flat
            lines.append(f"| {kind} | {label} | {count} of {len(values)} | step {warm} | "
                         f"{base:.1f} | {min(after):.1f} | {max(after):.1f} | {worst:.2%} | "
                         f"{'yes' if flat else 'NO'} |")
    lines += ["", f"All flat within {TOLERANCE:.0%}: {'yes' if all_flat else 'NO'}.", ""]
    with open(os.path.join(args.out, "summary.md"), "w") as f:
        f.write("\n".join(lines))
    with open(os.path.join(args.out, "soak.svg"), "w") as f:
        f.write(svg(series, args.title))
    print("\n".join(lines))
    return 0 if all_flat else 1


if __name__ == "__main__":
    sys.exit(main())
