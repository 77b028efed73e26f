#!/usr/bin/env python3
"""What scripts/exact-compare needs to run VTP on our meshes (python3, stdlib only).

  vtp-tools.py toobj MESH DIR           print an OBJ VTP reads: MESH itself if it is
                                        one, else MESH (PLY) converted into DIR
  vtp-tools.py srcmap OBJ V             print VTP's id of the OBJ's vertex V
  vtp-tools.py tof64 OBJ VTP_OUT OUT    VTP's distances (its ids) as little-endian
                                        float64 in the OBJ's vertex order

VTP's reader takes `v` and `f` lines (three indices, `a` or `a/b`), and welds vertices
whose `v` lines are the same text, numbering the rest in order of first appearance:
its ids (the source it is given, the distances it writes) are those.
"""
import array
import os
import struct
import sys


def vtp_ids(obj):
    """Per OBJ vertex, VTP's id for it, and how many ids VTP has."""
    seen, ids = {}, []
    with open(obj, "rb") as f:
        for raw in f:
            line = raw.rstrip(b"\n")
            if line[:2] == b"v ":
                ids.append(seen.setdefault(line, len(seen)))
            elif line[:2] in (b"vn", b"vp"):
                sys.exit(f"{obj}: VTP would read '{line[:2].decode()}' lines as vertices")
            elif line[:2] == b"f " and (len(line.split()) != 4 or b"//" in line):
                sys.exit(f"{obj}: VTP reads triangles of 'a' or 'a/b' indices only")
    return ids, len(seen)


def ply_to_obj(ply, obj):
    """A PLY (ASCII or binary) with x, y, z and triangles, as OBJ with exact doubles."""
    codes = {"char": "b", "int8": "b", "uchar": "B", "uint8": "B", "short": "h",
             "int16": "h", "ushort": "H", "uint16": "H", "int": "i", "int32": "i",
             "uint": "I", "uint32": "I", "float": "f", "float32": "f", "double": "d",
             "float64": "d"}
    with open(ply, "rb") as f:
        if f.readline().strip() != b"ply":
            sys.exit(f"{ply}: not a PLY file")
        fmt, elements = None, []
        for line in f:
            t = line.split()
            if not t:
                continue
            if t[0] == b"format":
                fmt = t[1].decode()
            elif t[0] == b"element":
                elements.append((t[1].decode(), int(t[2]), []))
            elif t[0] == b"property":
                prop = (t[2].decode(), t[3].decode(), t[4].decode()) if t[1] == b"list" \
                    else (None, t[1].decode(), t[2].decode())
                elements[-1][2].append(prop)
            elif t[0] == b"end_header":
                break
        vertices, faces = [], []
        if fmt == "ascii":
            words, pos = f.read().split(), 0
            for name, count, props in elements:
                for _ in range(count):
                    values = {}
                    for count_type, _, pname in props:
                        if count_type is None:
                            values[pname] = float(words[pos])
                            pos += 1
                        else:
                            n = int(words[pos])
                            values[pname] = [int(w) for w in words[pos + 1:pos + 1 + n]]
                            pos += 1 + n
                    if name == "vertex":
                        vertices.append((values["x"], values["y"], values["z"]))
                    elif name == "face":
                        faces.append(values.get("vertex_indices") or values["vertex_index"])
        else:
            end = "<" if fmt == "binary_little_endian" else ">"
            data, pos = f.read(), 0
            for name, count, props in elements:
                for _ in range(count):
                    values = {}
                    for count_type, type_, pname in props:
                        if count_type is None:
                            (values[pname],) = struct.unpack_from(end + codes[type_], data, pos)
                            pos += struct.calcsize(codes[type_])
                        else:
                            (n,) = struct.unpack_from(end + codes[count_type], data, pos)
                            pos += struct.calcsize(codes[count_type])
                            values[pname] = struct.unpack_from(end + codes[type_] * n, data, pos)
                            pos += struct.calcsize(codes[type_]) * n
                    if name == "vertex":
                        vertices.append((values["x"], values["y"], values["z"]))
                    elif name == "face":
                        faces.append(values.get("vertex_indices") or values["vertex_index"])
    with open(obj, "w") as o:
        for x, y, z in vertices:
            o.write(f"v {x!r} {y!r} {z!r}\n")
        for face in faces:
            if len(face) != 3:
                sys.exit(f"{ply}: a face that is not a triangle")
            o.write(f"f {face[0] + 1} {face[1] + 1} {face[2] + 1}\n")


def main(args):
    if args[0] == "toobj":
        mesh, folder = args[1], args[2]
        if not mesh.lower().endswith(".obj"):
            obj = os.path.join(folder, os.path.splitext(os.path.basename(mesh))[0] + ".obj")
            ply_to_obj(mesh, obj)
            mesh = obj
        vtp_ids(mesh)
        print(mesh)
    elif args[0] == "srcmap":
        print(vtp_ids(args[1])[0][int(args[2])])
    elif args[0] == "tof64":
        ids, count = vtp_ids(args[1])
        with open(args[2]) as f:
            values = [float(w) for w in f.read().split()]
        if len(values) != count:
            sys.exit(f"VTP wrote {len(values)} values for {count} vertices")
        out = array.array("d", (values[i] for i in ids))
        if sys.byteorder != "little":
            out.byteswap()
        with open(args[3], "wb") as f:
            out.tofile(f)
    else:
        sys.exit(__doc__)


if __name__ == "__main__":
    main(sys.argv[1:])
