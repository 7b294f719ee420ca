#!/usr/bin/env bash
# The simulate command end to end: table on stdout, CSVs on disk, errors for bad options.
set -euo pipefail
bin=$1
dir=$2
rm -rf "$dir" && mkdir -p "$dir"
fail() { echo "FAIL: $*"; exit 1; }

# Output is captured before it is searched: with pipefail, `cmd | grep -q` fails whenever grep
# exits early and the writer dies of SIGPIPE, which depends on the machine's timing.
help=$("$bin" simulate --help)
grep -q -- "--function" <<<"$help" || fail "help does not list --function"

out=$("$bin" simulate --function gaussian --dims 4 --trials 2 --iterations 6 --resolution 100 \
      --quiet --csv "$dir/t.csv" --per-trial-csv "$dir/p.csv")
echo "$out"
[ "$(echo "$out" | grep -cE '^ +[0-9]+ ')" = 6 ] || fail "expected 6 iteration rows"
[ "$(wc -l < "$dir/t.csv")" = 7 ] || fail "CSV should have a header and 6 rows"
[ "$(wc -l < "$dir/p.csv")" = 13 ] || fail "per-trial CSV should have a header and 12 rows"
grep -q "^iteration,mean_gap,sd_gap,median_gap" <<<"$(head -1 "$dir/t.csv")" || fail "CSV header"
# Every row has as many fields as the header, and the per-trial seconds average to the mean.
awk -F, 'NR==1 { n=NF } NF != n { exit 1 }' "$dir/t.csv" || fail "CSV rows do not match the header"
awk -F, 'NR==FNR { if (FNR>1 && $3==6) { s+=$5; c++ } next }
         FNR==7 { m=$5; exit (m - s/c > 1e-12 || s/c - m > 1e-12) }' "$dir/p.csv" "$dir/t.csv" \
  || fail "mean optimizer seconds disagree with the per-trial file"
# The gap never grows (best so far) and ends below where it started.
awk -F, 'NR>1 { if (NR>2 && $2 > prev + 1e-15) bad=1; if (NR==2) first=$2; prev=$2 }
         END { exit (bad || !(prev < first)) }' "$dir/t.csv" || fail "gap did not decrease"

for m in sps-random sls; do
  "$bin" simulate --method $m --user zoom --function rosenbrock --dims 3 --trials 1 \
    --iterations 3 --quiet > /dev/null || fail "method $m"
done
"$bin" simulate --user zoom --zoom-prefs --function ackley --dims 3 --trials 1 --iterations 3 \
  --quiet > /dev/null || fail "zoom prefs"

# The body benchmark: the product's session, a simulated person with a just-noticeable
# difference, the RMS distance in mm as the gap and the two look-alike / pinned columns.
out=$("$bin" simulate --function body --components 4 --trials 2 --iterations 3 --quiet \
      --csv "$dir/b.csv" --per-trial-csv "$dir/bp.csv")
echo "$out"
[ "$(echo "$out" | grep -cE '^ +[0-9]+ ')" = 3 ] || fail "body: expected 3 iteration rows"
grep -q "^iteration,mean_gap,sd_gap,median_gap,.*,duplicate_grids,pinned_fraction,mean_saved_gap,median_saved_gap,mean_last_pick_gap,median_last_pick_gap,edge_cells$" \
  <<<"$(head -1 "$dir/b.csv")" || fail "body CSV header"
awk -F, 'NR==1 { n=NF } NF != n { exit 1 }' "$dir/b.csv" || fail "body CSV rows do not match the header"
[ "$(wc -l < "$dir/bp.csv")" = 7 ] || fail "body per-trial CSV should have a header and 6 rows"
# Gaps are distances in mm: positive, never growing; fractions lie in [0, 1].
awk -F, 'NR>1 { if ($2 <= 0 || (NR>2 && $2 > prev + 1e-9) || $7 < 0 || $7 > 1 || $8 < 0 || $8 > 1) bad=1; prev=$2 }
         END { exit bad }' "$dir/b.csv" || fail "body gaps or fractions out of range"
