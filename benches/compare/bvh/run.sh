#!/usr/bin/env bash
# Whole-process BVH benchmark (issue 14): a 10-minute 120 fps clip with 60 joints (generated,
# deterministic, ~127 MiB) read, resampled to 60 fps and written as BVH by
# `inbetween interp clip.bvh --fps 60 -o out.bvh`, side by side with bvhio 1.5.4 reading the same
# file, keeping every other frame (bvhio cannot resample by time; see bvhio_resample.py) and
# writing a BVH. Alternating runs, medians, peak RSS (ru_maxrss), ratio measured in one run.
# Run by hand, not in CI:   bash benches/compare/bvh/run.sh [--repeat 5]
# Where inbetween's time and memory go (stages cut short, no profiler):   bash benches/compare/bvh/run.sh --stages
# Python: $BVHIO_PYTHON if set, else $CARGO_TARGET_DIR/ci-venv (created from
# fixtures/requirements.txt, wheels only, when missing). The clip and the outputs go to
# $CARGO_TARGET_DIR/bench-bvh/ (default target/), never into the repository.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(cd "$here/../../.." && pwd)"
target="${CARGO_TARGET_DIR:-$root/target}"
py="${BVHIO_PYTHON:-$target/ci-venv/bin/python}"
if [ ! -x "$py" ]; then
  python3 -m venv "$target/ci-venv"
  "$target/ci-venv/bin/pip" install -q --only-binary=:all: -r "$root/fixtures/requirements.txt"
  py="$target/ci-venv/bin/python"
fi
"$py" -c 'import importlib.metadata as m; v = m.version("bvhio"); assert v == "1.5.4", v'
(cd "$root" && cargo build --release -q)
work="$target/bench-bvh"
mkdir -p "$work"
clip="$work/clip120_10min_60j.bvh"
if [ ! -f "$clip" ]; then
  python3 "$here/gen_clip.py" "$clip.part" --minutes 10 --fps 120
  mv "$clip.part" "$clip"
fi
echo "clip sha256: $(sha256sum "$clip" | cut -d' ' -f1)"
exec "$py" "$here/bench.py" --bin "$target/release/inbetween" --clip "$clip" --outdir "$work" "$@"
