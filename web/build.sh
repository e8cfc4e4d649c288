#!/bin/sh
# Bundles the page into dist/, which the server embeds (include_str!).
# Deterministic: no timestamps, no source map, pinned esbuild; running it
# twice gives the same bytes, and CI checks dist/ is what this produces.
set -eu
cd "$(dirname "$0")"
if [ ! -x node_modules/.bin/esbuild ]; then
  npm ci --no-audit --no-fund
fi
mkdir -p dist
node_modules/.bin/esbuild src/main.js \
  --bundle --minify --format=iife --target=es2020 \
  --legal-comments=none --charset=utf8 --log-level=warning \
  --outfile=dist/page.js
cp src/index.html src/page.css dist/
