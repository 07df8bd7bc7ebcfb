#!/usr/bin/env python3
"""Check a DXF written by flatcut with ezdxf, independently of the Rust code.

Reads the file with ezdxf.readfile, runs doc.audit(), and checks:
  * the audit found no error (fixes are reported, and fail with --no-fixes);
  * the DXF version (--version AC1015);
  * the expected layers exist (--layer NAME, repeatable);
  * entity counts per layer and type (--count LAYER:TYPE:N, repeatable);
  * no SPLINE or ELLIPSE on a cut layer, every cut polyline closed, no zero-length segment.

Prints one JSON line with what it found; exits 1 when a check fails, 2 on bad usage.
Usage: dxf_check.py FILE [--version V] [--layer NAME]... [--count LAYER:TYPE:N]... [--no-fixes]
"""

import argparse
import collections
import json
import math
import sys

import ezdxf

CUT_LAYERS = ("CUT_OUTER", "CUT_INNER")
ZERO_LENGTH = 1e-9


def polyline_points(entity):
    """(x, y) of each vertex of an LWPOLYLINE or a 2D POLYLINE."""
    if entity.dxftype() == "LWPOLYLINE":
        return [(x, y) for x, y, *_ in entity.get_points("xyb")]
    return [(vertex.dxf.location.x, vertex.dxf.location.y) for vertex in entity.vertices]


def cut_defects(entity):
    """Defects of one entity on a cut layer."""
    kind = entity.dxftype()
    if kind in ("SPLINE", "ELLIPSE"):
        return [f"{kind} on cut layer {entity.dxf.layer}"]
    if kind not in ("LWPOLYLINE", "POLYLINE"):
        return []
    defects = []
    if not entity.is_closed:
        defects.append(f"open {kind} on cut layer {entity.dxf.layer}")
    points = polyline_points(entity)
    for index, point in enumerate(points):
        following = points[(index + 1) % len(points)]
        if math.dist(point, following) <= ZERO_LENGTH:
            defects.append(f"zero-length segment at vertex {index} of a {kind} on {entity.dxf.layer}")
    return defects


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("file")
    parser.add_argument("--version")
    parser.add_argument("--layer", action="append", default=[])
    parser.add_argument("--count", action="append", default=[])
    parser.add_argument("--no-fixes", action="store_true")
    arguments = parser.parse_args()

    failures = []
    try:
        document = ezdxf.readfile(arguments.file)
    except (IOError, ezdxf.DXFStructureError) as error:
        print(json.dumps({"file": arguments.file, "ok": False, "failures": [f"unreadable: {error}"]}))
        return 1
    auditor = document.audit()
    errors = [str(error.message) for error in auditor.errors]
    fixes = [str(fix.message) for fix in auditor.fixes]
    failures += [f"audit error: {message}" for message in errors]
    if arguments.no_fixes:
        failures += [f"audit fix: {message}" for message in fixes]

    if arguments.version and document.dxfversion != arguments.version:
        failures.append(f"version {document.dxfversion}, expected {arguments.version}")
    layers = sorted(layer.dxf.name for layer in document.layers)
    failures += [f"missing layer {name}" for name in arguments.layer if name not in layers]

    counts = collections.Counter()
    for entity in document.modelspace():
        counts[f"{entity.dxf.layer}:{entity.dxftype()}"] += 1
        if entity.dxf.layer in CUT_LAYERS:
            failures += cut_defects(entity)
    for expectation in arguments.count:
        layer, kind, expected = expectation.rsplit(":", 2)
        found = counts[f"{layer}:{kind}"]
        if found != int(expected):
            failures.append(f"{found} {kind} on {layer}, expected {expected}")

    report = {
        "file": arguments.file,
        "ok": not failures,
        "dxfversion": document.dxfversion,
        "units": document.header.get("$INSUNITS"),
        "audit_errors": len(errors),
        "audit_fixes": fixes,
        "layers": layers,
        "entities": dict(sorted(counts.items())),
        "failures": failures,
    }
    print(json.dumps(report))
    return 0 if not failures else 1


if __name__ == "__main__":
    sys.exit(main())
