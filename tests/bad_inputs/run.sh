#!/usr/bin/env bash
# The bad-input table: every case in cases.txt is one sewer3d command with malformed or extreme
# input, the exit code it must end with and a fragment its one stderr line must hold.
# Each case runs under a time limit and an address-space limit, so a hang or a memory blow-up
# fails its case instead of the machine.
#   SEWER3D=build/sewer3d bash tests/bad_inputs/run.sh [NAME_REGEX]
# With SEWER3D_SHARD=K/N only every N-th case from the K-th on runs, so CTest runs the table as
# N tests side by side. The fixtures take a minute to write: `run.sh --prepare DIR` writes them
# once into DIR, and SEWER3D_FIXTURES=DIR makes a run copy them from there (each shard its own
# copy: cases may write beside them) instead of writing its own.
set -u
S=${SEWER3D:?set SEWER3D to the sewer3d binary}
S=$(cd "$(dirname "$S")" && pwd)/$(basename "$S")
here=$(cd "$(dirname "$0")" && pwd)
if [ "${1:-}" = "--prepare" ]; then
  dir=${2:?--prepare needs a folder}
  rm -rf "$dir" && mkdir -p "$dir" || exit 1
  export S
  bash "$here/fixtures.sh" "$dir" || { echo "FAIL: fixtures"; exit 1; }
  touch "$dir/.complete"
  exit 0
fi
only=${1:-}
shard=${SEWER3D_SHARD:-1/1}
shard_k=${shard%/*}
shard_n=${shard#*/}
if ! [[ "$shard_k" =~ ^[1-9][0-9]*$ && "$shard_n" =~ ^[1-9][0-9]*$ ]] || ((shard_k > shard_n)); then
  echo "FAIL: SEWER3D_SHARD must be K/N with 1 <= K <= N, not '$shard'"
  exit 1
fi
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
export S T
# An address-space limit stops a memory blow-up; AddressSanitizer reserves terabytes of address
# space for its shadow, so an instrumented binary (ASAN_OPTIONS set) gets an RSS limit instead.
# Instrumented code runs several times slower: SLOW scales the time limits (cases use it too).
vlimit=6000000
SLOW=1
if [ -n "${ASAN_OPTIONS:-}" ]; then
  vlimit=unlimited
  SLOW=5
  export ASAN_OPTIONS="$ASAN_OPTIONS:hard_rss_limit_mb=6000"
fi
export SLOW

if [ -n "${SEWER3D_FIXTURES:-}" ]; then
  [ -f "$SEWER3D_FIXTURES/.complete" ] || { echo "FAIL: no fixtures in $SEWER3D_FIXTURES"; exit 1; }
  cp -a "$SEWER3D_FIXTURES/." "$T/" || { echo "FAIL: copying the fixtures"; exit 1; }
  # A workspace records its run's absolute path: point the copies' at the copied runs.
  from=$(cd "$SEWER3D_FIXTURES" && pwd)
  grep -rlF --include=workspace.json -- "$from" "$T" | while read -r f; do
    sed -i "s|$from/|$T/|g" "$f"
  done
else
  bash "$here/fixtures.sh" "$T" || { echo "FAIL: fixtures"; exit 1; }
fi

failures=0
cases=0
index=0
while IFS='|' read -r name want needle cmd; do
  case "$name" in '' | '#'*) continue ;; esac
  index=$((index + 1))
  (((index - 1) % shard_n == shard_k - 1)) || continue
  [[ -n "$only" && ! "$name" =~ $only ]] && continue
  cases=$((cases + 1))
  want=${want// /}
  needle=${needle#"${needle%%[![:space:]]*}"}
  needle=${needle%"${needle##*[![:space:]]}"}
  cd "$T" || exit 1
  (ulimit -v "$vlimit"; timeout -s KILL $((60 * SLOW)) bash -c "$cmd" </dev/null >"$T/out" 2>"$T/err")
  rc=$?
  why=""
  if [ "$rc" -eq 137 ]; then why="killed (hang or memory)";
  elif [ "$rc" -ne "$want" ]; then why="exit $rc, not $want";
  elif [ "$want" -ne 0 ]; then
    lines=$(wc -l <"$T/err")
    if [ "$lines" -ne 1 ]; then why="$lines stderr lines";
    elif ! grep -qF -- "$needle" "$T/err"; then why="no '$needle'";
    elif grep -q "check failed\|\.cpp:[0-9]\|terminate called\|json.exception\|OpenCV(\|bad_alloc\|libpng\|TIFFRead\|TIFFFetch" "$T/err"; then why="internals shown"; fi
  elif [ -n "$needle" ] && ! grep -qF -- "$needle" "$T/out" "$T/err"; then why="no '$needle'"; fi
  if [ -n "$why" ]; then
    failures=$((failures + 1))
    echo "FAIL $name: $why: $(head -c 300 "$T/err" | tr '\n' ' ')"
  else
    echo "ok   $name"
  fi
done <"$here/cases.txt"
echo "$((cases - failures)) of $cases cases pass"
[ "$failures" -eq 0 ]
