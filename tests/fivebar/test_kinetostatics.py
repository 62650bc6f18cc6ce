"""Kinetostatics of a five-bar: the virtual-work torques and the forces against an independent free-body
equilibrium, the derived Jacobians against finite differences of the forward kinematics, the transmission-angle
formula for the force in BE, no load no force, and bad loads."""
import subprocess
import sys
import tomllib
from pathlib import Path

import numpy as np
import pytest

from transplanter.errors import ProblemError
from transplanter.fivebar.kinetostatics import HINGES, jacobians, kinetostatics
from transplanter.fivebar.linkage import FiveBar
from transplanter.fivebar.load_spec import GRAVITY, LoadSpec
from transplanter.fivebar.problem import parse_problem
from transplanter.fivebar.relative_angle import RelativeAngle

ROOT = Path(__file__).resolve().parents[2]
EXAMPLE = ROOT / "examples/vegetable_planting.toml"
# A five-bar built here: the rod hangs from a 50 mm carrier, B-E-F closes all round (sin^2 EBF >= 0.07) and the
# relative angle increases (rho' >= 0.8), with a wavy spline so that rho' varies over the turn.
MECH = FiveBar(carrier_length=50.0, carrier_angle=0.3, rod_length=250.0, hinge_b=np.array([-150.0, -100.0]),
               receiving_length=220.0, e_local=np.array([40.0, 60.0]), f_local=np.array([-30.0, 20.0]), branch=1.0)
RELATIVE = RelativeAngle(-np.pi / 2 - 0.3, np.array([0, 0.1, -0.05, 0.08, 0, -0.1, 0.05, 0, 0.02, -0.03, 0, 0.04]))
KEY_TURNS = np.radians([0.0, 18.0, 50.0, 90.0])
TURNS = np.linspace(0, 2 * np.pi, 360, endpoint=False)
MASSES = {"carrier": 1.2, "rod": 0.7, "plate": 0.3, "receiving_plate": 0.4}
LOADS = {"resisting with masses": LoadSpec(masses_kg=MASSES),
         "constant force with masses": LoadSpec(force_n=np.array([15.0, -40.0]), masses_kg=MASSES),
         "resisting, no masses": LoadSpec(resisting_n=35.0)}


def cross(u, v):
    return u[0] * v[1] - u[1] * v[0]


def free_body(point, load_at_p, weights, slope):
    """Every link in equilibrium at one turn, solved for the unknowns f_E, f_F, f_A, f_O, f_B (N; the forces at E
    and F on the plate, at A on the rod, at O on the carrier, at B on BE), T_planet (the train on the rod), T_sun
    (the frame on the sun) and T_drive (on the carrier), counterclockwise (N mm). The train passes pure torques and
    loses no power: in the carrier's frame the sun turns at 1, the planet at rho', so T_sun = rho' T_planet, and it
    puts T_sun - T_planet on the carrier."""
    o, a, b, e, f, p = (point[name] for name in "OABEFP")
    centers = {"carrier": a / 2, "rod": (a + f) / 2, "plate": (e + f + p) / 3, "receiving_plate": (b + e) / 2}
    rows, rhs = [], []

    def equation(terms, value):
        row = np.zeros(13)
        for column, coefficient in terms:
            row[column] += coefficient
        rows.append(row)
        rhs.append(value)

    fe, ff, fa, fo, fb, planet, sun, drive = 0, 2, 4, 6, 8, 10, 11, 12
    for axis in range(2):      # forces on the plate, BE, the rod, the carrier
        equation([(fe + axis, 1), (ff + axis, 1)], -(load_at_p[axis] + weights["plate"][axis]))
        equation([(fb + axis, 1), (fe + axis, -1)], -weights["receiving_plate"][axis])
        equation([(fa + axis, 1), (ff + axis, -1)], -weights["rod"][axis])
        equation([(fo + axis, 1), (fa + axis, -1)], -weights["carrier"][axis])

    def moment(at, column, sign=1):      # cross(at, f) for the unknown force in ``column``
        return [(column, -sign * at[1]), (column + 1, sign * at[0])]

    equation(moment(e, fe) + moment(f, ff), -cross(p, load_at_p) - cross(centers["plate"], weights["plate"]))
    equation(moment(b, fb) + moment(e, fe, -1), -cross(centers["receiving_plate"], weights["receiving_plate"]))
    equation(moment(a, fa) + moment(f, ff, -1) + [(planet, 1)], -cross(centers["rod"], weights["rod"]))
    equation(moment(o, fo) + moment(a, fa, -1) + [(drive, 1), (sun, 1), (planet, -1)],
             -cross(centers["carrier"], weights["carrier"]))
    equation([(sun, 1), (planet, -slope)], 0.0)
    x = np.linalg.solve(np.array(rows), np.array(rhs))
    return {"E": x[fe:fe + 2], "F": x[ff:ff + 2], "A": x[fa:fa + 2], "O": x[fo:fo + 2], "B": x[fb:fb + 2],
            "planet": x[planet], "drive": x[drive]}


