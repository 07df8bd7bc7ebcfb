"""Sample generator (not part of the build or the tests): writes flatcut's STEP samples with
FreeCAD's Part workbench, i.e. the OpenCASCADE STEP writer, so that flatcut is checked against
files another CAD system wrote.

Run from the repository root, headless:

    freecadcmd samples/step-sources/freecad_samples.py

(FreeCAD 0.20, OpenCASCADE 7.6). It writes, in samples/:

- cone_frustum_freecad.step: the full closed side face of a cone frustum (bottom radius 100 mm,
  top radius 50 mm, height 80 mm), one ADVANCED_FACE on a CONICAL_SURFACE with a seam edge,
  AP214, millimetres.
- bspline_loft_freecad.step: a doubly curved B-spline face interpolated through a 5 x 4 grid of
  points (200 x 150 mm), B_SPLINE_SURFACE_WITH_KNOTS, AP214, millimetres.
- box_fillet_pocket_inch.step: a solid box 4 x 3 x 2 in with one edge filleted (radius 0.5 in)
  and a blind hole (diameter 1 in, depth 1 in) in its top face: MANIFOLD_SOLID_BREP with planes,
  cylinders and a face with an inner loop, AP214, inches.

- hemisphere_freecad.step: the spherical face of a hemisphere (radius 80 mm): one face on a
  SPHERICAL_SURFACE whose loop runs along the equator and up and down a seam through the pole
  (the degenerate edge at the pole is not written), AP214, millimetres.
- cone_apex_freecad.step: a solid cone (base radius 60 mm, height 100 mm, apex on top): a
  CONICAL_SURFACE face through its apex and a plane disk, AP214, millimetres.
- torus_quarter_freecad.step: a quarter of a torus (radii 100 and 25 mm), the toroidal face
  only, TOROIDAL_SURFACE, AP214, millimetres.
- sphere_freecad.step: a full sphere (radius 50 mm), one SPHERICAL_SURFACE face bounded by a
  VERTEX_LOOP at its south pole only (no edge at all), AP214, millimetres.
- spheroid_freecad.step: a prolate spheroid (semi-axes 40 mm along the axis, 25 mm across): a half
  ellipse revolved a full turn, one face on a SURFACE_OF_REVOLUTION of the whole ELLIPSE bounded
  by a VERTEX_LOOP only, AP214, millimetres.
- gusset_bracket_freecad.step: an L bracket (60 mm long, legs 40 mm, 2 mm thick) with a
  triangular gusset (legs 28 mm, 2 mm thick) in its corner: a MANIFOLD_SOLID_BREP of planes only,
  with two triangular faces and long thin side faces, AP214, millimetres. Area 10663.196 mm^2
  (2 x 156 + 160 x 60 for the L, + 784 + 56 sqrt 2 - 112 for the gusset).
- vase_revolved_freecad.step: a solid of revolution whose side is a B-spline profile revolved
  a full turn (SURFACE_OF_REVOLUTION) between two plane disks, AP214, millimetres.

- sheet_l_hole_freecad.step, sheet_u_freecad.step, sheet_z_freecad.step and
  sheet_readme_case_freecad.step: bent sheet-metal solids (see sheet_profile and the functions
  after it for their legs, radii and thicknesses); FLATCUT_SAMPLE_SET=sheet writes only these.

- sheet_two_bodies_freecad.step: a multi-body part, the U and the L with a hole beside a cube,
  three solids in one file (FLATCUT_SAMPLE_SET=two_bodies writes only it).

It prints each shape's area (OpenCASCADE's own integration) in mm^2: flatcut's tests compare
its tessellated areas with these figures.
"""

import math
import os
import shutil
import subprocess

import FreeCAD

