#!/usr/bin/env python3
"""Instruction profile of a QEMU run logged with `-d in_asm,exec,nochain`.

Usage: profile.py EXEC_LOG ELF [--lines N]

Every executed translation block is weighed by its instruction count (from
the block's `IN:` listing) and summed per function (the log's symbol) and,
with llvm-addr2line, per source location of its first instruction,
inlining included (the innermost frame). See firmware/src/bin/profile.rs.
"""
import collections
import re
import subprocess
import sys


def main():
    log, elf = sys.argv[1], sys.argv[2]
    nlines = int(sys.argv[4]) if len(sys.argv) > 4 and sys.argv[3] == "--lines" else 40
    size = {}  # block start pc -> instruction count
    cur, n = None, 0
    execs = collections.Counter()
    sym_of = {}
    with open(log, errors="replace") as f:
        for line in f:
            if line.startswith("IN:"):
                cur, n = None, 0
                continue
            m = re.match(r"0x([0-9a-f]{8}):\s", line)
            if m:
                pc = int(m.group(1), 16)
                if cur is None:
                    cur = pc
                n += 1
                size[cur] = n
                continue
            m = re.match(r"Trace \d+: 0x[0-9a-f]+ \[[0-9a-f]+/([0-9a-f]+)/[0-9a-f]+/[0-9a-f]+\] (\S*)", line)
            if m:
                pc = int(m.group(1), 16)
                execs[pc] += 1
                sym_of[pc] = m.group(2)
                cur = None
    total = sum(size.get(pc, 1) * k for pc, k in execs.items())
    by_sym = collections.Counter()
    for pc, k in execs.items():
        by_sym[sym_of[pc]] += size.get(pc, 1) * k
    print(f"total {total} instructions")
    for s, v in by_sym.most_common(25):
        print(f"{v:>10} {100 * v / total:5.1f}%  {s}")
    pcs = sorted(execs)
    out = subprocess.run(
        ["llvm-addr2line-14", "-e", elf, "-i", "-f", "-C", "--no-addresses"] + [hex(p) for p in pcs],
        capture_output=True, text=True,
    ).stdout
    # With -i, each address gives one or more (function, file:line) pairs,
    # innermost first, and a blank separator is not printed: use the
    # addresses one by one instead when the count does not match.
    by_loc = collections.Counter()
    for pc in pcs:
        r = subprocess.run(["llvm-addr2line-14", "-e", elf, "-f", "-C", "-i", hex(pc)],
                           capture_output=True, text=True).stdout.splitlines()
        fn, loc = (r[0], r[1]) if len(r) >= 2 else ("?", "?")
        loc = re.sub(r".*/(fpt-nostd|firmware|\.cargo/registry/src/[^/]+)/", "", loc)
        by_loc[f"{fn} @ {loc}"] += size.get(pc, 1) * execs[pc]
    print()
    for s, v in by_loc.most_common(nlines):
        print(f"{v:>10} {100 * v / total:5.1f}%  {s}")


if __name__ == "__main__":
    main()
