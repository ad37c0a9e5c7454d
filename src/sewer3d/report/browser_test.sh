#!/usr/bin/env bash
# CTest report/browser (docs/report.md): builds a tiny workspace with a known bump
# (report_browser_fixture), opens its report in headless Chromium and checks it through the
# DevTools protocol (browser_test.mjs). Exit 77 (SKIP) when chromium or node is missing;
# scripts/install_deps.sh installs both.
# usage: browser_test.sh FIXTURE ARTIFACT_DIR
set -euo pipefail
fixture=$1
artifacts=$2
chromium=${CHROMIUM:-$(command -v chromium || command -v chromium-browser || true)}
if [ -z "$chromium" ]; then echo "SKIP: chromium not installed"; exit 77; fi
if ! command -v node >/dev/null; then echo "SKIP: node not installed"; exit 77; fi
ws=$(mktemp -d)
trap 'rm -rf "$ws"' EXIT
"$fixture" "$ws"
mkdir -p "$artifacts"
node "$(dirname "$0")/browser_test.mjs" "$chromium" \
  "$ws/report/index.html" "$ws/expected.json" "$artifacts/report_viewer.png"