def hinges(turns):
    state = MECH.forward(turns, RELATIVE.evaluate(turns))
    return {"O": np.zeros((len(turns), 2)), "A": state["a"], "B": np.broadcast_to(MECH.hinge_b, (len(turns), 2)),
            "E": state["e"], "F": state["f"], "P": state["p"]}


def test_the_constructed_design_closes_and_turns_its_rod_forward():
    """The premise of the tests below: no dead point, a positive ratio, a load on part of the turn."""
    state = MECH.forward(TURNS, RELATIVE.evaluate(TURNS))
    assert state["margin"].min() > 0.05
    assert RELATIVE.evaluate(TURNS, 1).min() > 0.5


@pytest.mark.parametrize("name", sorted(LOADS))
def test_virtual_work_matches_free_body_equilibrium(name):
    """Carrier and planet torques (virtual work through the derived Jacobians), the force in BE and the hinge
    forces equal those of the plate, rod, carrier and receiving plate each in equilibrium, at every turn."""
    load = LOADS[name]
    result = kinetostatics(MECH, RELATIVE, KEY_TURNS, load, TURNS)
    point = hinges(TURNS)
    weights = {link: np.array([0.0, -mass * GRAVITY]) for link, mass in load.masses_kg.items()}
    slope = RELATIVE.evaluate(TURNS, 1)
    scale = np.abs(result.force_at_p).max() + GRAVITY * sum(MASSES.values())
    for k in range(len(TURNS)):
        body = free_body({key: value[k] for key, value in point.items()}, result.force_at_p[k], weights, slope[k])
        assert result.carrier_torque[k] == pytest.approx(-body["drive"] / 1000, abs=1e-9 * scale)
        assert result.planet_torque[k] == pytest.approx(body["planet"] / 1000, abs=1e-9 * scale)
        for hinge in HINGES:
            np.testing.assert_allclose(result.hinge_forces[hinge][k], body[hinge], atol=1e-9 * scale, rtol=0)
        toward_b = (MECH.hinge_b - point["E"][k]) / MECH.receiving_length
        assert result.be_force[k] == pytest.approx(body["E"] @ toward_b, abs=1e-9 * scale)
    assert np.abs(result.carrier_torque).max() > 0.1 and np.abs(result.be_force).max() > 1.0


@pytest.mark.parametrize("held", [False, True])
def test_jacobians_match_finite_differences_of_the_forward_kinematics(held):
    """dP/dc, dE/dc, dF/dc and dA/dc (carrier turning, rho(c) driving the rod), and the same with the carrier
    held and the rod turned about A, against central differences of ``FiveBar.forward``."""
    per_turn, per_rod_turn = jacobians(MECH, RELATIVE, TURNS)
    step = 1e-6

    def place(shift):
        if held:
            return MECH.forward(TURNS, RELATIVE.evaluate(TURNS) + shift)
        return MECH.forward(TURNS + shift, RELATIVE.evaluate(TURNS + shift))

    ahead, behind = place(step), place(-step)
    derived = per_rod_turn if held else per_turn
    for name, output in (("p", "point_p"), ("e", "hinge_e"), ("f", "hinge_f"), ("a", "hinge_a")):
        difference = (ahead[name] - behind[name]) / (2 * step)
        np.testing.assert_allclose(derived[output], difference, atol=1e-6 * np.abs(difference).max(), rtol=0)
    plate_center = (ahead["e"] + ahead["f"] + ahead["p"] - behind["e"] - behind["f"] - behind["p"]) / (6 * step)
    np.testing.assert_allclose(derived["plate_center"], plate_center, atol=1e-6 * np.abs(plate_center).max(), rtol=0)


