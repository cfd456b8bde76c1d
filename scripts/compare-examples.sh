#!/usr/bin/env bash
# Runs the shipped examples with two rheodda binaries and compares their outputs byte for byte
# (summary.json without its wall-clock fields). Usage: compare-examples.sh BASE_BIN NEW_BIN [examples...]
set -u
base=$1; new=$2; shift 2
ex=("$@")
[ ${#ex[@]} -eq 0 ] && ex=(shear-creep-test sliding-block power-law-creep-test damage-creep-test creeping-slope-failure goodman-toppling-creep rockmass/jointed-slope rockmass/tunnel goodman-toppling)
root=/work/main/examples
out=/tmp/cmp; rm -rf $out; mkdir -p $out
status=0
for e in "${ex[@]}"; do
  n=$(echo $e | tr / _)
  $base run $root/$e.yaml -o $out/base-$n > $out/base-$n.log 2>&1 &
  $new run $root/$e.yaml -o $out/new-$n > $out/new-$n.log 2>&1
  wait
  for f in $out/base-$n/summary.json $out/new-$n/summary.json; do
    python3 -c "import json,sys; d=json.load(open('$f')); [d.pop(k,None) for k in ['wall_seconds','solve_seconds','assembly_seconds','started','finished','rheodda_version','cpu_seconds']]; json.dump(d,open('$f.cmp','w'),indent=1,sort_keys=True)"
  done
  if diff -rq -x summary.json -x '*.log' -x .rheodda.lock -x checkpoint.json $out/base-$n $out/new-$n > /dev/null && diff -q $out/base-$n/summary.json.cmp $out/new-$n/summary.json.cmp >/dev/null; then
    echo "$e: identical"
  else
    echo "$e: DIFFERENT"; diff -rq -x summary.json -x .rheodda.lock -x checkpoint.json $out/base-$n $out/new-$n | head -5; diff $out/base-$n/summary.json.cmp $out/new-$n/summary.json.cmp | head -10; status=1
  fi
done
exit $status
