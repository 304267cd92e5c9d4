#!/usr/bin/env bash
# Screenshots of the built docs site as a reader sees it (an on-demand check, not in the
# suite): the home page and the coupling.yaml reference, by Debian's Chromium headless
# (installed here when missing), into build/docs-screenshots/. Look at them.
#   docs/screenshots.sh
set -euo pipefail
TOP=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
OUT="$TOP/build/docs-screenshots"
if ! command -v chromium > /dev/null; then
    echo "installing Debian's chromium (for the screenshots)"
    if [ "$(id -u)" -eq 0 ]; then apt-get install -y -qq --no-install-recommends chromium > /dev/null
    else sudo apt-get install -y -qq --no-install-recommends chromium > /dev/null; fi
fi
site=$(python3 "$TOP/docs/build.py" | tail -n 1)
site=$(dirname "$site")
mkdir -p "$OUT"
profile=$(mktemp -d)
trap 'rm -rf "$profile"' EXIT
for page in index.html reference/coupling-yaml/index.html reference/commands/index.html getting-started/own-bed/index.html validation/index.html; do
    name=$(echo "$page" | sed 's|/index.html||; s|\.html||; s|/|-|g')
    chromium --headless --no-sandbox --disable-gpu --disable-quic --no-first-run --disable-background-networking \
        --disable-component-update --disable-sync --user-data-dir="$profile" --window-size=1280,1600 \
        --screenshot="$OUT/$name.png" "file://$site/$page" > /dev/null 2>&1
    echo "$OUT/$name.png"
done
