#!/usr/bin/env python3
"""The publishing metadata of the crates that go to crates.io (what `cargo package` does not check).

For every workspace member not marked `publish = false` (from `cargo metadata --no-deps`):
a description, the licence, repository, homepage, rust-version and a readme file that exists in
the crate's folder; 1 to 5 keywords as crates.io accepts them (ASCII letters first, then letters,
digits, `_` or `-`, at most 20 characters); 1 to 5 categories, each a slug of crates.io's list
(src/boot/categories.toml of crates.io; the slugs below are those we may use, all on it); and
every dependency on another workspace crate with a version requirement that the crate's own
version meets. Exit status 1 and one line per finding.
"""
import json
import re
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
KEYWORD = re.compile(r"^[A-Za-z][A-Za-z0-9_-]{0,19}$")
# Slugs of crates.io's categories that fit this project (all exist on crates.io's list).
CATEGORIES = {
    "command-line-utilities", "game-development", "graphics", "mathematics", "multimedia",
    "parser-implementations", "rendering::data-formats", "science", "science::robotics",
    "simulation", "visualization", "encoding",
}


def main():
    meta = json.loads(subprocess.run(
        ["cargo", "metadata", "--format-version", "1", "--no-deps", "--locked"],
        cwd=ROOT, check=True, capture_output=True, text=True).stdout)
    members = {p["name"]: p for p in meta["packages"]}
    problems = []
    published = [p for p in meta["packages"] if p.get("publish") != []]
    for p in published:
        name = p["name"]
        for field in ("description", "license", "repository", "homepage", "rust_version", "readme"):
            if not p.get(field):
                problems.append(f"{name}: no `{field.replace('_', '-')}`")
        if p.get("readme") and not (Path(p["manifest_path"]).parent / p["readme"]).is_file():
            problems.append(f"{name}: readme {p['readme']!r} is not a file")
        kws = p.get("keywords") or []
        if not 1 <= len(kws) <= 5:
            problems.append(f"{name}: {len(kws)} keywords, crates.io takes 1 to 5")
        problems += [f"{name}: keyword {k!r} is not one crates.io accepts" for k in kws if not KEYWORD.match(k)]
        cats = p.get("categories") or []
        if not 1 <= len(cats) <= 5:
            problems.append(f"{name}: {len(cats)} categories, crates.io takes 1 to 5")
        problems += [f"{name}: category {c!r} is not a crates.io slug we use" for c in cats if c not in CATEGORIES]
        for dep in p["dependencies"]:
            if dep["name"] in members and dep["kind"] in (None, "build"):
                version = members[dep["name"]]["version"]
                if dep["req"] in ("*", "") or dep["req"].lstrip("^=") != version:
                    problems.append(f"{name}: dependency {dep['name']} needs a version ({version}), found {dep['req']!r}")
    names = sorted(p["name"] for p in published)
    for line in problems:
        print(line, file=sys.stderr)
    if not problems:
        print(f"publishing metadata complete: {', '.join(names)}")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
