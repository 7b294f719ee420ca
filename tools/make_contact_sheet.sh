#!/usr/bin/env bash
# Contact sheets of the built-in body models: per model, the mean body and each of the first 10
# shape components at -3 and +3, front and side views, labelled with the change in height and
# mass (from `sequential-gallery measure`); and 1000 px close-ups of the mean body's head, hand,
# knees and feet. Rendered with the project's headless renderer (`sequential-gallery render`, EGL
# surfaceless) and put together with ImageMagick's montage.
# usage: tools/make_contact_sheet.sh [EXECUTABLE] [MODELS...]   (default: female male neutral)
# writes docs/default-model-<model>.png, docs/default-model-<model>-closeup.png and
# docs/default-model-{female,male}-random.png
set -euo pipefail
cd "$(dirname "$0")/.."
exe=${1:-./build/sequential-gallery}
shift || true
models=("$@")
[ ${#models[@]} -eq 0 ] && models=(female male neutral)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

measure() {  # model betas -> "height_m mass_kg"
  "$exe" measure --model "$1" --betas="$2" |
    awk '/^height/ {h = $2} /^mass/ {m = $2} END {print h, m}'
}

for model in "${models[@]}"; do
  read -r h0 m0 < <(measure "$model" 0)
  args=()
  cells=()  # betas label, in montage order (rows: front -3, front +3, side -3, side +3)
  for view in front side; do
    for sign in -3 3; do
      for k in 0 1 2 3 4 5 6 7 8 9 10; do
        name="$tmp/$model-$view-$k-$sign.png"
        if [ "$k" -eq 0 ]; then
          betas=0
          label=$(printf 'mean (%s)\n%.2f m, %.1f kg' "$view" "$h0" "$m0")
        else
          zeros=""
          for ((i = 1; i < k; ++i)); do zeros+="0,"; done
          betas="${zeros}${sign}"
          read -r h m < <(measure "$model" "$betas")
          label=$(awk -v k="$k" -v s="$sign" -v v="$view" -v h="$h" -v h0="$h0" -v m="$m" \
            -v m0="$m0" 'BEGIN {printf "c%d %+d (%s)\n%+.1f cm, %+.1f kg", k, s, v,
                               100 * (h - h0), m - m0}')
        fi
        "$exe" render --model "$model" --betas="$betas" --view "$view" --size 270x330 \
          -o "$name" >/dev/null
        args+=(-label "$label" "$name")
      done
    done
  done
  montage "${args[@]}" -tile 11x4 -geometry +3+3 -pointsize 13 -background white \
    "docs/default-model-$model.png"
  echo "wrote docs/default-model-$model.png"

  # Close-ups of the mean body (its height decides where the head, hand, knees and feet are;
  # the template is 1.70 m with the arms 50 degrees from the vertical).
  scale=$(awk -v h="$h0" 'BEGIN {print h / 1.7}')
  at() { awk -v s="$scale" -v v="$1" 'BEGIN {print s * v}'; }
  head_y=$(awk -v h="$h0" 'BEGIN {print h - 0.11}')
  "$exe" render --model "$model" --size 1000x1000 --target 0 "$head_y" 0.02 --distance 0.75 \
    --yaw 30 --pitch 0 -o "$tmp/head.png" >/dev/null
  "$exe" render --model "$model" --size 1000x1000 --target "$(at 0.65)" "$(at 0.975)" 0.03 \
    --distance 0.5 --yaw 60 --pitch 0 -o "$tmp/hand.png" >/dev/null
  "$exe" render --model "$model" --size 1000x1000 --target 0.0 "$(at 0.46)" 0.0 --distance 1.1 \
    --yaw 25 --pitch 0 -o "$tmp/knee.png" >/dev/null
  "$exe" render --model "$model" --size 1000x1000 --target 0.0 0.07 0.05 --distance 0.75 \
    --yaw 35 --pitch 15 -o "$tmp/feet.png" >/dev/null
  montage -label "$model: head" "$tmp/head.png" -label "hand" "$tmp/hand.png" \
    -label "knees" "$tmp/knee.png" -label "feet" "$tmp/feet.png" -tile 4x1 \
    -geometry 1000x1000+3+3 -pointsize 20 -background white \
    "docs/default-model-$model-closeup.png"
  echo "wrote docs/default-model-$model-closeup.png"
done

# Nine random bodies of the female and of the male model (betas ~ N(0, 1) on the first 10
# components, seeded), front and three-quarter view: what a person sees of a population, as
# opposed to one component at a time.
for model in female male; do
  args=()
  for i in 1 2 3 4 5 6 7 8 9; do
    betas=$(awk -v seed="$i" -v m="$model" 'BEGIN {
      srand(seed * 7919 + (m == "male") * 104729);
      s = "";
      for (k = 0; k < 10; ++k) {
        z = sqrt(-2 * log(1 - rand())) * cos(6.283185307 * rand());
        s = s (k ? "," : "") sprintf("%.2f", z);
      }
      print s }')
    read -r h m < <(measure "$model" "$betas")
    for view in front three-quarter; do
      "$exe" render --model "$model" --betas="$betas" --view "$view" --size 270x330 \
        -o "$tmp/random-$i-$view.png" >/dev/null
    done
    montage "$tmp/random-$i-front.png" "$tmp/random-$i-three-quarter.png" -tile 2x1 \
      -geometry +0+0 "$tmp/random-$i.png"
    args+=(-label "$(printf '%s %d: %.2f m, %.1f kg' "$model" "$i" "$h" "$m")" "$tmp/random-$i.png")
  done
  montage "${args[@]}" -tile 3x3 -geometry +3+3 -pointsize 13 -background white \
    "docs/default-model-$model-random.png"
  echo "wrote docs/default-model-$model-random.png"
done
