#!/usr/bin/env python3
"""THIRD-PARTY-LICENSES: the licences of the third-party code that what we distribute contains.

What we distribute is built from two crates: `inbetween-cli` (the `inbetween` binary) and
`inbetween-py` (the extension module of the Python package `inbetween-rs`). Each links the
crates of its normal dependency tree, as `cargo tree --locked -p CRATE -e normal,no-proc-macro
--target T …` lists them from Cargo.lock with that crate's own features, for the desktop
platforms in TARGETS (Linux, macOS and Windows on x86_64 and arm64: a build from the sdist or
with `cargo install` on any of them links no crate outside the list; build scripts, procedural
macros and test-only crates run at build time and are not distributed). For each crate, `cargo metadata
--format-version 1 --locked` gives its declared licence and its folder in cargo's registry,
where its licence files are (LICENSE*, LICENCE*, COPYING*, NOTICE*, UNLICENSE*, and the
manifest's `license-file`). A crate that ships none has its text checked in under
tools/licenses/ (`<crate>-LICENSE`); a crate with neither is an error, never a silent gap.

    python3 tools/licenses.py           # writes THIRD-PARTY-LICENSES at the repository root
    python3 tools/licenses.py --check   # exit 1 if that file is not what this would write, or
                                        # our own licence fields and files disagree

The check also holds our own licence to one value: the workspace's `license`, every member
crate's (from cargo metadata), pyproject.toml's `license`, and the LICENSE-MIT and
LICENSE-APACHE that every crate's folder links to (the root's, byte for byte).
"""
import difflib
import json
import re
import subprocess
import sys
import tomllib
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
OUT = ROOT / "THIRD-PARTY-LICENSES"
OVERRIDES = ROOT / "tools" / "licenses"
# The artifacts we distribute: the crate each is built from, and its name in the file.
ARTIFACTS = [
    ("inbetween-cli", "cli", "the command line `inbetween` (crate inbetween-cli)"),
    ("inbetween-py", "wheel", "the Python package `inbetween-rs` (crate inbetween-py, its extension module)"),
]
# The platforms whose dependencies are listed (a UEFI or wasm build would need others).
TARGETS = ["x86_64-unknown-linux-gnu", "aarch64-unknown-linux-gnu", "x86_64-apple-darwin",
           "aarch64-apple-darwin", "x86_64-pc-windows-msvc", "aarch64-pc-windows-msvc"]
OUR_LICENSE = "MIT OR Apache-2.0"
OUR_FILES = ["LICENSE-MIT", "LICENSE-APACHE"]
LICENSE_NAME = re.compile(r"^(LICEN[CS]E|COPYING|NOTICE|UNLICENSE)", re.IGNORECASE)


def cargo(*args):
    return subprocess.run(["cargo", *args], cwd=ROOT, check=True, capture_output=True, text=True).stdout


def linked(crate, ours):
    """(name, version) of every crate `crate` links, the workspace's own (`ours`) aside."""
    targets = [a for t in TARGETS for a in ("--target", t)]
    out = cargo("tree", "--locked", "-p", crate, "-e", "normal,no-proc-macro", *targets,
                "--prefix", "none", "-f", "{p}")
    found = set()
    for line in out.splitlines():
        m = re.match(r"^(\S+) v(\S+)(.*)$", line.strip())
        if not m:
            continue
        if m.group(1) in ours:
            continue
        found.add((m.group(1), m.group(2)))
    return found


def normalise(text):
    """A licence text with Unix line ends, no trailing blanks, one final newline."""
    lines = [line.rstrip() for line in text.replace("\r\n", "\n").replace("\r", "\n").split("\n")]
    while lines and not lines[-1]:
        lines.pop()
    while lines and not lines[0]:
        lines.pop(0)
    return "\n".join(lines) + "\n"


def licence_files(pkg):
    """[(file name, text)] of a registry crate's licence files, or the checked-in override."""
    folder = Path(pkg["manifest_path"]).parent
    names = sorted(p.name for p in folder.iterdir() if p.is_file() and LICENSE_NAME.match(p.name))
    if pkg.get("license_file"):
        extra = Path(pkg["license_file"]).name
        if extra not in names and (folder / pkg["license_file"]).is_file():
            names.append(extra)
    files = [(n, normalise((folder / n).read_text(encoding="utf-8", errors="replace"))) for n in names]
    override = OVERRIDES / f"{pkg['name']}-LICENSE"
    if not files and override.is_file():
        files = [(f"{override.name} (tools/licenses/: the crate ships no licence file)",
                  normalise(override.read_text(encoding="utf-8")))]
    return files


def note(pkg):
    """What else a crate's licence covers, for the crates that bundle code of another language."""
    if pkg["name"] == "ufbx":
        header = Path(pkg["manifest_path"]).parent / "ufbx" / "ufbx.h"
        m = re.search(r"#define UFBX_HEADER_VERSION ufbx_pack_version\((\d+), (\d+), (\d+)\)",
                      header.read_text(encoding="utf-8", errors="replace"))
        version = ".".join(m.groups()) if m else "(version not found)"
        return f"bundles the ufbx C library {version} (ufbx/ufbx.c), under the licence text below"
    return ""