# FreeCAD's Part module reads the STEP export unit (0 millimetres, 1 metres, 2 inches) and the
# schema from these preferences once, when it is imported: one process writes one unit, so the
# inch sample is written by a second run of this script with FLATCUT_SAMPLE_UNIT=in.
UNIT = os.environ.get("FLATCUT_SAMPLE_UNIT", "mm")
# FLATCUT_SAMPLE_SET=sheet writes only the sheet-metal samples (the others keep their bytes).
SAMPLE_SET = os.environ.get("FLATCUT_SAMPLE_SET", "all")
for group in ("Mod/Part/STEP", "Mod/Import/hSTEP"):
    STEP_PREFERENCES = FreeCAD.ParamGet("User parameter:BaseApp/Preferences/" + group)
    STEP_PREFERENCES.SetInt("Unit", {"mm": 0, "in": 2}[UNIT])
    STEP_PREFERENCES.SetString("Scheme", "AP214IS")

import Part  # noqa: E402  (after the preferences, see above)

SCRIPT = os.path.abspath(__file__) if "__file__" in globals() else \
    os.path.abspath("samples/step-sources/freecad_samples.py")
SAMPLES = os.path.normpath(os.path.join(os.path.dirname(SCRIPT), ".."))


def export(shape, name):
    path = os.path.join(SAMPLES, name)
    shape.exportStep(path)
    print("%s: %d faces, area %.6f mm^2" % (name, len(shape.Faces), shape.Area))


def cone_frustum_side():
    cone = Part.makeCone(100.0, 50.0, 80.0)
    side = [f for f in cone.Faces if f.Surface.__class__.__name__ == "Cone"][0]
    return Part.Shell([side])


def bspline_loft():
    rows = []
    for j in range(4):
        y = 150.0 * j / 3.0
        row = []
        for i in range(5):
            x = 200.0 * i / 4.0
            z = 30.0 * math.sin(math.pi * x / 200.0) + 20.0 * math.cos(math.pi * y / 150.0) \
                + 0.0005 * (x - 100.0) * (y - 75.0)
            row.append(FreeCAD.Vector(x, y, z))
        rows.append(row)
    surface = Part.BSplineSurface()
    surface.interpolate(rows)
    return Part.Shell([surface.toShape()])


def box_fillet_pocket():
    inch = 25.4
    box = Part.makeBox(4 * inch, 3 * inch, 2 * inch)
    edge = [e for e in box.Edges
            if abs(e.BoundBox.ZMin - 2 * inch) < 1e-9 and abs(e.BoundBox.ZMax - 2 * inch) < 1e-9
            and abs(e.BoundBox.YMin) < 1e-9 and abs(e.BoundBox.YMax) < 1e-9][0]
    filleted = box.makeFillet(0.5 * inch, [edge])
    hole = Part.makeCylinder(0.5 * inch, 1 * inch + 1.0,
                             FreeCAD.Vector(2.5 * inch, 1.75 * inch, 1 * inch))
    return filleted.cut(hole)


def faces_on(shape, kind):
    return Part.Shell([f for f in shape.Faces if f.Surface.__class__.__name__ == kind])


def hemisphere():
    return faces_on(Part.makeSphere(80.0, FreeCAD.Vector(0, 0, 0), FreeCAD.Vector(0, 0, 1), 0, 90,
                                    360), "Sphere")


def torus_quarter():
    return faces_on(Part.makeTorus(100.0, 25.0, FreeCAD.Vector(0, 0, 0), FreeCAD.Vector(0, 0, 1),
                                   -180, 180, 90), "Toroid")


def vase_revolved():
    vector = FreeCAD.Vector
    profile = Part.BSplineCurve()
    profile.interpolate([vector(60, 0, 0), vector(75, 0, 30), vector(50, 0, 70),
                         vector(40, 0, 100), vector(55, 0, 130)])
    wire = Part.Wire([Part.LineSegment(vector(0, 0, 0), vector(60, 0, 0)).toShape(),
                      profile.toShape(),
                      Part.LineSegment(vector(55, 0, 130), vector(0, 0, 130)).toShape(),
                      Part.LineSegment(vector(0, 0, 130), vector(0, 0, 0)).toShape()])
    return Part.Face(wire).revolve(vector(0, 0, 0), vector(0, 0, 1), 360)


def sphere_full():
    return Part.Shell(Part.makeSphere(50.0).Faces)


