#!/usr/bin/env bash
# Instructions per sample inside the library's entry points under valgrind --tool=callgrind: a
# repeatable figure for changes too small to see through timing noise, the same on every host
# for one binary. Valgrind runs AVX2 but not AVX-512.
# usage: bench/instr.sh BENCH_BINARY              every configuration, scalar and AVX2
#        bench/instr.sh BENCH_BINARY BUDGETS      the budgets' rows (configuration isa instructions),
#                                                 exit 1 if any is over
set -euo pipefail
bench=$1
budgets=${2:-}
batch=4096
entry_points="hb_eval_angles hb_sample_angles hb_pdf_angles hb_eval_near hb_sample_near hb_pdf_near
              hb_eval_pdf_angles hb_eval_pdf_vectors hb_eval_angles_absorption hb_eval_near_spectral hb_eval_angles_spectral"

# instructions per sample of one batch of configuration $1 on ISA $2
count() {
  local out toggles=() total
  out=$(mktemp)
  # a dual row counts hb_dual_eval alone: its table's build evaluates f through the other entry points
  case "$1" in */dual/*) toggles=(--toggle-collect=hb_dual_eval) ;; *) for f in $entry_points; do toggles+=(--toggle-collect="$f"); done ;; esac
  HB_ISA=$2 valgrind --tool=callgrind --callgrind-out-file="$out" --collect-atstart=no "${toggles[@]}" \
    "$bench" --once "$1" >/dev/null 2>&1
  total=$(callgrind_annotate "$out" 2>/dev/null | awk '/PROGRAM TOTALS/ { gsub(",", "", $1); print $1 }')
  rm -f "$out"
  echo $(( ${total:-0} / batch ))
}

if [ -z "$budgets" ]; then
  printf '| configuration | ISA | instructions/sample |\n|---|---|---|\n'
  for isa in scalar avx2; do
    for config in $("$bench" --list); do
      printf '| %s | %s | %d |\n' "$config" "$isa" "$(count "$config" "$isa")"
    done
  done
  exit 0
fi

over=0
while read -r config isa limit; do
  case "$config" in ''|'#'*) continue ;; esac
  n=$(count "$config" "$isa")
  if [ "$n" -le 0 ] || [ "$n" -gt "$limit" ]; then
    echo "OVER INSTRUCTION BUDGET: $config on $isa: $n instructions/sample > $limit"
    over=1
  else
    echo "instruction budget ok: $config on $isa: $n instructions/sample <= $limit"
  fi
done < "$budgets"
exit $over
