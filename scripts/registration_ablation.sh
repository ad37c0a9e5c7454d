#!/usr/bin/env bash
# Ablation of the registration's evidence (issue 15; docs/registration.md): the registration
# stage rerun with more and more edge types on one capture run whose RGB-D stage is done, each
# judged by `sewer3d evaluate registration` (ATE after one rigid alignment, per material).
# Usage: scripts/registration_ablation.sh RUN WS [OUT] (WS holds rgbd/; OUT default
# out/ablation; each row gets OUT/<row>/ with rgbd/ hard-linked from WS).
set -euo pipefail
cd "$(dirname "$0")/.."
bin=./build/sewer3d
run=$1
ws=$2
out=${3:-out/ablation}
rows=(
  "odometry-only none"
  "features feature"
  "features+projection feature,projection"
  "+texture feature,projection,texture"
  "+rig+odometry feature,projection,texture,rig,odometry"
  "+straightness feature,projection,texture,rig,odometry,straightness"
  "+bias feature,projection,texture,rig,odometry,straightness,bias"
  "+gravity feature,projection,texture,rig,odometry,straightness,bias,gravity"
  "+scale feature,projection,texture,rig,odometry,straightness,bias,gravity,scale"
  "+centreline feature,projection,texture,rig,odometry,straightness,bias,gravity,scale,centreline"
)
printf '| evidence | ATE RMS (mm) | max (mm) | per material (RMS mm) | edges accepted / rejected |\n'
printf '|---|---|---|---|---|\n'
for row in "${rows[@]}"; do
  read -r name edges <<<"$row"
  dir="$out/$name"
  rm -rf "$dir" && mkdir -p "$dir"
  cp -al "$ws/rgbd" "$dir/rgbd"
  cp "$ws/workspace.json" "$dir/"  # records the rgbd stage; --force replaces any register record
  "$bin" register "$run" --out "$dir" --edges "$edges" --threads 2 --quiet --force \
    >"$dir/register.log"
  "$bin" evaluate registration --run "$run" --workspace "$dir" >"$dir/evaluate.log"
  ate=$(grep -m1 'absolute trajectory error' "$dir/evaluate.log" | sed -E 's/.*RMS ([0-9.]+) mm, max ([0-9.]+) mm.*/\1 \2/')
  materials=$(grep -E '^  [a-z_]+ +[0-9]+ nodes' "$dir/evaluate.log" | awk '{printf "%s%s %s", (NR>1?", ":""), $1, $5}')
  edges_line=$(grep -m1 '^register:' "$dir/register.log" | sed -E 's/.*: ([0-9]+) feature, ([0-9]+) projection.*; ([0-9]+) rig.*; ([0-9]+) rejected.*/\1 feature, \2 projection, \3 prior; \4 rejected/')
  read -r rms max <<<"$ate"
  printf '| %s | %s | %s | %s | %s |\n' "$name" "$rms" "$max" "$materials" "$edges_line"
done