def spheroid():
    vector = FreeCAD.Vector
    # Major semi-axis (40 mm) along z, minor (25 mm) along x; the half with x > 0 is revolved.
    ellipse = Part.Ellipse(vector(0, 0, 40), vector(25, 0, 0), vector(0, 0, 0))
    start = 0.0 if ellipse.value(math.pi / 2).x > 0 else math.pi
    arc = Part.ArcOfEllipse(ellipse, start, start + math.pi)
    axis = Part.LineSegment(arc.EndPoint, arc.StartPoint)
    half = Part.Face(Part.Wire([arc.toShape(), axis.toShape()]))
    return Part.Shell(half.revolve(vector(0, 0, 0), vector(0, 0, 1), 360).Faces)


def gusset_bracket():
    vector = FreeCAD.Vector
    base = Part.makeBox(60.0, 40.0, 2.0)
    wall = Part.makeBox(60.0, 2.0, 40.0)
    outline = Part.makePolygon([vector(29, 2, 2), vector(29, 30, 2), vector(29, 2, 30), vector(29, 2, 2)])
    gusset = Part.Face(outline).extrude(vector(2, 0, 0))
    return base.fuse(wall).fuse(gusset).removeSplitter()


def sheet_profile(steps, radius, thickness, width):
    """A bent sheet: a thick 2D profile in the xy plane extruded along z by `width`.

    `steps` walks side A of the sheet from the origin along +x: a number is a straight of that
    length, a pair ("bend", degrees) turns by that angle (positive to the left, towards side B,
    which lies `thickness` to the left of side A). Every bend has inner radius `radius`; side A
    and side B are concentric arcs of radii `radius` and `radius + thickness` about one centre.
    The straights have the same length on both sides, so the flat length at K is
    sum(straights) + sum(radians * (radius + K * thickness)).
    """
    vector = FreeCAD.Vector
    point, heading = (0.0, 0.0), 0.0
    side_a, side_b = [], []

    def left(angle):
        return (-math.sin(angle), math.cos(angle))

    def at(p, angle, offset):
        n = left(angle)
        return vector(p[0] + offset * n[0], p[1] + offset * n[1], 0)

    for step in steps:
        if isinstance(step, tuple):
            turn = math.radians(step[1])
            n = left(heading)
            if turn > 0:
                radius_a, radius_b, sign = radius + thickness, radius, 1.0
            else:
                radius_a, radius_b, sign = radius, radius + thickness, -1.0
            centre = (point[0] + sign * radius_a * n[0], point[1] + sign * radius_a * n[1])

            def on_arc(r, angle):
                # The point of the arc of radius r about the centre where the heading is `angle`.
                m = left(angle)
                return vector(centre[0] - sign * r * m[0], centre[1] - sign * r * m[1], 0)

            end = heading + turn
            middle = heading + turn / 2
            side_a.append(Part.Arc(on_arc(radius_a, heading), on_arc(radius_a, middle),
                                   on_arc(radius_a, end)).toShape())
            side_b.append(Part.Arc(on_arc(radius_b, heading), on_arc(radius_b, middle),
                                   on_arc(radius_b, end)).toShape())
            last = on_arc(radius_a, end)
            point, heading = (last.x, last.y), end
        else:
            start = point
            point = (point[0] + step * math.cos(heading), point[1] + step * math.sin(heading))
            side_a.append(Part.LineSegment(at(start, heading, 0), at(point, heading, 0)).toShape())
            side_b.append(Part.LineSegment(at(start, heading, thickness),
                                           at(point, heading, thickness)).toShape())
    end_cap = Part.LineSegment(side_a[-1].Vertexes[-1].Point, side_b[-1].Vertexes[-1].Point)
    start_cap = Part.LineSegment(side_b[0].Vertexes[0].Point, side_a[0].Vertexes[0].Point)
    edges = side_a + [end_cap.toShape()] + [e.reversed() for e in reversed(side_b)] + \
        [start_cap.toShape()]
    face = Part.Face(Part.Wire(Part.__sortEdges__(edges)))
    return face.extrude(vector(0, 0, width))


def sheet_l_hole():
    # L: legs 50 and 30 mm, 90 degree bend, R 2, t 2, 40 wide; a 10 mm hole through the 50 leg.
    solid = sheet_profile([50.0, ("bend", 90.0), 30.0], 2.0, 2.0, 40.0)
    hole = Part.makeCylinder(5.0, 10.0, FreeCAD.Vector(25.0, -4.0, 20.0), FreeCAD.Vector(0, 1, 0))
    return solid.cut(hole).removeSplitter()


