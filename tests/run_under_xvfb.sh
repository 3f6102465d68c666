#!/usr/bin/env bash
# run_under_xvfb.sh COMMAND [ARGS...] - runs COMMAND with DISPLAY set to a fresh Xvfb server
# that this script starts (on a free display number, chosen by Xvfb itself via -displayfd) and
# stops afterwards. Exits with COMMAND's status, or 77 (ctest SKIP_RETURN_CODE) with a message
# when Xvfb is not installed or cannot start.
set -u
if ! command -v Xvfb >/dev/null 2>&1; then
  echo "SKIP: Xvfb is not installed (Debian package xvfb, listed in third_party/packages.txt)"
  exit 77
fi
dir=$(mktemp -d)
trap 'kill "$xvfb_pid" 2>/dev/null; wait "$xvfb_pid" 2>/dev/null; rm -rf "$dir"' EXIT
xvfb_pid=0
# 24-bit colour: the swapchain's B8G8R8A8 images map 1:1 to the X visual.
Xvfb -displayfd 3 -screen 0 1280x1024x24 -nolisten tcp 3>"$dir/display" 2>"$dir/xvfb.log" &
xvfb_pid=$!
for _ in $(seq 1 100); do
  [ -s "$dir/display" ] && break
  kill -0 "$xvfb_pid" 2>/dev/null || break
  sleep 0.1
done
if [ ! -s "$dir/display" ]; then
  echo "SKIP: Xvfb did not start within 10 s:"
  cat "$dir/xvfb.log"
  exit 77
fi
export DISPLAY=":$(head -n1 "$dir/display")"
echo "run_under_xvfb: Xvfb on DISPLAY=$DISPLAY"
"$@"
