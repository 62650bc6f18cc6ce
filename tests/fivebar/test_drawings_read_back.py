"""What a designer takes to CAD (DXF, SVG, CSV) and the animation, read back."""
import json
import os
import xml.etree.ElementTree as ElementTree
from pathlib import Path

import ezdxf
import numpy as np
import pytest
import shapely
from matplotlib.figure import Figure
from PIL import Image, ImageChops

from tests.cli.command_result_checks import check_protocol
from transplanter import fivebar, gears
from transplanter.cli import main
from transplanter.drawing.gear_sheet import GearDrawing, write_gear_sheets
from transplanter.drawing.sheet import LAYERS, TitleBlock
from transplanter.fivebar.animation import FRAMES, render_frames, write_animation
from transplanter.fivebar.drawings import LABEL_FRACTION, gear_drawings
from transplanter.fivebar.gears_on_carrier import (
    DRAWN_WITHIN_MODULES,
    carrier_to_world,
    gears_on_carrier,
    tooth_outlines,
)
from transplanter.fivebar.loop_closure import close_loop
from transplanter.gears.teeth import driven_table, driver_table
from transplanter.geometry.outline_thinning import thinned
from transplanter.shafts.keyed_bore import KeyedBore

ROOT = Path(__file__).resolve().parents[2]
EXAMPLE = ROOT / "examples/vegetable_planting.toml"
DXF_MM = 4          # $INSUNITS code of millimetres


@pytest.fixture(scope="module")
def result(example_result):
    return example_result


@pytest.fixture(scope="module")
def folder(example_result_drawings):
    return example_result_drawings[0].parent


def _table(path: Path):
    header = path.read_text().splitlines()[0].split(",")
    return dict(zip(header, np.loadtxt(path, delimiter=",", skiprows=1).T, strict=True))


def test_linkage_dxf_is_the_assembly_at_pose_1_in_millimetres(result, folder):
    document = ezdxf.readfile(folder / "linkage.dxf")
    assert document.header["$INSUNITS"] == DXF_MM
    assert set(LAYERS) <= {layer.dxf.name for layer in document.layers}
    space = document.modelspace()
    mech, rho1 = result.design.mech, result.design.relative_angle.rho1
    # pose 1 by the verification's own loop closure, not by the drawing's plate_points
    closed = close_loop(mech, [0.0], [rho1])
    expected = {"O": [0, 0], "A": closed["a"][0], "B": mech.hinge_b, "E": closed["e"][0], "F": closed["f"][0],
                "P": closed["p"][0]}
    size = np.abs(np.array(list(expected.values()), float)).max()
    holes = {(round(circle.dxf.radius, 9), tuple(np.round(np.array(circle.dxf.center)[:2], 6)))
             for circle in space.query("CIRCLE[layer=='BORE']")}
    centres = np.array([centre for _, centre in holes])
    for name in "OABEF":
        assert np.linalg.norm(centres - expected[name], axis=1).min() < 1e-6
    shafts = result.shafts.shafts
    pin_holes = [radius for radius, centre in holes
                 if min(np.linalg.norm(np.subtract(centre, expected[name])) for name in "BEF") < 1e-6]
    assert set(pin_holes) == {round(shafts["hinge"].diameter / 2, 9)}
    height = LABEL_FRACTION * float(np.linalg.norm(np.subtract(expected["B"], expected["P"])))
    labels = {text.dxf.text: np.array(text.dxf.insert)[:2] for text in space.query("TEXT[layer=='TEXT']")}
    assert set("OABEFP") | set(result.problem.labels) <= set(labels)
    for name, point in expected.items():
        assert np.linalg.norm(labels[name] - point) < 4 * height
    lengths = [np.linalg.norm(np.subtract(line.dxf.end, line.dxf.start)[:2])
               for line in space.query("LINE[layer=='CENTERLINES']")]
    for length in (mech.carrier_length, mech.rod_length, mech.receiving_length, np.hypot(*mech.hinge_b)):
        assert np.abs(np.array(lengths) - length).min() < 1e-12 * size
    triangles = [np.array(line.get_points("xy")) for line in space.query("LWPOLYLINE[layer=='CENTERLINES']")
                 if line.closed and len(line) == 3]
    (corners,) = triangles
    sides = sorted(np.linalg.norm(corners - np.roll(corners, 1, axis=0), axis=1))
    assert np.allclose(sides, sorted([mech.link_length, mech.ep, mech.fp]), rtol=1e-12)
    # the link plates and the four gears, in place
    assert len(space.query("LWPOLYLINE[layer=='OUTLINE']")) == 4 + 4
    assert len(space.query("ARC[layer=='BORE']")) == 4 and len(space.query("LWPOLYLINE[layer=='KEYWAY']")) == 4