def sheet_u():
    # U: legs 40, 60, 40 mm, two 90 degree bends the same way, R 3, t 1.5, 30 wide.
    return sheet_profile([40.0, ("bend", 90.0), 60.0, ("bend", 90.0), 40.0], 3.0, 1.5, 30.0)


def sheet_z():
    # Z: legs 30, 40, 30 mm, bends of +90 and -90 degrees, R 2, t 2, 25 wide.
    return sheet_profile([30.0, ("bend", 90.0), 40.0, ("bend", -90.0), 30.0], 2.0, 2.0, 25.0)


def sheet_readme_case():
    # FreeCAD SheetMetal README test case: t 2, inner radius 1.64, 90 degrees, legs 48.12 mm
    # (flange 51.76 mm outside), 30 wide.
    return sheet_profile([48.12, ("bend", 90.0), 48.12], 1.64, 2.0, 30.0)


def sheet_hat():
    # Hat section: brims 20, sides 30, top 40 mm; bends +90, -90, -90, +90; R 2, t 2, 30 wide.
    steps = [20.0, ("bend", 90.0), 30.0, ("bend", -90.0), 40.0, ("bend", -90.0), 30.0,
             ("bend", 90.0), 20.0]
    return sheet_profile(steps, 2.0, 2.0, 30.0)


def sheet_hem():
    # Hem: legs 40 and 20 mm folded back by 180 degrees, R 1, t 1, 30 wide (the legs' inner skins
    # 2 mm apart).
    return sheet_profile([40.0, ("bend", 180.0), 20.0], 1.0, 1.0, 30.0)


def sheet_flange_holes():
    # L: legs 60 and 40 mm, R 2, t 2, 50 wide; three 6 mm holes across the 40 mm flange (the
    # flange that is not the base face), 15 mm up it, at 10, 25 and 40 mm across.
    radius, thickness = 2.0, 2.0
    solid = sheet_profile([60.0, ("bend", 90.0), 40.0], radius, thickness, 50.0)
    x = 60.0 + radius + thickness
    for across in (10.0, 25.0, 40.0):
        hole = Part.makeCylinder(3.0, 10.0, FreeCAD.Vector(x - 5.0, radius + thickness + 15.0,
                                                          across), FreeCAD.Vector(1, 0, 0))
        solid = solid.cut(hole)
    return solid.removeSplitter()


def relief_box(radius, thickness, flange):
    # Box with four flanges and corner reliefs: base 60 x 40 mm (flat parts), flanges `flange`
    # up on all four sides. Two U profiles share the base: the one across the 60 mm side
    # extruded over the other's 40 mm flat base only, and the other way round, so each corner
    # is open where the two bends would meet (a rectangular relief as wide as the bend zones).
    # Its base face meets its other side only through the bends (the reliefs leave its corners
    # bare): no wall joins the two sides of the base.
    setback = radius + thickness
    across_60 = sheet_profile([flange, ("bend", 90.0), 60.0, ("bend", 90.0), flange], radius,
                              thickness, 40.0)
    across_60.translate(FreeCAD.Vector(0, 0, setback))
    across_40 = sheet_profile([flange, ("bend", 90.0), 40.0, ("bend", 90.0), flange], radius,
                              thickness, 60.0)
    # In its own frame the base runs along y at x = flange + setback (outer skin); turn it about
    # that line so its base runs along z, then move its extrusion onto y.
    across_40.rotate(FreeCAD.Vector(flange + setback, 0, 0), FreeCAD.Vector(1, 0, 0), 90.0)
    across_40.translate(FreeCAD.Vector(0, setback + 60.0, 0))
    return across_60.fuse(across_40)


def sheet_box():
    # The relief box (R 2, t 2, flanges 20) with a 10 mm hole in the middle of its base.
    radius, thickness, flange = 2.0, 2.0, 20.0
    setback = radius + thickness
    box = relief_box(radius, thickness, flange)
    hole = Part.makeCylinder(5.0, 10.0, FreeCAD.Vector(flange + setback - 5.0, setback + 30.0,
                                                      setback + 20.0), FreeCAD.Vector(1, 0, 0))
    return box.cut(hole).removeSplitter()


