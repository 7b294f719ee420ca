#!/usr/bin/env bash
# ctest body_cli: the headless body subcommands on a fixture model written by
# body_fixture_writer (a closed cylinder, radius 0.15 m, 32 segments, height 1.7 m).
# usage: cli_test.sh SEQUENTIAL_GALLERY FIXTURE_WRITER WORK_DIR VALIDATE_JS
set -euo pipefail
exe=$1 writer=$2 dir=$3 validator=$4
rm -rf "$dir"
mkdir -p "$dir"
"$writer" "$dir/cyl.npz"

fail() { echo "FAIL: $*" >&2; exit 1; }
expect() {  # expect TEXT PATTERN
  grep -Eq -- "$2" <<<"$1" || fail "output does not match /$2/:
$1"
}

echo "== inspect"
out=$("$exe" inspect --model "$dir/cyl.npz")
echo "$out"
expect "$out" "shapedirs +float32 +\(1314, 3, 10\) +deflate"
expect "$out" "usable  yes: 1314 vertices, 2624 faces, 24 joints \(root 'pelvis'\), 10 shape components"

out=$("$exe" inspect --model female)  # a built-in name reads the embedded model
expect "$out" "usable  yes: [0-9]+ vertices"

echo "== measure (radius x 1.25 -> girth 64 * 0.1875 * sin(pi/32) = 1.1762 m)"
out=$("$exe" measure --model "$dir/cyl.npz" --betas 0.25 0)
echo "$out"
expect "$out" "height  1\.7000 m"
expect "$out" "chest   1\.1762 m"
expect "$out" "waist   1\.1762 m"
expect "$out" "hips    1\.1762 m"
out=$("$exe" measure --model "$dir/cyl.npz" --x 0.5 0.6)  # beta1 = 0.6 -> height x 1.6
expect "$out" "height  2\.7200 m"

echo "== export"
"$exe" export --model "$dir/cyl.npz" --betas 0.5 -0.5 1 -o "$dir/body.glb"
"$exe" export --model "$dir/cyl.npz" --x 0.2 0.9 --no-morph -o "$dir/body.gltf"
"$exe" export --model "$dir/cyl.npz" --betas 0.5 -0.5 --morph-betas -o "$dir/betas.gltf" |
  grep -q "10 morph targets" || fail "--morph-betas: expected 10 morph targets"
grep -q '"shape_09"' "$dir/betas.gltf" || fail "--morph-betas: no target shape_09"
[ -s "$dir/body.glb" ] || fail "body.glb not written"
grep -q '"shape_09_neg"' "$dir/body.glb" || fail "default: no split target shape_09_neg"
[ "$(head -c 4 "$dir/body.glb")" = "glTF" ] || fail "body.glb is not binary glTF"
grep -q '"targetNames"' "$dir/body.glb" || fail "no morph targets in body.glb"
grep -q '"left_shoulder"' "$dir/body.gltf" || fail "no SMPL joint names in body.gltf"
if grep -q '"targets"' "$dir/body.gltf"; then fail "--no-morph still wrote morph targets"; fi
command -v node >/dev/null || fail "node is not installed (bash tools/setup.sh --test)"
node "$validator" "$dir/body.glb" "$dir/body.gltf" "$dir/betas.gltf"

echo "== rest pose, presets, VRM"
help=$("$exe" export --help)
for p in blender unity unreal threejs vrm; do expect "$help" "^  $p "; done
"$exe" export --model "$dir/cyl.npz" --betas 0.5 --rest-pose t -o "$dir/t.glb" >/dev/null
"$exe" export --betas 0.5 --preset vrm -o "$dir/avatar.vrm" --vrm-authors "A; B" >/dev/null
grep -q '"VRMC_vrm"' "$dir/avatar.vrm" || fail "avatar.vrm has no VRMC_vrm"
grep -q '"authors":\["A","B"\]' "$dir/avatar.vrm" || fail "avatar.vrm: authors not set"
"$exe" export --betas 0.5 --preset unity -o "$dir/unity.glb" >/dev/null
grep -q '"leftUpperArm"' "$dir/unity.glb" || fail "--preset unity: no humanoid bone names"
"$exe" export --betas 0.5 --preset unreal -o "$dir/unreal.glb" >/dev/null
grep -q '"upperarm_l"' "$dir/unreal.glb" || fail "--preset unreal: no UE5 mannequin bone names"
if grep -q '"leftUpperArm"' "$dir/unreal.glb"; then fail "--preset unreal: humanoid names"; fi
"$writer" "$dir/smpl.npz" smpl  # SMPL look-alike with posedirs (207 columns)
"$exe" export --model "$dir/smpl.npz" --rest-pose t -o "$dir/smpl_t.gltf" >/dev/null
grep -q "T (model's skinning and pose correctives)" "$dir/smpl_t.gltf" ||
  fail "--rest-pose t on a model with posedirs did not apply them"
