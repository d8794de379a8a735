#!/usr/bin/env bash
# The Blender extension (blender/, docs/blender.md): headless Blender as the `bpy` module from
# PyPI — 5.0.1 (layered actions) in target/bpy-venv and 4.2 LTS in target/bpy42-venv (the legacy
# action API), pinned by blender/requirements-test*.txt, kept between local runs and rebuilt when
# the requirements or the interpreter change, like .ci/run's venvs — the extension built and
# validated by Blender 5.0.1's own extension builder (blender/build.sh; INBETWEEN_WHEEL=PATH
# bundles a prebuilt wheel instead of building one), then blender/tests on both Blenders, which
# compare with the command line (target/debug/inbetween, built here when .ci/run has not).
set -euo pipefail
cd "$(dirname "$0")/.."
start=$(date +%s)

if ! python3 -c 'import sys; sys.exit(sys.version_info[:2] != (3, 11))'; then
  echo "bpy 4.2 and 5.0 need CPython 3.11; python3 is $(python3 --version 2>&1)" >&2
  exit 1
fi
. .ci/venv.sh
cached_venv target/bpy-venv blender/requirements-test.txt
cached_venv target/bpy42-venv blender/requirements-test-4.2.txt

echo "== blender/build.sh ${INBETWEEN_WHEEL:-(wheel from crates/inbetween-py)}"
zip="$(PYTHON=target/bpy-venv/bin/python blender/build.sh ${INBETWEEN_WHEEL:+"$INBETWEEN_WHEEL"} | tail -n 1)"

echo "== blender_ext.py validate, Blender 4.2 LTS's (the zip's floor, blender_version_min)"
target/bpy42-venv/bin/python "$(find target/bpy42-venv -path '*/bl_pkg/cli/blender_ext.py' | head -n 1)" validate "$zip"

echo "== cargo build --locked -p inbetween-cli (the command line the tests compare with)"
cargo build --locked -q -p inbetween-cli

# FBX output (docs/spec.md §3, FBX output) imported by Blender 5.0.1's own FBX importer and
# compared with the tool's frames at every frame (its self-test first: a shifted frame fails).
echo "== FBX output read by Blender's importer (fixtures/fbx/check_written.py --self-test)"
mkdir -p target/blender
if target/bpy-venv/bin/python fixtures/fbx/check_written.py --self-test target/debug/inbetween \
    >target/blender/fbx-written.log 2>&1; then
  grep -E '^(ok|self-test)' target/blender/fbx-written.log
else
  grep -E '^(ok|FAIL|self-test|Traceback|[A-Za-z]*Error)' target/blender/fbx-written.log
  echo "fixtures/fbx/check_written.py failed (whole log: target/blender/fbx-written.log)" >&2
  exit 1
fi

for venv in target/bpy-venv target/bpy42-venv; do
  version="$("$venv/bin/python" -c 'import bpy; print(bpy.app.version_string)' 2>/dev/null | tail -n 1)"
  echo "== blender/tests on Blender $version ($venv, $zip)"
  log="target/blender/tests-${version%% *}.log"
  if INBETWEEN_BLENDER_ZIP="$zip" INBETWEEN_REQUIRE_CLI=1 INBETWEEN_BIN="$PWD/target/debug/inbetween" \
      "$venv/bin/python" -m pytest -q -s -p no:cacheprovider blender/tests >"$log" 2>&1; then
    grep '^FIGURES' "$log" || true
    tail -n 1 "$log"
  else
    tail -n 60 "$log"
    echo "blender/tests failed on Blender $version (whole log: $log)" >&2
    exit 1
  fi
done
echo "== .ci/blender.sh: $(($(date +%s) - start)) s"
