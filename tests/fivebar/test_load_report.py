"""The loads' report object, its Markdown lines and the figure, on a five-bar built here."""
import numpy as np
import pytest

from transplanter.fivebar.kinetostatics import HINGES, kinetostatics
from transplanter.fivebar.linkage import FiveBar
from transplanter.fivebar.load_figures import draw_load_figure
from transplanter.fivebar.load_report import load_json, load_markdown
from transplanter.fivebar.load_spec import LoadSpec
from transplanter.fivebar.relative_angle import RelativeAngle

MECH = FiveBar(carrier_length=50.0, carrier_angle=0.3, rod_length=250.0, hinge_b=np.array([-150.0, -100.0]),
               receiving_length=220.0, e_local=np.array([40.0, 60.0]), f_local=np.array([-30.0, 20.0]), branch=1.0)
RELATIVE = RelativeAngle(-np.pi / 2 - 0.3, np.array([0, 0.1, -0.05, 0.08, 0, -0.1, 0.05, 0, 0.02, -0.03, 0, 0.04]))
KEY_TURNS = np.radians([0.0, 18.0, 50.0, 90.0])


@pytest.fixture(scope="module")
def loads():
    return kinetostatics(MECH, RELATIVE, KEY_TURNS, LoadSpec(masses_kg={"rod": 0.7, "plate": 0.3}))


def test_json_gives_the_load_used_and_every_peak_where_it_occurs(loads):
    report = load_json(loads)
    assert report["resisting_n"] == 20.0 and "force_n" not in report
    assert report["masses_kg"] == {"carrier": 0.0, "rod": 0.7, "plate": 0.3, "receiving_plate": 0.0}
    assert report["stroke_deg"] == pytest.approx([0.0, 90.0])
    k = np.argmax(np.abs(loads.carrier_torque))
    assert (report["carrier_torque_peak_nm"], report["carrier_torque_peak_at_deg"]) == \
        (loads.carrier_torque[k], pytest.approx(np.degrees(loads.turns[k])))
    k = np.argmax(np.abs(loads.be_force))
    assert report["be_force_peak_n"] == loads.be_force[k]
    assert report["be_force_peak_at_deg"] == pytest.approx(np.degrees(loads.turns[k]))
    assert report["planet_torque_peak_nm"] == loads.planet_torque[np.argmax(np.abs(loads.planet_torque))]
    for name in HINGES:
        size = np.linalg.norm(loads.hinge_forces[name], axis=1)
        assert report["hinge_force_peak_n"][name] == pytest.approx(size.max(), rel=1e-14)
        assert report["hinge_force_peak_at_deg"][name] == pytest.approx(np.degrees(loads.turns[np.argmax(size)]))


def test_json_names_a_constant_force():
    loads = kinetostatics(MECH, RELATIVE, KEY_TURNS, LoadSpec(force_n=np.array([5.0, -8.0])))
    report = load_json(loads)
    assert report["force_n"] == [5.0, -8.0] and "resisting_n" not in report


def test_markdown_states_the_load_and_the_peaks(loads):
    report = load_json(loads)
    text = "\n".join(load_markdown(loads))
    assert "20 N at P against its velocity" in text and "rod 0.7 kg, plate 0.3 kg" in text
    assert f"{report['carrier_torque_peak_nm']:.3f} N m" in text
    assert f"{report['be_force_peak_n']:.1f} N" in text
    assert all(f"{name} {report['hinge_force_peak_n'][name]:.1f} N" in text for name in HINGES)


def test_figure_has_units_the_stroke_and_legends_off_the_data(loads):
    figure = draw_load_figure(loads, r"a $\frac{$ b")
    torques, forces = figure.axes
    assert torques.get_ylabel() == "torque (N m)" and forces.get_ylabel() == "force (N)"
    assert "(deg)" in forces.get_xlabel()
    for ax in (torques, forces):
        assert ax.get_legend().get_bbox_to_anchor().x0 > ax.get_window_extent().x1 - 1
        shaded = ax.patches[0]
        assert (shaded.get_x(), shaded.get_x() + shaded.get_width()) == pytest.approx((0.0, 90.0))
    figure.draw_without_rendering()
