"""A result's figure drawers draw nothing until called, each one figure, under the stems ``draw_figures`` gives."""
from __future__ import annotations

from matplotlib.figure import Figure

from transplanter import burmester

from .test_python_api import EXAMPLES


def _counting_figures(monkeypatch) -> list[Figure]:
    made: list[Figure] = []
    original = Figure.__init__

    def counted(self, *args, **kwargs):
        made.append(self)
        original(self, *args, **kwargs)
    monkeypatch.setattr(Figure, "__init__", counted)
    return made


def test_the_five_bar_drawers_draw_one_figure_each_when_called(example_result, monkeypatch):
    made = _counting_figures(monkeypatch)
    drawers = example_result.figure_drawers()
    assert made == []
    assert set(drawers) == {"region", "relative_angle", "gears", "trajectory", "tradeoff", "loads", "pressure_angle",
                            "tolerance_trajectory", "tolerance_band", "tolerance_contributions"}
    figure = drawers["tolerance_band"]()
    assert made == [figure]


def test_draw_figures_draws_what_the_drawers_draw(monkeypatch):
    result = burmester.synthesize(burmester.load_problem(EXAMPLES / "burmester_4poses.toml"))
    made = _counting_figures(monkeypatch)
    figures = burmester.draw_figures(result)
    assert list(figures) == list(result.figure_drawers()) == ["burmester"] and made == [figures["burmester"]]
