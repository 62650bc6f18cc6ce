"""Other passes of P by a return point (``return_passes.other_passes``, ``DesignSolver.restroke``): the NLP keeps each
return point on the pass its start assigns, and the example's better optimum has P8 on its other pass."""
import numpy as np
import pytest

from transplanter.fivebar.nlp import MIN_STEP
from transplanter.fivebar.return_passes import other_passes


def _distance(design, point, turns):
    turns = np.atleast_1d(np.asarray(turns, float))
    p = design.mech.forward(turns, design.relative_angle.evaluate(turns))["p"]
    return np.linalg.norm(p - point, axis=-1)


def test_other_passes_are_local_minima_of_the_distance_within_the_stroke_order(example_result):
    """Each pass found is checked by forward kinematics of its own: P is nearer the return point there than
    0.2 deg to either side, the turn lies between its neighbours' return turns (the last key pose and a
    full turn at the ends) by at least MIN_STEP, and it is not the design's own pass."""
    problem, design = example_result.problem, example_result.design
    own = design.stroke.carrier_turns
    bounds = np.r_[problem.carrier_turns[-1], own, 2 * np.pi]
    passes = other_passes(problem, design)
    assert passes
    step = np.radians(0.2)
    for j, turn in passes:
        point = problem.return_points[j]
        here, left, right = _distance(design, point, [turn, turn - step, turn + step])
        assert here <= min(left, right)
        assert bounds[j] + MIN_STEP < turn < bounds[j + 2] - MIN_STEP
        assert abs(turn - own[j]) > np.radians(1.0)


def test_the_example_is_built_with_p8_on_its_other_pass(example_result):
    """The region's starts put P8 on the pass of P near carrier turn 304 deg; the built design passes it near
    219 deg (its return turn there, by forward kinematics within the 1 mm tolerance). Whichever path reached it
    (a start moved by ``restroke`` here; on other hardware a start may reach it directly), an alternative that
    was moved says so, and its line's angles agree with its own evaluation and rise."""
    problem, built = example_result.problem, example_result.alternatives[0]
    j = problem.return_labels.index("P8")
    turn = built.design.stroke.carrier_turns[j]
    assert 200 < np.degrees(turn) < 240
    assert _distance(built.design, problem.return_points[j], turn)[0] <= problem.return_tolerance_mm * (1 + 1e-6)
    moved = [a for a in example_result.alternatives if a.restroke]
    for alternative in moved:
        moved = alternative.restroke.split("smallest transmission angle at E ")[1].rstrip(" deg)")
        before, after = (float(v) for v in moved.split(" -> "))
        assert after == pytest.approx(np.degrees(alternative.transmission_angle), abs=5e-4) and after > before
