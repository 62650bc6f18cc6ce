"""A STEP solid read back and checked against the outline it was made from: volume = area x height within 0.1 %,
the outline's bounding box and the height, the holes through its top face; how far its top face's outer edges are
from an outline.

The test command installs the optional extra transplanter[cad], so a STEP test fails without build123d; it skips
only where ``WITHOUT_CAD`` = 1 in the environment says the extra is absent on purpose."""
import importlib
import os
from pathlib import Path

import numpy as np
import pytest
from scipy.interpolate import BSpline
from scipy.spatial import cKDTree

from transplanter.shafts.keyed_bore import KeyedBore
from transplanter.solids.step import cad_installed, write_step

#: Vertices of the sampled lines whose neighbouring segments ``distance_to_lines`` measures, per point.
NEAREST = 8
#: Points ``distance_to_lines`` measures at a time.
BLOCK = 4096
#: Set to 1 to skip the STEP tests in an environment without the optional extra transplanter[cad].
WITHOUT_CAD = "TRANSPLANTER_WITHOUT_CAD"

if not cad_installed() and os.environ.get(WITHOUT_CAD) == "1":
    pytest.skip(f"{WITHOUT_CAD}=1: no transplanter[cad]", allow_module_level=True)


def kernel():
    """build123d; a failed test where it is missing and ``WITHOUT_CAD`` does not say so."""
    if not cad_installed():
        pytest.fail(f"build123d is missing: install .[dev,cad] as the test command does, or set {WITHOUT_CAD}=1 "
                    "to skip the STEP tests", pytrace=False)
    return importlib.import_module("build123d")


def read_step(path: Path):
    """The solid of a STEP file."""
    return kernel().import_step(str(path))


def read_back(solid, path: Path):
    write_step(solid, path)
    return read_step(path)


def check_solid(solid, outline: np.ndarray, area: float, height: float, holes: int, within: float = 1e-6):
    """Volume = area x height within 0.1 %, the outline's bounding box and z from 0 to ``height`` within ``within``
    mm (a polyline's solid 1e-6 mm; one of smooth curves is as far from the outline's points as its curves, the bound of
    ``solids.step``, and OpenCASCADE widens a curved solid's box by 2e-7 mm), ``holes`` through the top.

    The volume is the top face's area times the height, the faces at both ends of equal area: OpenCASCADE's own
    volume integrates each face at a fixed number of Gauss points, 0.9 % off on a gear's side faces of hundreds of
    knot spans, where the area of a plane face, integrated to a given accuracy, is exact."""
    bottom_face, top_face = end_faces(solid)
    top, bottom = face_area(top_face), face_area(bottom_face)
    assert bottom == pytest.approx(top, rel=1e-9)
    assert top * height == pytest.approx(area * height, rel=1e-3)
    box = solid.bounding_box()
    assert np.allclose([box.min.X, box.min.Y, box.max.X, box.max.Y], [*outline.min(axis=0), *outline.max(axis=0)],
                       rtol=0, atol=within)
    assert abs(box.min.Z) < within and abs(box.max.Z - height) < within          # from z = 0 up
    assert len(top_face.inner_wires()) == holes


def end_faces(solid):
    """The solid's bottom and top face: of its faces in a plane across Z (there are two), the lowest and the highest
    plane. Found by each face's plane, not by its centre of mass, which OpenCASCADE integrates over every edge of a
    gear's outline."""
    from OCP.BRepAdaptor import BRepAdaptor_Surface
    from OCP.GeomAbs import GeomAbs_Plane

    across = []
    for face in solid.faces():
        surface = BRepAdaptor_Surface(face.wrapped)
        if surface.GetType() == GeomAbs_Plane:
            plane = surface.Plane()
            if abs(abs(plane.Axis().Direction().Z()) - 1) < 1e-12:
                across.append((plane.Location().Z(), face))
    assert len(across) == 2, f"{len(across)} faces across Z"
    (_, bottom), (_, top) = sorted(across, key=lambda height_face: height_face[0])
    return bottom, top


def keyed_hole_area(bore: KeyedBore) -> float:
    """The disk, less its segment beyond the keyway's chord, plus the keyway's rectangle from that chord out."""
    r, alpha = bore.radius, bore.half_angle
    return (np.pi * r**2 - r**2 * (alpha - np.sin(alpha) * np.cos(alpha))
            + bore.key.width * (bore.reach - r * np.cos(alpha)))


def face_area(face) -> float:
    """The face's area (mm^2), integrated by OpenCASCADE to a relative accuracy of 1e-9."""
    from OCP.BRepGProp import BRepGProp
    from OCP.GProp import GProp_GProps

    properties = GProp_GProps()
    BRepGProp.SurfaceProperties_s(face.wrapped, properties, 1e-9)
    return properties.Mass()


