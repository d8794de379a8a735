#!/usr/bin/env python3
"""Process a folder of motion files on a Dask cluster with ``inbetween.process_file``.

The same code runs on a local cluster (``--workers N`` processes on this machine) or on a
multi-machine one (``--scheduler tcp://host:8786``, workers started with ``dask worker``, each
with ``inbetween`` installed). Every file of IN (recursively; hidden files left out) is one task:
``inbetween <command> <file> -o <out>`` run inside the worker by the command line's own code, its
output under OUT at the file's path relative to IN, with the extension the command line's batch
gives it (``--output-format``'s, else the input's own; keys as ``.json`` for ``convert`` and
``reduce`` of BVH, FBX or USD) — the
layout, bytes and records of the command line's ``--out-dir`` batch. The records go to
``--manifest`` (JSON Lines) as tasks finish; the exit code is 0 when every file succeeded or was
skipped, 2 when one was refused, 1 on an internal error.

    python examples/python/dask_batch.py clips/ out/ --command interp --workers 2 -- --fps 30
    python examples/python/dask_batch.py clips/ out/ --command reduce --scheduler tcp://10.0.0.5:8786 \\
        -- --tolerance 0.5 --translation-tolerance 0.1

Options after ``--`` are the command's own, as on the command line (``--shared-keys`` alone is
a bare flag).
"""

from __future__ import annotations

import argparse
import functools
import json
import os
import sys
from pathlib import Path

import inbetween


def files_below(folder: Path) -> list[Path]:
    """Every non-hidden file below ``folder``, in path order (as the command line walks it)."""
    out = []
    for root, dirs, names in os.walk(folder):
        dirs[:] = sorted(d for d in dirs if not d.startswith("."))
        out.extend(Path(root) / n for n in sorted(names) if not n.startswith("."))
    return sorted(out)


def command_options(words: list[str]) -> dict:
    """``["--fps", "30", "--shared-keys"]`` as ``{"fps": "30", "shared_keys": True}``."""
    options: dict = {}
    i = 0
    while i < len(words):
        word = words[i]
        if not word.startswith("--"):
            raise SystemExit(f"expected an option (--name), found {word!r}")
        name = word[2:].replace("-", "_")
        if i + 1 < len(words) and not words[i + 1].startswith("--"):
            options[name] = words[i + 1]
            i += 2
        else:
            options[name] = True
            i += 1
    return options


def output_path(source: Path, folder: Path, out: Path, command: str, options: dict) -> Path:
    """Where the command line's ``--out-dir`` puts ``source``'s output (docs/spec.md, Batch)."""
    ext = options.get("output_format") or source.suffix.lstrip(".").lower()
    if ext in ("fbx", "") or (command != "interp" and ext in ("bvh", "usda")):
        ext = "json"
    return (out / source.relative_to(folder)).with_suffix("." + ext)


def main(argv: list[str]) -> int:
    split = argv.index("--") if "--" in argv else len(argv)
    own, rest = argv[:split], argv[split + 1:]
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("input", type=Path)
    p.add_argument("out", type=Path)
    p.add_argument("--command", default="interp", choices=["interp", "convert", "reduce"])
    p.add_argument("--workers", type=int, default=2, help="local cluster processes")
    p.add_argument("--scheduler", help="address of a running scheduler (else a local cluster)")
    p.add_argument("--manifest", type=Path)
    p.add_argument("--refresh", action="store_true")
    args = p.parse_args(own)
    options = command_options(rest)

    from dask.distributed import Client, LocalCluster, as_completed

    if args.scheduler:
        client = Client(args.scheduler)
    else:
        cluster = LocalCluster(n_workers=args.workers, threads_per_worker=1, processes=True,
                               dashboard_address=None)
        client = Client(cluster)
    sources = files_below(args.input)
    outputs = [output_path(s, args.input, args.out, args.command, options) for s in sources]
    task = functools.partial(inbetween.process_file, command=args.command, refresh=args.refresh,
                             **options)
    futures = client.map(task, [str(s) for s in sources], [str(o) for o in outputs], pure=False)
    manifest = args.manifest.open("a") if args.manifest else None
    counts = {"ok": 0, "skipped": 0, "failed": 0}
    worst = 0
    for future in as_completed(futures):
        record = future.result()
        counts[record["status"]] += 1
        worst = max(worst, record.get("exit_code", 0))
        if record.get("error"):
            print(f"inbetween: error: {record['error']}", file=sys.stderr)
        if manifest:
            manifest.write(json.dumps(record) + "\n")
            manifest.flush()
    print(f"{len(sources)} inputs: {counts['ok']} ok, {counts['skipped']} skipped, "
          f"{counts['failed']} failed", file=sys.stderr)
    client.close()
    return 1 if worst == 1 else (2 if worst else 0)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