def sheet_box_plain():
    # The relief box (R 2, t 2, flanges 20) as it usually is: no hole anywhere, so its base
    # meets its other skin only through the four bends. Flat at K: a cross of arms 20 + BA over
    # a 60 x 40 base, 60 + 2 (20 + BA) by 40 + 2 (20 + BA).
    return relief_box(2.0, 2.0, 20.0).removeSplitter()


def sheet_dimple(centre_z=20.0):
    # The L of sheet_l_hole without its hole (legs 50 and 30, R 2, t 2, 40 wide) with a round
    # dimple pressed out of the 50 mm leg's outside (side A, y = 0), centred at x 25, z 20: in
    # every plane through its axis (the line x 25, z 20 along y) side A is a spherical cap of
    # radius 20 about (rho 0, y 20 - D) running, at 30 degrees from the axis, tangent into a
    # fillet of radius 5 about (rho 12.5, y -5) that meets the flat tangent at rho 12.5; side B
    # is the same arcs at 2 mm along their normals (radii 18 and 7), so the dimple is a sheet of
    # thickness 2 too. Depth D = 25 (1 - cos 30) = 3.3494. Its faces are two spheres and two
    # tori: not developable. A stretch-formed feature: the blank under it is flat.
    vector = FreeCAD.Vector
    radius, thickness, width = 2.0, 2.0, 40.0
    cap, fillet, beta = 20.0, 5.0, math.radians(30.0)
    rim = (cap + fillet) * math.sin(beta)
    depth = (cap + fillet) * (1.0 - math.cos(beta))
    centre_x, outer = 25.0, 15.0
    solid = sheet_profile([50.0, ("bend", 90.0), 30.0], radius, thickness, width)

    def point(rho, y):
        return vector(centre_x + rho, y, centre_z)

    def cap_point(r, phi):
        return point(r * math.sin(phi), cap - depth - r * math.cos(phi))

    def fillet_point(r, psi):
        return point(rim - r * math.sin(psi), -fillet + r * math.cos(psi))

    edges = []
    for offset in (0.0, thickness):
        r_cap, r_fillet = cap - offset, fillet + offset
        edges.append(Part.Arc(cap_point(r_cap, 0.0), cap_point(r_cap, beta / 2),
                              cap_point(r_cap, beta)).toShape())
        edges.append(Part.Arc(fillet_point(r_fillet, beta), fillet_point(r_fillet, beta / 2),
                              fillet_point(r_fillet, 0.0)).toShape())
        edges.append(Part.LineSegment(point(rim, offset), point(outer, offset)).toShape())
    edges.append(Part.LineSegment(point(outer, 0.0), point(outer, thickness)).toShape())
    edges.append(Part.LineSegment(cap_point(cap, 0.0), cap_point(cap - thickness, 0.0)).toShape())
    profile = Part.Face(Part.Wire(Part.__sortEdges__(edges)))
    disc = profile.revolve(vector(centre_x, 0, centre_z), vector(0, 1, 0), 360)
    if centre_z - outer < 0.0:
        # Cut by the sheet's edge (z = 0): only the part over the sheet stays.
        disc = disc.common(Part.makeBox(60.0, 60.0, width, vector(0.0, -30.0, 0.0)))
    hole = Part.makeCylinder(outer, 10.0, vector(centre_x, -5.0, centre_z), vector(0, 1, 0))
    return solid.cut(hole).fuse(disc).removeSplitter()


def sheet_spline_flange():
    # The L of sheet_l_hole without its hole (legs 50 and 30, R 2, t 2, 40 wide) whose 30 mm
    # flange has both its sides written as B-spline surfaces (flat ones, as some exporters
    # write planes): a formed region, to flatcut, that runs into the bend, so it cannot be drawn
    # as its projection onto one flange.
    solid = sheet_profile([50.0, ("bend", 90.0), 30.0], 2.0, 2.0, 40.0)
    faces = []
    for face in solid.Faces:
        flat_x = face.Surface.__class__.__name__ == "Plane" and abs(face.Area - 1200.0) < 1e-6
        faces.append(face.toNurbs().Faces[0] if flat_x else face)
    shell = Part.Shell(faces)
    shell.sewShape()
    return Part.Solid(shell)


