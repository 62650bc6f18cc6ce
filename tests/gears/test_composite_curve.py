"""Composite pitch curves with corners (the cusp-pitch-curve paper): segments, closure, cusps, driven corners,
curvature centres."""
import numpy as np
import pytest
import sympy as sp

from derivations import cusp as derivation
from derivations.gears import phi
from transplanter._generated.cusp import corner_angles
from transplanter._generated.gears import ellipse_center_distance
from transplanter.errors import ProblemError
from transplanter.gears import parse_problem, synthesize
from transplanter.gears.composite_curve import curvature, cusps
from transplanter.generated import numpy_twin

A, E = 30.0, 0.3
P = A * (1 - E**2)


def ellipse_and_chord(extra=None, line=None):
    segments = [{"kind": "ellipse", "phi_deg": [-150, 150], "semi_major_axis": A, "eccentricity": E},
                {"kind": "line", "phi_deg": [150, 210], **(line or {})}]
    return {"driver": {"family": "composite", "segments": segments}, "pair": extra or {}}


def r_ellipse(angle):
    return P / (1 - E * np.cos(angle))


def test_driven_radius_tangent_angle_equals_the_drivers():
    """tan mu2 = r2 / (dr2/dtheta2) reduces to r1 / r1' (the derivation), and the generated atan2s agree for a > r1."""
    a = sp.Symbol("a", positive=True)
    f = sp.Function("r1")(phi)
    r2, rate = derivation.driven_radius_and_rate(a, f)
    assert sp.simplify(r2 / rate - f / f.diff(phi)) == 0
    rng = np.random.default_rng(4)
    r, slope = rng.uniform(1, 5, 50), rng.normal(0, 5, 50)
    mu1, mu2 = numpy_twin(corner_angles)([r + rng.uniform(0.1, 5, 50)], [r], [slope])
    assert np.allclose(mu1, mu2, rtol=0, atol=1e-14)


def test_curvature_center_of_an_arc_and_of_the_ellipse_vertex():
    problem = parse_problem({"driver": {"family": "composite", "segments": [
        {"kind": "arc", "phi_deg": [0, 180], "center": [3.0, 1.0], "radius": 20.0},
        {"kind": "arc", "phi_deg": [180, 360], "center": [3.0, 1.0], "radius": 20.0}]}})
    angles = np.linspace(0, 2 * np.pi, 37)[:-1]
    radius, cross, center = curvature(problem.driver, angles)
    assert np.allclose(radius, 20.0, rtol=1e-12) and (cross > 0).all()
    assert np.allclose(center, [3.0, 1.0], atol=1e-11)
    ellipse = parse_problem(ellipse_and_chord()).driver
    radius, _, center = curvature(ellipse, np.array([0.0]))
    b2 = A**2 * (1 - E**2)                      # vertex of the ellipse: radius b^2 / a on the major axis
    assert radius[0] == pytest.approx(b2 / A, rel=1e-12)
    assert np.allclose(center[0], [A * (1 + E) - b2 / A, 0.0], atol=1e-11)


def test_straight_segment_has_an_exactly_infinite_radius():
    driver = parse_problem(ellipse_and_chord()).driver
    on_line = np.radians(np.linspace(151, 209, 30))
    radius, cross, center = curvature(driver, on_line)
    assert np.isinf(radius).all() and (cross == 0).all() and np.isnan(center).all()
    r, slope, bend = driver.evaluate(on_line)        # the generic formula divides by rounding noise there
    assert np.abs(r**2 + 2 * slope**2 - r * bend).max() < 1e-9 * r.max() ** 2


