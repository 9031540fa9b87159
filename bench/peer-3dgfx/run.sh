#!/bin/sh
# Builds and runs every configuration of the peer benchmark under QEMU and
# prints one `peer ...` line each (see README.md).
#
#   bench/peer-3dgfx/run.sh            # from anywhere
#   PEER_FRAMES=20 bench/peer-3dgfx/run.sh
#
# The sizes are the largest squares that fit each MCU's RAM: RAM minus the
# measured statics other than the two buffers and the measured stack peak,
# divided by 4 bytes a pixel (RGB565 + 16-bit depth); see README.md:
#   M4F 147×147: the whole mesh recorded into one command buffer (the peer's
#                record/execute as documented);
#   M4F 174×174: recorded and executed 32 triangles at a time, a 1.4 KiB
#                command buffer instead of 37 KiB (bigger frame, slower);
#   M0   41×41:  32 triangles at a time (the whole-mesh command buffer
#                alone is over twice the M0's 16 KiB).
# 240×240 fits neither: its framebuffer and 16-bit z-buffer alone take
# 225 KiB.
set -eu
cd "$(dirname "$0")"
export PEER_FRAMES="${PEER_FRAMES:-100}"

run() { # target size chunk
    # A stack that overflowed into the statics could hang the run: time out.
    out=$(PEER_SIZE=$2 PEER_CHUNK=$3 timeout 1200 cargo run --quiet --release --target "$1" 2>&1) || {
        printf '%s\n' "$out" >&2
        echo "peer run failed: target=$1 size=$2 chunk=$3" >&2
        exit 1
    }
    printf '%s\n' "$out" | grep '^peer '
}

run thumbv7em-none-eabihf 147 0
run thumbv7em-none-eabihf 174 32
run thumbv6m-none-eabi 41 32