def test_trajectory_csv_passes_the_key_poses_in_mm_and_degrees(result, folder):
    table = _table(folder / "trajectory.csv")
    assert list(table) == ["carrier_turn_deg", "carrier_angle_deg", "x_mm", "y_mm", "plate_angle_deg"]
    assert np.allclose(np.diff(table["carrier_turn_deg"]), 0.1)
    problem = result.problem
    rows = np.rint(np.degrees(problem.carrier_turns) / 0.1).astype(int)
    size = np.abs(problem.poses[:, :2]).max()
    assert np.abs(np.c_[table["x_mm"], table["y_mm"]][rows] - problem.poses[:, :2]).max() < 1e-9 * size
    assert np.abs(table["plate_angle_deg"][rows] - np.degrees(problem.poses[:, 2])).max() < 1e-9
    assert np.allclose(table["carrier_angle_deg"],
                       np.degrees(result.design.mech.carrier_angle) - table["carrier_turn_deg"])


def test_relative_angle_csv_slope_is_the_derivative_of_its_angle(folder):
    table = _table(folder / "relative_angle.csv")
    assert list(table) == ["carrier_turn_deg", "rho_deg", "rho_slope", "total_ratio_i0"]
    centred = np.gradient(table["rho_deg"], table["carrier_turn_deg"])
    assert np.abs(centred[1:-1] - table["rho_slope"][1:-1]).max() < 1e-4
    assert np.allclose(table["total_ratio_i0"] * table["rho_slope"], 1.0)
    assert table["rho_deg"][-1] - table["rho_deg"][0] == pytest.approx(360 * (1 - 1 / 3600), rel=1e-3)


def test_pitch_curve_csvs_mesh_at_the_center_distances_and_roll_equal_arcs(result, folder):
    tables = {name: _table(folder / f"pitch_curve_{name}.csv")
              for name in ("sun", "first_intermediate", "second_intermediate", "planet")}
    for table in tables.values():
        assert list(table) == ["angle_deg", "radius_mm", "x_mm", "y_mm"]
        assert np.allclose(table["radius_mm"], np.hypot(table["x_mm"], table["y_mm"]), rtol=1e-12)
        assert np.allclose(np.exp(1j * np.radians(table["angle_deg"])),
                           np.exp(1j * np.arctan2(table["y_mm"], table["x_mm"])))
    stages = (("sun", "first_intermediate"), ("second_intermediate", "planet"))
    for (driver, driven), distance in zip(stages, result.train.center_distances, strict=True):
        one, two = tables[driver], tables[driven]
        assert np.abs(one["radius_mm"] + two["radius_mm"] - distance).max() < 1e-9 * distance
        arcs = [np.linalg.norm(np.diff(np.c_[t["x_mm"], t["y_mm"]], axis=0), axis=1).sum() for t in (one, two)]
        assert arcs[0] == pytest.approx(arcs[1], rel=1e-5)


