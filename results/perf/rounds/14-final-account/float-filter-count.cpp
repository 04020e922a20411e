// Counts how often the float walk of sat leaves a test undecided (CPU, a mesh in a cubic grid).
// Build against a tree with float-walk-f3.patch applied, e.g. from the repository root:
//   g++ -O2 -std=c++20 -ffp-contract=off -I. -o count float-filter-count.cpp
//   ./count assets/meshes/stanford-bunny-lowres.obj 512
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>
#include "strategies/voxelizer/sat_device.h"
using namespace dv;
int main(int argc, char** argv) {
  std::ifstream in(argv[1]);
  int res = atoi(argv[2]);
  std::vector<dvec3> v;
  std::vector<ivec3> f;
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream s(line);
    std::string k;
    s >> k;
    if (k == "v") {
      dvec3 p;
      s >> p.x >> p.y >> p.z;
      v.push_back(p);
    } else if (k == "f") {
      int a[3];
      for (int i = 0; i < 3; ++i) {
        std::string t;
        s >> t;
        a[i] = std::stoi(t) - 1;
      }
      f.push_back({a[0], a[1], a[2]});
    }
  }
  dvec3 lo(1e300), hi(-1e300);
  for (auto& p : v) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  double side = std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z}) * (1 + 1.0 / 10001);
  long cols = 0, colfb = 0, tests = 0, fb = 0, tris = 0;
  for (auto& t : f) {
    dvec3 p[3];
    for (int i = 0; i < 3; ++i) p[i] = (v[t[i]] - lo) / side * double(res);
    SatTriangle st;
    if (!sat_setup(p[0], p[1], p[2], ivec3(res), st) || st.degenerate) continue;
    ++tris;
    SatWalk c = sat_walk(st);
    SatFilter fl = sat_filter(c);
    for (int pw = c.range_w.first; pw <= c.range_w.last; ++pw)
      for (int pu = c.range_u.first; pu <= c.range_u.last; ++pu) {
        ++cols;
        bool enters = true, misses = false;
        float fu = pu - c.range_u.first, fw = pw - c.range_w.first;
        sat_edges_filter(fl.across, fl.err_across, fu, fw, enters, misses);
        if (!enters && !misses) ++colfb;
        if (misses || (!enters && !sat_column_enters_exact(c, pu, pw))) continue;
        for (int s = c.range_a.first; s <= c.range_a.last; ++s) {
          float fs = s - c.range_a.first;
          float base = fl.n_u * fu + fl.n_w * fw;
          float np = fl.n_a * fs + base;
          float lo2 = np + fl.d_min, hi2 = np + fl.d_max;
          bool i2 = (lo2 < -fl.err_plane) & (hi2 > fl.err_plane),
               o2 = (lo2 > fl.err_plane) | (hi2 < -fl.err_plane);
          sat_edges_filter(fl.along_u, fl.err_u, fw, fs, i2, o2);
          sat_edges_filter(fl.along_w, fl.err_w, fs, fu, i2, o2);
          if (o2) continue;
          ++tests;
          if (!i2) ++fb;
        }
      }
  }
  printf(
      "res %d tris %ld columns %ld column-fallbacks %ld (%.3f%%) plane-range voxel tests %ld "
      "fallbacks %ld (%.3f%%)\n",
      res, tris, cols, colfb, 100.0 * colfb / cols, tests, fb, 100.0 * fb / std::max(1L, tests));
}
