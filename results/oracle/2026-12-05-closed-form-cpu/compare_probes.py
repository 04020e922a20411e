#!/usr/bin/env python3
"""Probe points around the CT, the smoke and the floor of the Knecht-like scenes (seeded), and
the comparison of two `deepvox probe` outputs: per scene the number of values, the largest
|T_a - T_b| and how many differ by more than 1e-9 (luminance and colour columns alike).

  compare_probes.py points > pts.csv
  compare_probes.py compare A.csv B.csv
"""
import csv
import random
import sys


def points():
    random.seed(5)
    print("x,y,z")
    boxes = [((-1.1, 0.55, -0.3), 0.6), ((1.0, 0.75, -0.6), 0.8), ((0.0, 0.3, 0.0), 3.0)]
    for i in range(3000):
        (cx, cy, cz), h = boxes[i % 3]
        print("%.6f,%.6f,%.6f" % (cx + random.uniform(-h, h),
                                  max(0.001, cy + random.uniform(-h, h)),
                                  cz + random.uniform(-h, h)))


def compare(a_path, b_path):
    a = list(csv.reader(open(a_path)))
    b = list(csv.reader(open(b_path)))
    largest, over, count = 0.0, 0, 0
    for ra, rb in zip(a[1:], b[1:]):
        for j in range(3, len(a[0])):
            d = abs(float(ra[j]) - float(rb[j]))
            count += 1
            largest = max(largest, d)
            over += d > 1e-9
    print("values %d, max |a - b| %.3g, over 1e-9: %d" % (count, largest, over))


if __name__ == "__main__":
    points() if sys.argv[1] == "points" else compare(sys.argv[2], sys.argv[3])
