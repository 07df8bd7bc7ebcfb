#!/usr/bin/env python3
"""Smoothness of flatcut's crest-line cuts (issue 13), measured on the written outputs.

Usage: python3 bench/cut_smoothness.py [--sections] OUT [OUT ...]

With --sections, the section curves between pieces (the seams of kind `section` in the report:
one per run of one plane section along a piece's outline) are measured instead of the cuts. A
slit's tip inside a run (the points before and after it are the same) is a dart tip, counted
apart and not as an inner point. The corners where two runs meet on a piece's outline (an end
shared by two of the piece's section seams) are not inner points of either; they are counted
apart too, with the share of them turning by more than 20 degrees in the pattern.

For every part of OUT/report.json with cuts, and every cut (its 3D polyline `points`):
- the turning angle at each inner point of the cut, on each side of the cut in the pattern
  (OUT/<part>.pattern.obj): the angle between the two pattern boundary edges that join the
  point's copy to the copies of its neighbours on the cut (mesh vertices are matched to cut points
  by their 3D position in OUT/<part>.mesh.obj). The cut's first point (on the boundary or an
  earlier cut) and its last (a dart's tip) are not inner points;
- the length of each side of the cut in the pattern (what the DXF contour follows) against its
  length after smoothing: 20 rounds of moving every inner point half-way to the mean of its two
  neighbours (ends fixed). A zig-zag loses length, a smooth curve keeps it. A section seam
  holding a slit is measured as its runs between the slit's tips.
- the same turning angles on the cut file itself (OUT/<part>.dxf, or .REJECTED.dxf; read with
  ezdxf): at every vertex of the DXF contour that is a copy of an inner cut point, the angle
  between the contour's segments before and after it (a cut point the contour fitting dropped
  lies inside a straight segment and does not turn).
Prints per part: cuts, inner points, share of inner points over 20 degrees, worst angle, the
largest length change, the DXF's angles, and per cut the same.
"""
import json
import math
import sys
from collections import defaultdict

LIMIT_DEGREES = 20.0
SMOOTHING_ROUNDS = 20


def read_obj(path):
    vertices, faces = [], []
    with open(path) as f:
        for line in f:
            parts = line.split()
            if not parts:
                continue
            if parts[0] == "v":
                vertices.append(tuple(float(x) for x in parts[1:4]))
            elif parts[0] == "f":
                faces.append([int(x.split("/")[0]) - 1 for x in parts[1:]])
    return vertices, faces


def boundary_neighbours(faces):
    count = defaultdict(int)
    for face in faces:
        for k in range(len(face)):
            a, b = face[k], face[(k + 1) % len(face)]
            count[(min(a, b), max(a, b))] += 1
    neighbours = defaultdict(set)
    for (a, b), n in count.items():
        if n == 1:
            neighbours[a].add(b)
            neighbours[b].add(a)
    return neighbours


def key(p):
    return tuple(round(x, 6) for x in p)


def turning(a, b, c):
    u = (b[0] - a[0], b[1] - a[1])
    v = (c[0] - b[0], c[1] - b[1])
    nu, nv = math.hypot(*u), math.hypot(*v)
    if nu == 0 or nv == 0:
        return 180.0
    cosine = max(-1.0, min(1.0, (u[0] * v[0] + u[1] * v[1]) / (nu * nv)))
    return math.degrees(math.acos(cosine))


def length(points):
    return sum(math.dist(points[i], points[i + 1]) for i in range(len(points) - 1))


def smoothed(points):
    points = [list(p) for p in points]
    for _ in range(SMOOTHING_ROUNDS):
        points = [points[0]] + [
            [0.5 * points[i][k] + 0.25 * (points[i - 1][k] + points[i + 1][k])
             for k in range(len(points[i]))]
            for i in range(1, len(points) - 1)
        ] + [points[-1]]
    return points


