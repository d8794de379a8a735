# Sourced by .ci/run, .ci/blender.sh and tools/wheel/build.sh: `cached_venv VENV REQUIREMENTS`
# makes the virtual environment VENV (under target/, ignored by git, kept between local runs)
# with the pinned REQUIREMENTS, wheels only, never a source build. It is rebuilt when missing,
# or when the requirements file or the interpreter changed since it was built (stamp file
# VENV/.installed); otherwise left as it is.
cached_venv() {
  local venv="$1" req="$2" stamp
  stamp="$(python3 --version 2>&1; cat "$req")"
  if [ ! -x "$venv/bin/python" ] || [ "$(cat "$venv/.installed" 2>/dev/null)" != "$stamp" ]; then
    echo "== python venv ($venv, $req)"
    rm -rf "$venv"
    python3 -m venv "$venv"
    "$venv/bin/python" -m pip install -q --disable-pip-version-check --only-binary=:all: -r "$req"
    printf '%s\n' "$stamp" >"$venv/.installed"
  fi
}
