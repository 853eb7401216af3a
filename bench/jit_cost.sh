#!/usr/bin/env bash
# What llvmpipe's JIT of the path tracer costs for one shader tree against another, in alternating rounds: each
# round renders the default scene (16x16, 3 spp) with an empty Mesa cache and a warm SPIR-V cache, and takes the
# first frame minus the median of the later ones (the first trace compiles the pipeline to machine code). Also
# checks that the trees render the same image (RMSE against the first tree's render at 64x64, 16 spp).
#   bash bench/jit_cost.sh [-b build/workbench] [-r rounds] TREE... [-- render flags]
# TREE is a folder holding a shaders/ tree (e.g. the repository root, or a copy with one file changed).
# Results and the breakdown they gave: docs/bench/lavapipe_jit_cost.md.
set -euo pipefail
wb=build/workbench
rounds=5
while [ $# -gt 0 ]; do
  case $1 in
    -b) wb=$2; shift 2 ;;
    -r) rounds=$2; shift 2 ;;
    *) break ;;
  esac
done
flags=()
trees=()
while [ $# -gt 0 ]; do
  if [ "$1" = -- ]; then
    shift
    flags=("$@")
    break
  fi
  trees+=("$(realpath "$1")")
  shift
done
[ ${#trees[@]} -gt 0 ] || { echo "usage: bash bench/jit_cost.sh [-b BIN] [-r ROUNDS] TREE... [-- RENDER FLAGS]" >&2; exit 2; }
wb=$(realpath "$wb")
repo=$(cd "$(dirname "$0")/.." && pwd)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
# Mesa's cache folder is chosen by hand below, so the width is too (vk/driver_env.h sets both together).
export LP_NATIVE_VECTOR_WIDTH=${LP_NATIVE_VECTOR_WIDTH:-128}

root_of() {  # a project root for tree $1: its shaders/, the repository's assets/
  local r=$tmp/root$2
  if [ ! -d "$r" ]; then
    mkdir -p "$r"
    ln -s "$1/shaders" "$r/shaders"
    ln -s "$repo/assets" "$r/assets"
  fi
  echo "$r"
}

i=0
for t in "${trees[@]}"; do
  r=$(root_of "$t" $i)
  # Warm the SPIR-V cache and render the image the trees are compared on.
  ref=()
  [ $i -gt 0 ] && ref=(--reference "$tmp/img0.exr")
  WB_ROOT=$r WB_SHADER_CACHE_DIR=$tmp/spv$i MESA_SHADER_CACHE_DIR=$tmp/mesa_img$i \
    "$wb" render --size 64x64 --spp 16 "${flags[@]}" --out "$tmp/img$i.exr" --stats "$tmp/img$i.json" "${ref[@]}" >/dev/null
  i=$((i + 1))
done

for round in $(seq 1 "$rounds"); do
  i=0
  for t in "${trees[@]}"; do
    r=$(root_of "$t" $i)
    rm -rf "$tmp/mesa"
    WB_ROOT=$r WB_SHADER_CACHE_DIR=$tmp/spv$i MESA_SHADER_CACHE_DIR=$tmp/mesa \
      "$wb" render --size 16x16 --spp 3 "${flags[@]}" --out "$tmp/cold.png" --stats "$tmp/cold_${round}_$i.json" >/dev/null
    python3 - "$tmp/cold_${round}_$i.json" "$i" >>"$tmp/rows" <<'PY'
import json, sys, statistics
s = json.load(open(sys.argv[1]))
f = s["frame_seconds"]
print(sys.argv[2], (f[0] - statistics.median(f[1:])) * 1000.0, s["shader_cache"]["compiles"])
PY
    i=$((i + 1))
  done
done

python3 - "$tmp" "${#trees[@]}" "${trees[@]}" <<'PY'
import json, sys, statistics
tmp, n, trees = sys.argv[1], int(sys.argv[2]), sys.argv[3:]
rows = [l.split() for l in open(f"{tmp}/rows")]
print("| tree | JIT ms per round | median | glslang compiles | RMSE vs first tree | rays (64x64, 16 spp) |")
print("|---|---|---|---|---|---|")
for i, t in enumerate(trees):
    ms = [float(r[1]) for r in rows if int(r[0]) == i]
    comp = {r[2] for r in rows if int(r[0]) == i}
    img = json.load(open(f"{tmp}/img{i}.json"))
    rmse = img.get("error_vs_reference", {}).get("rmse", 0.0) if i else 0.0
    print(f"| {t} | {' '.join(f'{m:.0f}' for m in ms)} | {statistics.median(ms):.0f} | {','.join(sorted(comp))} | "
          f"{rmse:.3g} | {img['rays']} |")
PY