def cut_sides(cut, copies, flat, neighbours):
    """The cut's sides in the pattern: chains of boundary edges through copies of its points."""
    points = [key(p) for p in cut["points"]]
    sides = []
    for first in sorted(copies[points[0]]):
        for second in sorted(neighbours[first] & copies[points[1]]):
            chain = [first, second]
            for i in range(2, len(points)):
                following = sorted(neighbours[chain[-1]] & copies[points[i]])
                if not following:
                    break
                chain.append(following[0])
            sides.append([flat[v][:2] for v in chain])
    return sides


def inner_copies(cut, copies, neighbours):
    """Each inner point's copies on the outline, with their outline neighbours on the cut (a
    slit's tip, where the cut turns back on itself, left out)."""
    points = [key(p) for p in cut["points"]]
    found = []
    for i in range(1, len(points) - 1):
        if points[i - 1] == points[i + 1]:
            continue
        for v in copies[points[i]]:
            before = [w for w in neighbours[v] if w in copies[points[i - 1]]]
            after = [w for w in neighbours[v] if w in copies[points[i + 1]]]
            if before and after:
                found.append((before[0], v, after[0]))
    return found


def cut_angles(cut, copies, flat, neighbours):
    return [turning(flat[b], flat[v], flat[a]) for b, v, a in inner_copies(cut, copies, neighbours)]


def dxf_contour_turns(path):
    """Turning angle at every vertex of every closed contour of the DXF, by 2D position."""
    import ezdxf

    turns = {}
    for entity in ezdxf.readfile(path).modelspace():
        if entity.dxftype() != "LWPOLYLINE" or not entity.closed:
            continue
        ring = [tuple(p) for p in entity.get_points("xy")]
        for i, p in enumerate(ring):
            turns[key(p)] = turning(ring[i - 1], p, ring[(i + 1) % len(ring)])
    return turns


def dxf_angles(out, name, cuts, copies, flat, neighbours):
    """The DXF contour's turning angles at the copies of the cuts' inner points; None without
    a DXF."""
    for path in (f"{out}/{name}.dxf", f"{out}/{name}.REJECTED.dxf"):
        try:
            turns = dxf_contour_turns(path)
        except OSError:
            continue
        return [turns[key(flat[v][:2])]
                for cut in cuts
                for _, v, _ in inner_copies(cut, copies, neighbours)
                if key(flat[v][:2]) in turns]
    return None


def slit_tips(cut):
    """The inner points of a cut where it turns back on itself (a slit's tip)."""
    points = [key(p) for p in cut["points"]]
    return sum(points[i - 1] == points[i + 1] for i in range(1, len(points) - 1))


def split_at_slit_tips(cut):
    """The cut as the runs between its slits' tips (each side of a slit a run of its own, as
    the dart's two cuts are), for the length measure."""
    points = cut["points"]
    keys = [key(p) for p in points]
    tips = [i for i in range(1, len(points) - 1) if keys[i - 1] == keys[i + 1]]
    bounds = [0] + tips + [len(points) - 1]
    return [{"points": points[a:b + 1]} for a, b in zip(bounds, bounds[1:]) if b > a]


def corner_angles(cuts, copies, flat, neighbours):
    """The pattern's turning angle at each corner where two of the part's section seams meet
    (an end shared by two of them), from the outline's edges on either side of it."""
    ends = defaultdict(int)
    for cut in cuts:
        for p in (cut["points"][0], cut["points"][-1]):
            ends[key(p)] += 1
    angles = []
    for point, count in ends.items():
        if count < 2:
            continue
        for v in copies[point]:
            around = sorted(neighbours[v])
            if len(around) == 2:
                angles.append(turning(flat[around[0]], flat[v], flat[around[1]]))
    return angles


def curves(part, sections):
    """The part's cuts, or with `sections` its section curves of more than two points."""
    if not sections:
        return part.get("cuts") or []
    return [seam for seam in part.get("seams") or []
            if seam.get("kind") == "section" and len(seam["points"]) > 2]