def test_chord_joins_the_ellipse_and_the_corner_turns_as_the_geometry_says():
    driver = parse_problem(ellipse_and_chord()).driver
    for angle in np.radians([150.0, 210.0]):
        r, slope, _ = driver.evaluate(np.array([angle - 1e-12, angle + 1e-12]))
        assert abs(r[0] - r[1]) < 1e-9
    ends = [r_ellipse(t) * np.array([np.cos(t), np.sin(t)]) for t in np.radians([150.0, 210.0])]
    chord_direction = np.arctan2(*(ends[1] - ends[0])[::-1])
    t = np.radians(150.0)                      # ellipse tangent d/dphi (r u) at 150 deg
    dr = -P * E * np.sin(t) / (1 - E * np.cos(t)) ** 2
    tangent = np.arctan2(dr * np.sin(t) + r_ellipse(t) * np.cos(t), dr * np.cos(t) - r_ellipse(t) * np.sin(t))
    expected = np.degrees(np.mod(chord_direction - tangent + np.pi, 2 * np.pi) - np.pi)
    found = {round(c["phi_deg"]): c for c in cusps(driver, 60.0)}
    assert found[150]["turn_deg"] == pytest.approx(expected, abs=1e-6) and expected > 0
    assert found[210]["turn_deg"] == pytest.approx(expected, abs=1e-6)        # symmetric about the x axis
    assert found[150]["driven_turn_deg"] == pytest.approx(-expected, abs=1e-6)


def test_closure_and_the_driven_corner_seen_on_the_driven_polyline():
    result = synthesize(parse_problem(ellipse_and_chord()))
    d = result.design
    assert abs(d.closure_error) < 1e-9
    grid = np.linspace(0, 2 * np.pi, 100001)        # independent: trapezoid over a dense grid
    r = d.driver.evaluate(grid)[0]
    turn = np.sum((r[1:] / (d.center_distance - r[1:]) + r[:-1] / (d.center_distance - r[:-1])) / 2 * np.diff(grid))
    assert turn == pytest.approx(2 * np.pi, rel=1e-6)
    assert d.rolling_mismatch_mm < 1e-6 * d.perimeters[0]
    report = result.to_json()
    assert [round(c["phi_deg"]) for c in report["cusps"]] == [210, 150]
    points = d.points[1]                            # driven polyline in its frame, running clockwise
    for cusp in report["cusps"]:
        k = int(np.argmin(np.abs(d.phi1 - np.radians(cusp["phi_deg"]))))
        turns = []
        for step in (1, 2):     # chords' turn, linear in the step: extrapolated to a zero step
            before, after = points[k] - points[k - step], points[k + step] - points[k]
            turns.append(np.arctan2(before[0] * after[1] - before[1] * after[0], np.dot(before, after)))
        # clockwise traversal: its left turn is the counterclockwise curve's right turn
        assert -np.degrees(2 * turns[0] - turns[1]) == pytest.approx(cusp["driven_turn_deg"], abs=0.01)
    assert report["min_curvature_radius"][0] == pytest.approx(A * (1 - E**2), rel=1e-6)   # b^2/a at the vertex


def test_one_family_split_in_two_is_the_family():
    """An ellipse cut at 0 and 180 deg closes at the generated closed-form center distance, with no cusp."""
    halves = parse_problem({"driver": {"family": "composite", "segments": [
        {"kind": "ellipse", "phi_deg": [0, 180], "semi_major_axis": A, "eccentricity": E},
        {"kind": "ellipse", "phi_deg": [180, 360], "semi_major_axis": A, "eccentricity": E}]}})
    closed = numpy_twin(ellipse_center_distance)
    result = synthesize(halves)
    assert result.design.center_distance == pytest.approx(float(np.ravel(closed([A], [E], [1.0])[0])[0]), rel=1e-12)
    assert result.to_json()["cusps"] == []