def test_gears_mesh_on_the_carrier_sun_stays_fixed_and_planet_turns_with_rod_one(result):
    placed = gears_on_carrier(result.train, result.design.mech.carrier_length)
    one, two = result.train.stage_one, result.train.stage_two
    rows = np.arange(0, len(one.phi1) - 1, 29)
    contacts = []
    for (driver, driven), c in ((placed[:2], one.phi1[rows]), (placed[2:], result.train.intermediate_turn.inverse(
            two.phi1[rows]))):
        for k, row in enumerate(rows):
            contacts.append(driver.placed(driver.pitch_curve[row:row + 1], c[k])[0, 0]
                            - driven.placed(driven.pitch_curve[row:row + 1], c[k])[0, 0])
    assert np.abs(contacts).max() < 1e-9 * result.design.mech.carrier_length
    turns = np.linspace(0, 2 * np.pi, 13)
    mech, sun = result.design.mech, placed[0]
    in_world = np.array([carrier_to_world(mech, sun.placed(sun.pitch_curve[::60], c)[0], c) for c in turns])
    assert np.abs(in_world - in_world[0]).max() < 1e-9 * mech.carrier_length
    planet_minus_rod = placed[3].angle(turns) - result.design.relative_angle.evaluate(turns)
    assert np.ptp(planet_minus_rod) < 1e-9


def test_gear_drawings_read_back_with_teeth_pitch_keyed_bore_and_mark(tmp_path):
    pair = gears.synthesize(gears.load_problem(ROOT / "examples/gear_ellipse.toml"))
    pitch = (driver_table(pair.design).points, driven_table(pair.design).points)
    drawings = [GearDrawing(name, outline, curve, KeyedBore.for_shaft(20.0, direction), TitleBlock(name, 1, "t"))
                for name, outline, curve, direction in zip(("driver", "driven"), pair.teeth.outlines, pitch,
                                                           (0.0, np.pi), strict=True)]
    written = write_gear_sheets(drawings, tmp_path)
    assert sorted(p.name for p in written) == ["driven.dxf", "driven.svg", "driver.dxf", "driver.svg"]
    for drawing in drawings:
        document = ezdxf.readfile(tmp_path / f"{drawing.name}.dxf")
        assert document.header["$INSUNITS"] == DXF_MM
        space = document.modelspace()
        teeth = list(space.query("LWPOLYLINE[layer=='OUTLINE']"))
        assert len(teeth) == 1 and teeth[0].closed
        assert np.allclose(np.array(teeth[0].get_points("xy")), drawing.outline, atol=1e-9)
        pitch_line = next(iter(space.query("LWPOLYLINE[layer=='PITCH']")))
        assert np.allclose(np.array(pitch_line.get_points("xy")), drawing.pitch_curve, atol=1e-9)
        (arc,) = space.query("ARC[layer=='BORE']")
        assert arc.dxf.radius == pytest.approx(10.0) and np.allclose(np.array(arc.dxf.center)[:2], 0)
        (keyway,) = space.query("LWPOLYLINE[layer=='KEYWAY']")
        ends = np.array(keyway.get_points("xy"))[[0, -1]]
        # the keyway starts and ends on the bore's arc, at its ends
        assert np.allclose([np.array(arc.start_point)[:2], np.array(arc.end_point)[:2]], ends[::-1], atol=1e-9)
        direction = drawing.bore.direction
        unit = np.array([np.cos(direction), np.sin(direction)])
        assert (np.array(keyway.get_points("xy")) @ unit).max() == pytest.approx(10.0 + 2.8)   # d/2 + t2, 20 mm
        mark = next(iter(space.query("LINE[layer=='MARK']")))
        start, end = np.array(mark.dxf.start)[:2], np.array(mark.dxf.end)[:2]
        root = np.linalg.norm(drawing.outline, axis=1).min()
        assert np.linalg.norm(start) == pytest.approx(12.8) and 12.8 < np.linalg.norm(end) < root
        assert np.arctan2(*(end - start)[::-1]) == pytest.approx(np.angle(np.exp(1j * direction)))
        measured = sorted(dimension.get_measurement() for dimension in space.query("DIMENSION"))
        assert np.allclose(measured, [20.0, 20.0 + 2.8], rtol=0, atol=1e-12)     # the bore, d + t2
        svg = ElementTree.parse(tmp_path / f"{drawing.name}.svg").getroot()
        assert svg.get("width").endswith("mm")
        tags = [child.tag.split("}")[-1] for child in svg]
        assert tags == ["polygon", "polyline", "polygon", "polyline"]


