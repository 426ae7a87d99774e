#!/bin/sh
# Reproduces docs/experiments/readers.md: FAIR=path/to/fair sh docs/experiments/readers/run.sh
# (the files it writes go to a fresh temporary directory).
FAIR=${FAIR:-fair}
cd "$(mktemp -d)"
python3 - <<'PY'
import math
pts=[(k/20, math.sin(3*k/20)*0.3) for k in range(21)]
open('yx.txt','w').write('y x\n'+''.join(f'{y} {x}\n' for x,y in pts))
cells=[(i,j,float(i),float(j),0.1*i*j+(0.05 if (i+j)%3==0 else 0)) for i in range(6) for j in range(5)]
open('ij.csv','w').write('i,j,x,y,z\n'+''.join(f'{i},{j},{x},{y},{z}\n' for i,j,x,y,z in cells))
open('xyzij.csv','w').write('x,y,z,i,j\n'+''.join(f'{x},{y},{z},{i},{j}\n' for i,j,x,y,z in cells))
open('jixyz.csv','w').write('j,i,x,y,z\n'+''.join(f'{j},{i},{x},{y},{z}\n' for i,j,x,y,z in cells))
import json
open('id.json','w').write('{"zulu": 1, "id": 12345678901234567890123, "points": '+json.dumps([list(p) for p in pts])+', "alpha": 1.50}\n')
open('dup.json','w').write('{"points": '+json.dumps([list(p) for p in pts])+',\n"units": "m",\n"units": "mm"}\n')
open('labels.csv','w').write('x,y, note \n'+''.join(f'{x},{y},  st {k} \n' for k,(x,y) in enumerate(pts)))
sw=list(pts); sw[5],sw[6]=sw[6],sw[5]
open('swapped.csv','w').write('x,y\n'+''.join(f'{x},{y}\n' for x,y in sw))
rows=''.join(f'{k/500000},{math.sin(k/50000)}\r' for k in range(500000))
open('cr.csv','w').write('x,y\r'+rows+'1,oops\r')
PY
echo "== y x whitespace table, file and stdin (--kind function holds only if x is the column named x)"
$FAIR curve yx.txt -o - -q --kind function | head -3
$FAIR curve - -o - -q --kind function < yx.txt | head -2
echo "== grids by name: outputs of x,y,z,i,j and j,i,x,y,z against i,j,x,y,z"
$FAIR surface ij.csv -o - -q | sort > ij.out
$FAIR surface xyzij.csv -o - -q | awk -F, 'NR>1{print $4","$5","$1","$2","$3} NR==1{print "i,j,x,y,z"}' | sort > xyzij.out
$FAIR surface jixyz.csv -o - -q | awk -F, 'NR>1{print $2","$1","$3","$4","$5} NR==1{print "i,j,x,y,z"}' | sort > jixyz.out
cmp ij.out xyzij.out && echo "x,y,z,i,j: same cells as i,j,x,y,z"
cmp ij.out jixyz.out && echo "j,i,x,y,z: same cells as i,j,x,y,z"
echo "== JSON other keys"
$FAIR curve id.json -o - -q | grep -n '"zulu"\|"id"\|"points"\|"alpha"'
$FAIR curve dup.json -o - -q; echo "exit $?"
echo "== labels"
$FAIR curve labels.csv -o - -q --method nurbs-weights | head -3 | cat -A | head -3
echo "== swapped x"
$FAIR curve swapped.csv -o - 2>&1 >/dev/null | grep note
$FAIR curve swapped.csv -o - --kind function >/dev/null; echo "exit $?"
echo "== CR-only 500 000-point file with a bad last line"
ls -l cr.csv | awk '{print $5" bytes"}'
$FAIR curve cr.csv -o - 2> cr.err; echo "exit $?"; wc -c cr.err; cat cr.err
echo "== swapped x: the first station's x after fairing (default method)"
$FAIR curve swapped.csv -o - -q | sed -n 2p
