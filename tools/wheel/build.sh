#!/usr/bin/env bash
# The Python distribution `inbetween-rs` as it is published: a portable wheel
# (cp39-abi3-manylinux_2_17_x86_64, that is manylinux2014: CPython 3.9 and later, glibc 2.17 and
# later) and an sdist, into target/dist/, then the package's tests against that wheel installed
# in a fresh venv. Run from anywhere; CI runs it from .ci/package.sh.
#
# 1. Tools: maturin, zig (the `ziglang` package) and auditwheel from PyPI, pinned in
#    tools/wheel/requirements.txt, in target/wheel-tools (kept between local runs, rebuilt when
#    that file or the interpreter changes; wheels only).
# 2. `maturin build --zig --compatibility manylinux2014`: zig compiles ufbx's C and links against
#    glibc 2.17's symbols whatever this machine's glibc; abi3 from pyo3's `abi3-py39` feature
#    (crates/inbetween-py/Cargo.toml); the `wheel` profile of pyproject.toml. Then the same
#    code again as `inbetween._inbetween_avx2`, for AVX2 without FMA (crates/inbetween-py/avx2),
#    added to the wheel by tools/wheel/add_module.py; the package imports it on CPUs with AVX2
#    (the same bits, tested; 1.3x less CPU for `Curve`, docs/performance.md). `maturin sdist`.
# 3. Checks that fail the script: the wheel's tags are cp39-abi3 and manylinux_2_17_x86_64;
#    `auditwheel show` finds it consistent with manylinux_2_17_x86_64 (or an older, more portable
#    policy); wheel and sdist carry LICENSE-MIT, LICENSE-APACHE and THIRD-PARTY-LICENSES and
#    declare `License-Expression: MIT OR Apache-2.0`; pyproject.toml's classifiers are all
#    known to trove-classifiers (PyPI refuses unknown ones); the sdist resolves offline to
#    exactly the versions Cargo.lock pins (cargo prunes the command line's crates from its copy).
# 4. A new venv (target/wheel-test-venv, made anew each run) with the pinned test requirements
#    (crates/inbetween-py/requirements-test.txt, wheels only) and the wheel; the module must be
#    imported from there, not from the source tree; then pytest on crates/inbetween-py/tests,
#    comparing with the debug command line (`cargo build` first: a no-op after `cargo test`) and
#    validating glTF with the Khronos validator (`npm ci --prefix tools/gltf-validator`) and the
#    checkers' Python (target/ci-venv), each made as .ci/run makes it when missing; all required.
set -euo pipefail
cd "$(dirname "$0")/../.."
root="$PWD"
t0=$SECONDS
step() { echo "== $1 ($((SECONDS - t0)) s)"; }

tools=target/wheel-tools
req=tools/wheel/requirements.txt
. .ci/venv.sh
cached_venv "$tools" "$req"

step "classifiers of crates/inbetween-py/pyproject.toml (trove-classifiers)"
"$tools/bin/python" - <<'EOF'
import sys, tomllib
from trove_classifiers import classifiers, deprecated_classifiers
project = tomllib.load(open("crates/inbetween-py/pyproject.toml", "rb"))["project"]
bad = [c for c in project["classifiers"] if c not in classifiers or c in deprecated_classifiers]
bad += [c for c in project["classifiers"] if c.startswith("License ::")]  # PEP 639: the expression only
if bad:
    sys.exit(f"pyproject.toml: classifiers PyPI would refuse: {bad}")
print(f"{len(project['classifiers'])} classifiers, all known")
EOF

dist=target/dist
# The features of the AVX2 module (src/lib.rs `cpu_has_avx2` tests for each of them).
avx2_flags="-C target-feature=+sse4.1,+sse4.2,+ssse3,+popcnt,+avx,+avx2"
rm -rf "$dist"
mkdir -p "$dist"
step "maturin build --zig --compatibility manylinux2014 (x86_64-unknown-linux-gnu)"
# maturin runs zig as `python -m ziglang` with the python on PATH: the tools' venv first.
PATH="$root/$tools/bin:$PATH" "$tools/bin/maturin" build --locked --zig --compatibility manylinux2014 \
  --target x86_64-unknown-linux-gnu --manifest-path crates/inbetween-py/Cargo.toml --out "$dist"
