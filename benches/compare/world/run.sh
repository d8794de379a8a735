#!/usr/bin/env bash
# Keys kept by `inbetween reduce --position-tolerance LEN` on public motion capture, against the
# per-joint --tolerance at the largest uniform angle that meets LEN in world space and against
# ozz-animation's optimizer rule (what each is: compare.py). Run by hand, not in CI:
#
#   bash benches/compare/world/run.sh [compare.py options]
#   bash benches/compare/world/run.sh --clips test_mocapbank,test_freebvh --lens 1
#   bash benches/compare/world/run.sh --schemes bezier,slerp
#   bash benches/compare/world/run.sh --schemes bezier,slerp --set held-out   (results-held-out.md)
#
# Builds the release binary (unless --bin is given), creates a venv with requirements.txt in
# $CARGO_TARGET_DIR/world-compare/venv, downloads the clips with
# benches/compare/reduce/fetch_clips.sh (never committed) to $CARGO_TARGET_DIR/reduce-compare/clips
# (shared with the reduce comparison), prints the tables and writes them to
# benches/compare/world/results.md (--out FILE elsewhere).
# compare.py options: --bin PATH, --set tuned|held-out, --clips a,b, --reuse-a JSON, --lens 0.5,1,2 (cm), --schemes bezier,slerp,
# --tau-fractions 0.1,0.25,0.5, --steps 12, --ozz-distances 0,10 (cm), --timeout S, --json FILE,
# --out FILE, --work DIR.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(cd "$here/../../.." && pwd)"
target="${CARGO_TARGET_DIR:-$root/target}"
venv="$target/world-compare/venv"
if [ ! -x "$venv/bin/python" ] || ! cmp -s "$here/requirements.txt" "$venv/requirements.txt"; then
  python3 -m venv "$venv"
  "$venv/bin/pip" install -q --only-binary=:all: -r "$here/requirements.txt"
  cp "$here/requirements.txt" "$venv/requirements.txt"
fi
clips="$target/reduce-compare/clips"
if [[ " $* " == *" --set held-out "* ]]; then
  clips="$target/world-compare/held-out"
  bash "$here/fetch_held_out.sh" "$clips" >/dev/null
else
  bash "$root/benches/compare/reduce/fetch_clips.sh" "$clips" "$venv/bin/pip"
fi
args=("$@")
if [[ " $* " != *" --bin "* ]]; then
  (cd "$root" && cargo build --release -q)
  args=(--bin "$target/release/inbetween" "${args[@]}")
fi
exec "$venv/bin/python" "$here/compare.py" --clip-dir "$clips" \
  --command "bash benches/compare/world/run.sh $*" "${args[@]}"