"$exe" export --model "$dir/cyl.npz" --rest-pose t -o "$dir/cyl_t.gltf" >/dev/null
grep -q "T (model's skinning, no pose correctives)" "$dir/cyl_t.gltf" ||
  fail "--rest-pose t without posedirs: extras do not say so"
node "$validator" "$dir/t.glb" "$dir/avatar.vrm" "$dir/unity.glb" "$dir/unreal.glb" \
  "$dir/smpl_t.gltf"

echo "== errors"
if out=$("$exe" export --model "$dir/cyl.npz" --components 16 -o "$dir/x.glb" 2>&1); then
  fail "--components 16 on a 10-component file accepted"
fi
expect "$out" "--components 16: the model 'cyl' has only 10 shape components"
if out=$("$exe" export --model "$dir/cyl.npz" --no-morph --morph-betas -o "$dir/x.glb" 2>&1); then
  fail "--no-morph with --morph-betas accepted"
fi
expect "$out" "--no-morph and --morph-betas"
if out=$("$exe" export --model "$dir/cyl.npz" --expressions 2 -o "$dir/x.glb" 2>&1); then
  fail "--expressions on a model without expressions accepted"
fi
expect "$out" "no expression components"
if out=$("$exe" export --preset vrm -o "$dir/x.glb" 2>&1); then fail "--preset vrm to .glb"; fi
expect "$out" "\*\.vrm"
if out=$("$exe" export --rest-pose a -o "$dir/x.vrm" 2>&1); then fail "A-pose .vrm accepted"; fi
expect "$out" "T-pose"
if out=$("$exe" export --rest-pose x -o "$dir/x.glb" 2>&1); then fail "--rest-pose x accepted"; fi
expect "$out" "a\|t"
[ ! -e "$dir/x.glb" ] && [ ! -e "$dir/x.vrm" ] || fail "a failed export left a file"
before=$(md5sum <"$dir/body.glb")
if out=$("$exe" export --model "$dir/cyl.npz" --betas 1 2 3 4 5 6 7 8 9 10 11 --components 10 \
          -o "$dir/body.glb" 2>&1); then fail "too many betas accepted"; fi
echo "$out"
expect "$out" "11 shape values"
[ "$(md5sum <"$dir/body.glb")" = "$before" ] || fail "a failed export changed body.glb"
if out=$("$exe" export --model "$dir/cyl.npz" -o "$dir/nowhere/x.glb" 2>&1); then
  fail "export into a missing folder succeeded"
fi
expect "$out" "does not exist"
if out=$("$exe" measure --model "$dir/cyl.npz" --x 1.5 2>&1); then fail "--x 1.5 accepted"; fi
expect "$out" "outside \[0, 1\]"
head -c 3000 "$dir/cyl.npz" >"$dir/cut.npz"
if out=$("$exe" inspect --model "$dir/cut.npz" 2>&1); then fail "truncated file called usable"; fi
echo "$out"
expect "$out" "usable  no: .*cut.npz"
if out=$("$exe" measure --model "$dir/missing.npz" 2>&1); then fail "missing model accepted"; fi
expect "$out" "missing.npz: file not found"

echo "== messages users met"
refuse() {  # refuse PATTERN COMMAND...: the command must fail with a message matching PATTERN
  local pattern=$1; shift
  if out=$("$@" 2>&1); then fail "accepted: $*"; fi
  echo "$out"
  expect "$out" "$pattern"
}
refuse "value number 1 is 1\.5, which is outside \[0, 1\]" "$exe" measure --model "$dir/cyl.npz" --x 1.5
refuse "value number 2 is 1e\+30, which is outside \[-10, 10\]" \
  "$exe" export --model "$dir/cyl.npz" --betas 0 1e30 -o "$dir/collapsed.glb"
[ -e "$dir/collapsed.glb" ] && fail "betas of 1e30 wrote a file"
refuse "'-inf' is not a number" "$exe" measure --model "$dir/cyl.npz" --betas -inf
refuse "empty value between commas" "$exe" measure --model "$dir/cyl.npz" --betas 1,,2
refuse "'0x10' is not a number" "$exe" measure --model "$dir/cyl.npz" --components 0x10
refuse "--components 17: the model 'cyl' has only 10 shape components" \
  "$exe" measure --model "$dir/cyl.npz" --components 17
refuse "--components 1000000000: .* has only 10" \
  "$exe" measure --model "$dir/cyl.npz" --components 1000000000
refuse "/dev/zero: not a regular file" "$exe" inspect --model /dev/zero
refuse "/dev/zero: not a regular file" "$exe" measure --model /dev/zero
refuse "--vrm-name: the text is not valid UTF-8" \
  "$exe" export --model "$dir/cyl.npz" --vrm-name $'caf\xe9' -o "$dir/latin1.vrm"
out=$("$exe" measure --model "$dir/cyl.npz" --betas 1e-320) || fail "--betas 1e-320 refused: $out"

