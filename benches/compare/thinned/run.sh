#!/usr/bin/env bash
# Thinned motion capture against scipy's RotationSpline (what it measures: thinned.py). By hand:
#
#   bash benches/compare/thinned/run.sh --set held-out [thinned.py options]   (18 clips)
#   bash benches/compare/thinned/run.sh --set tuning [thinned.py options]     (the reduce clips)
#   bash benches/compare/thinned/run.sh [thinned.py options] CLIP.bvh|DIR ...
#
# thinned.py options: --bin PATH (default target/release/inbetween), --extra "ARGS" (passed to
# interp, e.g. --extra "--scheme bezier"), --ks 2,4,8,16, --out FILE.
# Creates a venv with numpy and scipy pinned as fixtures/requirements.txt in
# $CARGO_TARGET_DIR/thinned-venv (else target/thinned-venv); downloads the held-out clips with
# benches/compare/world/fetch_held_out.sh and the tuning clips with
# benches/compare/reduce/fetch_clips.sh when they are missing (never committed).
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(cd "$here/../../.." && pwd)"
target="${CARGO_TARGET_DIR:-$root/target}"
venv="$target/thinned-venv"
pins="numpy==2.4.6 scipy==1.17.1"
if [ ! -x "$venv/bin/python" ] || [ "$(cat "$venv/pins" 2>/dev/null)" != "$pins" ]; then
  python3 -m venv "$venv"
  "$venv/bin/pip" install -q --only-binary=:all: $pins
  echo "$pins" > "$venv/pins"
fi
command="bash benches/compare/thinned/run.sh $*"
args=()
while [ $# -gt 0 ]; do
  if [ "$1" = --set ]; then
    case "$2" in
      held-out)
        dir="$target/world-compare/held-out"
        [ -d "$dir" ] || bash "$root/benches/compare/world/fetch_held_out.sh" "$dir" >/dev/null ;;
      tuning)
        dir="$target/reduce-compare/clips"
        [ -d "$dir" ] || bash "$root/benches/compare/reduce/fetch_clips.sh" "$dir" "$venv/bin/pip" >/dev/null ;;
      *) echo "run.sh: --set held-out|tuning, found $2" >&2; exit 2 ;;
    esac
    args+=("$dir")
    shift 2
  else
    args+=("$1")
    shift
  fi
done
exec "$venv/bin/python" "$here/thinned.py" --command "$command" "${args[@]}"
