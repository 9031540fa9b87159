"""Reads a QEMU log made with `-d in_asm,exec,nochain`: what
tools/profile.py and tools/profile_phases.py both count from.

Every `IN:` listing gives a translation block's instruction addresses,
every `Trace` line one execution of a block (with `nochain`, each
execution is logged), so an instruction's count is the executions of its
block.
"""
import collections
import re

TRACE = re.compile(r"Trace \d+: 0x[0-9a-f]+ \[[0-9a-f]+/([0-9a-f]+)/[0-9a-f]+/[0-9a-f]+\] (\S*)")


def read(log):
    """(blocks, execs, sym_of): each block's instruction addresses by its
    start, each block's executions, and the symbol QEMU names for it."""
    blocks, cur = {}, None
    execs, sym_of = collections.Counter(), {}
    with open(log, errors="replace") as f:
        for line in f:
            if line.startswith("IN:"):
                cur = None
                continue
            m = re.match(r"0x([0-9a-f]{8}):\s", line)
            if m:
                pc = int(m.group(1), 16)
                if cur is None:
                    cur = pc
                    blocks[cur] = []
                blocks[cur].append(pc)
                continue
            m = TRACE.match(line)
            if m:
                pc = int(m.group(1), 16)
                execs[pc] += 1
                sym_of[pc] = m.group(2)
                cur = None
    return blocks, execs, sym_of


def per_instruction(blocks, execs):
    """Instructions executed at each address."""
    per = collections.Counter()
    for pc, k in execs.items():
        for a in blocks.get(pc, [pc]):
            per[a] += k
    return per
