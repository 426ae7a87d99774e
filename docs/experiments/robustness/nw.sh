#!/bin/sh
# Usage: nw.sh FAIR DATA.csv: nurbs-weights on DATA at offsets 0 and 1e5, wall time of each.
fair=$1; data=$2; tmp=$(mktemp -d)
for off in 0 100000; do
  python3 - "$off" "$data" > "$tmp/in.csv" <<'PY'
import sys, csv
off = float(sys.argv[1]); rows = list(csv.reader(open(sys.argv[2])))
print(','.join(rows[0]))
for r in rows[1:]:
    if r: print(','.join(repr(float(v) + off) for v in r))
PY
  s=$(date +%s.%N); "$fair" curve "$tmp/in.csv" --method nurbs-weights -o "$tmp/out.csv" >/dev/null 2>&1; rc=$?; e=$(date +%s.%N)
  echo "offset $off: exit $rc, $(echo "$e - $s" | bc) s"
done
rm -r "$tmp"
