#!/usr/bin/env bash
# ctest threejs_export: exports loaded by three.js in node (npm three, @pixiv/three-vrm) as a
# web app would: bones, morph dictionary, zero-weight height = `measure`, the VRM humanoid.
# usage: threejs_test.sh SEQUENTIAL_GALLERY FIXTURE_WRITER WORK_DIR
set -euo pipefail
exe=$1 writer=$2 dir=$3
here=$(cd "$(dirname "$0")" && pwd)
fail() { echo "FAIL: $*" >&2; exit 1; }
command -v node >/dev/null || fail "node is not installed (bash tools/setup.sh --test)"
[ -d "$here/node_modules/three" ] && [ -d "$here/node_modules/@pixiv/three-vrm" ] ||
  fail "three / @pixiv/three-vrm are not installed in tests/threejs: bash tools/setup.sh --test"
rm -rf "$dir"
mkdir -p "$dir"
betas="0.8 -1.2 0.5 1.5"
height=$("$exe" measure --betas $betas | awk '/^height/ {print $2}')
[ -n "$height" ] || fail "measure printed no height"
echo "measure: height $height m"
check() {  # check NAME TARGETS EXPORT-OPTIONS...
  local name=$1 targets=$2
  shift 2
  "$exe" export --betas $betas "$@" -o "$dir/$name" >/dev/null
  node "$here/check_export.mjs" "$dir/$name" --joints 55 --targets "$targets" --height "$height" \
    --bone pelvis --bone left_wrist --bone left_index3 --bone jaw --uv \
    --materials skin,eye_white,eye_iris
}
check split.glb 20
check betas.glb 10 --morph-betas
check baked.glb 0 --no-morph
check tpose.glb 20 --rest-pose t
check blender.glb 20 --preset blender
check threejs.glb 10 --preset threejs
"$exe" export --betas $betas --preset unity -o "$dir/unity.glb" >/dev/null
node "$here/check_export.mjs" "$dir/unity.glb" --joints 55 --targets 20 --height "$height" \
  --bone hips --bone leftUpperArm --bone leftIndexProximal --bone rightThumbDistal --bone jaw \
  --uv --morph-normals
"$exe" export --betas $betas --preset unreal -o "$dir/unreal.glb" >/dev/null
node "$here/check_export.mjs" "$dir/unreal.glb" --joints 55 --targets 20 --height "$height" \
  --bone pelvis --bone spine_01 --bone thigh_l --bone calf_r --bone upperarm_l --bone hand_r \
  --bone index_01_l --bone thumb_03_r --bone eye_l --uv
"$exe" export --betas $betas --preset vrm -o "$dir/avatar.vrm" >/dev/null
node "$here/check_export.mjs" "$dir/avatar.vrm" --vrm --joints 55 --targets 20 --height "$height" \
  --uv --look-at --morph-normals --materials skin,eye_white,eye_iris

# SMPL+H and SMPL-X look-alikes (cylinders with their joint names, hierarchy, UVs, SMPL-X's
# 10 shape + 10 expression columns): names, humanoid fingers, UVs, the shape/expression split.
for family in smplh smplx; do
  "$writer" "$dir/$family.npz" "$family"
  h=$("$exe" measure --model "$dir/$family.npz" | awk '/^height/ {print $2}')
  if [ $family = smplh ]; then joints=52 targets=20 extra=(); else joints=55 targets=23 extra=(--expressions 3); fi
  "$exe" export --model "$dir/$family.npz" "${extra[@]}" --preset vrm -o "$dir/$family.vrm" >/dev/null
  node "$here/check_export.mjs" "$dir/$family.vrm" --vrm --no-geometry --uv --joints $joints \
    --targets $targets --height "$h" --bone left_index1 --bone right_thumb3
done
node "$here/check_export.mjs" "$dir/smplx.vrm" --vrm --no-geometry --bone jaw --bone left_eye_smplhf \
  --target shape_09_neg --target expr_02
# The UE5 mannequin's finger names on SMPL-X's 55 joints.
"$exe" export --model "$dir/smplx.npz" --preset unreal -o "$dir/smplx_unreal.glb" >/dev/null
node "$here/check_export.mjs" "$dir/smplx_unreal.glb" --no-geometry --joints 55 \
  --bone index_01_l --bone thumb_03_r --bone jaw --bone eye_l
echo "threejs_export: all checks passed"
