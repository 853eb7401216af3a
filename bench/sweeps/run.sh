#!/usr/bin/env bash
# Measures `workbench sweep` on the single-node Slurm cluster of scripts/slurm-local.sh against --local (not a
# test: the numbers go to docs/bench/sweeps.md):
#   1. the 200-run sweep (sweep200.json, 32x32) here with -j 2, then under Slurm: every task image bit for bit,
#      the reports equal except timings;
#   2. the same under Slurm with 10% of the runs cancelled mid-run (scancel), then `sweep resume --wait`;
#   3. a 1000-run sweep (sweep1000.json): its submission (real sbatch; its jobs cancelled right after), and its
#      merge on the real outputs of the same sweep run here;
#   4. `sweep status` of that 1000-task sweep.
# Run as root from the repository root after building: bash bench/sweeps/run.sh [OUT_FOLDER]
set -euo pipefail
wb=${WB:-$PWD/build/workbench}
spec=$PWD/bench/sweeps
out=${1:-/tmp/wb-sweep-bench}
rm -rf "$out"
mkdir -p "$out"
bash scripts/slurm-local.sh start

now() { date +%s.%N; }
since() { awk -v a="$1" -v b="$(now)" 'BEGIN { printf "%.2f", b - a }'; }
say() { echo "== $*"; }

# compare A B: task images bit for bit, each scene's converge.csv without its timing columns (seconds,
# seconds_min, seconds_max, efficiency), the error images.
compare() {
  local a=$1 b=$2 n=0 bad=0 f
  while IFS= read -r f; do
    n=$((n + 1))
    cmp -s "$a/$f" "$b/$f" || { bad=$((bad + 1)); echo "  differs: $f"; }
  done < <(cd "$a" && find tasks -name '*.exr' | sort)
  local nb
  nb=$(cd "$b" && find tasks -name '*.exr' | wc -l)
  [ "$n" = "$nb" ] || { echo "  image count differs: $n vs $nb"; bad=$((bad + 1)); }
  local csvs=0 csvbad=0
  for f in $(cd "$a/report" && ls -- */converge.csv); do
    csvs=$((csvs + 1))
    diff <(cut -d, -f1-3,7-18 "$a/report/$f") <(cut -d, -f1-3,7-18 "$b/report/$f") >/dev/null ||
      { csvbad=$((csvbad + 1)); echo "  report differs: $f"; }
  done
  local pngs=0 pngbad=0
  for f in $(cd "$a/report" && ls -- */error_*.png); do
    pngs=$((pngs + 1))
    cmp -s "$a/report/$f" "$b/report/$f" || { pngbad=$((pngbad + 1)); echo "  differs: $f"; }
  done
  echo "  compared $a with $b: $n task images ($bad differ), $csvs converge.csv without timings ($csvbad differ), $pngs error images ($pngbad differ)"
}

count() { # count DIR STATE
  "$wb" sweep status --json "$1" | awk -v s="\"$2\"" '$1 == s":" { gsub(/[^0-9]/, "", $2); print $2 }'
}

echo "machine: $(nproc) cores, $(awk '/MemTotal/ {printf "%.0f GB", $2 / 1048576}' /proc/meminfo), load $(cut -d' ' -f1-3 /proc/loadavg)"
echo "date: $(date -u +%Y-%m-%dT%H:%MZ), commit $(git rev-parse --short HEAD)"
"$wb" render --size 8x8 --spp 1 --out "$out/warm.png" >/dev/null # shader cache warm

sections=${SECTIONS:-1 2 3 4}
has() { case " $sections " in *" $1 "*) return 0 ;; *) return 1 ;; esac; }

if has 1 || has 2; then
say "1. 200 runs here (-j 2)$(has 1 && echo " and under Slurm")"
t=$(now)
"$wb" sweep "$spec/sweep200.json" --local -j 2 --out "$out/local200" >"$out/local200.log" 2>&1
echo "  local: $(since "$t") s"
fi
if has 1; then
t=$(now)
"$wb" sweep "$spec/sweep200.json" --slurm --wait --out "$out/slurm200" >"$out/slurm200.log" 2>&1
echo "  slurm (submit to merged): $(since "$t") s"
compare "$out/local200" "$out/slurm200"
fi

