#!/usr/bin/env bash
# Keys kept by `inbetween reduce` on public motion capture, against the slerp-greedy rule and
# glTF-Transform's resample() rule (issue 15; figures in docs/reduce.md). Run by hand, not in CI:
#
#   bash benches/compare/reduce/run.sh [compare.py options]
#   bash benches/compare/reduce/run.sh --seconds 2 --configs bezier:optimal:vel,bezier:greedy:vel
#
# Builds the release binary (unless --bin is given), creates a venv with requirements.txt in
# $CARGO_TARGET_DIR/reduce-compare/venv, downloads the clips (fetch_clips.sh; never committed) to
# $CARGO_TARGET_DIR/reduce-compare/clips, and prints the tables (compare.py: what each rule is).
# compare.py options: --bin PATH, --clips a,b, --seconds S [--offset S], --tolerances 0.25,0.5,
# --configs scheme:method:vel|novel,..., --methods greedy,optimal, --replay all|none|list,
# --timeout S (per reduce run), --json FILE.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(cd "$here/../../.." && pwd)"
target="${CARGO_TARGET_DIR:-$root/target}"
venv="$target/reduce-compare/venv"
if [ ! -x "$venv/bin/python" ] || ! cmp -s "$here/requirements.txt" "$venv/requirements.txt"; then
  python3 -m venv "$venv"
  "$venv/bin/pip" install -q --only-binary=:all: -r "$here/requirements.txt"
  cp "$here/requirements.txt" "$venv/requirements.txt"
fi
bash "$here/fetch_clips.sh" "$target/reduce-compare/clips" "$venv/bin/pip"
args=("$@")
if [[ " $* " != *" --bin "* ]]; then
  (cd "$root" && cargo build --release -q)
  args=(--bin "$target/release/inbetween" "${args[@]}")
fi
exec "$venv/bin/python" "$here/compare.py" --clip-dir "$target/reduce-compare/clips" "${args[@]}"
