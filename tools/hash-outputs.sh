#!/usr/bin/env bash
# Hashes every kind of file Sylva writes, so a refactor can prove it changed no byte:
#   tools/hash-outputs.sh [path/to/sylva] > before.txt   (on the old commit)
#   tools/hash-outputs.sh [path/to/sylva] > after.txt    (on the new one)
#   diff before.txt after.txt                             (must print nothing)
# Covers every built-in species at seeds 0-2 (GLB), OBJ + MTL, previews and renders, LOD
# chains, a forest, grown street trees (GLB, PNG, CSV, charts, comparison sheets), Nagel's
# fractal, whisk and stick trees (GLB, SVG, PNG, P/L vector files), line drawings of every view,
# Fields' three species (GLB, .tree, PNG), a street tree on a site (accounts, benefit bars,
# site pictures), three regions' ranks, and an Arbaro file. Pictures are drawn on the CPU
# rasteriser, the one backend whose bytes do not depend on the machine's driver.
set -euo pipefail
sylva=$(realpath "${1:-target/release/sylva}")
repo=$(cd "$(dirname "$0")/.." && pwd)
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
export SYLVA_RENDERER=cpu
cd "$out"
q() { "$sylva" "$@" > /dev/null; }

for id in $("$sylva" species list | awk '{print $1}'); do
  for seed in 0 1 2; do
    q generate "$id" --seed "$seed" -o "$id-$seed.glb"
  done
  q generate "$id" --quality 0.5 -o "$id.obj" --preview "$id-preview.png"
done
q generate quaking_aspen --lod-chain -o aspen-lod-chain.glb
q generate black_tupelo --levels 2 --no-leaves -o tupelo-bare.glb
q render black_tupelo --size 640x360 --view iso -o tupelo-iso.png
q render quaking_aspen --size 320x240 --turntable 4 -o aspen-turntable.png
q forest --species quaking_aspen,hazel,black_tupelo --count 40 --area 60x60 -o forest.glb
q render forest.glb --size 480x270 -o forest.png
q grow PLAC --from 10 --to 20 --step 10 --compare MAGR,CESI4 --size 300x300 -o grown
q grow PLAC --from 1 --to 8 --site "$repo/sites/narrow-under-wires.toml" --size 300x300 -o street
"$sylva" rank --region InlVal --years 4 --site "$repo/sites/boulevard.toml" --json > rank.jsonl
# Three regions' rankings in all, one of them on the narrow site with its pruning cycles.
"$sylva" rank --region NoEast --years 4 --json > rank-noeast.jsonl
"$sylva" rank --region PacfNW --years 4 --site "$repo/sites/narrow-under-wires.toml" --json > rank-pacfnw.jsonl
q fractal --depth 10 --leaves --vary-angle 8 -o fractal.glb -o fractal.svg -o fractal.png -o fractal.vec
q whisk --profile "$repo/profiles/conifer.csv" --density 4 --rings 6 --spokes 8 -o whisk.glb -o whisk.svg
q whisk --profile "$repo/profiles/vase.svg" -o vase.glb -o vase.png
q stick --branches "$repo/profiles/sticks.csv" --ribs 6 -o stick.glb -o stick.vec
for view in front side top perspective overlay; do
  q draw quaking_aspen --view "$view" -o "aspen-$view.svg"
done
q draw quaking_aspen -o aspen.vec -o aspen-front.png
q draw PLAC --age 20 --view top -o plac-plan.svg
for s in black_oak balsam_fir weeping_cherry; do
  q lobes "$s" -o "lobes-$s.glb" -o "lobes-$s.tree" -o "lobes-$s.png"
done
arbaro="$repo/../shared/data/arbaro-species/black_tupelo.xml"
if [ -e "$arbaro" ]; then
  q generate "$arbaro" -o arbaro-black_tupelo.obj
fi
find . -type f | LC_ALL=C sort | xargs sha256sum
