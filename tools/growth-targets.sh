#!/usr/bin/env bash
# Issue BB's growth targets, an old release build against a new one, run one after the other
# (docs/growth-speed.md):
#   tools/growth-targets.sh OLD_SYLVA NEW_SYLVA INVENTORY.csv [PRE_W_SYLVA]
# INVENTORY is a street-tree census in the NYC 2015 layout (about 10,000 rows). Needs curl,
# python3 and bc; writes its working files in a temporary folder.
set -u
OLD=$(realpath "$1"); NEW=$(realpath "$2"); INV=$(realpath "$3"); PREW=${4:-}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
echo "== grow PLAC to 60"
for i in 1 2 3; do for b in $OLD $NEW; do rm -rf g60; /usr/bin/time -f "grow60 $(basename $b) %e s" $b grow PLAC --region InlVal --from 60 --to 60 --no-pictures -o g60 > /dev/null 2>t.txt; tail -1 t.txt; done; done
echo "== bench --growth"
for b in ${PREW:+$(realpath "$PREW")} $OLD $NEW; do echo "$(basename $b)"; $b bench --growth 2>&1 | grep -E "^ +[0-9]+ +[0-9.]+ "; done
port=8400
page() {
  port=$((port+1))
  $1 serve --port $port > /dev/null 2>&1 & pid=$!
  for i in $(seq 100); do curl -s localhost:$port/api/regions >/dev/null && break; sleep 0.1; done
  for i in $(seq 600); do g=$(curl -s localhost:$port/api/status | python3 -c "import json,sys;print(json.load(sys.stdin)['growing'])"); [ "$g" = 0 ] && break; sleep 0.2; done
  s=$(date +%s.%N); code=$(curl -s -o g.json -w "%{http_code}" "localhost:$port/api/growth?region=InlVal&species=$2"); e=$(date +%s.%N)
  kill -9 $pid; wait $pid 2>/dev/null
  echo "page $2 $(basename $1) http $code $(echo "$e - $s" | bc) s rows $(python3 -c "import json;print(len(json.load(open('g.json'))['rows']))" 2>/dev/null)"
}
echo "== page"
for sp in ACSA1 ZESE CICA; do page $OLD $sp; page $NEW $sp; done
echo "== bench --city 10000"
for b in $OLD $NEW; do /usr/bin/time -f "benchcity $(basename $b) %e s" $b bench --city 10000 --runs 1 > bc_$(basename $b).log 2>&1; tail -6 bc_$(basename $b).log; done
echo "== city"
for b in $OLD $NEW; do rm -rf city_$(basename $b); /usr/bin/time -f "city $(basename $b) %e s %M KB" $b city $INV --years 0,20 --report --no-cache -o city_$(basename $b) > city_$(basename $b).log 2>&1; tail -2 city_$(basename $b).log; done
echo DONE
