#!/usr/bin/env bash
# Regenerates everything that depends on the default file options
# (`SerializeOptions::default` in fpt-build/src/serialize.rs: what
# `fpt build` writes without `--vertex-format`/`--records`, and what the
# project's scenes are written with), after a change to them or to the
# format:
#
# * firmware/trees: the frame set's trees (vise, house, bench_city),
#   frames.txt, and the accuracy study's trees (bench_city.{f32,q16,q32}.fpt,
#   pinned encodings: they change only with the format) and accuracy.txt
#   (`fpt frames --export`; checked by `firmware_crc::committed_trees_are_fresh`);
# * tests/golden/effects: the effect goldens (the reference pictures of
#   the scenes' trees; `FPT_BLESS=1`, `effects_golden`);
# * docs/img: the demo's pictures (`fpt demo`). (docs/img/effects, drawn
#   by the commands in docs/effects.md, are illustrations made by older
#   versions of the tool and are left as they are.)
#
# Usage: tools/regen-trees.sh   (from anywhere; then review `git status`
# and `git diff --stat`, and run the tests: the firmware's checksums must
# equal the new frames.txt, `cd firmware && cargo run --release --locked`
# and `... --no-default-features --features band`).
set -euo pipefail
cd "$(dirname "$0")/.."

echo "== fpt"
cargo build --release --locked -p host-sim --bin fpt
fpt=$PWD/target/release/fpt

echo "== firmware/trees"
"$fpt" frames --export firmware/trees >/dev/null

echo "== tests/golden/effects"
FPT_BLESS=1 cargo test --release --locked -p fpt-tests --test all effects_golden

echo "== docs/img (the demo's pictures)"
demo=$(mktemp -d)
trap 'rm -rf "$demo"' EXIT
"$fpt" demo --out "$demo" >/dev/null
for f in vise_1.png house_1.png bench_city_1.png robot_1.png robot_spin.gif; do
  cp "$demo/$f" docs/img/"$f"
done

git status --short firmware/trees tests/golden docs/img
