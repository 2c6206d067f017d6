#!/usr/bin/python3
"""Writes the small PLY files that tests/native/test_ply_reader.cpp reads.

The files are written with `struct` alone, independently of the C++ reader, so a reader bug cannot hide in a
writer that shares its code. Run it from anywhere; it writes beside itself into tests/data/ply/:

    /usr/bin/python3 tests/data/make_ply_files.py

The values are chosen to be exact in float32 where the tests compare them exactly.
"""

import math
import pathlib
import struct

OUTPUT_DIR = pathlib.Path(__file__).resolve().parent / "ply"


def header(format_name, elements, comments=()):
    """elements: [(name, count, [property line, ...])]"""
    lines = ["ply", f"format {format_name} 1.0"]
    lines += [f"comment {comment}" for comment in comments]
    for name, count, properties in elements:
        lines.append(f"element {name} {count}")
        lines += [f"property {line}" for line in properties]
    lines.append("end_header")
    return ("\n".join(lines) + "\n").encode("ascii")


def write(name, data):
    OUTPUT_DIR.mkdir(parents=True, exist_ok=True)
    (OUTPUT_DIR / name).write_bytes(data)


def ascii_file():
    # Properties in an unusual order, with every optional attribute, Windows line ends and a comment.
    properties = ["int type", "float life", "float x", "float vz", "float y", "float radius", "float z",
                  "float vx", "float vy"]
    rows = [
        "8 12.5 1.0 -3.0 2.0 0.05 3.0 1.0 2.0",
        "2 0.0 -1.5 0.0 0.25 0.125 1e3 0.5 -0.5",
        "4 7 0 1 0 0.5 -2 0 0",
    ]
    text = header("ascii", [("vertex", 3, properties)], comments=["written by make_ply_files.py"])
    text = text.replace(b"\n", b"\r\n") + ("\r\n".join(rows) + "\r\n").encode("ascii")
    write("ascii.ply", text)


def binary_little_endian_file():
    # Double positions, uchar type, float radius, properties the reader ignores, then a face element whose
    # list property must be skipped correctly.
    properties = ["double x", "double y", "double z", "int id", "uchar type", "float radius", "short ignored",
                  "list uchar float ignored_list_in_vertex"]
    vertices = [
        (0.1, 0.2, 0.3, 100, 8, 0.5, -7, [1.0, 2.0]),
        (-1.0, 2.5, 1e6, 101, 2, 0.25, 3, []),
        (4.0, -4.0, 0.0, 102, 0, 1.5, 0, [9.0]),
    ]
    faces = [[0, 1, 2], [2, 1, 0, 1]]
    data = header("binary_little_endian", [("vertex", len(vertices), properties),
                                           ("face", len(faces), ["list uchar int vertex_indices"])])
    for x, y, z, identifier, kind, radius, ignored, items in vertices:
        data += struct.pack("<dddiBfhB", x, y, z, identifier, kind, radius, ignored, len(items))
        data += struct.pack(f"<{len(items)}f", *items)
    for face in faces:
        data += struct.pack(f"<B{len(face)}i", len(face), *face)
    write("binary_little_endian.ply", data)


def binary_big_endian_file():
    # Type aliases (float32, int8, uint16 ...), `pscale` instead of `radius` and velocities.
    properties = ["float32 x", "float32 y", "float32 z", "float32 pscale", "int8 type", "uint16 life",
                  "float64 vx", "float64 vy", "float64 vz", "uint32 ignored"]
    vertices = [
        (1.0, 2.0, 3.0, 0.75, 4, 30, 0.5, -0.5, 2.0, 4000000000),
        (-8.0, 0.0, 0.5, 0.0625, -1, 65535, 0.0, 0.0, -9.5, 0),
    ]
    data = header("binary_big_endian", [("vertex", len(vertices), properties)])
    for vertex in vertices:
        data += struct.pack(">ffffbHdddI", *vertex)
    write("binary_big_endian.ply", data)


def non_finite_file():
    vertices = [(math.nan, 0.0, 0.0), (0.0, math.inf, 0.0), (0.0, 0.0, -math.inf), (1.0, 1.0, 1.0)]
    data = header("binary_little_endian", [("vertex", len(vertices), ["float x", "float y", "float z"])])
    for vertex in vertices:
        data += struct.pack("<fff", *vertex)
    write("non_finite.ply", data)


def pscale_and_radius_file():
    # With both, `radius` wins; `pscale` is Houdini's name for the same thing.
    data = header("ascii", [("vertex", 1, ["float pscale", "float x", "float y", "float z", "float radius"])])
    data += b"9 1 2 3 0.5\n"
    write("pscale_and_radius.ply", data)


def no_final_line_end_file():
    # The smallest rows there can be, and no line end after the last: the size guard must still accept it.
    data = header("ascii", [("vertex", 2, ["float x", "float y", "float z"])]) + b"0 0 0\n1 2 3"
    write("no_final_line_end.ply", data)


def empty_file():
    data = header("binary_little_endian", [("vertex", 0, ["float x", "float y", "float z"])])
    write("empty.ply", data)


def malformed_files():
    xyz = ["float x", "float y", "float z"]

    truncated = header("binary_little_endian", [("vertex", 4, xyz)])
    truncated += struct.pack("<9f", *range(9)) + struct.pack("<2f", 1.0, 2.0)
    write("truncated_binary.ply", truncated)

    truncated_list = header("binary_little_endian", [("vertex", 1, xyz),
                                                     ("face", 1, ["list uchar int vertex_indices"])])
    truncated_list += struct.pack("<3f", 0.0, 0.0, 0.0) + struct.pack("<B2i", 200, 0, 1)
    write("truncated_face_list.ply", truncated_list)

    missing_y = header("ascii", [("vertex", 1, ["float x", "float z"])]) + b"1 2\n"
    write("missing_y.ply", missing_y)

    bad_format = header("binary_middle_endian", [("vertex", 1, xyz)]) + b"\0" * 12
    write("bad_format.ply", bad_format)

    absurd_count = header("binary_little_endian", [("vertex", 10**12, xyz)]) + struct.pack("<3f", 1, 2, 3)
    write("absurd_count.ply", absurd_count)

    ascii_extra_rows = header("ascii", [("vertex", 2, xyz)]) + b"0 0 0\n1 1 1\n2 2 2\n"
    write("ascii_extra_rows.ply", ascii_extra_rows)

    ascii_short_row = header("ascii", [("vertex", 2, xyz)]) + b"10.5 20.5 30.5\n1.5 2.5\n"
    write("ascii_short_row.ply", ascii_short_row)

    binary_extra_bytes = header("binary_little_endian", [("vertex", 1, xyz)]) + struct.pack("<6f", *range(6))
    write("binary_extra_bytes.ply", binary_extra_bytes)

    no_end_header = b"ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n"
    write("no_end_header.ply", no_end_header)

    not_ply = b"PK\x03\x04 this is a zip file, not a PLY file\n"
    write("not_ply.ply", not_ply)

    unknown_type = header("ascii", [("vertex", 1, ["float x", "float y", "float z", "quad w"])]) + b"1 2 3 4\n"
    write("unknown_type.ply", unknown_type)

    no_vertex = header("ascii", [("face", 0, ["list uchar int vertex_indices"])])
    write("no_vertex.ply", no_vertex)


def main():
    ascii_file()
    binary_little_endian_file()
    binary_big_endian_file()
    non_finite_file()
    pscale_and_radius_file()
    no_final_line_end_file()
    empty_file()
    malformed_files()


if __name__ == "__main__":
    main()
