#!/usr/bin/env python3
"""Instruction profile of a QEMU run logged with `-d in_asm,exec,nochain`.

Usage: profile.py EXEC_LOG ELF [N]

Every executed instruction is counted (a translation block's executions
times each instruction of its `IN:` listing) and attributed, with
llvm-addr2line, to its innermost (inlined) function and source line. Prints
the totals per logged symbol, per inlined function and per source line (the
top N, default 40). See firmware/src/bin/profile.rs.
"""
import collections
import re
import subprocess
import sys

import qemu_log


def main():
    log, elf = sys.argv[1], sys.argv[2]
    top = int(sys.argv[3]) if len(sys.argv) > 3 else 40
    blocks, execs, sym_of = qemu_log.read(log)
    per_insn = qemu_log.per_instruction(blocks, execs)
    by_sym = collections.Counter()
    for pc, k in execs.items():
        by_sym[sym_of[pc]] += k * len(blocks.get(pc, [pc]))
    total = sum(per_insn.values())
    print(f"total {total} instructions\n\nper symbol:")
    for s, v in by_sym.most_common(15):
        print(f"{v:>10} {100 * v / total:5.1f}%  {s[:100]}")
    addrs = sorted(per_insn)
    out = subprocess.run(
        ["llvm-addr2line", "-e", elf, "-f", "-C"] + [hex(a) for a in addrs],
        capture_output=True, text=True,
    ).stdout.splitlines()
    by_fn = collections.Counter()
    by_line = collections.Counter()
    for i, a in enumerate(addrs):
        fn = out[2 * i] if 2 * i < len(out) else "?"
        loc = out[2 * i + 1] if 2 * i + 1 < len(out) else "?"
        fn = re.sub(r"::h[0-9a-f]{16}$", "", fn)
        loc = re.sub(r".*/(fpt-nostd/|firmware/|library/|\.cargo/registry/src/[^/]+/)", "", loc)
        by_fn[fn] += per_insn[a]
        by_line[loc] += per_insn[a]
    print("\nper inlined function:")
    for s, v in by_fn.most_common(top):
        print(f"{v:>10} {100 * v / total:5.1f}%  {s[:110]}")
    print("\nper source line:")
    for s, v in by_line.most_common(top):
        print(f"{v:>10} {100 * v / total:5.1f}%  {s}")


if __name__ == "__main__":
    main()
