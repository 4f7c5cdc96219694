#!/usr/bin/env bash
# The closed loop over ROS against the in-process benchmark, side by side on the same scenes:
#   1. `makeway bench nav --methods ours` on N generated scenes (the in-process `ours`);
#   2. for each scene: a ROS master, makeway_sim_node (the robot, with ~mission: the scene's
#      waypoint then goal sent as a user would, and the room's CAD models written for the node),
#      makeway_node (the system) on sim time; the sim node's report judges the run;
#   3. success, collisions, robot-caused contacts and risk time of both, means with 95 % bootstrap
#      intervals (ros-vs-bench.json, and a table on stdout).
#   4. the node's latency line per run (sweep arrival to /cmd_vel, median and p99; late control cycles).
# Usage: scripts/ros-vs-bench.sh [N=10] [OUT=out/ros_vs_bench]   (after `make ros`)
# SIM_NICE=10 runs the simulator at that nice value: it stands in for sensors and a robot base
# whose work costs the robot's computer nothing, and on 2 cores it otherwise takes one from the node.
set -euo pipefail
cd "$(dirname "$0")/.."
N=${1:-10}
OUT=${2:-out/ros_vs_bench}
SIM_NICE=${SIM_NICE:-0}
BIN=${BUILD:-build}/bin
for b in makeway makeway_node makeway_sim_node; do
    [[ -x $BIN/$b ]] || { echo "ros-vs-bench: $BIN/$b missing (make ros)" >&2; exit 2; }
done
mkdir -p "$OUT"
OUT=$(cd "$OUT" && pwd)
echo "== in-process: bench nav --methods ours, $N scenes"
"$BIN/makeway" bench nav --scenes "$N" --seed 0 --methods ours --out "$OUT/bench" > "$OUT/bench.log"
PORT=$((21000 + $$ % 20000))
export ROS_MASTER_URI=http://localhost:$PORT ROS_HOSTNAME=localhost ROS_HOME="$OUT" ROS_LOG_DIR="$OUT/logs"
mkdir -p "$OUT/logs" "$OUT/ros"
rosmaster --core -p "$PORT" > "$OUT/logs/master.log" 2>&1 &
MASTER=$!
trap 'kill $MASTER 2>/dev/null || true' EXIT
for _ in $(seq 50); do rosparam list > /dev/null 2>&1 && break; sleep 0.2; done
rosparam set /use_sim_time true
python3 - "$OUT/bench/results.json" > "$OUT/scenes.txt" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))
for run in r["runs"]:
    print(run["scene"], run["scene_index"])
PY
while read -r scene index; do
    echo "== over ROS: $scene"
    rm -rf "$OUT/ros/$scene.cad"
    nice -n "$SIM_NICE" "$BIN/makeway_sim_node" __name:=makeway_sim _scene:="$OUT/bench/scenes/$scene.yaml" _seed:="$index" _mission:=true \
        _duration:=180 _cad_out:="$OUT/ros/$scene.cad" _report:="$OUT/ros/$scene.json" > "$OUT/logs/$scene.sim.log" 2>&1 &
    SIM=$!
    for _ in $(seq 100); do [[ -d $OUT/ros/$scene.cad ]] && break; sleep 0.1; done
    "$BIN/makeway_node" __name:=makeway _model:=models/detector.pt _cad:="$OUT/ros/$scene.cad" > "$OUT/logs/$scene.node.log" 2>&1 &
    NODE=$!
    wait $SIM || true
    kill -INT $NODE 2>/dev/null || true
    wait $NODE || true
done < "$OUT/scenes.txt"
python3 - "$OUT" "$SIM_NICE" <<'PY'
import json, random, re, sys
out, sim_nice = sys.argv[1], int(sys.argv[2])
bench = json.load(open(f"{out}/bench/results.json"))["runs"]
rows = {"in-process": [], "over ROS": []}
for b in bench:
    rows["in-process"].append({"success": b["success"], "collisions": b["collisions"],
                               "robot_caused": b["robot_caused_contacts"], "risk_time_s": b["risk_time_s"]})
    r = json.load(open(f"{out}/ros/{b['scene']}.json"))
    rows["over ROS"].append({"success": r["mission"]["success"], "collisions": int(r["collided"]),
                             "robot_caused": r["robot_caused_contacts"], "risk_time_s": r["risk_time_s"]})
def ci(values, seed=0):
    rng = random.Random(seed)
    means = sorted(sum(rng.choice(values) for _ in values) / len(values) for _ in range(2000))
    return sum(values) / len(values), means[50], means[1949]
summary = {}
print("| | scenes | success [95 % CI] | collisions | robot-caused contacts | risk time mean [95 % CI] |")
print("| --- | --- | --- | --- | --- | --- |")
for name, rs in rows.items():
    s = ci([float(x["success"]) for x in rs])
    k = ci([x["risk_time_s"] for x in rs])
    summary[name] = {"scenes": len(rs), "success": s, "collisions": sum(x["collisions"] for x in rs),
                     "robot_caused_contacts": sum(x["robot_caused"] for x in rs), "risk_time_s": k}
    print(f"| {name} | {len(rs)} | {s[0]:.2f} [{s[1]:.2f}, {s[2]:.2f}] | {summary[name]['collisions']} | "
          f"{summary[name]['robot_caused_contacts']} | {k[0]:.2f} [{k[1]:.2f}, {k[2]:.2f}] |")
latency = []
for b in bench:
    text = open(f"{out}/logs/{b['scene']}.node.log").read()
    m = re.search(r"sweep to /cmd_vel: median ([0-9.]+) ms, p99 ([0-9.]+) ms.*control cycles ([0-9]+), late \(> 1.5 periods\) ([0-9]+)", text)
    if m:
        latency.append({"scene": b["scene"], "median_ms": float(m[1]), "p99_ms": float(m[2]),
                        "control_cycles": int(m[3]), "late_cycles": int(m[4])})
if latency:
    p99 = sorted(x["p99_ms"] for x in latency)
    print(f"node latency (simulator at nice {sim_nice}): median {min(x['median_ms'] for x in latency):.1f}-"
          f"{max(x['median_ms'] for x in latency):.1f} ms, p99 {p99[0]:.1f}-{p99[-1]:.1f} ms (median run {p99[len(p99) // 2]:.1f}); "
          f"runs with p99 <= 30 ms: {sum(x <= 30.0 for x in p99)} of {len(p99)}; late control cycles "
          f"{sum(x['late_cycles'] for x in latency)} of {sum(x['control_cycles'] for x in latency)}")
json.dump({"rows": rows, "summary": summary, "sim_nice": sim_nice, "latency": latency}, open(f"{out}/ros-vs-bench.json", "w"), indent=1)
PY
