#!/usr/bin/env bash
# Build the Blender extension zip: the inbetween wheel bundled into a copy of
# blender/inbetween_blender (wheels/ and the manifest's `wheels` list written there, the source
# tree left as it is), built and validated by Blender's own extension builder
# (bl_pkg/cli/blender_ext.py, shipped in the bpy wheel's scripts).
#
#   blender/build.sh [WHEEL]
#
# WHEEL: a prebuilt wheel, or a folder holding one (inbetween*.whl, whatever the distribution's
# name: the manylinux wheel of the release script); without it the wheel is built from
# crates/inbetween-py by `pip wheel` (maturin pinned in its pyproject.toml). The zip is written
# to target/blender/ and its path printed last.
#
# Environment: PYTHON (default target/bpy-venv/bin/python, else python3) runs the builder;
# BLENDER_EXT the path of blender_ext.py (default: found in that interpreter's bpy).
set -euo pipefail
cd "$(dirname "$0")/.."
out=target/blender
stage="$out/stage/inbetween_blender"
python="${PYTHON:-target/bpy-venv/bin/python}"
[ -x "$python" ] || python=python3

ext="${BLENDER_EXT:-}"
if [ -z "$ext" ]; then
  ext="$("$python" - <<'EOF'
import glob, importlib.util, os, sys
spec = importlib.util.find_spec("bpy")
if spec is None:
    sys.exit("build.sh: no bpy in this interpreter: set PYTHON or BLENDER_EXT")
root = os.path.dirname(spec.origin)
found = sorted(glob.glob(os.path.join(root, "*", "scripts", "addons_core", "bl_pkg", "cli", "blender_ext.py")))
if not found:
    sys.exit(f"build.sh: no bl_pkg/cli/blender_ext.py under {root}")
print(found[-1])
EOF
)"
fi

wheel_arg="${1:-}"
rm -rf "$out/stage" "$out/wheel"
mkdir -p "$out/wheel"
if [ -n "$wheel_arg" ]; then
  if [ -d "$wheel_arg" ]; then
    mapfile -t wheels < <(find "$wheel_arg" -maxdepth 1 -name 'inbetween*.whl' | sort)
  else
    wheels=("$wheel_arg")
  fi
  if [ "${#wheels[@]}" -ne 1 ] || [ ! -f "${wheels[0]}" ]; then
    echo "build.sh: expected one inbetween*.whl at $wheel_arg, found ${#wheels[@]}: ${wheels[*]:-none}" >&2
    exit 2
  fi
  cp "${wheels[0]}" "$out/wheel/"
else
  echo "== pip wheel --no-deps ./crates/inbetween-py" >&2
  python3 -m pip wheel -q --disable-pip-version-check --no-deps ./crates/inbetween-py -w "$out/wheel" >&2
fi
wheel="$(find "$out/wheel" -maxdepth 1 -name 'inbetween*.whl' | head -n 1)"
[ -n "$wheel" ] || { echo "build.sh: no inbetween*.whl was made" >&2; exit 1; }
case "$(basename "$wheel")" in
  *linux*x86_64.whl) ;;
  *) echo "build.sh: $(basename "$wheel") is not a linux x86_64 wheel (the manifest's platform, linux-x64)" >&2; exit 2 ;;
esac

mkdir -p "$stage/wheels"
cp -r blender/inbetween_blender/. "$stage/"
rm -rf "$stage/__pycache__" "$stage/wheels"/*
cp "$wheel" "$stage/wheels/"
"$python" - "$stage/blender_manifest.toml" "wheels/$(basename "$wheel")" <<'EOF'
import re, sys
path, wheel = sys.argv[1], sys.argv[2]
text = open(path, encoding="utf-8").read()
new, n = re.subn(r"(?m)^wheels = \[.*?\]$", f'wheels = ["./{wheel}"]', text)
if n != 1:
    sys.exit(f"build.sh: {path}: expected one line `wheels = [...]`, found {n}")
open(path, "w", encoding="utf-8").write(new)
EOF

echo "== blender_ext.py build ($(basename "$wheel"))" >&2
"$python" "$ext" build --source-dir "$stage" --output-dir "$out" >&2
version="$(sed -n 's/^version = "\(.*\)"$/\1/p' "$stage/blender_manifest.toml")"
zip="$out/inbetween-$version.zip"
[ -f "$zip" ] || { echo "build.sh: the builder wrote no $zip" >&2; exit 1; }
echo "== blender_ext.py validate $zip" >&2
"$python" "$ext" validate "$zip" >&2
echo "$zip"
