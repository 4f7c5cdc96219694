#!/usr/bin/env bash
# A picture of RViz (ros/makeway.rviz) while makeway_node drives the simulated robot through the
# test room: Xvfb, a ROS master on sim time, makeway_sim_node (~mission: the room's waypoint, then
# its goal), makeway_node and RViz; the screen is grabbed after SECONDS of driving.
# Usage: scripts/rviz-screenshot.sh [OUT=docs/rviz.png] [SECONDS=14]   (after `make ros`; needs
# Debian's rviz, xvfb and x11-apps)
set -euo pipefail
cd "$(dirname "$0")/.."
OUT=${1:-docs/rviz.png}
WAIT=${2:-14}
BIN=${BUILD:-build}/bin
TMP=$(mktemp -d)
PORT=$((21000 + $$ % 20000))
export ROS_MASTER_URI=http://localhost:$PORT ROS_HOSTNAME=localhost ROS_HOME=$TMP ROS_LOG_DIR=$TMP DISPLAY=:$((90 + $$ % 9))
PIDS=()
cleanup() { for p in "${PIDS[@]}"; do kill "$p" 2>/dev/null || true; done; rm -rf "$TMP"; }
trap cleanup EXIT
Xvfb "$DISPLAY" -screen 0 1200x800x24 > "$TMP/xvfb.log" 2>&1 & PIDS+=($!)
rosmaster --core -p "$PORT" > "$TMP/master.log" 2>&1 & PIDS+=($!)
for _ in $(seq 50); do rosparam list > /dev/null 2>&1 && break; sleep 0.2; done
rosparam set /use_sim_time true
"$BIN/makeway_sim_node" _scene:=tests/data/room_chair_table.yaml _mission:=true _duration:=60 > "$TMP/sim.log" 2>&1 & PIDS+=($!)
"$BIN/makeway_node" __name:=makeway _model:=models/detector.pt > "$TMP/node.log" 2>&1 & PIDS+=($!)
rviz -d ros/makeway.rviz > "$TMP/rviz.log" 2>&1 & PIDS+=($!)
sleep "$WAIT"
xwd -root -silent > "$TMP/screen.xwd"
python3 - "$TMP/screen.xwd" "$OUT" <<'PY'
# XWD (ZPixmap, 24/32 bits per pixel, as Xvfb writes it) to PNG, with the standard library only.
import struct, sys, zlib
data = open(sys.argv[1], "rb").read()
header_size, _, _, depth, width, height = struct.unpack(">6I", data[:24])
bits_per_pixel, bytes_per_line = struct.unpack(">2I", data[44:52])
ncolors = struct.unpack(">I", data[76:80])[0]
pixels = data[header_size + 12 * ncolors:]
byte_order = struct.unpack(">I", data[28:32])[0]  # 0: LSB first (BGRA)
rows = []
step = bits_per_pixel // 8
for y in range(height):
    line = pixels[y * bytes_per_line:(y * bytes_per_line) + width * step]
    out = bytearray()
    for x in range(0, len(line), step):
        b, g, r = (line[x], line[x + 1], line[x + 2]) if byte_order == 0 else (line[x + 3], line[x + 2], line[x + 1])
        out += bytes((r, g, b))
    rows.append(b"\0" + bytes(out))
def chunk(kind, body):
    return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body) & 0xffffffff)
png = b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">2I5B", width, height, 8, 2, 0, 0, 0))
png += chunk(b"IDAT", zlib.compress(b"".join(rows), 9)) + chunk(b"IEND", b"")
open(sys.argv[2], "wb").write(png)
print(f"rviz-screenshot: {sys.argv[2]} ({width}x{height})")
PY
