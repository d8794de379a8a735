#!/usr/bin/env bash
# Whole-process comparison of `inbetween interp` with scipy and numpy-quaternion (issue 6).
# Run by hand, not in CI:   bash benches/compare/run.sh [--frames 1000000] [--repeat 5]
# Creates benches/compare/.venv (numpy, scipy, numpy-quaternion), builds the release binary, and
# prints medians and ratios measured in one run.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(cd "$here/../.." && pwd)"
if [ ! -x "$here/.venv/bin/python" ]; then
  python3 -m venv "$here/.venv"
  "$here/.venv/bin/pip" install -q numpy scipy numpy-quaternion
fi
(cd "$root" && cargo build --release -q)
exec "$here/.venv/bin/python" "$here/compare.py" --bin "$root/target/release/inbetween" "$@"