def test_five_bar_gear_marks_point_at_the_contact_in_pose_1(result):
    placed = gears_on_carrier(result.train, result.design.mech.carrier_length)
    drawings = gear_drawings(result, {gear.name: gear.pitch_curve for gear in placed})
    for gear, drawing in zip(placed, drawings, strict=True):
        tip = gear.placed(drawing.mark[1:], 0.0)[0, 0]
        towards = (tip - gear.center) / np.linalg.norm(tip - gear.center)
        mate = (gear.mate_center - gear.center) / np.linalg.norm(gear.mate_center - gear.center)
        assert towards @ mate == pytest.approx(1.0, abs=1e-12)


def test_animation_gif_opens_with_its_frames_and_stays_small(result, tmp_path):
    written = write_animation(result, tmp_path)
    assert written[0] == tmp_path / "animation.gif"
    assert written[0].stat().st_size < 2e6
    with Image.open(written[0]) as gif:
        assert gif.format == "GIF" and gif.n_frames == FRAMES
        gif.seek(0)
        first = gif.convert("RGB")
        gif.seek(FRAMES // 2)
        assert ImageChops.difference(first, gif.convert("RGB")).getbbox() is not None


def test_tooth_outlines_are_drawn_over_the_pitch_curves(result):
    sun = gears_on_carrier(result.train, result.design.mech.carrier_length)[0]
    teeth = {"sun": (1.05 * sun.pitch_curve, sun.center, sun.angle)}
    plain, toothed = render_frames(result, None, 2), render_frames(result, teeth, 2)
    assert ImageChops.difference(plain[1], toothed[1]).getbbox() is not None


def _farthest_from_its_chord(outline: np.ndarray, drawn: np.ndarray) -> float:
    """``drawn`` must keep a subsequence of ``outline``'s vertices; the largest distance of a dropped vertex
    from the chord that replaced it (mm), a bound on its distance from the drawn outline."""
    kept = np.flatnonzero(np.isin(outline @ [1, 1j], drawn @ [1, 1j]))
    assert len(kept) == len(drawn) and kept[0] == 0
    start = np.repeat(kept, np.diff(np.r_[kept, len(outline)]))
    end = np.r_[kept[1:], 0][np.searchsorted(kept, np.arange(len(outline)), side="right") - 1]
    a, b = outline[start], outline[end]
    along = np.clip(np.einsum("ij,ij->i", outline - a, b - a) / np.einsum("ij,ij->i", b - a, b - a), 0, 1)
    return float(np.hypot(*(a + along[:, None] * (b - a) - outline).T).max())


def test_drawn_outlines_stay_within_their_tolerance_of_the_cut_ones_and_do_not_cross_themselves(result):
    tolerance = DRAWN_WITHIN_MODULES * result.toothed.module
    drawn = tooth_outlines(result.toothed)
    for gear in result.toothed.gears:
        outline = drawn[gear.name.replace(" ", "_")]
        assert _farthest_from_its_chord(gear.outline, outline) <= tolerance
        assert shapely.is_simple(shapely.linearrings(outline)) and len(outline) < len(gear.outline) / 4


def test_thinning_keeps_an_outline_simple_where_plain_douglas_peucker_would_cross_it():
    # a flat arch 0.04 high over a spike whose tip stands 0.02 high: the arch's chord would cut the spike
    outline = np.array([(0, 0), (5, 0.04), (10, 0), (10, -1), (5.01, -1), (5.005, 0.02), (5, -1), (0, -1)])
    plain = shapely.simplify(shapely.linearrings(outline), 0.05, preserve_topology=False)
    assert not shapely.is_simple(plain)
    kept = thinned(outline, 0.05)
    assert shapely.is_simple(shapely.linearrings(kept))
    assert shapely.distance(shapely.points(outline), shapely.linearrings(kept)).max() <= 0.05


@pytest.fixture
def no_solids(monkeypatch):
    """The parts' writer as without transplanter[cad]: no STEP solids (test_fivebar_solids.py writes and checks
    those of the example's result)."""
    from transplanter.solids import part_files

    monkeypatch.setattr(part_files, "cad_installed", lambda: False)


def test_the_design_is_a_command_result(result, example_result_drawings_copied, no_solids, tmp_path):
    """What the command runner reads of the five-bar design (``CommandResult``)."""
    check_protocol(result, tmp_path)


@pytest.fixture
def quick_command(example_result_from_synthesize, example_result_drawings_copied, no_solids, monkeypatch):
    """The fivebar command on the module's result with one small figure, a stand-in animation, the session's
    drawings copied and no solids (all tested above or elsewhere; here only what the command writes and lists)."""
    from transplanter.fivebar import output_files

    def stand_in(result, folder, teeth=None):
        (folder / "animation.gif").write_bytes(b"GIF89a")
        return [folder / "animation.gif"]
    monkeypatch.setattr(fivebar.FiveBarResult, "figure_drawers",
                        lambda result: {"trajectory": lambda: Figure(figsize=(1, 1))})
    monkeypatch.setattr(output_files, "write_animation", stand_in)


@pytest.mark.parametrize("animation", [True, False])
def test_fivebar_out_holds_and_lists_the_drawings_tables_and_animation(quick_command, tmp_path, capsys, animation):
    out = tmp_path / "out"
    assert main(["fivebar", str(EXAMPLE), "--out", str(out), "--json", *([] if animation else ["--no-animation"])]) == 0
    report = json.loads(capsys.readouterr().out)
    assert report == json.loads((out / "report.json").read_text())
    gears = [f"{gear}.{kind}" for gear in ("first_intermediate", "planet", "second_intermediate", "sun")
             for kind in ("dxf", "svg")]
    parts = [f"{part}.dxf" for part in ("carrier", "push_plate_EFP", "receiving_plate_BE", "rod_AF")]
    expected = {"design": ["design.toml"], "drawing": sorted(["linkage.dxf", "drawings.pdf", *gears, *parts]),
                "figure": ["trajectory.png"],
                "report": ["report.json", "report.md"],
                "table": ["parts.csv", "pitch_curve_first_intermediate.csv", "pitch_curve_planet.csv",
                          "pitch_curve_second_intermediate.csv", "pitch_curve_sun.csv", "relative_angle.csv",
                          "trajectory.csv"]}
    if animation:
        expected["animation"] = ["animation.gif"]
    assert report["files"] == expected
    assert {p.name for p in out.iterdir()} == {name for names in expected.values() for name in names}


def test_mp4_goes_through_ffmpeg_where_it_exists(result, tmp_path, monkeypatch):
    """A stand-in ffmpeg on PATH records what it is given: raw RGB frames of the GIF's size."""
    bin_folder = tmp_path / "bin"
    bin_folder.mkdir()
    fake = bin_folder / "ffmpeg"
    fake.write_text("#!/usr/bin/env python3\nimport json, sys\nframes = sys.stdin.buffer.read()\n"
                    "open(sys.argv[-1], 'w').write(json.dumps({'args': sys.argv[1:], 'bytes': len(frames)}))\n")
    fake.chmod(0o755)
    monkeypatch.setenv("PATH", f"{bin_folder}{os.pathsep}{os.environ['PATH']}")
    written = write_animation(result, tmp_path, frames=3)
    assert [p.name for p in written] == ["animation.gif", "animation.mp4"]
    record = json.loads((tmp_path / "animation.mp4").read_text())
    with Image.open(tmp_path / "animation.gif") as gif:
        width, height = gif.size
    assert record["args"][record["args"].index("-s") + 1] == f"{width}x{height}"
    assert record["bytes"] == 3 * width * height * 3
