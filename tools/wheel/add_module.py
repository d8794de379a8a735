"""Puts the AVX2 extension module of the wheel that maturin built in crates/inbetween-py/avx2
(`_inbetween_avx2/_inbetween_avx2.abi3.so` there) as `inbetween/_inbetween_avx2.abi3.so` into the `inbetween-rs` wheel, beside the portable
module, with its line in the wheel's RECORD (tools/wheel/build.sh).

    python tools/wheel/add_module.py MAIN.whl AVX2.whl

Refused (exit 1): no such module in AVX2.whl, MAIN.whl holding one already, or a fused
multiply-add instruction in the module (`objdump -d`): FMA rounds once where the portable code
rounds twice, which would give other bits than the portable module (tests/test_simd.py).
"""

import base64
import hashlib
import os
import re
import subprocess
import sys
import tempfile
import zipfile

PREFIX = "inbetween/_inbetween_avx2"
TARGET = "inbetween/_inbetween_avx2.abi3.so"


def fused_instructions(data: bytes) -> int:
    with tempfile.NamedTemporaryFile(suffix=".so") as f:
        f.write(data)
        f.flush()
        asm = subprocess.run(["objdump", "-d", "--no-show-raw-insn", f.name], check=True,
                             capture_output=True, text=True).stdout
    return len(re.findall(r"\bv?fn?m(?:add|sub)(?:sub|add)?\d*[ps][sd]\b", asm))


def main() -> None:
    main_whl, extra_whl = sys.argv[1:3]
    with zipfile.ZipFile(extra_whl) as z:
        # maturin puts it in a package of its own name (`_inbetween_avx2/`): taken from there.
        found = [i for i in z.infolist() if i.filename.rsplit("/", 1)[-1] == TARGET.rsplit("/", 1)[-1]]
        if len(found) != 1:
            sys.exit(f"{extra_whl}: expected one {TARGET.rsplit('/', 1)[-1]}, found {[i.filename for i in found]}")
        data = z.read(found[0])
        module = zipfile.ZipInfo(TARGET, date_time=found[0].date_time)
        module.external_attr = found[0].external_attr
        module.compress_type = zipfile.ZIP_DEFLATED
    fused = fused_instructions(data)
    if fused:
        sys.exit(f"{module.filename}: {fused} fused multiply-add instructions (built with FMA?)")
    digest = base64.urlsafe_b64encode(hashlib.sha256(data).digest()).rstrip(b"=").decode()
    out = main_whl + ".part"
    with zipfile.ZipFile(main_whl) as zin, zipfile.ZipFile(out, "w", zipfile.ZIP_DEFLATED) as zout:
        infos = zin.infolist()
        if any(i.filename.startswith(PREFIX) for i in infos):
            sys.exit(f"{main_whl} has an AVX2 module already")
        record = next(i for i in infos if i.filename.endswith(".dist-info/RECORD"))
        dist_info = record.filename.rsplit("/", 1)[0] + "/"
        for i in infos:
            if not i.filename.startswith(dist_info):
                zout.writestr(i, zin.read(i))
        zout.writestr(module, data)
        for i in infos:
            if i.filename.startswith(dist_info) and i is not record:
                zout.writestr(i, zin.read(i))
        lines = zin.read(record).decode().splitlines()
        lines.insert(len(lines) - 1 if lines[-1].startswith(record.filename) else len(lines),
                     f"{module.filename},sha256={digest},{len(data)}")
        zout.writestr(record, "\n".join(lines) + "\n")
    os.replace(out, main_whl)
    print(f"{main_whl}: + {module.filename} ({len(data)} bytes, no fused multiply-add)")


if __name__ == "__main__":
    main()
