#!/usr/bin/env bash
# Calibration accuracy over waters and light rigs, on dives lutex's simulator renders (README, 'Weights in
# albedo units'). For each water (clear, coastal, harbour) and rig (two spots at +-0.4 m; an asymmetric pair
# at -0.25 m and +0.5 m, one turned 10 degrees in and down, 12 and 22 W) it simulates the bundled example's
# survey (320 x 240, at 1.8 m), board frames and pure water, calibrates from the board and the pure water,
# restores the survey and prints the mean absolute error against the true albedo in percentage points.
# About 8 minutes on 2 cores.
#
# usage: [FORWARD_SCATTER=1] [CALIBRATE_OPTIONS="..."] [RESTORE_OPTIONS="..."] scripts/water_rig_sweep.sh [LUTEX_BINARY] [OUTPUT_FOLDER]
#   LUTEX_BINARY     default build/lutex; pass another build's binary to compare two versions
#   OUTPUT_FOLDER    default a new folder under /tmp; simulated dives there are reused by later runs
#   FORWARD_SCATTER  1: the dives are rendered with the water's forward scattering (lib/model/simulator.h),
#                    in folders of their own (NAME_fs)
#   CALIBRATE_OPTIONS more options for lutex calibrate, e.g. "--no-remove-forward-scatter --reference-water clear"
#   RESTORE_OPTIONS  more options for lutex restore, e.g. --no-smooth-noise
set -euo pipefail
repo="$(cd "$(dirname "$0")/.." && pwd)"
lutex="$(realpath "${1:-$repo/build/lutex}")"
out="${2:-$(mktemp -d /tmp/lutex_sweep_XXXXXX)}"
mkdir -p "$out"
echo "lutex: $lutex; dives in $out"

for water in clear coastal harbour; do
  for rig in sym asym; do
    dive="$out/${water}_$rig"
    if [ "${FORWARD_SCATTER:-0}" = 1 ]; then dive="${dive}_fs"; fi
    if [ ! -d "$dive/survey/images" ]; then
      mkdir -p "$dive"
      # The example's scene files with this water, this rig and a smaller camera.
      /usr/bin/python3 - "$repo/examples" "$water" "$rig" "$dive" "${FORWARD_SCATTER:-0}" <<'EOF'
import json, os, sys
examples, water, rig, dive, forward_scatter = sys.argv[1:]
waters = {
    "clear": {"description": "clear", "absorption": [0.35, 0.05, 0.02], "scattering": [0.04, 0.045, 0.05], "g": 0.88},
    "coastal": {"description": "coastal", "absorption": [0.45, 0.12, 0.25], "scattering": [0.35, 0.4, 0.38], "g": 0.9},
    "harbour": {"description": "harbour", "absorption": [0.6, 0.35, 0.75], "scattering": [0.8, 0.9, 0.85], "g": 0.92},
}
def spot(name, position, direction, power):
    return {"name": name, "position": position, "direction": direction, "power_W": power,
            "profile": "cycles_spot", "spot_size_deg": 110, "spot_blend": 0.5}
rigs = {
    "sym": [spot("left", [-0.4, 0, 0], [0, 0, 1], 15), spot("right", [0.4, 0, 0], [0, 0, 1], 15)],
    "asym": [spot("left", [-0.25, 0, 0], [0, 0, 1], 12), spot("right", [0.5, 0.1, 0], [-0.17, 0.17, 0.97], 22)],
}
camera = {"model": "PINHOLE", "width": 320, "height": 240, "params": [160, 160, 160, 120]}
for source, name in [("scenes/clear_two_lights.json", "survey"), ("dive/board.json", "board"), ("dive/purewater.json", "purewater")]:
    scene = json.load(open(os.path.join(examples, source)))
    scene.update(water=waters[water], lights=rigs[rig], camera=camera)
    if forward_scatter == "1":
        scene.setdefault("simulator", {})["forward_scatter"] = True
    if isinstance(scene.get("mesh"), str):
        scene["mesh"] = os.path.join(examples, os.path.dirname(source), scene["mesh"])
    if name == "survey":
        scene["survey"].update(altitude=1.8, images_per_line=6)
    json.dump(scene, open(os.path.join(dive, name + ".json"), "w"), indent=1)
EOF
      for part in survey board purewater; do
        "$lutex" simulate --scene "$dive/$part.json" --output "$dive/$part" --log-level error > /dev/null
      done
    fi
    run="$(mktemp -d "$dive/run_XXXXXX")"
    if ! "$lutex" calibrate --workspace "$dive/survey" --mesh "$dive/survey/scene/mesh.ply" \
        --targets "$repo/examples/dive/board_targets.json" --targets-workspace "$dive/board" \
        --targets-mesh "$dive/board/scene/mesh.ply" --pure-water "$dive/purewater" \
        --output "$run/lut.lut" --log-level error ${CALIBRATE_OPTIONS:-} > "$run/calibrate.log" 2>&1; then
      echo "$water $rig: calibration refused: $(tail -1 "$run/calibrate.log")"
      continue
    fi
    "$lutex" restore --workspace "$dive/survey" --mesh "$dive/survey/scene/mesh.ply" --lut "$run/lut.lut" \
      --output "$run/restored" --output-encoding linear16 --log-level error ${RESTORE_OPTIONS:-} > /dev/null
    /usr/bin/python3 - "$dive/survey" "$run/restored" "$water $rig" <<'EOF'
import glob, os, sys
import cv2, numpy as np
survey, restored, label = sys.argv[1:]
errors = []
for truth_path in sorted(glob.glob(os.path.join(survey, "ground_truth", "albedo", "*.png"))):
    truth = cv2.imread(truth_path, cv2.IMREAD_UNCHANGED)[:, :, ::-1] / 65535.0
    image = cv2.imread(os.path.join(restored, os.path.basename(truth_path)), cv2.IMREAD_UNCHANGED)[:, :, ::-1] / 65535.0
    # Surface pixels, 2 px away from the surface's edges.
    inside = cv2.erode((truth.sum(axis=2) > 0).astype(np.uint8), np.ones((5, 5), np.uint8)).astype(bool)
    errors.append(np.abs(image[inside] - truth[inside]))
errors = np.concatenate(errors) * 100
print("%s: mae %.2f pp, p95 %.2f, per channel %s" % (label, errors.mean(), np.percentile(errors, 95),
                                                     " ".join("%.2f" % e for e in errors.mean(axis=0))))
EOF
  done
done