def sheet_perforated():
    # A 504-face sheet part for the timing measure (README, docs/sheet-metal.md): a U of legs
    # 60, 200 and 60 mm, R 2, t 1.5, 300 wide, with 490 holes of 4 mm: a 7 x 40 grid through
    # the first leg (y in [0, t]) and a 7 x 30 grid through the base (x in [62, 63.5]). Faces:
    # 10 on the skins, 4 walls round the edge, 490 hole walls.
    solid = sheet_profile([60.0, ("bend", 90.0), 200.0, ("bend", 90.0), 60.0], 2.0, 1.5, 300.0)
    vector = FreeCAD.Vector
    holes = []
    for i in range(40):
        for j in range(7):
            holes.append(Part.makeCylinder(2.0, 10.0, vector(8.0 + 6.5 * j, -4.0, 10.0 + 7.0 * i),
                                           vector(0, 1, 0)))
    for i in range(30):
        for j in range(7):
            holes.append(Part.makeCylinder(2.0, 10.0, vector(70.0, 15.0 + 25.0 * j, 12.0 + 9.5 * i),
                                           vector(-1, 0, 0)))
    return solid.cut(Part.makeCompound(holes)).removeSplitter()


def sheet_cone_flange():
    # A hopper: a conical wall (radii 60 and 30 at the bottom and top, 50 high, 1.5 thick
    # radially) on a flat flange ring 1.5 thick out to radius 80. Sheet metal with a conical
    # transition, which flatcut refuses as sheet metal with its reason (not unfolded yet).
    wall = Part.makeCone(60.0, 30.0, 50.0).cut(Part.makeCone(58.5, 28.5, 50.0))
    flange = Part.makeCylinder(80.0, 1.5).cut(Part.makeCylinder(58.5, 1.5))
    return wall.fuse(flange).removeSplitter()


def sheet_conical_bend():
    # A conical bend between two flat rectangular flanges: the bend's inner skin is a cone of
    # half-angle alpha (tan alpha = 0.1) about the z axis, apex at the origin, its outer skin the
    # coaxial cone 2 mm away along the normal (apex 2 / sin alpha down the axis). The sheet's
    # cross-section in the meridian plane is the rectangle {s g + d n}, s (slant from the inner
    # apex) in [20, 60], d in [0, 2], g the generator and n the outward normal: revolved about the
    # axis by dphi it is the bend (inner radius of curvature s tan alpha: 2 at the small end, 6 at
    # the large one; its end walls are normal to the sheet), extruded along the circumferential
    # direction it is a flange tangent to the bend along a generator: 50 long on one side, 30 on
    # the other. dphi makes the flanges' dihedral angle 90 degrees: cos dphi = -tan^2 alpha.
    # Flat at K (docs/sheet-metal.md, "Conical bends"): an annular sector of angle
    # dphi sin alpha and radii 20 + K t cot alpha + [0, 40], a 40 x 50 and a 40 x 30 rectangle
    # on its two straight edges.
    vector = FreeCAD.Vector
    tan_alpha, thickness, slant, width = 0.1, 2.0, 20.0, 40.0
    alpha = math.atan(tan_alpha)
    dphi = math.degrees(math.acos(-tan_alpha ** 2))
    generator = vector(math.sin(alpha), 0, math.cos(alpha))
    normal = vector(math.cos(alpha), 0, -math.sin(alpha))
    corners = [generator * s + normal * d for s, d in
               ((slant, 0.0), (slant + width, 0.0), (slant + width, thickness),
                (slant, thickness))]
    profile = Part.Face(Part.makePolygon(corners + [corners[0]]))
    bend = profile.revolve(vector(0, 0, 0), vector(0, 0, 1), dphi)
    first = profile.extrude(vector(0, -50.0, 0))
    turned = profile.copy()
    turned.rotate(vector(0, 0, 0), vector(0, 0, 1), dphi)
    onward = vector(-math.sin(math.radians(dphi)), math.cos(math.radians(dphi)), 0)
    second = turned.extrude(onward * 30.0)
    return bend.fuse([first, second]).removeSplitter()