# What the window would save and the last pick are bodies too (gaps > 0); the best pick so far
# is never behind the last pick; edge cells are a fraction.
awk -F, 'NR>1 { if ($9 <= 0 || $11 < $2 - 1e-9 || $13 < 0 || $13 > 1) bad=1 }
         END { exit bad }' "$dir/b.csv" || fail "body saved / last-pick gaps or edge cells out of range"
grep -q "^trial,seed,iteration,gap_best_so_far,.*,saved_gap,last_pick_gap,cells,edge_cells$" \
  <<<"$(head -1 "$dir/bp.csv")" || fail "body per-trial CSV header"
"$bin" simulate --function body --components 3 --target-betas 1 -0.5 --method sls --trials 1 \
  --iterations 2 --quiet > /dev/null || fail "body with fixed target and sls"
# The built-in female and male models are searched, not the neutral one in their place: the
# same target betas lie at different distances from the same first plane.
for m in neutral female male; do
  "$bin" simulate --function body --components 3 --model $m --target-betas 1 -0.5 0.5 --trials 1 \
    --iterations 1 --quiet > "$dir/m_$m.csv" 2> "$dir/m_$m.err" || fail "body on the $m model"
  grep -qi "falling back\|using the embedded default" "$dir/m_$m.err" && fail "$m fell back to the default"
done
gap() { awk '$1 == "1" { print $2 }' "$dir/m_$1.csv"; }
differ() { awk -v a="$1" -v b="$2" 'BEGIN { d = a - b; if (d < 0) d = -d; exit !(d > 1e-3 * a) }'; }
differ "$(gap neutral)" "$(gap female)" || fail "female run gives the neutral run's gap"
differ "$(gap female)" "$(gap male)" || fail "male run gives the female run's gap"
# Holds: the target's height held in every grid; the title says so and the time
# spent projecting is reported.
out=$("$bin" simulate --function body --components 4 --trials 1 --iterations 2 --hold height \
      --hold mass 2>"$dir/hold.err")
echo "$out"
grep -q "holding the target's height, mass" <<<"$out" || fail "body --hold: no hold in the title"
grep -q "cells projected" "$dir/hold.err" || fail "body --hold: no projection timing"
# --zoom-factors: the paper's zoom (0.5) and the default (0.7, then 0.8) give different runs.
zoom_gap() {
  local table
  table=$("$bin" simulate --function body --components 4 --trials 1 --iterations 2 --quiet "$@")
  awk '$1 == 2 { print $2 }' <<<"$table"
}
paper_zoom=$(zoom_gap --zoom-factors 0.5)
default_zoom=$(zoom_gap)
[ -n "$paper_zoom" ] && [ -n "$default_zoom" ] || fail "body --zoom-factors: no gap printed"
differ "$default_zoom" "$paper_zoom" || fail "--zoom-factors 0.5 gives the default zoom's gap"

# Bad input: a clear message and a non-zero exit, never a crash.
for args in "--method nope" "--function nope" "--dims 0" "--grid 4" "--optimum 2" "--bogus 1" \
            "--function rosenbrock --optimum 0.5" "--function body --user argmax" \
            "--function body --jnd-mm -1" "--function body --target-betas 1 2 3 4 5 6 7 8 9 10 11" \
            "--function body --model /nonexistent.npz" "--function body --grid 7" \
            "--function body --hold weight" "--function body --hold mass --hold mass" \
            "--function body --zoom-factors 0" "--function body --threads 0" "--dims 100000" \
            "--function body --jnd-px 2 --jnd-mm 5" "--function body --jnd-px 2 --cell-px 4" \
            "--function body --jnd-px -1" \
            "--function body --zoom-factors 0.7,1.5" "--function body --zoom-factors x"; do
  if err=$("$bin" simulate $args --trials 1 --iterations 1 2>&1); then fail "accepted: $args"; fi
  grep -qi "error" <<<"$err" || fail "no error message for: $args"
  # A message for the user, not a bug report ("internal error" names a bug).
  ! grep -qi "internal error" <<<"$err" || fail "internal error for: $args: $err"
