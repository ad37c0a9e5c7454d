#!/usr/bin/env bash
# Fails when a C++ file differs from .clang-format (Google base, 100 columns); lists them.
# Fix with: clang-format -i FILES. Run by CTest (repo/format) and so by scripts/test.sh.
set -euo pipefail
cd "$(dirname "$0")/.."
if git rev-parse --is-inside-work-tree >/dev/null 2>&1; then
  mapfile -t files < <(git ls-files '*.cpp' '*.hpp' '*.h')
else
  mapfile -t files < <(find src bench -name '*.cpp' -o -name '*.hpp' -o -name '*.h')
fi
bad=()
for f in "${files[@]}"; do
  [ -f "$f" ] || continue
  clang-format --dry-run -Werror "$f" >/dev/null 2>&1 || bad+=("$f")
done
if [ ${#bad[@]} -gt 0 ]; then
  printf 'not clang-formatted: %s\n' "${bad[@]}"
  echo "format: ${#bad[@]} of ${#files[@]} files differ (clang-format -i them)"
  exit 1
fi
echo "format: all ${#files[@]} files follow .clang-format"
