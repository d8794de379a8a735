#!/usr/bin/env bash
# Whole-process time of `inbetween interp` against the number of tracks (issue 11): 10^4 and
# 10^5 two-key tracks (rows interleaved across tracks, a 90° turn each), 2 fps, CSV to a file;
# medians of 5, alternating sizes. Run by hand:   bash benches/scale/run.sh
set -euo pipefail
root="$(cd "$(dirname "$0")/../.." && pwd)"
(cd "$root" && cargo build --release -q)
exec python3 - "$root/target/release/inbetween" <<'PY'
import os, statistics, subprocess, sys, tempfile, time
binary, tmp = sys.argv[1], tempfile.mkdtemp()
sizes = (10_000, 100_000)
for n in sizes:
    with open(os.path.join(tmp, f"{n}.csv"), "w") as f:
        f.write("track,time,w,x,y,z\n")
        f.writelines(f"t{i},0,1,0,0,0\n" for i in range(n))
        f.writelines(f"t{i},1,0.7071067811865476,0.7071067811865476,0,0\n" for i in range(n))
times = {n: [] for n in sizes}
for _ in range(5):
    for n in sizes:
        t0 = time.perf_counter()
        subprocess.run([binary, "interp", os.path.join(tmp, f"{n}.csv"), "--fps", "2",
                        "-o", os.path.join(tmp, "out.csv")], check=True)
        times[n].append(time.perf_counter() - t0)
a, b = (statistics.median(times[n]) for n in sizes)
print(f"10^4 tracks {a * 1e3:.1f} ms, 10^5 tracks {b * 1e3:.1f} ms, ratio {b / a:.2f} (medians of 5)")
PY
