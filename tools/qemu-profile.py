#!/usr/bin/env python3
"""`tools/qemu-profile.sh top|diff`: a profile's counts per PC summed by
the outermost function of each PC's inline chain (llvm-addr2line -i), the
function that is out of line in the ELF."""
import collections
import json
import re
import subprocess
import sys


def clean(name):
    """A demangled name without generic arguments and hash."""
    while True:
        shorter = re.sub(r"<[^<>]*>", "", name)
        if shorter == name:
            return re.sub(r"::h[0-9a-f]{16}$", "", name)
        name = shorter


def by_function(elf, counts_file):
    rows = [l.split() for l in open(counts_file) if len(l.split()) == 2]
    out = subprocess.run(
        ["llvm-addr2line", "-f", "-i", "-C", "--output-style=JSON", "-e", elf],
        input="\n".join("0x" + a for _, a in rows) + "\n",
        capture_output=True,
        text=True,
        check=True,
    ).stdout.strip().split("\n")
    total = collections.Counter()
    for (count, _), line in zip(rows, out):
        chain = json.loads(line)["Symbol"]
        total[clean(chain[-1]["FunctionName"])] += int(count)
    return total


def main(argv):
    if len(argv) >= 3 and argv[0] == "top":
        n = int(argv[3]) if len(argv) > 3 else 30
        for name, c in by_function(argv[1], argv[2]).most_common(n):
            print(f"{c:>12} {name}")
    elif len(argv) >= 5 and argv[0] == "diff":
        a = by_function(argv[1], argv[2])
        b = by_function(argv[3], argv[4])
        n = int(argv[5]) if len(argv) > 5 else 30
        keys = sorted(set(a) | set(b), key=lambda k: -abs(b[k] - a[k]))
        print(f"{'B - A':>10} {'A':>12} {'B':>12} function")
        for k in keys[:n]:
            print(f"{b[k] - a[k]:>10} {a[k]:>12} {b[k]:>12} {k}")
    else:
        print("error: usage: qemu-profile.sh top ELF CNT [N] | diff ELF_A CNT_A ELF_B CNT_B [N]", file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
