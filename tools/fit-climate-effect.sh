#!/usr/bin/env bash
# Fits every region's climate effect (sylva::street::climate_effect) and writes
# crates/sylva/data/itree-streets/climate-effect.csv. Each region's every growable species is
# grown to 20, 30 and 40 cm DBH and set around the standard house at i-Tree's typical
# positions; the fit is what i-Tree Streets' energy figures hold beyond that shade, per m² of
# crown projection. About 5 minutes on 2 cores with a release build.
#
#   cargo build --release -p sylva-cli && tools/fit-climate-effect.sh
set -euo pipefail
cd "$(dirname "$0")/.."
sylva=${SYLVA:-target/release/sylva}
out=crates/sylva/data/itree-streets/climate-effect.csv
# The Urban Tree Database's 17 regions (street::climate::CLIMATES).
regions="CenFla GulfCo InlEmp InlVal InterW LoMidW MidWst NMtnPr NoCalC NoEast PacfNW Piedmt SacVal SoCalC SWDsrt TpIntW Tropic"
tmp=$(mktemp)
{
  echo "# Each region's climate effect per m² of crown projection, calibrated against i-Tree Streets'"
  echo "# energy figures (see crates/sylva/src/street/climate_effect.rs and docs/benefits.md)."
  echo "# Written by tools/fit-climate-effect.sh (seed 0); rerun it whenever the shade model or growth changes."
  echo "# points: calibration rows (species x DBH) the cooling fit read; deciduous_points and"
  echo "# evergreen_points: the rows the heating and useful winter share fit read together (the share"
  echo "# is empty where the region has no evergreen to fit it)."
  echo "region,cooling_kwh_per_m2,heating_kbtu_per_m2,useful_winter_share,points,deciduous_points,evergreen_points"
  for r in $regions; do
    "$sylva" rank --region "$r" --calibrate --fit
  done
} > "$tmp"
mv "$tmp" "$out"
cat "$out"
