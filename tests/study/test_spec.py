"""Study files: the cases they make, their ids, and bad input refused with one line before any case runs."""
from __future__ import annotations

import pytest

from tests.study.studies import EXAMPLES, gear_study, gear_study_data
from transplanter import gears
from transplanter.errors import ProblemError
from transplanter.study import parse_study, run, study_cases
from transplanter.study.cases import inputs_hash
from transplanter.study.field_paths import read, replaced
from transplanter.toml_fields import read_toml


def test_cases_are_the_product_of_the_lists_each_named_by_its_problem():
    cases = study_cases(gear_study())
    base = read_toml(EXAMPLES / "gear_ellipse.toml")
    assert [c.values for c in cases] == [{"driver.eccentricity": e, "pair.teeth": t}
                                         for e in (0.3, 0.8) for t in (30, 40)]
    for case in cases:
        expected = {**base, "driver": {**base["driver"], "eccentricity": case.values["driver.eccentricity"]},
                    "pair": {**base["pair"], "teeth": case.values["pair.teeth"]}}
        assert case.problem == expected
        assert case.case_id == inputs_hash("gear", expected)
    assert len({c.case_id for c in cases}) == 4
    assert base["driver"]["eccentricity"] == 0.3        # the base problem is not changed


def test_a_repeated_case_is_kept_once_and_an_id_is_the_same_in_another_study():
    twice = gear_study(vary=[{"field": "driver.eccentricity", "values": [0.3, 0.3, 0.5]}])
    cases = study_cases(twice)
    assert [c.values["driver.eccentricity"] for c in cases] == [0.3, 0.5]
    other = study_cases(gear_study(title="another", vary=[{"field": "driver.eccentricity", "values": [0.5]}]))
    assert other[0].case_id == cases[1].case_id


@pytest.mark.parametrize("method, samples", [("latin_hypercube", 7), ("sobol", 8)])
def test_band_samples_are_seeded_and_stay_in_their_bands(method, samples):
    data = gear_study_data(vary=[{"field": "driver.eccentricity", "band": [0.2, 0.4]},
                                 {"field": "pair.teeth", "values": [30, 40]}],
                           sampling={"method": method, "samples": samples, "seed": 3})
    cases = study_cases(parse_study(data))
    assert len(cases) == 2 * samples
    drawn = sorted({c.values["driver.eccentricity"] for c in cases})
    assert len(drawn) == samples and drawn[0] >= 0.2 and drawn[-1] <= 0.4
    assert [c.case_id for c in study_cases(parse_study(data))] == [c.case_id for c in cases]
    reseeded = study_cases(parse_study({**data, "sampling": {**data["sampling"], "seed": 4}}))
    assert {c.case_id for c in reseeded}.isdisjoint(c.case_id for c in cases)
    if method == "latin_hypercube":     # one sample in each of the equal strata of the band
        assert sorted(int((x - 0.2) / 0.2 * samples) for x in drawn) == list(range(samples))


def test_field_paths_read_and_replace_tables_and_arrays():
    document = {"a": [{"x": 1.0}, {"x": 2.0}], "b": {"c": "t"}}
    assert read(document, "a.1.x") == 2.0 and read(document, "b.c") == "t"
    assert replaced(document, {"a.0.x": 5.0, "b.c": "u"}) == {"a": [{"x": 5.0}, {"x": 2.0}], "b": {"c": "u"}}
    assert document["a"][0]["x"] == 1.0


@pytest.mark.parametrize("changes, named", [
    ({"vary": [{"field": "pair.teath", "values": [30]}]}, "vary[0].field = 'pair.teath'"),
    ({"vary": [{"field": "pair", "values": [30]}]}, "vary[0].field = 'pair'"),
    ({"vary": [{"field": "pair.teeth", "values": [30], "band": [1, 2]}]}, "vary[0]"),
    ({"vary": [{"field": "pair.teeth", "range": [40, 30], "step": 1}]}, "vary[0].range"),
    ({"command": "fiveba"}, "command = 'fiveba'"),
    ({"collect": ["a", "a"]}, "collect"),
    ({"objectives": [{"quantity": "center_distance", "goal": "min"}]}, "objectives"),
    ({"objectives": [{"quantity": "nothing", "goal": "min"}, {"quantity": "closure_error", "goal": "min"}]},
     "objectives[0].quantity = 'nothing'"),
    ({"vary": [{"field": "driver.eccentricity", "band": [0.2, 0.4]}],
      "sampling": {"method": "sobol", "samples": 6}}, "sampling.samples = 6"),
    ({"vary": [{"field": "driver.eccentricity", "band": [0.2, 0.4]}]}, "sampling"),
    ({"executor": {"case_timeout_s": -1.0}}, "executor.case_timeout_s = -1.0"),
    ({"executor": {"scheduler": "localhost"}}, "executor.scheduler = 'localhost'"),
])
def test_a_bad_study_names_its_field(changes, named):
    with pytest.raises(ProblemError, match="^<gear study>: " + named.replace("[", r"\[").replace("(", r"\(")):
        parse_study(gear_study_data(**changes), "<gear study>")


def test_a_value_outside_the_fields_range_is_refused_before_any_case_runs(tmp_path):
    spec = gear_study(vary=[{"field": "driver.eccentricity", "values": [0.3, 1.5]}])
    with pytest.raises(ProblemError) as refused:
        gears.parse_problem(study_cases(spec)[1].problem, "x")
    with pytest.raises(ProblemError, match=r"case [0-9a-f]{16}: driver.eccentricity = 1.5\).*driver.eccentricity") \
            as caught:
        run(spec, tmp_path / "out")
    assert str(refused.value).removeprefix("x: ") in str(caught.value)
    assert not (tmp_path / "out").exists()
