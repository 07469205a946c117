#!/usr/bin/python3
"""Writes a low-poly shoe surface (OBJ, metres) for sneaker_grass: a side
profile of a sneaker (sole, rounded toe, vamp, ankle collar, heel counter)
extruded 10 cm across. Deterministic; tetrahedralized by
`tcbench_mesh3 surface shoe.obj 0.012 data/meshes/shoe.mesh`.
Usage: /usr/bin/python3 tools/mesh3/shoe_surface.py OUT.obj"""
import sys

# Side profile, counter-clockwise in (x = length, y = height), metres.
PROFILE = [(0.000, 0.000), (0.140, -0.002), (0.270, 0.000), (0.288, 0.012), (0.292, 0.030),
           (0.280, 0.048), (0.250, 0.062), (0.200, 0.074), (0.150, 0.090), (0.120, 0.112),
           (0.095, 0.118), (0.040, 0.116), (0.012, 0.108), (-0.004, 0.080), (-0.008, 0.040)]
HALF_WIDTH = 0.05


def area2(a, b, c):
    return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])


def ear_clip(poly):
    """Triangles (index triples, counter-clockwise) of a simple CCW polygon."""
    idx = list(range(len(poly)))
    tris = []
    while len(idx) > 3:
        for k in range(len(idx)):
            i, j, l = idx[k - 1], idx[k], idx[(k + 1) % len(idx)]
            if area2(poly[i], poly[j], poly[l]) <= 0:
                continue  # reflex corner
            if any(area2(poly[i], poly[j], poly[m]) >= 0 and area2(poly[j], poly[l], poly[m]) >= 0
                   and area2(poly[l], poly[i], poly[m]) >= 0 for m in idx if m not in (i, j, l)):
                continue  # another vertex inside the ear
            tris.append((i, j, l))
            del idx[k]
            break
        else:
            raise ValueError("profile is not a simple counter-clockwise polygon")
    tris.append(tuple(idx))
    return tris


def main(out):
    n = len(PROFILE)
    lines = [f"v {x:.6f} {y:.6f} {z:.6f}" for z in (HALF_WIDTH, -HALF_WIDTH) for x, y in PROFILE]
    faces = []
    for a, b, c in ear_clip(PROFILE):
        faces.append((a, b, c))              # front cap (z = +w), normal +z
        faces.append((n + a, n + c, n + b))  # back cap (z = -w), normal -z
    for i in range(n):
        j = (i + 1) % n
        faces.append((i, n + i, n + j))      # side quad, outward for a CCW profile
        faces.append((i, n + j, j))
    lines += [f"f {a + 1} {b + 1} {c + 1}" for a, b, c in faces]
    with open(out, "w") as f:
        f.write("# low-poly shoe for tcbench's sneaker_grass (tools/mesh3/shoe_surface.py)\n")
        f.write("\n".join(lines) + "\n")


if __name__ == "__main__":
    main(sys.argv[1])
