# Shared by the real-window tests (sourced, not run): a scratch folder, the app's process
# cleaned up on exit, failure reporting with the app's log, polling, and finding the window.
# The sourcing script sets `set -euo pipefail` first and starts the app with its output in
# "$T/log" and its pid in APP_PID.
T=$(mktemp -d)
APP_PID=
cleanup() {
  if [[ -n "$APP_PID" ]]; then kill "$APP_PID" 2>/dev/null || true; fi
  rm -rf "$T"
}
trap cleanup EXIT
fail() {
  echo "FAIL: $*"
  echo "--- app log (layout lines left out)"
  grep -v '^\[layout\]' "$T/log" 2>/dev/null || true
  exit 1
}
wait_for() {  # wait_for SECONDS COMMAND...: poll until the command succeeds
  local limit=$1
  shift
  for ((i = 0; i < limit * 10; ++i)); do
    if "$@"; then return 0; fi
    sleep 0.1
  done
  return 1
}
shown() {  # shown KIND PATTERN: the window showed a message of that kind matching the pattern
  grep -qs "^\[message\] $1 .*$2" "$T/log"
}
shown_any() {  # shown_any KIND: the window showed a message of that kind
  grep -qs "^\[message\] $1 " "$T/log"
}
wait_for_window() {  # sets WIN once the app has reported its grid and its window exists
  wait_for 30 grep -qs '^\[layout\] cell 9 ' "$T/log" || fail "no window / grid within 30 s"
  WIN=$(xdotool search --sync --name '^Sequential Gallery$')
  WIN=${WIN%%$'\n'*}  # the first window; not `| head -1`, which races with pipefail
  [[ -n "$WIN" ]] || fail "window not found"
  sleep 1  # let GLFW/ImGui take focus
}