if has 2; then
say "2. 200 runs under Slurm, 10% cancelled mid-run, then resume"
t=$(now)
"$wb" sweep "$spec/sweep200.json" --slurm --out "$out/cancel200" >"$out/cancel200.log" 2>&1
while [ "$(count "$out/cancel200" done)" -lt 60 ]; do sleep 1; done
# 20 runs not done yet: two killed while they run (caught by polling `sweep status`: a run lasts well under a
# second here), and pending ones spread over the rest of the sweep.
queued() {
  "$wb" sweep status --json "$out/cancel200" | awk '
    /"id":/ { id = $2 } /"job":/ { job = $2 } /"state":/ { st = $2
      if (id !~ /ref/ && job != "\"\",") { gsub(/[",]/, "", job); gsub(/[",]/, "", st); print st, job } }'
}
killed=""
for _ in $(seq 600); do
  r=$(queued | awk '$1 == "running" { print $2; exit }')
  if [ -n "$r" ]; then
    scancel "$r"
    killed="$killed $r"
    [ "$(echo $killed | wc -w)" -ge 2 ] && break
  fi
  sleep 0.05
done
pending=$(queued | awk '$1 == "pending" { print $2 }' | awk 'NR % 3 == 1' | head -n $((20 - $(echo $killed | wc -w))))
jobs="$pending"
echo "  at $(count "$out/cancel200" done) done: killed $(echo $killed | wc -w) running runs ($killed), cancelling $(echo $pending | wc -w) pending: $(echo $pending | tr '\n' ' ')"
# shellcheck disable=SC2086
scancel $jobs
while [ "$(count "$out/cancel200" pending)" != 0 ] || [ "$(count "$out/cancel200" running)" != 0 ]; do sleep 1; done
echo "  after the cancel: $(count "$out/cancel200" done) done, $(count "$out/cancel200" failed) failed"
"$wb" sweep resume --wait "$out/cancel200" >"$out/resume200.log" 2>&1
echo "  resumed: $(grep -o 'resuming [0-9]* of [0-9]* task(s)' "$out/resume200.log"); complete after $(since "$t") s in all"
compare "$out/local200" "$out/cancel200"
fi

if has 3 || has 4; then
say "3. 1000 runs: submission, and merge of real outputs"
for i in 1 2 3; do
  rm -rf "$out/submit1000"
  t=$(now)
  "$wb" sweep "$spec/sweep1000.json" --slurm --out "$out/submit1000" >"$out/submit1000.log" 2>&1
  echo "  submit (spec read and checked, scripts, 3 sbatch): $(since "$t") s"
  # shellcheck disable=SC2046
  scancel $(awk '/"job":/ { gsub(/[",]/, "", $2); print $2 } /"merge":/ { gsub(/[",]/, "", $2); print $2 }' "$out/submit1000/slurm/jobs.json")
done
t=$(now)
"$wb" sweep "$spec/sweep1000.json" --local -j 2 --out "$out/local1000" >"$out/local1000.log" 2>&1
echo "  the 1001 tasks here (-j 2) with their merge: $(since "$t") s"
for i in 1 2 3; do
  t=$(now)
  "$wb" sweep merge "$out/local1000" >/dev/null
  echo "  merge of 1001 task results: $(since "$t") s"
done
du -sh "$out/local1000/tasks" | awk '{print "  task outputs: " $1}'

say "4. status of 1001 tasks"
for i in 1 2 3; do
  t=$(now)
  "$wb" sweep status "$out/local1000" >/dev/null
  echo "  status: $(since "$t") s"
done
grep -A8 "^| seconds | mean" "$out/local1000/report/summary.md"
grep "^Shader cache" "$out/local1000/report/summary.md"
fi
echo "machine load at the end: $(cut -d' ' -f1-3 /proc/loadavg)"
