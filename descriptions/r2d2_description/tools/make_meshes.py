"""Regenerate the R2D2 gripper finger meshes (binary STL, metres). Run from this folder:

    python make_meshes.py

The shapes are our own: a tapered finger and a small fingertip wedge, sized like the URDF
tutorial's gripper so that the joint origins of the tutorial fit.
"""
import struct
from pathlib import Path


def prism(profile, z0, z1):
    """Extrude a convex 2-D profile (list of (x, y), counter-clockwise) from z0 to z1."""
    n = len(profile)
    bottom = [(x, y, z0) for x, y in profile]
    top = [(x, y, z1) for x, y in profile]
    tris = []
    for i in range(1, n - 1):
        tris.append((bottom[0], bottom[i + 1], bottom[i]))
        tris.append((top[0], top[i], top[i + 1]))
    for i in range(n):
        j = (i + 1) % n
        tris.append((bottom[i], bottom[j], top[j]))
        tris.append((bottom[i], top[j], top[i]))
    return tris


def normal(a, b, c):
    u = [b[k] - a[k] for k in range(3)]
    v = [c[k] - a[k] for k in range(3)]
    n = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]]
    length = sum(x * x for x in n) ** 0.5 or 1.0
    return [x / length for x in n]


def write_stl(path, tris):
    with open(path, "wb") as f:
        f.write(b"urdf-lint r2d2 finger".ljust(80, b" "))
        f.write(struct.pack("<I", len(tris)))
        for t in tris:
            f.write(struct.pack("<3f", *normal(*t)))
            for v in t:
                f.write(struct.pack("<3f", *v))
            f.write(b"\0\0")


if __name__ == "__main__":
    out = Path(__file__).resolve().parent.parent / "meshes"
    finger = [(0.0, -0.012), (0.095, -0.004), (0.095, 0.012), (0.0, 0.012)]
    tip = [(0.0, -0.006), (0.05, 0.0), (0.0, 0.01)]
    write_stl(out / "l_finger.stl", prism(finger, -0.01, 0.01))
    write_stl(out / "l_finger_tip.stl", prism(tip, -0.008, 0.008))
    print("wrote", out / "l_finger.stl", out / "l_finger_tip.stl")
