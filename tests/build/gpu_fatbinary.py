#!/usr/bin/env python3
"""The GPU sweep's device code was compiled and linked: the fatbinary in BINARY's .nv_fatbin
section (what cuobjdump --list-elf lists; this CUDA toolkit has no cuobjdump) holds machine
code (an ELF image) for each SM in SMS whose symbols include the kernel KERNEL, and PTX for
each virtual target in PTX.

Usage: gpu_fatbinary.py OBJCOPY BINARY KERNEL SMS PTX   (SMS, PTX: comma lists, e.g. 90 and 80)
"""
import os
import struct
import subprocess
import sys
import tempfile

objcopy, binary, kernel, sms, ptxs = sys.argv[1:6]
want_sm = {int(s) for s in sms.split(",") if s}
want_ptx = {int(s) for s in ptxs.split(",") if s}
with tempfile.TemporaryDirectory() as tmp:
    out = os.path.join(tmp, "fatbin")
    subprocess.run([objcopy, "-O", "binary", "--only-section=.nv_fatbin", binary, out],
                   check=True)
    data = open(out, "rb").read() if os.path.exists(out) else b""
if not data:
    sys.exit(f"gpu_fatbinary: FAILED: {binary} has no .nv_fatbin section (no device code)")

elf, ptx, pos = {}, set(), 0
while pos + 16 <= len(data):
    magic, _version, header, size = struct.unpack_from("<IHHQ", data, pos)
    if magic != 0xBA55ED50:  # padding between the fatbinaries of several objects
        pos += 8
        continue
    entry, end = pos + header, pos + header + size
    while entry + 32 <= end:
        kind, _, entry_header, payload = struct.unpack_from("<HHIQ", data, entry)
        arch = struct.unpack_from("<I", data, entry + 28)[0]
        body = data[entry + entry_header: entry + entry_header + payload]
        if kind == 2:
            elf[arch] = elf.get(arch, b"") + body
        elif kind == 1:
            ptx.add(arch)
        entry += entry_header + payload
    pos = end
print(f"gpu_fatbinary: {binary}: machine code for sm_{', sm_'.join(map(str, sorted(elf)))}; "
      f"PTX for compute_{', compute_'.join(map(str, sorted(ptx)))}")
status = 0
for sm in sorted(want_sm):
    if sm not in elf:
        print(f"gpu_fatbinary: FAILED: no machine code for sm_{sm}", file=sys.stderr)
        status = 1
    elif kernel.encode() not in elf[sm]:
        print(f"gpu_fatbinary: FAILED: the sm_{sm} image has no kernel named {kernel}",
              file=sys.stderr)
        status = 1
    else:
        print(f"gpu_fatbinary: sm_{sm} holds the kernel {kernel}")
for arch in sorted(want_ptx - ptx):
    print(f"gpu_fatbinary: FAILED: no PTX for compute_{arch}", file=sys.stderr)
    status = 1
sys.exit(status)
