"""A monotone map of the turn (``geometry.turn_map``) and its inverse, against a map known in closed form."""
import numpy as np

from transplanter.geometry.turn_map import TurnMap


def test_turn_map_inverts_a_known_map():
    turn = TurnMap(lambda x: 1 + 0.6 * np.cos(x))
    x = np.linspace(0, 2 * np.pi, 97)
    assert np.abs(turn(x) - (x + 0.6 * np.sin(x))).max() < 1e-13
    assert np.abs(turn.inverse(x + 0.6 * np.sin(x)) - x).max() < 1e-12
