#!/bin/sh
# Runs tests/e2e/page.mjs against a fresh `graftal serve`:
#   web/e2e.sh [GRAFTAL_BINARY] [SCREENSHOT_OUT]
# It serves a scratch pfg file, reads the URL the server prints
# ("graftal serve: open http://127.0.0.1:PORT/"), runs the test and stops
# the server. Needs web/node_modules (npm ci) and Chromium
# ($GRAFTAL_CHROMIUM, by default /usr/bin/chromium).
set -eu
here=$(cd "$(dirname "$0")" && pwd)
graftal=${1:-"$here/../target/debug/graftal"}
shot=${2:-"$(mktemp -d)/picture.png"}
work=$(mktemp -d)
printf 'angle factor: 4\naxiom: F-F-F-F\nF --> F-F+F+FF-F-F+F\n' > "$work/koch.l"

"$graftal" serve --port 0 "$work/koch.l" > "$work/out" 2> "$work/err" &
server=$!
trap 'kill "$server" 2>/dev/null || true; rm -rf "$work"' EXIT

url=""
for _ in $(seq 1 60); do
  url=$(sed -n 's|.*open \(http://[^ ]*\).*|\1|p' "$work/out" | head -n 1)
  [ -n "$url" ] && break
  kill -0 "$server" 2>/dev/null || break
  sleep 0.5
done
if [ -z "$url" ]; then
  echo "e2e: graftal serve printed no URL within 30 s" >&2
  cat "$work/err" >&2
  exit 1
fi
node "$here/../tests/e2e/page.mjs" "$url" "$shot"
