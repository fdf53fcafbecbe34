#!/usr/bin/env bash
# Instructions per sample inside hb_eval_angles (hb_sample_angles, hb_pdf_angles) under valgrind --tool=callgrind: a repeatable
# figure for changes too small to see through timing noise. Valgrind runs AVX2 but not AVX-512.
# usage: bench/instr.sh BENCH_BINARY
set -euo pipefail
bench=$1
batch=4096
printf '| configuration | ISA | instructions/sample |\n|---|---|---|\n'
for isa in scalar avx2; do
  for config in $("$bench" --list); do
    out=$(mktemp)
    HB_ISA=$isa valgrind --tool=callgrind --callgrind-out-file="$out" --collect-atstart=no \
      --toggle-collect=hb_eval_angles --toggle-collect=hb_sample_angles \
      --toggle-collect=hb_pdf_angles "$bench" --once "$config" >/dev/null 2>&1
    total=$(callgrind_annotate "$out" 2>/dev/null | awk '/PROGRAM TOTALS/ { gsub(",", "", $1); print $1 }')
    rm -f "$out"
    printf '| %s | %s | %d |\n' "$config" "$isa" $(( ${total:-0} / batch ))
  done
done
