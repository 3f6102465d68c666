#!/usr/bin/env bash
# Checks that every C++ file in the tree is formatted by .clang-format, or with --fix formats them.
#   bash tools/check_format.sh          exit 1 and list the files that differ (ctest: format_check)
#   bash tools/check_format.sh --fix    rewrite them in place
# The style is pinned to clang-format 14 (Debian bookworm's, third_party/packages.txt): other
# versions break some lines differently, so the check refuses them rather than report noise.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"
fix=0
case "${1:-}" in
  --fix) fix=1 ;;
  "") ;;
  *) echo "usage: $0 [--fix]" >&2; exit 2 ;;
esac
if ! command -v clang-format >/dev/null; then
  echo "check_format: clang-format is not installed (bash third_party/install_deps.sh installs it)" >&2
  exit 2
fi
version=$(clang-format --version | sed -n 's/.*version \([0-9]*\)\..*/\1/p')
if [ "$version" != 14 ]; then
  echo "check_format: clang-format $version found; the style is pinned to version 14" >&2
  exit 2
fi
# The C++ sources: engine, samples, tests and tools (third_party and build folders are not ours).
if git rev-parse --is-inside-work-tree >/dev/null 2>&1; then
  mapfile -t files < <(git ls-files -- '*.cpp' '*.hpp' '*.h')
else
  mapfile -t files < <(find engine samples tests tools \( -name '*.cpp' -o -name '*.hpp' -o -name '*.h' \) | sort)
fi
if [ "$fix" = 1 ]; then
  clang-format -i --style=file "${files[@]}"
  echo "check_format: formatted ${#files[@]} files"
  exit 0
fi
bad=()
for f in "${files[@]}"; do
  if ! clang-format --dry-run -Werror --style=file "$f" >/dev/null 2>&1; then bad+=("$f"); fi
done
if [ "${#bad[@]}" -gt 0 ]; then
  echo "check_format: ${#bad[@]} of ${#files[@]} files are not formatted by .clang-format:" >&2
  printf '  %s\n' "${bad[@]}" >&2
  echo "check_format: run bash tools/check_format.sh --fix (clang-format 14)" >&2
  exit 1
fi
echo "check_format: ${#files[@]} files formatted"