def test_be_force_is_the_moment_about_f_over_the_transmission_angle():
    """|F_BE| = M_F / (EF sin mu), mu the angle between EF and BE at E, M_F the moment about F of the
    loads on the plate (the planting force and the plate's own weight; BE weightless, a two-force link)."""
    load = LoadSpec(force_n=np.array([-12.0, 25.0]), masses_kg={"plate": 0.5, "rod": 2.0})
    result = kinetostatics(MECH, RELATIVE, KEY_TURNS, load, TURNS)
    point = hinges(TURNS)
    e, f, p, b = point["E"], point["F"], point["P"], point["B"]
    weight = np.array([0.0, -0.5 * GRAVITY])
    moment_f = cross((p - f).T, result.force_at_p.T) + cross(((e + f + p) / 3 - f).T, weight)
    plate = np.linalg.norm(e - f, axis=1)
    sin_mu = np.abs(cross((f - e).T, (b - e).T)) / (plate * MECH.receiving_length)
    np.testing.assert_allclose(np.abs(result.be_force), np.abs(moment_f) / (plate * sin_mu), rtol=1e-10, atol=1e-10)


def test_default_load_resists_p_on_the_pushing_stroke_only():
    """20 N against P's velocity from the first to the last key pose's turn (ends included), nothing elsewhere."""
    result = kinetostatics(MECH, RELATIVE, KEY_TURNS, LoadSpec(), TURNS)
    stroke = np.degrees(TURNS) <= 90.0 + 1e-9
    size = np.linalg.norm(result.force_at_p, axis=1)
    np.testing.assert_allclose(size[stroke], 20.0, rtol=1e-12)
    assert np.all(size[~stroke] == 0)
    step = 1e-6
    velocity = (MECH.forward(TURNS + step, RELATIVE.evaluate(TURNS + step))["p"]
                - MECH.forward(TURNS - step, RELATIVE.evaluate(TURNS - step))["p"]) / (2 * step)
    velocity = velocity[stroke]
    along = np.einsum("ni,ni->n", result.force_at_p[stroke], velocity) / np.linalg.norm(velocity, axis=1)
    np.testing.assert_allclose(along, -20.0, rtol=1e-6)
    assert np.array_equal(result.on_stroke, stroke)


@pytest.mark.parametrize("load", [LoadSpec(resisting_n=0.0), LoadSpec(force_n=np.zeros(2))], ids=["resisting", "force"])
def test_no_load_and_no_mass_give_no_force(load):
    result = kinetostatics(MECH, RELATIVE, KEY_TURNS, load, TURNS)
    for values in (result.force_at_p, result.carrier_torque, result.planet_torque, result.be_force,
                   *result.hinge_forces.values()):
        assert np.all(values == 0)
    assert all(value == 0 for value, _ in result.peaks().values())


def test_weight_alone_is_carried_to_the_frame():
    """With no planting force, the frame's hinges O and B together hold the links' whole weight."""
    result = kinetostatics(MECH, RELATIVE, KEY_TURNS, LoadSpec(resisting_n=0.0, masses_kg=MASSES), TURNS)
    held = result.hinge_forces["O"] + result.hinge_forces["B"]
    np.testing.assert_allclose(held, np.broadcast_to([0.0, GRAVITY * sum(MASSES.values())], held.shape), atol=1e-9)


