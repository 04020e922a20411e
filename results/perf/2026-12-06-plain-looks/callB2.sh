#!/usr/bin/env bash
# Device call B2/C (session 7): one session of issue 55's replicate protocol for the accuracy suite
# (5 process runs, items permuted per run, ABBA claim pairs, A/A copies) on this device lease.
# Arg 1: the session's name (s1, s2). The folder comes back as one tar per run plus the top folder.
set -uo pipefail
G=$PWD/.gpu7; mkdir -p $G/x && [ -x $G/x/deepvox-lean ] || { xz -T4 -dc $G/bin/deepvox-lean.xz > $G/x/deepvox-lean; chmod +x $G/x/deepvox-lean; }
export DEEPVOX_SOURCE_DIR=$PWD DEEPVOX_ASSETS=$PWD/experiments/assets
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm,persistence_mode --format=csv,noheader
O=/tmp/suites-$1; mkdir -p $O
timeout ${2:-560} $G/x/deepvox-lean suite accuracy --backend cuda --protocol replicate --out $O > $O/suite.log 2>&1; echo "suite rc=$? t=$SECONDS"; tail -4 $O/suite.log
D=$(ls -d $O/accuracy/*/ | head -1); echo "folder $D"; du -sh $D
tar -cJf /tmp/accuracy-$1.tar.xz -C $O . ; split -b 15m -d /tmp/accuracy-$1.tar.xz $OUT/accuracy-$1.tar.xz.part; ls -la $OUT; echo all-done t=$SECONDS
