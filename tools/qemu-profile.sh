#!/usr/bin/env bash
# Instruction counts per function of a firmware ELF run under QEMU: where
# a frame's instructions go, and, given two profiles, where they moved.
# Session 27 found the default switch's costs with it (docs/tree-format.md).
#
# Usage:
#   tools/qemu-profile.sh run ELF OUT.cnt [m4f|m0]   # counts per PC (one line each: COUNT ADDR)
#   tools/qemu-profile.sh top ELF OUT.cnt [N]        # instructions by outermost function (inlining folded in)
#   tools/qemu-profile.sh diff ELF_A A.cnt ELF_B B.cnt [N]   # B − A by outermost function
#
# `run` single-steps QEMU (`-singlestep -d exec,nochain`: one trace line an
# instruction) into a FIFO that awk counts, so no trace file is written; a
# run of 20 M instructions takes about a minute. The counts include
# start-up (tree validation, the checksum): profile an ELF that draws
# only the frames of interest (the firmware's `main` loop cut to one
# view, or `fpt mcu-bench`'s ELF with FPT_BENCH_FRAMES=2 under
# firmware/target/mcu-bench). Needs llvm-addr2line (apt
# package llvm) for `top` and `diff`; the firmware's release profile has
# debug info.
set -euo pipefail
cmd=${1:-}
machine() {
  case "${1:-m4f}" in
    m4f) echo "-machine netduinoplus2 -cpu cortex-m4" ;;
    m0) echo "-machine microbit -cpu cortex-m0" ;;
    *) echo "error: unknown cpu '$1' (expected m4f or m0)" >&2; exit 2 ;;
  esac
}
case "$cmd" in
  run)
    [ $# -ge 3 ] || { echo "error: usage: $0 run ELF OUT.cnt [m4f|m0]" >&2; exit 2; }
    elf=$2; out=$3; m=$(machine "${4:-m4f}")
    dir=$(mktemp -d); trap 'rm -rf "$dir"' EXIT
    mkfifo "$dir/trace"
    # The guest PC is the second field of the bracketed CPU state.
    awk '{ split($4, f, "/"); c[f[2]]++ } END { for (k in c) print c[k], k }' "$dir/trace" \
      | sort -rn > "$out" &
    # shellcheck disable=SC2086
    qemu-system-arm $m -nographic -semihosting-config enable=on,target=native \
      -icount shift=0 -singlestep -d exec,nochain -D "$dir/trace" -kernel "$elf"
    wait
    echo "$(awk '{ s += $1 } END { print s }' "$out") instructions -> $out" >&2
    ;;
  top | diff)
    exec python3 "$(dirname "$0")/qemu-profile.py" "$@"
    ;;
  *)
    echo "error: usage: $0 run|top|diff ... (see the comments at the top)" >&2
    exit 2
    ;;
esac
