#!/usr/bin/env python3
"""A garment's flatcut pattern against its real sewing pattern, on the same three figures.

USAGE
    python3 bench/garment_vs_real.py [--panels] GARMENT.obj [OUT ...]

GARMENT.obj is the draped mesh carrying its real sewing pattern in `vt` (the charts of the
texture layout are the panels; the layout may be scaled, so the real pattern is measured at the
one scale that best fits its edge lengths to the drape). Each OUT is a `flatcut flatten`
output folder of that mesh: every `*.mesh.obj` with its `*.pattern.obj` is one piece.

For the real pattern and for each OUT, printed as one JSON line:
    pieces     number of panels or pieces
    E_S, E_C   area and shape error of the whole pattern, in per cent: sum over the pieces'
               triangles of |A - A'| over sum of A (A' oriented: a triangle turned against its
               piece's majority counts A + |A'|), and sum over the pieces' edges of |L - L'| over
               sum of L (an edge on a seam counts once in each of its two pieces, for both)
    seam_cut   total length of seams and cuts on the drape: half of (the pieces' boundary
               length minus the garment's own boundary length), in the mesh's units; a seam
               between two pieces bounds both and a slit cut has two sides, so each is counted
               once

With --panels (for OUT folders of `flatcut flatten --seams from-uv`), each flatcut piece is
also matched to the real panel holding most of its triangles (by their corners' 3D positions)
and printed as one JSON line: the piece, its panel, its vertices and those of the triangles the
panel holds (a triangle a cut made has no texture points), and its match: the RMS distance
between those vertices' flat points and their texture points (each vertex's at its corner of
the panel's triangle: a panel sewn into a tube meets itself along a seam, where one 3D point
has a texture point on each side) after a rigid motion of each piece and one scale common to all
(the least-squares fit), in per cent of the piece's bounding-box diagonal, whether the best
fit mirrors the panel, and the panel's own E_S against the drape (at the real pattern's scale):
a panel far from its drape's developed shape cannot be matched by a flattening that is not.

Nothing here is flatcut's own code: the figures are recomputed from the OBJ files.
"""

import glob
import json
import math
import os
import sys
from collections import defaultdict


def read_obj(path):
    """Vertices (3D), texture coordinates and faces as lists of (v, vt or None) triples."""
    vertices, texture, faces = [], [], []
    with open(path) as handle:
        for line in handle:
            fields = line.split()
            if not fields:
                continue
            if fields[0] == "v":
                vertices.append(tuple(float(x) for x in fields[1:4]))
            elif fields[0] == "vt":
                texture.append((float(fields[1]), float(fields[2])))
            elif fields[0] == "f":
                corners = []
                for corner in fields[1:]:
                    parts = corner.split("/")
                    v = int(parts[0])
                    v = v - 1 if v > 0 else len(vertices) + v
                    t = None
                    if len(parts) > 1 and parts[1]:
                        t = int(parts[1])
                        t = t - 1 if t > 0 else len(texture) + t
                    corners.append((v, t))
                for k in range(1, len(corners) - 1):
                    faces.append((corners[0], corners[k], corners[k + 1]))
    return vertices, texture, faces


def distance(a, b):
    return math.sqrt(sum((x - y) ** 2 for x, y in zip(a, b)))


def area_3d(a, b, c):
    u = [b[i] - a[i] for i in range(3)]
    w = [c[i] - a[i] for i in range(3)]
    cross = (u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0])
    return 0.5 * math.sqrt(sum(x * x for x in cross))


def signed_area_2d(a, b, c):
    return 0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1]))


def boundary_length(points, faces):
    """Length of the edges used by exactly one face (faces index `points`)."""
    count = defaultdict(int)
    for face in faces:
        for k in range(3):
            a, b = face[k], face[(k + 1) % 3]
            count[(min(a, b), max(a, b))] += 1
    return sum(distance(points[a], points[b]) for (a, b), n in count.items() if n == 1)


class Piece:
    """One panel or piece: 3D corners and 2D corners of each of its triangles."""

    def __init__(self, triangles_3d, triangles_2d):
        self.triangles_3d = triangles_3d
        self.triangles_2d = triangles_2d

    def edges(self):
        """(3D length, 2D length) of each edge of the piece, once."""
        seen = {}
        for t3, t2 in zip(self.triangles_3d, self.triangles_2d):
            for k in range(3):
                key = frozenset((t2[k], t2[(k + 1) % 3]))
                if key not in seen:
                    seen[key] = (distance(t3[k], t3[(k + 1) % 3]), distance(t2[k], t2[(k + 1) % 3]))
        return list(seen.values())