def render(metadata):
    packages = {(p["name"], p["version"]): p for p in metadata["packages"]}
    members = set(metadata["workspace_members"])
    ours = {p["name"] for p in metadata["packages"] if p["id"] in members}
    users = {}
    for crate, short, _ in ARTIFACTS:
        for key in linked(crate, ours):
            users.setdefault(key, []).append(short)
    errors = []
    rows, texts = [], {}
    for key in sorted(users):
        pkg = packages[key]
        files = licence_files(pkg)
        if not files:
            errors.append(f"{key[0]} {key[1]}: no licence file in the crate and no "
                          f"tools/licenses/{key[0]}-LICENSE")
        if not pkg.get("license"):
            errors.append(f"{key[0]} {key[1]}: no `license` in its manifest")
        rows.append((f"{key[0]} {key[1]}", pkg.get("license") or "?", ", ".join(users[key]), note(pkg)))
        for name, text in files:
            texts.setdefault(text, []).append(f"{key[0]} {key[1]} ({name})")
    if errors:
        raise SystemExit("tools/licenses.py:\n" + "\n".join("  " + e for e in errors))

    out = ["THIRD-PARTY LICENSES of inbetween", "=" * 33, ""]
    out += [
        "inbetween itself is licensed under MIT OR Apache-2.0 (LICENSE-MIT, LICENSE-APACHE). What it",
        "distributes contains the third-party crates listed here, under their own licences:",
        "",
    ]
    out += [f"- {short}: {what}" for _, short, what in ARTIFACTS]
    out += [
        "",
        "The crates are those each links (normal dependencies from Cargo.lock, on Linux, macOS and",
        "Windows, x86_64 and arm64); build scripts, procedural macros and test-only crates run at",
        "build time and are not distributed. Both also link the Rust standard library (MIT OR",
        "Apache-2.0).",
        "",
        "Generated by tools/licenses.py from `cargo metadata --locked`, `cargo tree --locked` and",
        "each crate's own licence files: do not edit by hand; run `python3 tools/licenses.py` after",
        "a dependency changes (.ci/package.sh checks that this file is up to date).",
        "",
        "Crates",
        "------",
        "",
    ]
    width = max(len(r[0]) for r in rows)
    lwidth = max(len(r[1]) for r in rows)
    for name, lic, used, extra in rows:
        out.append(f"{name:<{width}}  {lic:<{lwidth}}  {used}")
        if extra:
            out.append(f"{'':<{width}}  {extra}")
    out += ["", "Licence texts", "-------------", ""]
    # One section per distinct text, its crates named (most Apache-2.0 texts are the same bytes).
    for text, owners in sorted(texts.items(), key=lambda kv: kv[1][0]):
        out.append("=" * 78)
        out.append("Used by: " + "; ".join(owners))
        out.append("=" * 78)
        out.append("")
        out.append(text)
    return "\n".join(out).rstrip("\n") + "\n"


def our_licence(metadata):
    """Mismatches between our own licence fields and files (empty when they agree)."""
    problems = []
    workspace = tomllib.loads((ROOT / "Cargo.toml").read_text())
    declared = workspace["workspace"]["package"].get("license")
    if declared != OUR_LICENSE:
        problems.append(f"Cargo.toml [workspace.package] license = {declared!r}, expected {OUR_LICENSE!r}")
    members = set(metadata["workspace_members"])
    for pkg in metadata["packages"]:
        if pkg["id"] in members and pkg.get("license") != OUR_LICENSE:
            problems.append(f"crate {pkg['name']}: license = {pkg.get('license')!r}, expected {OUR_LICENSE!r}")
        if pkg["id"] in members:
            folder = Path(pkg["manifest_path"]).parent
            for name in OUR_FILES:
                mine, root = folder / name, ROOT / name
                if not mine.is_file() or mine.read_bytes() != root.read_bytes():
                    problems.append(f"{mine.relative_to(ROOT)}: missing or not the root's {name}")
    py = tomllib.loads((ROOT / "crates" / "inbetween-py" / "pyproject.toml").read_text())["project"]
    if py.get("license") != OUR_LICENSE:
        problems.append(f"crates/inbetween-py/pyproject.toml license = {py.get('license')!r}, expected {OUR_LICENSE!r}")
    for name in OUR_FILES:
        if not (ROOT / name).is_file():
            problems.append(f"{name}: missing at the repository root")
    return problems


def main(argv):
    check = "--check" in argv[1:]
    metadata = json.loads(cargo("metadata", "--format-version", "1", "--locked"))
    text = render(metadata)
    if not check:
        OUT.write_text(text)
        print(f"wrote {OUT.relative_to(ROOT)} ({len(text)} bytes)")
        return 0
    problems = our_licence(metadata)
    current = OUT.read_text() if OUT.is_file() else ""
    if current != text:
        diff = list(difflib.unified_diff(current.splitlines(), text.splitlines(),
                                         "THIRD-PARTY-LICENSES (checked in)", "tools/licenses.py", lineterm="", n=1))
        problems.append("THIRD-PARTY-LICENSES is out of date: run `python3 tools/licenses.py`\n"
                        + "\n".join(diff[:40]) + ("\n…" if len(diff) > 40 else ""))
    for p in problems:
        print(p, file=sys.stderr)
    if not problems:
        print(f"THIRD-PARTY-LICENSES up to date; licence {OUR_LICENSE!r} everywhere")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