def test_peaks_are_the_largest_magnitudes_with_their_turns():
    result = kinetostatics(MECH, RELATIVE, KEY_TURNS, LoadSpec(masses_kg=MASSES), TURNS)
    peaks = result.peaks()
    k = np.argmax(np.abs(result.be_force))
    assert peaks["be_force"] == (result.be_force[k], TURNS[k])
    assert peaks["O"][0] == np.linalg.norm(result.hinge_forces["O"], axis=1).max()
    assert set(peaks) == {"carrier_torque", "planet_torque", "be_force", *HINGES}


def _problem(load_table):
    data = tomllib.loads(EXAMPLE.read_text())
    data["load"] = load_table
    return parse_problem(data, "problem.toml")


def test_load_table_is_read():
    assert _problem({}).load == LoadSpec()
    assert _problem({}).load.resisting_n == 20.0
    load = _problem({"force_n": [3.0, -4.0], "masses_kg": {"rod": 0.5}}).load
    assert load.force_n.tolist() == [3.0, -4.0] and load.resisting_n is None
    assert load.masses_kg == {"carrier": 0.0, "rod": 0.5, "plate": 0.0, "receiving_plate": 0.0}
    assert _problem({"resisting_n": 35}).load.resisting_n == 35.0


BAD_LOADS = {
    "force not finite": ({"force_n": [float("nan"), 1.0]}, ["load.force_n", "nan", "two finite numbers (N)"]),
    "force of three": ({"force_n": [1.0, 2.0, 3.0]}, ["load.force_n", "[1.0, 2.0, 3.0]", "[fx, fy]"]),
    "resisting infinite": ({"resisting_n": float("inf")}, ["load.resisting_n", "inf", "finite force from 0"]),
    "resisting negative": ({"resisting_n": -5.0}, ["load.resisting_n", "-5.0", "finite force from 0"]),
    "both": ({"force_n": [1.0, 2.0], "resisting_n": 20.0}, ["load", "force_n", "resisting_n", "not both"]),
    "negative mass": ({"masses_kg": {"rod": -0.1}}, ["load.masses_kg.rod", "-0.1", "finite mass from 0"]),
    "unknown link": ({"masses_kg": {"wheel": 1.0}}, ["load.masses_kg.wheel", "no such field", "receiving_plate"]),
    "unknown key": ({"torque_nm": 1.0}, ["load.torque_nm", "no such field", "resisting_n"]),
    "not a table": (5, ["load = 5", "a table"]),
}


@pytest.mark.parametrize("name", sorted(BAD_LOADS))
def test_bad_load_names_field_value_and_expectation(name):
    table, fragments = BAD_LOADS[name]
    with pytest.raises(ProblemError) as error:
        _problem(table)
    message = str(error.value)
    assert message.startswith("problem.toml: ")
    for fragment in fragments:
        assert fragment in message, (fragment, message)


@pytest.mark.parametrize("fields,fragment", [({"force_n": [1.0, np.inf]}, "LoadSpec.force_n"),
                                             ({"resisting_n": -1.0}, "LoadSpec.resisting_n"),
                                             ({"force_n": [1.0, 2.0], "resisting_n": 3.0}, "LoadSpec.resisting_n"),
                                             ({"masses_kg": {"plate": np.nan}}, "LoadSpec.masses_kg")])
def test_load_spec_built_in_python_is_checked(fields, fragment):
    with pytest.raises(ProblemError, match=fragment):
        LoadSpec(**fields)


def test_command_refuses_a_load_that_is_not_finite(tmp_path):
    """One line naming the field, its value and what was expected; exit 2; nothing written."""
    problem = tmp_path / "problem.toml"
    problem.write_text(EXAMPLE.read_text() + "\n[load]\nforce_n = [inf, 0.0]\n")
    out = tmp_path / "out"
    run = subprocess.run([sys.executable, "-m", "transplanter", "fivebar", str(problem), "--out", str(out)],
                         capture_output=True, text=True, cwd=ROOT)
    assert run.returncode == 2
    lines = run.stderr.strip().splitlines()
    assert len(lines) == 1 and "load.force_n = [inf, 0.0]: expected [fx, fy]" in lines[0], run.stderr
    assert not out.exists()