def errors(pieces, scale):
    """Whole-pattern E_S and E_C (fractions) with the 2D coordinates multiplied by `scale`."""
    area_sum, area_error, length_sum, length_error = 0.0, 0.0, 0.0, 0.0
    for piece in pieces:
        areas = [(area_3d(*t3), signed_area_2d(*t2) * scale * scale)
                 for t3, t2 in zip(piece.triangles_3d, piece.triangles_2d)]
        majority = 1.0 if sum(a2 for _, a2 in areas) >= 0 else -1.0
        for a3, a2 in areas:
            area_sum += a3
            area_error += abs(a3 - majority * a2)
        for l3, l2 in piece.edges():
            length_sum += l3
            length_error += abs(l3 - scale * l2)
    return area_error / area_sum, length_error / length_sum


def best_scale(pieces):
    """The scale s minimising the sum of (L - s L')² over the pieces' edges."""
    numerator = denominator = 0.0
    for piece in pieces:
        for l3, l2 in piece.edges():
            numerator += l3 * l2
            denominator += l2 * l2
    return numerator / denominator


def welded(vertices):
    """Index of the first vertex at each vertex's position (exact duplicates welded)."""
    first = {}
    return [first.setdefault(v, i) for i, v in enumerate(vertices)]


def real_panels(vertices, texture, faces):
    """The charts of the texture layout, connected through shared texture edges."""
    if any(t is None for face in faces for _, t in face):
        sys.exit("the garment has a face corner without vt: no real pattern to compare")
    parent = list(range(len(faces)))

    def find(i):
        while parent[i] != i:
            parent[i] = parent[parent[i]]
            i = parent[i]
        return i

    by_edge = {}
    for index, face in enumerate(faces):
        for k in range(3):
            a, b = face[k], face[(k + 1) % 3]
            key = (frozenset((a[0], b[0])), frozenset((a[1], b[1])))
            if key in by_edge:
                parent[find(index)] = find(by_edge[key])
            else:
                by_edge[key] = index
    charts = defaultdict(list)
    for index in range(len(faces)):
        charts[find(index)].append(faces[index])
    pieces = []
    for chart in charts.values():
        triangles_3d = [tuple(vertices[v] for v, _ in face) for face in chart]
        triangles_2d = [tuple(texture[t] for _, t in face) for face in chart]
        pieces.append(Piece(triangles_3d, triangles_2d))
    boundary = sum(
        boundary_length(
            {(v, t): vertices[v] for face in chart for v, t in face},
            [tuple((v, t) for v, t in face) for face in chart])
        for chart in charts.values())
    return pieces, boundary


def flatcut_pieces(folder):
    """Every piece of a flatcut output folder, and the pieces' total 3D boundary length."""
    pieces, boundary = [], 0.0
    for mesh_path in sorted(glob.glob(os.path.join(folder, "*.mesh.obj"))):
        pattern_path = mesh_path[: -len(".mesh.obj")] + ".pattern.obj"
        points_3d, _, faces = read_obj(mesh_path)
        points_2d, _, pattern_faces = read_obj(pattern_path)
        indices = [tuple(v for v, _ in face) for face in faces]
        if [tuple(v for v, _ in face) for face in pattern_faces] != indices:
            sys.exit(f"{pattern_path}: its faces are not those of {mesh_path}")
        triangles_3d = [tuple(points_3d[v] for v in face) for face in indices]
        triangles_2d = [tuple(points_2d[v][:2] for v in face) for face in indices]
        pieces.append(Piece(triangles_3d, triangles_2d))
        boundary += boundary_length(points_3d, indices)
    if not pieces:
        sys.exit(f"{folder}: no *.mesh.obj with its *.pattern.obj")
    return pieces, boundary


def summary(name, pieces, boundary, garment_boundary, scale):
    e_s, e_c = errors(pieces, scale)
    return {
        "pattern": name,
        "pieces": len(pieces),
        "E_S": round(100 * e_s, 3),
        "E_C": round(100 * e_c, 3),
        "seam_cut": round((boundary - garment_boundary) / 2, 3),
    }


def corner_key(point):
    return tuple(round(x, 6) for x in point)


def panel_faces(panels):
    """Each real panel triangle by its three 3D corners (sorted): the panels holding such a
    triangle, each with the texture point at each of its corners. A triangle, not a corner, is
    the key: a panel sewn into a tube (a sleeve, a cuff) meets itself along a seam, where one 3D
    corner has two texture points, one on each side."""
    faces = defaultdict(list)
    for index, panel in enumerate(panels):
        for t3, t2 in zip(panel.triangles_3d, panel.triangles_2d):
            keys = [corner_key(p) for p in t3]
            faces[tuple(sorted(keys))].append((index, dict(zip(keys, t2))))
    return faces


