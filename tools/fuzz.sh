#!/usr/bin/env bash
# Builds the libFuzzer targets (tests/fuzz/, clang with -fsanitize=fuzzer,address,undefined)
# into build/fuzz and runs each for SECONDS (default 60), nproc at a time, from the committed
# seed corpora (tests/fuzz/corpus/<target>/; new inputs go to build/fuzz/corpus/<target>/).
# Prints executions and crashes per target; exits 1 if any target crashed (the input is kept
# under build/fuzz/artifacts/ -- turn it into an ordinary regression test). Exits 77 without
# running anything when clang is missing, so that ctest reports fuzz.smoke as skipped (its
# SKIP_RETURN_CODE) instead of passed.
#   tools/fuzz.sh [SECONDS] [TARGET...]
#   tools/fuzz.sh --seeds BUILD_DIR   regenerate the committed seeds with BUILD_DIR's
#                                     fuzz_corpus_writer (after changing the fixtures)
set -uo pipefail
cd "$(dirname "$0")/.."
root=$PWD

if [ "${1:-}" = "--seeds" ]; then
  writer="${2:-build}/tests/fuzz_corpus_writer"
  [ -x "$writer" ] || { echo "fuzz: $writer not built (cmake --build build --target fuzz_corpus_writer)"; exit 1; }
  rm -rf tests/fuzz/corpus && mkdir -p tests/fuzz/corpus && "$writer" tests/fuzz/corpus
  exit $?
fi

seconds=${1:-60}
shift || true
targets=("$@")
[ ${#targets[@]} -gt 0 ] || targets=(npy npz_model session plane_search)

if ! command -v clang++ >/dev/null || ! command -v clang >/dev/null; then
  echo "fuzz: NOTICE: clang is not installed; the fuzz run is SKIPPED" \
       "(bash tools/setup.sh --test installs clang and libclang-rt-14-dev)"
  exit 77
fi

build=build/fuzz
launcher=()
command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache)
cmake -S tests/fuzz -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_C_COMPILER=clang \
      -DCMAKE_CXX_COMPILER=clang++ "${launcher[@]}" >"$build.configure.log" 2>&1 ||
  { cat "$build.configure.log"; echo "fuzz: configuring the fuzz targets failed"; exit 1; }
cmake --build "$build" -j"$(nproc)" >"$build.build.log" 2>&1 ||
  { tail -50 "$build.build.log"; echo "fuzz: building the fuzz targets failed"; exit 1; }

mkdir -p "$build/artifacts"
# One target's run: its summary line goes to $build/$t.summary, a finding also to stdout.
fuzz_target() {
  local t=$1 seeds="tests/fuzz/corpus/$1" work="$build/corpus/$1" log="$build/$1.log"
  local stamp="$build/$1.started" rc execs crashes
  mkdir -p "$work"
  touch "$stamp"
  echo "fuzz: $t for ${seconds}s (seeds: $(ls "$seeds" | wc -l) files in $seeds)"
  # One process, one core; an input that needs over 2 GB or 30 s is a finding too.
  ASAN_OPTIONS=detect_leaks=1:allocator_may_return_null=1 \
  UBSAN_OPTIONS=print_stacktrace=1 \
    nice "$build/fuzz_$t" -max_total_time="$seconds" -print_final_stats=1 -timeout=30 \
      -rss_limit_mb=2048 -malloc_limit_mb=2048 -artifact_prefix="$build/artifacts/$t-" \
      "$work" "$seeds" >"$log" 2>&1
  rc=$?
  execs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$' | tail -1)
  crashes=$(find "$build/artifacts" -name "$t-*" -newer "$stamp" | wc -l)
  echo "$t: ${execs:-?} executions in ${seconds}s, exit $rc, $crashes crash/timeout/oom input(s)" \
    >"$build/$t.summary"
  if [ $rc -ne 0 ]; then
    { echo "fuzz: FINDING in $t:"
      grep -m 20 -E "ERROR|SUMMARY|runtime error|abort|Test unit written" "$log" || true; } |
      flock "$build/artifacts" cat
  fi
  return $rc
}
# As many targets at once as there are cores: each runs single-threaded for the same
# SECONDS, so the smoke run takes SECONDS per nproc targets instead of per target (in CI the
# other tests have mostly finished by the time the sanitizer build is done).
jobs_max=$(nproc)
# A summary left by an earlier run must not stand in for a run that died before writing one.
for t in "${targets[@]}"; do rm -f "$build/$t.summary"; done
running=0
status=0
for t in "${targets[@]}"; do
  if [ $running -ge "$jobs_max" ]; then
    wait -n || status=1
    running=$((running - 1))
  fi
  fuzz_target "$t" &
  running=$((running + 1))
done
while [ $running -gt 0 ]; do
  wait -n || status=1
  running=$((running - 1))
done
echo "fuzz summary:"
for t in "${targets[@]}"; do
  printf '  %s\n' "$(cat "$build/$t.summary" 2>/dev/null || echo "$t: no summary (the run did not finish)")"
done
exit $status
