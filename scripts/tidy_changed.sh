#!/usr/bin/env bash
# clang-tidy (.clang-tidy) on the C++ sources changed since the commit in .ci/tidy-base, with
# the build's compile_commands.json; warnings are errors. After a clean run a session may move
# .ci/tidy-base to HEAD. usage: tidy_changed.sh BUILD_DIR
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
base=$(tr -d '[:space:]' < .ci/tidy-base)
if ! git rev-parse --is-inside-work-tree >/dev/null 2>&1 || ! git cat-file -e "$base^{commit}" 2>/dev/null; then
  echo "tidy: no git history with $base here; nothing to compare against"
  exit 0
fi
mapfile -t files < <(git diff --name-only --diff-filter=AM "$base" -- 'src/*.cpp' 'bench/*.cpp' | sort)
existing=()
for f in "${files[@]}"; do [ -f "$f" ] && existing+=("$f"); done
if [ ${#existing[@]} -eq 0 ]; then
  echo "tidy: no C++ source changed since ${base:0:12}"
  exit 0
fi
echo "tidy: ${#existing[@]} source(s) changed since ${base:0:12}"
jobs=$(nproc 2>/dev/null || echo 2)
printf '%s\n' "${existing[@]}" |
  xargs -P "$jobs" -n 4 clang-tidy -p "$build" --quiet --warnings-as-errors='*' 2>/dev/null
echo "tidy: clean"