def edge_samples(solid, spacing: float) -> list[np.ndarray]:
    """The outer edges of the solid's top face, each sampled (M, 2) at parameters about ``spacing`` mm apart (the
    solids' curves take the arc length of their points for parameter) by ``curve_samples``."""
    from OCP.BRepAdaptor import BRepAdaptor_Curve

    top = end_faces(solid)[1]
    return [curve_samples(BRepAdaptor_Curve(edge.wrapped), max(2, int(np.ceil(edge.length / spacing)) + 1))
            for edge in top.outer_wire().edges()]


def curve_samples(curve, count: int) -> np.ndarray:
    """``count`` points (M, 2) of an edge's curve as OpenCASCADE read it, at evenly spaced parameters: a line's
    between its ends, a B-spline's by scipy from its poles, knots and degree (the solids' edges are of these two
    kinds), all at once rather than a call into OpenCASCADE per point; both ends are held to OpenCASCADE's own."""
    from OCP.GeomAbs import GeomAbs_BSplineCurve, GeomAbs_Line

    first, last = curve.FirstParameter(), curve.LastParameter()
    ends = np.array([(point.X(), point.Y()) for point in (curve.Value(first), curve.Value(last))])
    along = np.linspace(0.0, 1.0, count)[:, None]
    if curve.GetType() == GeomAbs_Line:
        return ends[0] + along * (ends[1] - ends[0])
    assert curve.GetType() == GeomAbs_BSplineCurve, curve.GetType()
    spline = curve.BSpline()
    assert not spline.IsRational() and not spline.IsPeriodic()
    poles = np.array([(pole.X(), pole.Y()) for pole in spline.Poles()])
    knots = np.repeat(list(spline.Knots()), list(spline.Multiplicities()))
    samples = BSpline(knots, poles, spline.Degree())(first + along[:, 0] * (last - first))
    np.testing.assert_allclose(samples[[0, -1]], ends, rtol=0, atol=1e-9)
    return samples


def distance_to_lines(points: np.ndarray, lines: list[np.ndarray], spacing: float) -> np.ndarray:
    """Each point's distance (mm) to the nearest of the open polylines ``lines`` (each (M, 2)), their segments cut
    to at most ``spacing`` mm: the least distance to the segments on either side of its ``NEAREST`` nearest
    vertices (exact for a point nearer a line than ``spacing``, where lines meet at a corner too).

    Each segment's start and run are taken once per vertex (a line's last vertex starts none: its run is zero and
    its distance left out) and the points measured ``BLOCK`` at a time, so the (points, 2 ``NEAREST``) arrays stay
    small."""
    dense = [_cut(line, spacing) for line in lines]
    vertices = np.vstack(dense)
    x, y = vertices[:, 0].copy(), vertices[:, 1].copy()
    dx, dy = np.diff(x, append=x[-1]), np.diff(y, append=y[-1])  # segment i: vertex i -> i + 1
    ends = np.cumsum([len(line) for line in dense]) - 1
    dx[ends] = dy[ends] = 0.0
    run = dx * dx + dy * dy
    run[ends] = 1.0
    left_out = np.zeros(len(vertices))
    left_out[ends] = np.inf
    nearest = cKDTree(vertices).query(points, k=NEAREST)[1]
    squared = np.empty(len(points))
    for start in range(0, len(points), BLOCK):
        near, block = nearest[start:start + BLOCK], points[start:start + BLOCK]
        first = np.hstack([near - 1, near])     # (n, 2 NEAREST): the segments first -> first + 1
        before_start = first < 0
        first[before_start] = 0
        ax, ay = x[first] - block[:, :1], y[first] - block[:, 1:]  # from the point to each segment's start
        sx, sy = dx[first], dy[first]
        along = np.clip(-(ax * sx + ay * sy) / run[first], 0, 1)
        to_segment = (ax + along * sx) ** 2 + (ay + along * sy) ** 2 + left_out[first]
        to_segment[before_start] = np.inf
        squared[start:start + BLOCK] = np.minimum(to_segment.min(axis=1),
                                                  ((block - vertices[near[:, 0]]) ** 2).sum(axis=1))
    return np.sqrt(squared)


def _cut(line: np.ndarray, spacing: float) -> np.ndarray:
    """The polyline (M, 2) with points added along each segment so none is longer than ``spacing``."""
    pieces = np.maximum(1, np.ceil(np.hypot(*np.diff(line, axis=0).T) / spacing)).astype(int)
    segment = np.repeat(np.arange(len(pieces)), pieces)
    fraction = np.arange(len(segment)) - np.repeat(np.cumsum(pieces) - pieces, pieces)
    along = (fraction / pieces[segment])[:, None]
    return np.vstack([line[segment] + along * (line[segment + 1] - line[segment]), line[-1:]])
