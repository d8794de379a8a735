#!/usr/bin/env bash
# The batch benchmark of docs/performance.md (issue 28): one folder of real clips reduced by
#   (1) inbetween reduce DIR --out-dir … --jobs 1
#   (2) inbetween reduce DIR --out-dir … --jobs 2
#   (3) a shell loop starting one inbetween process per clip
#   (4) examples/python/dask_batch.py on a two-worker LocalCluster (its start included)
# interleaved, RUNS times each, wall-clock medians. Run by hand, not in CI:
#
#   bash benches/compare/batch/run.sh [COPIES] [RUNS]
#
# The clips are the reduce comparison's eight (benches/compare/reduce/fetch_clips.sh, never
# committed), COPIES copies of each (default 4: 32 files). Needs the release binary and the
# Python package with dask installed in target/py-venv (.ci/run builds it).
set -euo pipefail
root="$(cd "$(dirname "$0")/../../.." && pwd)"
target="${CARGO_TARGET_DIR:-$root/target}"
copies="${1:-4}"
runs="${2:-3}"
bin="$target/release/inbetween"
py="$target/py-venv/bin/python"
clips="$target/reduce-compare/clips"
bash "$root/benches/compare/reduce/fetch_clips.sh" "$clips" >/dev/null
(cd "$root" && cargo build --release -q -p inbetween-cli)
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
mkdir -p "$work/in"
for c in $(seq 1 "$copies"); do
  for f in "$clips"/*.bvh; do cp "$f" "$work/in/$(basename "$f" .bvh)_$c.bvh"; done
done
n=$(ls "$work/in" | wc -l)
opts=(--tolerance 0.5 --translation-tolerance 0.1 --output-format json)
declare -A times
time_of() { local t0 t1; t0=$(date +%s.%N); "$@" >/dev/null 2>&1; t1=$(date +%s.%N); echo "$t1 - $t0" | bc; }
for r in $(seq 1 "$runs"); do
  rm -rf "$work"/o*
  times[jobs1]+="$(time_of "$bin" reduce "$work/in" "${opts[@]}" --out-dir "$work/o1" --jobs 1) "
  times[jobs2]+="$(time_of "$bin" reduce "$work/in" "${opts[@]}" --out-dir "$work/o2" --jobs 2) "
  mkdir -p "$work/o3"
  times[loop]+="$(time_of bash -c "for f in '$work'/in/*.bvh; do '$bin' reduce \"\$f\" ${opts[*]} -o '$work'/o3/\$(basename \"\$f\" .bvh).json; done") "
  times[dask]+="$(time_of "$py" "$root/examples/python/dask_batch.py" "$work/in" "$work/o4" --command reduce --workers 2 -- "${opts[@]}") "
  cmp -s <(cd "$work/o1" && cat $(ls)) <(cd "$work/o2" && cat $(ls)) || { echo "jobs 1 and 2 differ" >&2; exit 1; }
  cmp -s <(cd "$work/o2" && cat $(ls)) <(cd "$work/o3" && cat $(ls)) || { echo "loop differs" >&2; exit 1; }
  cmp -s <(cd "$work/o2" && cat $(ls)) <(cd "$work/o4" && cat $(ls)) || { echo "dask differs" >&2; exit 1; }
done
median() { tr ' ' '\n' | grep . | sort -g | awk '{a[NR]=$1} END {print (NR%2 ? a[(NR+1)/2] : (a[NR/2]+a[NR/2+1])/2)}'; }
j1=$(echo "${times[jobs1]}" | median); j2=$(echo "${times[jobs2]}" | median)
lp=$(echo "${times[loop]}" | median); dk=$(echo "${times[dask]}" | median)
echo "$n files ($copies copies of the 8 clips), $runs runs each, wall medians (s), $(git -C "$root" rev-parse --short HEAD)"
printf '| run | wall s | ratio to --jobs 2 |\n|---|---|---|\n'
for k in "jobs 1:$j1" "jobs 2:$j2" "shell loop:$lp" "dask 2 workers:$dk"; do
  printf '| %s | %.2f | %.2f |\n' "${k%%:*}" "${k#*:}" "$(echo "${k#*:} / $j2" | bc -l)"
done
echo "every run's outputs identical across the four (cmp)"
