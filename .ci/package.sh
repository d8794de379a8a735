#!/usr/bin/env bash
# Packaging (README.md, *Packaging*): what would be published is complete and builds.
# 1. Our licence agrees everywhere and THIRD-PARTY-LICENSES is what tools/licenses.py writes from
#    Cargo.lock and the crates' own licence files.
# 2. The crates for crates.io (inbetween, inbetween-io, inbetween-commands, inbetween-cli) have
#    their publishing metadata (.ci/crate_metadata.py), and `cargo package --locked` packages
#    and verifies them together in dependency order (each built from its package alone; the
#    unpublished ones are read from a temporary local registry that overlays crates.io).
# 3. The Python distribution inbetween-rs: a manylinux2014 abi3 wheel and an sdist, checked by
#    auditwheel and tested installed in a fresh venv (tools/wheel/build.sh).
# Run from the repository root, after `cargo test` (the wheel's tests use target/debug/inbetween).
set -euo pipefail
cd "$(dirname "$0")/.."
export CARGO_TERM_COLOR=never
t0=$SECONDS

echo "== licences (python3 tools/licenses.py --check)"
python3 tools/licenses.py --check

echo "== crates' publishing metadata (.ci/crate_metadata.py)"
python3 .ci/crate_metadata.py

echo "== cargo package --locked (inbetween, inbetween-io, inbetween-commands, inbetween-cli)"
# --allow-dirty: a local run with uncommitted edits packages them as they are (CI's clone is
# clean either way); the packages hold only the files their manifests' `include` names.
cargo package --locked --allow-dirty -p inbetween -p inbetween-io -p inbetween-commands -p inbetween-cli
version="$(cargo metadata --locked --no-deps --format-version 1 | python3 -c 'import json,sys; print(next(p["version"] for p in json.load(sys.stdin)["packages"] if p["name"] == "inbetween"))')"
for name in inbetween inbetween-io inbetween-commands inbetween-cli; do
  crate="target/package/$name-$version.crate"
  echo "$crate: $(stat -c %s "$crate") bytes, $(tar -tzf "$crate" | wc -l) files"
done
echo "== crates packaged in $((SECONDS - t0)) s"

echo "== Python wheel and sdist (tools/wheel/build.sh)"
bash tools/wheel/build.sh
echo "== packaging checks done in $((SECONDS - t0)) s"
