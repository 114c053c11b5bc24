#!/usr/bin/env bash
# Builds the browser playground into web/dist/: static files (index.html,
# the bundled JavaScript, the WebAssembly module) that any static host
# serves. Installs what it needs the first time: the wasm32-unknown-unknown
# target (rustup), the wasm-bindgen command line at the version of the
# crate that web/Cargo.toml pins (cargo install, into target/, about 4 min
# once), the npm packages of web/package-lock.json (npm ci: CodeMirror,
# esbuild, binaryen's wasm-opt, playwright-core).
#
#   bash web/build.sh
#   python3 -m http.server -d web/dist --bind 127.0.0.1 8000   # then open http://127.0.0.1:8000/
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
export CARGO_TARGET_DIR="$root/target"

version=$(sed -n 's/^wasm-bindgen = "=\(.*\)"$/\1/p' web/Cargo.toml)
if command -v rustup >/dev/null; then
    rustup target add wasm32-unknown-unknown >/dev/null 2>&1
fi
cli="$root/target/wasm-bindgen-cli/$version/bin/wasm-bindgen"
if [ ! -x "$cli" ]; then
    echo "installing wasm-bindgen-cli $version into target/wasm-bindgen-cli/$version (once)"
    cargo install -q wasm-bindgen-cli --version "$version" --root "$root/target/wasm-bindgen-cli/$version"
fi

cargo build -q --release --locked --manifest-path web/Cargo.toml --target wasm32-unknown-unknown
pkg="$root/target/web/pkg"
rm -rf "$pkg"
"$cli" --target web --no-typescript --out-dir "$pkg" target/wasm32-unknown-unknown/release/rayrepl_web.wasm
# wasm-opt from npm's binaryen (Debian 12's binaryen 108 breaks the
# reference types wasm-bindgen uses), for size: about 25 s.
if [ ! -d web/node_modules/esbuild ] || [ web/package-lock.json -nt web/node_modules/.package-lock.json ]; then
    (cd web && npm ci --no-audit --no-fund --loglevel=error)
fi
if ! web/node_modules/.bin/wasm-opt -Oz --enable-bulk-memory --enable-nontrapping-float-to-int --enable-sign-ext \
    --enable-mutable-globals --enable-reference-types --enable-multivalue \
    "$pkg/rayrepl_web_bg.wasm" -o "$pkg/rayrepl_web_bg.wasm"; then
    echo "note: wasm-opt (npm binaryen) did not run: the module is not optimised further"
fi

rm -rf web/dist
node web/build.mjs "$pkg" web/dist
cp "$pkg/rayrepl_web_bg.wasm" web/dist/
echo "built web/dist/ ($(du -sh web/dist | cut -f1)); serve it with: python3 -m http.server -d web/dist --bind 127.0.0.1 8000"
