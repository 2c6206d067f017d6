#!/usr/bin/env python3
"""Compares two Mantaflow caches file by file, ignoring what differs between two bakes of the same scene.

    python3 examples/bakelib/compare_caches.py CACHE_A CACHE_B

OpenVDB writes a random UUID into every file's header (36 ASCII bytes after the magic number, the file
version, the library version and the grid-offsets flag: bytes 21-56), so two bakes of the same scene are
never byte-identical; everything else must be. Exits 1 and names the first files that differ otherwise.
"""

import os
import sys

VDB_UUID = slice(21, 57)


def comparable(path):
    with open(path, "rb") as handle:
        data = bytearray(handle.read())
    if path.endswith(".vdb") and len(data) >= VDB_UUID.stop:
        data[VDB_UUID] = b"\0" * (VDB_UUID.stop - VDB_UUID.start)
    return bytes(data)


def files_under(root):
    return sorted(os.path.relpath(os.path.join(folder, name), root)
                  for folder, _, names in os.walk(root) for name in names)


def main():
    first, second = sys.argv[1:3]
    names = files_under(first)
    missing = sorted(set(names) ^ set(files_under(second)))
    different = [name for name in names if name not in missing and
                 comparable(os.path.join(first, name)) != comparable(os.path.join(second, name))]
    print(f"{len(names)} files; {len(missing)} only on one side; {len(different)} differ beyond the VDB UUID")
    for name in (missing + different)[:10]:
        print(f"  {name}")
    return 1 if missing or different else 0


if __name__ == "__main__":
    sys.exit(main())