step "the AVX2 module: maturin build in crates/inbetween-py/avx2, RUSTFLAGS=\"$avx2_flags\""
# The same code compiled a second time for AVX2 and not FMA (a fused multiply-add rounds once
# where the portable code rounds twice: other bits), into its own target folder, and put beside
# the portable module in the wheel (tools/wheel/add_module.py refuses a fused instruction). The
# package imports it where the CPU has these features (python/inbetween/__init__.py);
# tests/test_simd.py holds its results to the portable module's bits (required below).
avx2_dist="$(mktemp -d)"
(cd crates/inbetween-py/avx2 && PATH="$root/$tools/bin:$PATH" CARGO_TARGET_DIR="$root/target/avx2" \
  RUSTFLAGS="$avx2_flags" "$root/$tools/bin/maturin" build --locked --zig --compatibility manylinux2014 \
  --target x86_64-unknown-linux-gnu --out "$avx2_dist")
"$tools/bin/python" tools/wheel/add_module.py "$dist"/*.whl "$avx2_dist"/*.whl
rm -rf "$avx2_dist"
step "maturin sdist"
PATH="$root/$tools/bin:$PATH" "$tools/bin/maturin" sdist --manifest-path crates/inbetween-py/Cargo.toml --out "$dist"

shopt -s nullglob
wheels=("$dist"/*.whl)
sdists=("$dist"/*.tar.gz)
if [ "${#wheels[@]}" -ne 1 ] || [ "${#sdists[@]}" -ne 1 ]; then
  echo "expected one wheel and one sdist in $dist, found: $(ls "$dist")" >&2
  exit 1
fi
wheel="${wheels[0]}"
sdist="${sdists[0]}"
ls -l "$wheel" "$sdist"

step "the wheel's tags and licence files"
"$tools/bin/python" - "$wheel" "$sdist" <<'EOF'
import re, sys, tarfile, zipfile
wheel, sdist = sys.argv[1], sys.argv[2]
problems = []
with zipfile.ZipFile(wheel) as z:
    names = z.namelist()
    info = next(n for n in names if n.endswith(".dist-info/WHEEL"))
    tags = re.findall(r"^Tag: (\S+)$", z.read(info).decode(), flags=re.M)
    meta = z.read(next(n for n in names if n.endswith(".dist-info/METADATA"))).decode()
    print("wheel tags:", " ".join(tags))
    if not any(t.startswith("cp39-abi3-manylinux_2_17_x86_64") or t == "cp39-abi3-manylinux2014_x86_64" for t in tags):
        problems.append(f"{wheel}: tags {tags}, expected cp39-abi3-manylinux_2_17_x86_64")
    for f in ("LICENSE-MIT", "LICENSE-APACHE", "THIRD-PARTY-LICENSES"):
        if not any(n.endswith(".dist-info/licenses/" + f) for n in names):
            problems.append(f"{wheel}: no {f} in its .dist-info/licenses/")
with tarfile.open(sdist) as t:
    snames = t.getnames()
    pkg_info = t.extractfile(next(n for n in snames if n.count("/") == 1 and n.endswith("/PKG-INFO"))).read().decode()
    for f in ("LICENSE-MIT", "LICENSE-APACHE", "THIRD-PARTY-LICENSES"):
        if not any(n.endswith("/" + f) for n in snames):
            problems.append(f"{sdist}: no {f}")
for what, m in (("wheel", meta), ("sdist", pkg_info)):
    if "License-Expression: MIT OR Apache-2.0" not in m.splitlines():
        problems.append(f"{what}: metadata has no `License-Expression: MIT OR Apache-2.0`")
    lic_files = sorted(re.findall(r"^License-File: (.+)$", m, flags=re.M))
    print(f"{what}: Name: {re.search(r'^Name: (.+)$', m, flags=re.M).group(1)}, License-File: {', '.join(lic_files)}")
if problems:
    sys.exit("\n".join(problems))
EOF

step "the sdist resolves offline to Cargo.lock's pins (cargo metadata --offline in it)"
# What pip does with the sdist, short of compiling: its Cargo.lock, pruned to the crates the
# sdist's workspace keeps, must pin every package to the version this repository's lock pins.
unpacked="$(mktemp -d)"
tar -xzf "$sdist" -C "$unpacked"
top="$(ls "$unpacked")"
cargo metadata --offline --format-version 1 --manifest-path "$unpacked/$top/Cargo.toml" >/dev/null
"$tools/bin/python" - Cargo.lock "$unpacked/$top/Cargo.lock" <<'EOF'
import sys, tomllib
repo, sdist = (tomllib.load(open(p, "rb"))["package"] for p in sys.argv[1:])
pins = {(p["name"], p["version"]) for p in repo}
extra = sorted(f"{p['name']} {p['version']}" for p in sdist if (p["name"], p["version"]) not in pins)
if extra or not sdist:
    sys.exit(f"the sdist resolves to versions Cargo.lock does not pin: {extra}")
print(f"{len(sdist)} packages, every one at the version Cargo.lock pins ({len(repo)} there)")
EOF
rm -rf "$unpacked"

step "auditwheel show"
audit="$("$tools/bin/auditwheel" show "$wheel")"
echo "$audit"
# auditwheel names the most portable policy the wheel's symbols allow: manylinux_2_17 or older.
policy="$(echo "$audit" | tr -s ' \n' ' ' | grep -oE 'consistent with the following platform tag: "manylinux_2_[0-9]+_x86_64"' | grep -oE 'manylinux_2_[0-9]+' || true)"
if [ -z "$policy" ] || [ "${policy#manylinux_2_}" -gt 17 ]; then
  echo "auditwheel: $wheel is not consistent with manylinux_2_17_x86_64 (found: ${policy:-no manylinux policy})" >&2
  exit 1
fi

step "what the tests compare with: the command line, the glTF Validator, the checkers' Python"
cargo build --locked -q -p inbetween-cli
if [ ! -d tools/gltf-validator/node_modules/gltf-validator ]; then
  npm ci --prefix tools/gltf-validator --no-audit --no-fund --loglevel=error >/dev/null
fi
# The checkers' Python (numpy, scipy, pygltflib: fixtures/requirements.txt) that some tests run
# (.ci/run has made it already; for a run on its own).
cached_venv target/ci-venv fixtures/requirements.txt

venv=target/wheel-test-venv
step "a fresh venv ($venv): the wheel and crates/inbetween-py/requirements-test.txt"
rm -rf "$venv"
python3 -m venv "$venv"
"$venv/bin/python" -m pip install -q --disable-pip-version-check --only-binary=:all: \
  -r crates/inbetween-py/requirements-test.txt "$wheel"
"$venv/bin/python" - "$root/$venv" <<'EOF'
import importlib.metadata, pathlib, sys
import inbetween, inbetween._inbetween
venv = pathlib.Path(sys.argv[1]).resolve()
for f in (inbetween.__file__, inbetween._inbetween.__file__, inbetween._ext.__file__):
    if venv not in pathlib.Path(f).resolve().parents:
        sys.exit(f"imported {f}, not the wheel installed in {venv}")
print(f"inbetween {inbetween.__version__} from {pathlib.Path(inbetween._ext.__file__).relative_to(venv)}")
EOF

step "pytest crates/inbetween-py/tests against the installed wheel"
# The AVX2 module is required where the CPU has AVX2 (CI's does): test_simd.py then compares it
# with the portable one, bit for bit.
require_avx2="$("$venv/bin/python" -c 'import inbetween; print(int(inbetween._inbetween.cpu_has_avx2()))')"
INBETWEEN_REQUIRE_AVX2="$require_avx2" INBETWEEN_REQUIRE_CLI=1 INBETWEEN_BIN="$root/target/debug/inbetween" "$venv/bin/python" -m pytest -q -p no:cacheprovider crates/inbetween-py/tests
step "done: $wheel, $sdist"
