#!/usr/bin/env bash
# The simulate command end to end: table on stdout, CSVs on disk, errors for bad options.
set -euo pipefail
bin=$1
dir=$2
rm -rf "$dir" && mkdir -p "$dir"
fail() { echo "FAIL: $*"; exit 1; }

"$bin" simulate --help | grep -q -- "--function" || fail "help does not list --function"

out=$("$bin" simulate --function gaussian --dims 4 --trials 2 --iterations 6 --resolution 100 \
      --quiet --csv "$dir/t.csv" --per-trial-csv "$dir/p.csv")
echo "$out"
[ "$(echo "$out" | grep -cE '^ +[0-9]+ ')" = 6 ] || fail "expected 6 iteration rows"
[ "$(wc -l < "$dir/t.csv")" = 7 ] || fail "CSV should have a header and 6 rows"
[ "$(wc -l < "$dir/p.csv")" = 13 ] || fail "per-trial CSV should have a header and 12 rows"
head -1 "$dir/t.csv" | grep -q "^iteration,mean_gap,sd_gap,median_gap" || fail "CSV header"
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
head -1 "$dir/b.csv" | grep -q "^iteration,mean_gap,sd_gap,median_gap,.*,duplicate_grids,pinned_fraction$" \
  || fail "body CSV header"
awk -F, 'NR==1 { n=NF } NF != n { exit 1 }' "$dir/b.csv" || fail "body CSV rows do not match the header"
[ "$(wc -l < "$dir/bp.csv")" = 7 ] || fail "body per-trial CSV should have a header and 6 rows"
# Gaps are distances in mm: positive, never growing; fractions lie in [0, 1].
awk -F, 'NR>1 { if ($2 <= 0 || (NR>2 && $2 > prev + 1e-9) || $7 < 0 || $7 > 1 || $8 < 0 || $8 > 1) bad=1; prev=$2 }
         END { exit bad }' "$dir/b.csv" || fail "body gaps or fractions out of range"
"$bin" simulate --function body --components 3 --target-betas 1 -0.5 --method sls --trials 1 \
  --iterations 2 --quiet > /dev/null || fail "body with fixed target and sls"
"$bin" simulate --function body --components 3 --model female --trials 1 --iterations 1 --quiet \
  2>&1 >/dev/null | grep -qi "default" || fail "no note when falling back to the default model"

# Bad input: a clear message and a non-zero exit, never a crash.
for args in "--method nope" "--function nope" "--dims 0" "--grid 4" "--optimum 2" "--bogus 1" \
            "--function rosenbrock --optimum 0.5" "--function body --user argmax" \
            "--function body --jnd-mm -1" "--function body --target-betas 1 2 3 4 5 6 7 8 9 10 11" \
            "--function body --model /nonexistent.npz" "--function body --grid 7"; do
  if err=$("$bin" simulate $args --trials 1 --iterations 1 2>&1); then fail "accepted: $args"; fi
  echo "$err" | grep -qi "error" || fail "no error message for: $args"
done
echo "ok"
