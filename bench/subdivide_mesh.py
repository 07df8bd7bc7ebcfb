#!/usr/bin/env python3
"""Large test scans made from the real meshes: midpoint subdivision, optionally with scanner noise.

Each subdivision splits every triangle into four at its edges' midpoints (no smoothing: the
surface keeps its shape and its curvature stays at the original vertices), so a 20k-triangle scan
becomes 80k, then 320k. With --noise S every vertex then moves along its normal by a normally
distributed distance of standard deviation S times the mean edge length (seeded: the same file
for the same arguments), which puts curvature at every vertex as a real fine scan has.

Usage: python3 bench/subdivide_mesh.py IN.obj OUT.obj LEVELS [--noise S] [--seed N]
Only `v` and `f` lines are read (polygons are fanned into triangles); plain Python, no packages.
"""

import argparse
import math
import random


def read_obj(path):
    """Vertices and triangles (0-based) of an OBJ file."""
    vertices, triangles = [], []
    with open(path, encoding="utf-8") as lines:
        for line in lines:
            fields = line.split()
            if not fields:
                continue
            if fields[0] == "v":
                vertices.append(tuple(float(x) for x in fields[1:4]))
            elif fields[0] == "f":
                corners = [int(field.split("/")[0]) for field in fields[1:]]
                corners = [c - 1 if c > 0 else len(vertices) + c for c in corners]
                triangles.extend(
                    (corners[0], corners[k], corners[k + 1]) for k in range(1, len(corners) - 1)
                )
    return vertices, triangles


def subdivide(vertices, triangles):
    """Each triangle split into four at its edges' midpoints, shared midpoints made once."""
    vertices = list(vertices)
    midpoints = {}

    def midpoint(a, b):
        key = (min(a, b), max(a, b))
        if key not in midpoints:
            vertices.append(tuple((p + q) / 2 for p, q in zip(vertices[a], vertices[b])))
            midpoints[key] = len(vertices) - 1
        return midpoints[key]

    finer = []
    for a, b, c in triangles:
        ab, bc, ca = midpoint(a, b), midpoint(b, c), midpoint(c, a)
        finer += [(a, ab, ca), (ab, b, bc), (ca, bc, c), (ab, bc, ca)]
    return vertices, finer


def add_noise(vertices, triangles, scale, seed):
    """Each vertex moved along its area-weighted normal by N(0, scale × mean edge length)."""
    normals = [[0.0, 0.0, 0.0] for _ in vertices]
    edge_sum = 0.0
    for corners in triangles:
        p, q, r = (vertices[i] for i in corners)
        u = [q[k] - p[k] for k in range(3)]
        v = [r[k] - p[k] for k in range(3)]
        n = (u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0])
        for i in corners:
            for k in range(3):
                normals[i][k] += n[k]
        edge_sum += math.dist(p, q)
    sigma = scale * edge_sum / len(triangles)
    rng = random.Random(seed)
    moved = []
    for point, normal in zip(vertices, normals):
        length = math.sqrt(sum(x * x for x in normal)) or 1.0
        step = rng.gauss(0.0, sigma) / length
        moved.append(tuple(point[k] + normal[k] * step for k in range(3)))
    return moved


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("source")
    parser.add_argument("target")
    parser.add_argument("levels", type=int)
    parser.add_argument("--noise", type=float, default=0.0)
    parser.add_argument("--seed", type=int, default=1)
    arguments = parser.parse_args()
    vertices, triangles = read_obj(arguments.source)
    for _ in range(arguments.levels):
        vertices, triangles = subdivide(vertices, triangles)
    if arguments.noise > 0.0:
        vertices = add_noise(vertices, triangles, arguments.noise, arguments.seed)
    with open(arguments.target, "w", encoding="utf-8") as out:
        out.writelines("v %.9g %.9g %.9g\n" % v for v in vertices)
        out.writelines("f %d %d %d\n" % (a + 1, b + 1, c + 1) for a, b, c in triangles)
    print(f"{arguments.target}: {len(vertices)} vertices, {len(triangles)} triangles")


if __name__ == "__main__":
    main()
