#!/usr/bin/env bash
# Contact sheet of the default body model: the mean body and each of the first 5 shape
# components at -3 and +3, front and side views, rendered with the project's headless
# renderer (`sequential-gallery render`) and put together with ImageMagick's montage.
# usage: tools/make_contact_sheet.sh [EXECUTABLE] [MODEL.npz] [OUT.png]
set -euo pipefail
cd "$(dirname "$0")/.."
exe=${1:-./build/sequential-gallery}
model=${2:-neutral}
out=${3:-docs/default-model-contact-sheet.png}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

render() {  # name betas view label
  "$exe" render --model "$model" --betas="$2" --view "$3" --size 260x420 -o "$tmp/$1-$3.png" \
    >/dev/null
}

labels=()
names=()
add() {  # name betas label
  render "$1" "$2" front
  render "$1" "$2" side
  names+=("$1")
  labels+=("$3")
}

add mean "0" "mean"
for k in 1 2 3 4 5; do
  zeros=""
  for ((i = 1; i < k; ++i)); do zeros+="0,"; done
  add "c${k}m" "${zeros}-3" "component $k: -3"
  add "c${k}p" "${zeros}3" "component $k: +3"
done

args=()
for view in front side; do
  for i in "${!names[@]}"; do
    args+=(-label "${labels[$i]} ($view)" "$tmp/${names[$i]}-$view.png")
  done
done
montage "${args[@]}" -tile "${#names[@]}x2" -geometry +4+4 -pointsize 14 -background white "$out"
echo "wrote $out"