echo "== measurement targets: the cylinder's height is 1.7 (1 + beta2)"
out=$("$exe" measure --model "$dir/cyl.npz" --target height=2.04 2>&1) || fail "target refused: $out"
echo "$out"
expect "$out" "height  2.04[0-9]* m"
expect "$out" "target: reached height 204.0 cm"
out=$("$exe" measure --model "$dir/cyl.npz" --target height=170cm --target mass=150kg 2>&1) ||
  fail "two targets refused: $out"
expect "$out" "mass    1[45][0-9]\.[0-9] kg"
"$exe" export --model "$dir/cyl.npz" --target height=1.9 -o "$dir/target.glb" >/dev/null 2>&1 ||
  fail "export --target failed"
[ -s "$dir/target.glb" ] || fail "export --target wrote nothing"
refuse "height '9' is out of range" "$exe" measure --model "$dir/cyl.npz" --target height=9
# The built-in model stays human inside +-3 SD: 2.6 m is out of its reach.
refuse "out of reach .*height 260\.0 cm.* nearest reachable: height" \
  "$exe" measure --target height=2.6
refuse "height 'nan' is not a number" "$exe" measure --model "$dir/cyl.npz" --target height=nan
refuse "unknown measurement 'weight'.*known: height, mass" \
  "$exe" measure --model "$dir/cyl.npz" --target weight=80
refuse "mass '-3' is out of range" "$exe" export --model "$dir/cyl.npz" --target mass=-3 -o "$dir/m.glb"
# Height, mass and BMI that no body has together: refused, not "nearest reachable: the start".
refuse "make a BMI of 33.2, not 10.0" \
  "$exe" measure --target bmi=10 --target mass=120 --target height=1.9

echo "== bench-survey reads the survey tables it is given, or says what is wrong where"
refuse "bench-survey needs --female, --male or both" "$exe" bench-survey
refuse "nosuch.csv: no such file" "$exe" bench-survey --female "$dir/nosuch.csv"
printf 'stature,weightkg\n1650,612\n' >"$dir/narrow.csv"
refuse "narrow.csv: no column 'chestcircumference'" "$exe" bench-survey --male "$dir/narrow.csv"
cols="stature,weightkg,chestcircumference,waistcircumference,buttockcircumference"
cols+=",biacromialbreadth,crotchheight,acromionradialelength,radialestylionlength"
cols+=",neckcircumference,bideltoidbreadth,bicepscircumferenceflexed,thighcircumference"
cols+=",calfcircumference"
row="1650,612,900,800,1000,360,780,310,240,330,430,290,600,360"
printf '%s\n%s\n%s\n1650,61' "$cols" "$row" "$row" >"$dir/cut.csv"
refuse "cut.csv: row 3 \(line 4\) has 2 fields, the header 14" "$exe" bench-survey --female "$dir/cut.csv"
printf '%s\n%s\n1650,612,900,eight hundred,1000,360,780,310,240,330,430,290,600,360\n' "$cols" \
  "$row" >"$dir/words.csv"
refuse "words.csv: row 2 \(line 3\), column 'waistcircumference': 'eight hundred' is not a number" \
  "$exe" bench-survey --female "$dir/words.csv"
printf '%s\n%s\n%s\n' "$cols" "$row" "1700,700,950,850,1020,370,800,320,250,340,440,300,610,370" \
  >"$dir/two.csv"
out=$("$exe" bench-survey --female "$dir/two.csv" --samples 5 2>&1) || fail "bench-survey: $out"
expect "$out" "model female \(5 bodies\) against ANSUR II women, two.csv \(2 people\)"
expect "$out" "height +167.5"
expect "$out" "correlations within 0.15: [0-9]+ of [0-9]+"

echo "== fit-survey fits surveyed people and writes its table, or says what is wrong"
refuse "fit-survey needs --model and --csv" "$exe" fit-survey --model female
refuse "nosuch.csv: no such file" "$exe" fit-survey --model female --csv "$dir/nosuch.csv"
refuse "the sample of 3 is larger than the survey's 2 people" \
  "$exe" fit-survey --model female --csv "$dir/two.csv" --sample 3
refuse "cannot fit \"foo\"; the measurements are: height, mass" \
  "$exe" fit-survey --model female --csv "$dir/two.csv" --sample 1 --measurements foo
refuse "--out needs a file name" "$exe" fit-survey --model female --csv "$dir/two.csv" --out ""
out=$("$exe" fit-survey --model female --csv "$dir/two.csv" --sample 2 --threads 2 \
  --measurements height,mass,hips --out "$dir/fit.csv" 2>&1) || fail "fit-survey: $out"
expect "$out" "model female \(10 components\) against 2 people of two.csv"
expect "$out" "height +cm"
head -1 "$dir/fit.csv" | grep -qx "measurement,unit,median_abs_error,p95_abs_error" ||
  fail "fit.csv header: $(head -1 "$dir/fit.csv")"
[ "$(wc -l <"$dir/fit.csv")" -eq 4 ] || fail "fit.csv: $(cat "$dir/fit.csv")"
grep -q "^mass,kg," "$dir/fit.csv" || fail "fit.csv has no mass row: $(cat "$dir/fit.csv")"
echo "body_cli: all checks passed"