def measure(out, sections=False):
    report = json.load(open(f"{out}/report.json"))
    totals = [0, 0, 0, 0]
    corner_totals = [0, 0, 0]
    for part in report["parts"]:
        cuts = curves(part, sections)
        if not cuts:
            continue
        name = part["name"]
        mesh, faces = read_obj(f"{out}/{name}.mesh.obj")
        flat, _ = read_obj(f"{out}/{name}.pattern.obj")
        copies = defaultdict(set)
        for v, p in enumerate(mesh):
            copies[key(p)].add(v)
        neighbours = boundary_neighbours(faces)
        every, rows, worst_change = [], [], 0.0
        for cut in cuts:
            angles = cut_angles(cut, copies, flat, neighbours)
            every += angles
            change = max((1 - length(smoothed(side)) / length(side)
                          for part_of_cut in split_at_slit_tips(cut)
                          for side in cut_sides(part_of_cut, copies, flat, neighbours)),
                         default=0.0)
            worst_change = max(worst_change, change)
            over = sum(a > LIMIT_DEGREES for a in angles)
            rows.append(f"  cut {cut['length']:.1f}: {len(angles)} angles, {over} over "
                        f"{LIMIT_DEGREES:.0f} deg, worst {max(angles, default=0):.1f} deg, "
                        f"length change after smoothing {100 * change:.2f} %")
        over = sum(a > LIMIT_DEGREES for a in every)
        totals[0] += len(every)
        totals[1] += over
        share = 100.0 * over / max(len(every), 1)
        print(f"{out} {name}: {len(cuts)} {'sections' if sections else 'cuts'}, "
              f"{sum(cut['length'] for cut in cuts):.1f} long, "
              f"E_S {100 * part['area_error']:.3f} % E_C {100 * part['shape_error']:.3f} %; "
              f"{len(every)} inner-point angles, {share:.1f} % over {LIMIT_DEGREES:.0f} deg, "
              f"worst {max(every, default=0):.1f} deg; largest length change "
              f"{100 * worst_change:.2f} %")
        dxf = dxf_angles(out, name, cuts, copies, flat, neighbours)
        if dxf is not None:
            over = sum(a > LIMIT_DEGREES for a in dxf)
            totals[2] += len(dxf)
            totals[3] += over
            print(f"  DXF contour: {len(dxf)} vertices at inner cut points, {over} over "
                  f"{LIMIT_DEGREES:.0f} deg, worst {max(dxf, default=0):.1f} deg")
        if sections:
            corners = corner_angles(cuts, copies, flat, neighbours)
            tips = sum(slit_tips(cut) for cut in cuts)
            over = sum(a > LIMIT_DEGREES for a in corners)
            corner_totals[0] += len(corners)
            corner_totals[1] += over
            corner_totals[2] += tips
            print(f"  corners where two sections meet: {len(corners)}, {over} over "
                  f"{LIMIT_DEGREES:.0f} deg; slit tips: {tips}")
        for row in rows:
            print(row)
    print(f"{out}: {totals[0]} inner-point angles, {totals[1]} over {LIMIT_DEGREES:.0f} deg "
          f"({100.0 * totals[1] / max(totals[0], 1):.1f} %); on the DXF contours {totals[2]} "
          f"vertices at inner points, {totals[3]} over {LIMIT_DEGREES:.0f} deg "
          f"({100.0 * totals[3] / max(totals[2], 1):.1f} %)")
    if sections:
        print(f"{out}: {corner_totals[0]} corners where two sections meet, {corner_totals[1]} "
              f"over {LIMIT_DEGREES:.0f} deg; {corner_totals[2]} slit tips")


if __name__ == "__main__":
    arguments = sys.argv[1:]
    with_sections = "--sections" in arguments
    for out in (a for a in arguments if a != "--sections"):
        measure(out, with_sections)