done
# The pixel person: 2 px of a 210 px cell are 20.4 mm, for the person, the session and the
# look-alike count alike.
out=$("$bin" simulate --function body --components 4 --trials 1 --iterations 2 --quiet \
      --jnd-px 2 --cell-px 210)
grep -qE "JND 20\.4[0-9]* mm = 2 px in a 210 px cell, close-ups; look-alikes under 20\.4" <<<"$out" ||
  fail "pixel person title: $out"
# The whole-body framing on request; anything else is refused with the choices named.
out=$("$bin" simulate --function body --components 4 --trials 1 --iterations 2 --quiet \
      --jnd-px 2 --cell-px 210 --framing whole-body)
grep -q "210 px cell, whole-body;" <<<"$out" || fail "whole-body framing title: $out"
if err=$("$bin" simulate --function body --components 4 --trials 1 --iterations 1 --quiet \
      --jnd-px 2 --framing sideways 2>&1); then
  fail "--framing sideways was accepted"
fi
grep -q "close-ups or whole-body" <<<"$err" || fail "--framing sideways: $err"
# The uncertainty planes' size is checked by the search's one rule, whichever option is off,
# for bodies and photos alike.
for args in "--function body --choice-region-slack 5000" "--function body --uncertainty-extent 0" \
            "--function photo --uncertainty-min-lengths 11"; do
  if err=$("$bin" simulate $args --trials 1 --iterations 1 2>&1); then fail "accepted: $args"; fi
  grep -q "must lie in" <<<"$err" || fail "no range named for: $args: $err"
done

# The photo benchmark: the window's 3x3 grids kept 3.5 Delta E apart, a 2.3-JND person, the
# body benchmark's columns; a named task is one fixed edit for every trial.
out=$("$bin" simulate --function photo --trials 2 --iterations 3 --quiet --csv "$dir/photo.csv")
grep -q "on photo (built-in landscape, 12 parameters), user zoom-jnd (3x3, 4 levels, JND 2.3" \
  <<<"$out" || fail "photo title: $out"
head -1 "$dir/photo.csv" | grep -q "duplicate_grids,.*,edge_cells$" ||
  fail "photo csv has no duplicate_grids or edge_cells"
awk -F, 'NR > 1 { if ($2 <= 0 || $2 > 60) exit 1 }' "$dir/photo.csv" ||
  fail "photo gap outside (0, 60] Delta E: $(cat "$dir/photo.csv")"
named=$("$bin" simulate --function photo --target warmer-brighter --trials 1 --iterations 2 --quiet)
grep -q "target warmer-brighter" <<<"$named" || fail "named photo target: $named"
# The paper's 5x5 grids near the box's faces: this trial's edit (seed 1001) showed look-alike
# first grids on planes 7, 8 and 10 (cells between the 3x3 ones clamped onto colours a person
# cannot tell apart) before the session's last fallbacks: the population's other axis pairs,
# then the part of the plane where the cells differ.
"$bin" simulate --function photo --grid 5 --trials 1 --seed 1001 --iterations 10 --quiet \
  --csv "$dir/photo5.csv" >/dev/null || fail "photo on 5x5 grids failed"
awk -F, 'NR == 1 { for (i = 1; i <= NF; ++i) if ($i == "duplicate_grids") c = i; next }
         { if (!c || $c != 0) exit 1 }' "$dir/photo5.csv" ||
  fail "look-alike grids on 5x5 photo grids: $(cat "$dir/photo5.csv")"
png="$dir/tiny.png"
printf '\x89PNG\r\n\x1a\n' >"$png"  # a PNG signature and nothing else
for args in "--target bogus" "--jnd-delta-e -1" "--grid 4" "--user argmax" \
            "--distinct-delta-e 0" "--image /nonexistent.png" "--image $png" \
            "--min-plane-delta-e 1000"; do
  if err=$("$bin" simulate --function photo $args --trials 1 --iterations 1 2>&1); then
    fail "accepted: --function photo $args"
  fi
  grep -qi "error" <<<"$err" || fail "no error message for: --function photo $args"
  ! grep -qi "internal error" <<<"$err" || fail "internal error for: --function photo $args: $err"
done
echo "ok"
