#!/usr/bin/env bash
# What the web renderer's test (tests/test_web.cpp, docs/web.md) needs: Debian's
# chromium-headless-shell (apt-get, when missing; apart from packages.txt, so that a machine
# without it still builds the rest), and web/'s npm packages (web/package-lock.json: three, and
# for the test puppeteer-core and meshoptimizer) in web/node_modules by `npm ci`. Idempotent:
# does nothing when both are there and node_modules matches the lock. Exit 77 when there is no
# Node.js at all; any other failure is an error (1).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
web="$root/web"
sudo=""
[ "$(id -u)" -eq 0 ] || sudo="sudo"
if ! dpkg-query -W -f='${Status}' chromium-headless-shell 2>/dev/null | grep -q 'install ok installed'; then
  echo "jade: installing Debian's chromium-headless-shell (the web renderer's test)" >&2
  export DEBIAN_FRONTEND=noninteractive
  { $sudo apt-get update -qq && $sudo apt-get install -y -qq --no-install-recommends chromium-headless-shell >/dev/null; } ||
    { echo "jade: cannot install chromium-headless-shell: the web renderer's test cannot run" >&2; exit 1; }
fi
if ! command -v node >/dev/null 2>&1; then
  echo "jade: no Node.js (node) on this machine: the web renderer's packages cannot be installed" >&2
  exit 77
fi
if ! command -v npm >/dev/null 2>&1; then
  echo "jade: installing Debian's npm (Node.js is here, npm is not)" >&2
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends npm >/dev/null ||
    { echo "jade: cannot install npm: web/'s packages cannot be installed" >&2; exit 1; }
fi
# npm ci records what it installed in node_modules/.package-lock.json; a copy of the lock beside
# it says which lock that was.
stamp="$web/node_modules/.jade-package-lock.json"
if [ -f "$stamp" ] && cmp -s "$stamp" "$web/package-lock.json"; then
  exit 0
fi
exec 9>"$web/.install.lock"
flock 9
if [ -f "$stamp" ] && cmp -s "$stamp" "$web/package-lock.json"; then
  exit 0
fi
(cd "$web" && npm ci --no-audit --no-fund --loglevel=error >&2) ||
  { echo "jade: npm ci in web/ failed (three, puppeteer-core and meshoptimizer from the npm registry)" >&2; exit 1; }
cp "$web/package-lock.json" "$stamp"
echo "jade: installed web/'s npm packages into web/node_modules" >&2
