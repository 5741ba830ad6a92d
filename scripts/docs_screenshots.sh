#!/usr/bin/env bash
# Makes the pictures in docs/ that the README links: the first command's image, the maps of
# door seen side by side, and compare's page on desk, each page shot by headless Chromium
# (Debian's `chromium`). About 3 minutes on 2 cores (the desk reference render included).
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release
fp=target/release/footprint
tmp=$(mktemp -d)
shoot() { # URL OUT WIDTH HEIGHT
  chromium --no-sandbox --headless --disable-gpu --disable-background-networking \
    --disable-component-update --no-first-run --hide-scrollbars \
    --user-data-dir="$(mktemp -d)" --screenshot="$2" --window-size="$3,$4" "$1" 2>/dev/null
}
"$fp" render scenes/desk/desk.toml --out "$tmp/desk.exr"
cp "$tmp/desk.png" docs/desk.png
"$fp" maps scenes/door/door.toml --out "$tmp/maps-door"
cat > "$tmp/maps.html" <<HTML
<!DOCTYPE html><html><head><meta charset="utf-8"><style>body{font-family:sans-serif;margin:16px}
img{width:512px;image-rendering:pixelated}.row{display:flex;gap:16px}.c{text-align:center}
</style></head><body><div class="row"><div class="c"><img src="maps-door/photons.png"><br>door: photons.png</div>
<div class="c"><img src="maps-door/importons.png"><br>door: importons.png</div></div></body></html>
HTML
shoot "file://$tmp/maps.html" docs/maps-door.png 1090 640
"$fp" compare scenes/desk/desk.toml --resolution 128x128 --time 8 \
  --reference-cache "$tmp" --out "$tmp/compare-desk"
shoot "file://$tmp/compare-desk/index.html" docs/compare-desk.png 1100 1790
echo "wrote docs/desk.png docs/maps-door.png docs/compare-desk.png"
