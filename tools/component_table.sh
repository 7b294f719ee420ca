#!/usr/bin/env bash
# The "What the components do" tables of docs/default-model.md: per built-in model, the mean
# body's measurements and, per component 1-10, its variance share, its mean and largest vertex
# displacement at +-3 (from `generate-default-model`, which prints them) and the change in
# height, chest, waist and hip girths, volume and mass at -3 and +3 (from `measure`).
# usage: tools/component_table.sh [EXECUTABLE]   (prints markdown on stdout)
set -euo pipefail
cd "$(dirname "$0")/.."
exe=${1:-./build/sequential-gallery}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
"$exe" generate-default-model --output-dir "$tmp" >"$tmp/generate.txt"

measure() {  # model betas -> "height chest waist hips volume mass" (cm, cm, cm, cm, l, kg)
  "$exe" measure --model "$1" --betas="$2" | awk '
    /^height/ {h = 100 * $2} /^chest/ {c = 100 * $2} /^waist/ {w = 100 * $2}
    /^hips/ {p = 100 * $2} /^volume/ {v = 1000 * $2} /^mass/ {m = $2}
    END {print h, c, w, p, v, m}'
}

for model in female male neutral; do
  read -r h0 c0 w0 p0 v0 m0 < <(measure "$model" 0)
  echo "### $model"
  echo
  printf 'Mean body: height %.1f cm, chest %.1f cm, waist %.1f cm, hips %.1f cm, volume %.1f l, mass %.1f kg.\n\n' \
    "$h0" "$c0" "$w0" "$p0" "$v0" "$m0"
  echo "| component | share | mean / max displacement at +-3 (mm) | at -3: height / chest / waist / hips (cm), volume (l), mass (kg) | at +3: the same |"
  echo "|---|---|---|---|---|"
  for k in 1 2 3 4 5 6 7 8 9 10; do
    # "   k: share   mean /   max  (max at ...)" in this model's block of the generator's output
    read -r share dmean dmax < <(awk -v m="$model:" -v k="$k:" '
      $1 == m {inside = 1; next} /^[a-z]+: vertices/ {inside = 0}
      inside && $1 == k {printf "%.3f %s %s\n", $2, $3, $5; exit}' "$tmp/generate.txt")
    zeros=""
    for ((i = 1; i < k; ++i)); do zeros+="0,"; done
    cells=()
    for sign in -3 3; do
      read -r h c w p v m < <(measure "$model" "${zeros}${sign}")
      cells+=("$(awk -v h="$h" -v c="$c" -v w="$w" -v p="$p" -v v="$v" -v m="$m" -v h0="$h0" \
        -v c0="$c0" -v w0="$w0" -v p0="$p0" -v v0="$v0" -v m0="$m0" 'BEGIN {
        printf "%+.1f / %+.1f / %+.1f / %+.1f, %+.1f l, %+.1f kg", h - h0, c - c0, w - w0,
               p - p0, v - v0, m - m0}')")
    done
    echo "| $k | $share | $dmean / $dmax | ${cells[0]} | ${cells[1]} |"
  done
  echo
done
