#!/usr/bin/env bash
# Times simit-run against the Eigen implementation on the same scene, side by
# side in one run: ROUNDS rounds, each running the Eigen implementation once
# and simit-run once per thread count of THREADS, N frames per run; each run
# reports the median ms/frame of frames 2..N, and the script prints, per
# scene and thread count, the median over rounds of both, their ratio
# (simit / eigen; the Eigen implementation runs on one thread), each one's
# assembly and solve parts (simit-run --time; the Eigen step's own timers),
# and simit-run's compile time without the compile cache (--no-cache).
#
#   bench/compare-simit-eigen.sh [build-dir]   (default: <repo>/build)
#   SCENES="springs-bunny fem-dragon"  FRAMES=20  ROUNDS=3  THREADS="1 2"
#   (scenes: springs-bunny, fem-bar, fem-dragon, fem-dragon-refined)
set -euo pipefail

repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${1:-$repo/build}"
frames="${FRAMES:-20}"
rounds="${ROUNDS:-3}"
threads="${THREADS:-1 $(nproc)}"
out="$(mktemp -d)"
trap 'rm -rf "$out"' EXIT

scene_file() {
  case "$1" in
    springs-bunny) echo "$repo/examples/springs/springs-bunny.json" ;;
    fem-dragon) echo "$repo/examples/fem/fem-dragon.json" ;;
    fem-dragon-refined) echo "$repo/examples/fem/fem-dragon-refined.json" ;;
    fem-bar) echo "$repo/examples/fem/fem-bar.json" ;;
    *) echo "unknown scene $1" >&2; exit 1 ;;
  esac
}
# The Eigen implementation's arguments for the same scene.
eigen_args() {
  case "$1" in
    fem-dragon-refined) echo "--scene fem-dragon --refine 1" ;;
    *) echo "--scene $1" ;;
  esac
}
median() { sort -g | awk '{v[NR]=$1} END {print v[int((NR+1)/2)]}'; }

printf '%-18s %7s %10s %10s %7s | %9s %9s | %9s %9s | %10s\n' scene threads \
  simit_ms eigen_ms ratio simit_asm simit_sol eigen_asm eigen_sol compile_ms
for scene in ${SCENES:-springs-bunny fem-dragon}; do
  for f in eigen eigen_asm eigen_sol; do : > "$out/$f"; done
  for t in $threads; do
    for f in simit compile simit_asm simit_sol; do : > "$out/$f.$t"; done
  done
  for ((r = 0; r < rounds; r++)); do
    # shellcheck disable=SC2046 # eigen_args is a list of arguments
    log=$("$build/bin/simit-bench-eigen" $(eigen_args "$scene") --frames "$frames")
    sed -n 's/^median .*total \([0-9.]*\) ms.*/\1/p' <<<"$log" >> "$out/eigen"
    sed -n 's/^median .*assembly \([0-9.]*\) ms.*/\1/p' <<<"$log" >> "$out/eigen_asm"
    sed -n 's/^median .*solve \([0-9.]*\) ms.*/\1/p' <<<"$log" >> "$out/eigen_sol"
    for t in $threads; do
      log=$("$build/bin/simit-run" --scene "$(scene_file "$scene")" --frames "$frames" \
        --time --no-progress --no-cache --threads "$t" --output-dir "$out")
      sed -n 's/^frame: *\([0-9.]*\) ms.*/\1/p' <<<"$log" >> "$out/simit.$t"
      sed -n 's/^  assembly: *\([0-9.]*\) ms.*/\1/p' <<<"$log" >> "$out/simit_asm.$t"
      sed -n 's/^  solve: *\([0-9.]*\) ms.*/\1/p' <<<"$log" >> "$out/simit_sol.$t"
      sed -n 's/^compile: *\([0-9.]*\) ms.*/\1/p' <<<"$log" >> "$out/compile.$t"
    done
  done
  m() { median < "$out/$1"; }
  e=$(m eigen)
  for t in $threads; do
    s=$(m "simit.$t")
    printf '%-18s %7s %10.2f %10.2f %7.2f | %9.2f %9.2f | %9.2f %9.2f | %10.1f\n' "$scene" "$t" \
      "$s" "$e" "$(awk -v s="$s" -v e="$e" 'BEGIN {print s / e}')" \
      "$(m "simit_asm.$t")" "$(m "simit_sol.$t")" "$(m eigen_asm)" "$(m eigen_sol)" \
      "$(m "compile.$t")"
  done
done