@pytest.mark.parametrize("change,message", [
    ({"line": {"distance": 20.0, "normal_deg": 180.0}}, "driver.segments[1]: starts at r ="),
    ({"segments_range": [150, 200]}, "driver.segments[1].phi_deg = [150, 200]: expected a range that ends"),
    ({"arc": True}, "driver.segments[1].center = [30.0, 0.0]: expected a point inside the circle"),
    ({"kind": "oval"}, "driver.segments[1].kind = 'oval'"),
    ({"range_reversed": True}, "driver.segments[0].phi_deg = [150.0, -150.0]: expected start < end"),
    ({"ellipse_field": {"distance": 3.0}}, "driver.segments[0].distance = 3.0: expected no such field here (known: "
                                           "eccentricity, kind, order, phi_deg, rotation_deg, semi_major_axis)"),
    ({"chord_through_centre": True}, "driver.segments[1]: the pitch radius reaches"),
])
def test_bad_segments(change, message):
    data = ellipse_and_chord(line=change.get("line"))
    second = data["driver"]["segments"][1]
    if "segments_range" in change:
        second["phi_deg"] = change["segments_range"]
    if "arc" in change:
        second.update(kind="arc", center=[30.0, 0.0], radius=10.0)
    if "kind" in change:
        second["kind"] = change["kind"]
    first = data["driver"]["segments"][0]
    if "range_reversed" in change:
        first["phi_deg"] = [150.0, -150.0]
    first.update(change.get("ellipse_field", {}))
    if "chord_through_centre" in change:                # the ellipse's ends at +-90 deg are in line with its focus
        first["phi_deg"], second["phi_deg"] = [-90, 90], [90, 270]
    with pytest.raises(ProblemError, match=None) as error:
        parse_problem(data, "f.toml")
    assert message in str(error.value) and "\n" not in str(error.value)


def test_command_gives_one_line_and_exit_2_for_segments_that_do_not_join(tmp_path, capsys):
    from transplanter.cli import main

    path = tmp_path / "bad.toml"
    path.write_text('[driver]\nfamily = "composite"\n[[driver.segments]]\nkind = "ellipse"\nphi_deg = [-150.0, 150.0]\n'
                    'semi_major_axis = 30.0\neccentricity = 0.3\n[[driver.segments]]\nkind = "line"\n'
                    'phi_deg = [150.0, 210.0]\ndistance = 15.0\nnormal_deg = 180.0\n')
    assert main(["gear", str(path)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "driver.segments[1]: starts at r =" in err


@pytest.mark.parametrize("pair,message", [
    ({"module": 2.0, "teeth": 30, "cutter": "rack"}, "pair.cutter = 'rack': expected no cutter or \"shaper\""),
    ({"driver_speed_rpm": 0.0}, "pair.driver_speed_rpm = 0.0: expected a speed other than 0"),
])
def test_bad_pair_fields_of_a_composite(pair, message):
    with pytest.raises(ProblemError) as error:
        parse_problem(ellipse_and_chord(pair), "f.toml")
    assert message in str(error.value) and "\n" not in str(error.value)


def test_corner_pressure_angle_on_a_curve_without_corners_is_refused():
    with pytest.raises(ProblemError, match=r"pair.corner_pressure_angle_deg = 22.0: expected no such field for a "
                                           r"pitch curve without corners"):
        parse_problem({"driver": {"family": "ellipse", "semi_major_axis": 30.0, "eccentricity": 0.3},
                       "pair": {"corner_pressure_angle_deg": 22.0}}, "f.toml")


def test_a_composite_without_corners_gets_the_shaper_teeth_of_its_family():
    """Two halves of one ellipse: no corner, so no corner tooth; the teeth are those the shaper cuts on the ellipse
    family itself (it raised an IndexError looking for corners before)."""
    halves = ellipse_and_chord({"module": 2.0, "teeth": 30})
    halves["driver"]["segments"] = [{"kind": "ellipse", "phi_deg": [-90, 90], "semi_major_axis": A, "eccentricity": E},
                                    {"kind": "ellipse", "phi_deg": [90, 270], "semi_major_axis": A, "eccentricity": E}]
    whole = {"driver": {"family": "ellipse", "semi_major_axis": A, "eccentricity": E},
             "pair": {"module": 2.0, "teeth": 30, "cutter": "shaper"}}
    split, family = synthesize(parse_problem(halves)), synthesize(parse_problem(whole))
    assert split.to_json()["cusps"] == [] and split.to_json()["cutter"] == "shaper"
    for ours, theirs in zip(split.teeth.outlines, family.teeth.outlines, strict=True):
        assert len(ours) == len(theirs) and np.abs(ours - theirs).max() < 1e-9 * A