def boxes_touching():
    # Two 20 mm cubes sharing one corner and two 10 x 10 x 5 plates sharing one edge: four
    # solids in one file, which must stay four parts (not welded at the shared corner and edge).
    vector = FreeCAD.Vector
    solids = [
        Part.makeBox(20.0, 20.0, 20.0),
        Part.makeBox(20.0, 20.0, 20.0, vector(20.0, 20.0, 20.0)),
        Part.makeBox(10.0, 10.0, 5.0, vector(60.0, 0.0, 0.0)),
        Part.makeBox(10.0, 10.0, 5.0, vector(70.0, 0.0, 5.0)),
    ]
    return Part.makeCompound(solids)


def sheet_two_bodies():
    # A multi-body part: the U and the L with a hole (sheet_u, sheet_l_hole) 200 mm apart, and a
    # 20 mm cube, three solids in one file. Each sheet unfolds on its own; the cube is a block.
    vector = FreeCAD.Vector
    bent_l = sheet_l_hole()
    bent_l.translate(vector(200.0, 0.0, 0.0))
    return Part.makeCompound([sheet_u(), bent_l, Part.makeBox(20.0, 20.0, 20.0, vector(-100.0, 0.0, 0.0))])


def sheet_samples():
    export(sheet_l_hole(), "sheet_l_hole_freecad.step")
    export(sheet_u(), "sheet_u_freecad.step")
    export(sheet_z(), "sheet_z_freecad.step")
    export(sheet_readme_case(), "sheet_readme_case_freecad.step")
    export(sheet_hat(), "sheet_hat_freecad.step")
    export(sheet_hem(), "sheet_hem_freecad.step")
    export(sheet_flange_holes(), "sheet_flange_holes_freecad.step")
    export(sheet_box(), "sheet_box_freecad.step")


def main():
    if SAMPLE_SET == "sheet":
        sheet_samples()
    elif SAMPLE_SET == "cone":
        export(sheet_cone_flange(), "sheet_cone_flange_freecad.step")
        export(boxes_touching(), "boxes_touching_freecad.step")
    elif SAMPLE_SET == "conical_bend":
        export(sheet_conical_bend(), "sheet_conical_bend_freecad.step")
    elif SAMPLE_SET == "box_plain":
        export(sheet_box_plain(), "sheet_box_plain_freecad.step")
    elif SAMPLE_SET == "dimple":
        export(sheet_dimple(), "sheet_dimple_freecad.step")
        export(sheet_spline_flange(), "sheet_spline_flange_freecad.step")
    elif SAMPLE_SET == "edge_dimple":
        # The dimple 8 mm from the 50 mm leg's edge: cut by it, so it reaches a wall.
        export(sheet_dimple(8.0), "sheet_edge_dimple_freecad.step")
    elif SAMPLE_SET == "perforated":
        export(sheet_perforated(), "sheet_perforated_freecad.step")
    elif SAMPLE_SET == "two_bodies":
        export(sheet_two_bodies(), "sheet_two_bodies_freecad.step")
    elif UNIT == "mm":
        export(cone_frustum_side(), "cone_frustum_freecad.step")
        export(bspline_loft(), "bspline_loft_freecad.step")
        export(hemisphere(), "hemisphere_freecad.step")
        export(Part.makeCone(60.0, 0.0, 100.0), "cone_apex_freecad.step")
        export(torus_quarter(), "torus_quarter_freecad.step")
        export(vase_revolved(), "vase_revolved_freecad.step")
        export(sphere_full(), "sphere_freecad.step")
        export(spheroid(), "spheroid_freecad.step")
        export(gusset_bracket(), "gusset_bracket_freecad.step")
        sheet_samples()
        environment = dict(os.environ, FLATCUT_SAMPLE_UNIT="in")
        subprocess.run([shutil.which("freecadcmd"), SCRIPT], env=environment, check=True)
    else:
        export(box_fillet_pocket(), "box_fillet_pocket_inch.step")


main()
