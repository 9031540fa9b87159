#!/usr/bin/env python3
"""Instruction profile of a QEMU run by phase of the renderer, or the
difference of two runs (a band frame against the full frame).

Usage: profile_phases.py LOG ELF [LOG2 ELF2]

LOG is a QEMU log made with `-d in_asm,exec,nochain` (see
firmware/src/bin/profile_set.rs). Every executed instruction is counted (as
tools/profile.py does) and given to the first phase below whose pattern
matches a function of its inline chain, innermost first (llvm-addr2line
-i): so a row loop inlined into the replay counts as rows, and the replay's
own code as replay. With two runs, prints both and their difference per
phase (the first minus the second). Function names differ between builds,
phases do not: that is what makes two builds comparable.
"""
import collections
import re
import subprocess
import sys

import qemu_log

# (phase, pattern of a function name), tried in order for each inline
# frame from the innermost out.
PHASES = [
    ("harness: checksum", r"crc|PixelCrc"),
    ("harness: tree checks", r"validate"),
    ("clear", r"fill_rows|fill_all|open_band"),
    ("rows and pixels", r"span_run|span_rows|Dda32::step|scan::scan|pair_rows"),
    ("kept-state ring", r"Ring::|carry::capacity"),
    ("band index", r"index_bands|list::place|DisplayList::band"),
    ("list push", r"DisplayList::(push|count|add|table_after|seal|note)"),
    ("list read", r"DisplayList::(record|rows_at|polygon|group)"),
    ("set-up: box", r"Bbox::of"),
    ("set-up: monotonicity", r"is_y_monotone"),
    ("set-up: edge starts", r"Dda32::(start|rows)|div_floor"),
    ("set-up: chain seeks", r"seek"),
    ("vertices: load, transform", r"load_cached|load_tagged|VertexCache|project|transform|prefill"),
    ("shading", r"shade"),
    ("walk", r"Order|Walk::|next_range|facing"),
    ("set-up: carried quads, polygons", r"start_quad|start_poly|TriangleBand.*(quad|poly)|run_chains|as_quad"),
    ("set-up: triangles", r"TriangleBand|fill_triangle"),
    ("set-up: general fill", r"fill_polygon_in|fill_monotone|fill_ready|Chain::"),
    ("replay (its own code)", r"replay"),
    ("memcpy", r"memcpy"),
]


def phases(log, elf):
    """Instructions per phase."""
    per = qemu_log.per_instruction(*qemu_log.read(log)[:2])
    addrs = sorted(per)
    out = subprocess.run(
        ["llvm-addr2line", "-e", elf, "-f", "-C", "-i", "-a"] + [hex(a) for a in addrs],
        capture_output=True, text=True,
    ).stdout.splitlines()
    chains, cur, i = {}, None, 0
    while i < len(out):
        if out[i].startswith("0x"):
            cur = int(out[i], 16)
            chains[cur] = []
            i += 1
            continue
        chains[cur].append(out[i])
        i += 2  # the function, then its file and line
    total = collections.Counter()
    for a, k in per.items():
        phase = "other"
        for fn in chains.get(a, []):
            hit = next((p for p, pat in PHASES if re.search(pat, fn)), None)
            if hit:
                phase = hit
                break
        total[phase] += k
    return total


def main():
    args = sys.argv[1:]
    if len(args) not in (2, 4):
        sys.exit(__doc__)
    a = phases(args[0], args[1])
    b = phases(args[2], args[3]) if len(args) == 4 else None
    names = [p for p, _ in PHASES] + ["other"]
    for p in sorted(names, key=lambda p: -a[p]):
        if b is None:
            print(f"{a[p]:>10}  {p}")
        else:
            print(f"{a[p]:>10} {b[p]:>10} {a[p] - b[p]:>+10}  {p}")
    ta = sum(a.values())
    if b is None:
        print(f"{ta:>10}  total")
    else:
        tb = sum(b.values())
        print(f"{ta:>10} {tb:>10} {ta - tb:>+10}  total")


if __name__ == "__main__":
    main()