def rigid_fit(pairs):
    """For (texture, flat) point pairs, centred: the best rotation's (or mirror's) sum of
    singular values, the texture points' and the flat points' squared norms, and whether the
    mirror fits better."""
    n = len(pairs)
    mean_u = [sum(u[i] for u, _ in pairs) / n for i in range(2)]
    mean_p = [sum(p[i] for _, p in pairs) / n for i in range(2)]
    c = [[0.0, 0.0], [0.0, 0.0]]
    norm_u = norm_p = 0.0
    for u, p in pairs:
        du = (u[0] - mean_u[0], u[1] - mean_u[1])
        dp = (p[0] - mean_p[0], p[1] - mean_p[1])
        for i in range(2):
            for j in range(2):
                c[i][j] += du[i] * dp[j]
        norm_u += du[0] ** 2 + du[1] ** 2
        norm_p += dp[0] ** 2 + dp[1] ** 2
    rotation = math.hypot(c[0][0] + c[1][1], c[0][1] - c[1][0])
    mirror = math.hypot(c[0][0] - c[1][1], c[0][1] + c[1][0])
    return max(rotation, mirror), norm_u, norm_p, mirror > rotation


def panel_matches(folder, panels):
    """One line per flatcut piece of `folder`: the real panel holding most of its triangles and
    the match over the vertices of the triangles the panel holds (a triangle a cut made has no
    texture points), each vertex paired with the texture point of its corner there."""
    faces_of = panel_faces(panels)
    rows = []
    for mesh_path in sorted(glob.glob(os.path.join(folder, "*.mesh.obj"))):
        pattern_path = mesh_path[: -len(".mesh.obj")] + ".pattern.obj"
        points_3d, _, faces = read_obj(mesh_path)
        points_2d, _, _ = read_obj(pattern_path)
        keys = [corner_key(p) for p in points_3d]
        triangles = [tuple(v for v, _ in face) for face in faces]
        found = [faces_of.get(tuple(sorted(keys[v] for v in t)), []) for t in triangles]
        votes = defaultdict(int)
        for candidates in found:
            for index in {index for index, _ in candidates}:
                votes[index] += 1
        panel = max(sorted(votes), key=lambda index: votes[index])
        texture_of = {}
        for triangle, candidates in zip(triangles, found):
            corners = next((c for index, c in candidates if index == panel), None)
            if corners is not None:
                for v in triangle:
                    texture_of.setdefault(v, corners[keys[v]])
        name = os.path.basename(mesh_path)[: -len(".mesh.obj")]
        pairs = [(texture, points_2d[v][:2]) for v, texture in sorted(texture_of.items())]
        flat = [p[:2] for p in points_2d]
        diagonal = math.hypot(max(p[0] for p in flat) - min(p[0] for p in flat),
                              max(p[1] for p in flat) - min(p[1] for p in flat))
        rows.append({"piece": name, "panel": panel, "vertices": len(points_3d),
                     "matched": len(pairs), "fit": rigid_fit(pairs), "diagonal": diagonal})
    scale = sum(row["fit"][0] for row in rows) / sum(row["fit"][1] for row in rows)
    real_scale = best_scale(panels)
    for row in rows:
        row["panel_E_S"] = round(100 * errors([panels[row["panel"]]], real_scale)[0], 3)
        sigma, norm_u, norm_p, mirrored = row.pop("fit")
        residual = max(scale * scale * norm_u - 2 * scale * sigma + norm_p, 0.0)
        rms = math.sqrt(residual / row["matched"])
        row["rms_percent"] = round(100 * rms / row.pop("diagonal"), 3)
        row["mirrored"] = mirrored
        print(json.dumps(row))


def main(argv):
    panels_wanted = "--panels" in argv
    argv = [arg for arg in argv if arg != "--panels"]
    if len(argv) < 2:
        sys.exit(__doc__)
    vertices, texture, faces = read_obj(argv[1])
    weld = welded(vertices)
    garment_boundary = boundary_length(vertices, [tuple(weld[v] for v, _ in f) for f in faces])
    panels, panel_boundary = real_panels(vertices, texture, faces)
    print(json.dumps(summary("real", panels, panel_boundary, garment_boundary,
                             best_scale(panels))))
    for folder in argv[2:]:
        pieces, boundary = flatcut_pieces(folder)
        print(json.dumps(summary(folder, pieces, boundary, garment_boundary, 1.0)))
        if panels_wanted:
            panel_matches(folder, panels)


if __name__ == "__main__":
    main(sys.argv)
