#!/usr/bin/env bash
# False positives on clutter (issue 32): a 10 x 6 m room (room.ply) holding only things of furniture
# size that are not furniture (clutter.ply: a crate, a cabinet, a bin, a sofa-sized block, a shelf,
# a plant, a standing figure, a low box, a small box). The robot drives through it; the whole
# system runs on the recording without CAD models and with five procedural ones. Every detection
# and every object of the final map is a false positive.
#   docs/clutter_room/measure.sh [OUT]      (MAKEWAY=path/to/makeway to use another build)
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
mw=${MAKEWAY:-build/bin/makeway}
out=${1:-out/clutter_room}
"$mw" simulate --scene "$here/room.yaml" --frames 150 --out "$out/sim"
"$mw" run --clouds "$out/sim/clouds" --odometry "$out/sim/odometry.txt" --png-every 0 \
    --out "$out/without_cad"
mkdir -p "$out/cad"
for style in four_leg_chair office_chair stool rect_table conference_table; do
    class=chair
    [[ $style == *table ]] && class=table
    "$mw" cad --style "$style" --seed 1 --out "$out/cad/${class}_$style.obj" > /dev/null
done
"$mw" run --clouds "$out/sim/clouds" --odometry "$out/sim/odometry.txt" --cad "$out/cad" \
    --png-every 0 --out "$out/with_cad"
for run in without_cad with_cad; do
    echo "== $run"
    grep -E '"(keyframes|detections|verified_accepted|objects|chairs|tables)"' \
        "$out/$run/summary.json"
done
