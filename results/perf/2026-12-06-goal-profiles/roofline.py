#!/usr/bin/env python3
# Roofline point of each profiled kernel from `ncu --page raw --csv` files: achieved FP64 FLOP/s
# (dadd + dmul + 2 dfma per cycle elapsed, times the SM clock), DRAM bytes/s, their ratio
# (arithmetic intensity) against the device's ridge point (peak FP64 over peak DRAM bandwidth).
import csv, sys
print("| kernel | ms | regs | achieved occupancy % | FP64 GFLOP/s (% of peak) | DRAM GB/s (% of peak) | FLOP/DRAM byte (ridge) | L1 hit % | warp cycles/instr | active threads/warp |")
print("| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |")
for f in sys.argv[1:]:
    rows = list(csv.reader(open(f)))
    h, u, v = rows[0], rows[1], rows[2]
    m = {k: (v[i], u[i]) for i, k in enumerate(h)}
    g = lambda k: float(m[k][0].replace(",", ""))
    clk = g("sm__cycles_elapsed.avg.per_second")  # units?
    cu = m["sm__cycles_elapsed.avg.per_second"][1]
    clk *= {"Ghz": 1e9, "GHz": 1e9, "Mhz": 1e6, "MHz": 1e6, "hz": 1, "Hz": 1}.get(cu, 1)
    flop_cycle = (g("smsp__sass_thread_inst_executed_op_dadd_pred_on.sum.per_cycle_elapsed")
                  + g("smsp__sass_thread_inst_executed_op_dmul_pred_on.sum.per_cycle_elapsed")
                  + 2 * g("smsp__sass_thread_inst_executed_op_dfma_pred_on.sum.per_cycle_elapsed"))
    peak_cycle = 2 * g("sm__sass_thread_inst_executed_op_dfma_pred_on.sum.peak_sustained")
    flops = flop_cycle * clk; peak = peak_cycle * clk
    bw = g("dram__bytes.sum.per_second") * 1e9
    dclk = g("dram__cycles_elapsed.avg.per_second") * 1e9
    bw_peak = g("dram__bytes.sum.peak_sustained") * 1e3 * dclk
    ms = g("gpu__time_duration.sum")
    if m["gpu__time_duration.sum"][1] == "us": ms /= 1000
    print(f"| {f.replace('-raw.csv','')} | {ms:.2f} | {int(g('launch__registers_per_thread'))} | {g('sm__warps_active.avg.pct_of_peak_sustained_active'):.1f} | "
          f"{flops/1e9:.0f} ({100*flops/peak:.1f} %) | {bw/1e9:.0f} ({100*bw/bw_peak:.1f} %) | {flops/bw if bw else float('inf'):.1f} ({peak/bw_peak:.1f}) | "
          f"{g('l1tex__t_sector_hit_rate.pct'):.1f} | {g('smsp__average_warp_latency_per_inst_issued.ratio') if 'smsp__average_warp_latency_per_inst_issued.ratio' in m else g('smsp__average_warps_issue_stalled_per_issue_active.ratio'):.2f} | {g('smsp__thread_inst_executed_per_inst_executed.ratio'):.1f} |")
