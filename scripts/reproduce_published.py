"""Recompute every finding of docs/published.md from scratch and print it, printed against derived.

    python scripts/reproduce_published.py

Each function below computes the findings on one paper (docs/references.md names the papers)
from the derivations, the bundled examples and the fixed relative angle of
``examples/published/relative_angle_wang2025.toml``; nothing is read from an earlier run.
``tests/docs/test_published_findings.py`` pins every number to the precision the docs state it with. The
whole run takes 7-25 s on the 2-core development machine, most of it the rice-transplanter train.
"""
from __future__ import annotations

import dataclasses
import sys
import time
import tomllib
import warnings
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from transplanter import burmester, fivebar, reverse
from transplanter._generated.fivebar import fivebar_discriminant, fivebar_half_angle_quadratic
from transplanter._generated.gears import limacon_driven_convexity, ratio_pair_pitch
from transplanter._generated.planetary import arm_lengths_from_extremes, pickup_tip
from transplanter.errors import TransplanterWarning
from transplanter.fivebar.relative_angle import RelativeAngle
from transplanter.gears.pair import design_pair
from transplanter.gears.pitch_curves import denatured_limacon, denatured_partner
from transplanter.generated import numpy_twin
from transplanter.geometry.dyad import verify_dyad
from transplanter.geometry.turn_map import TurnMap
from transplanter.trains.planetary import correction_factor, printed_correction, printed_peak_to_valley_turn

ROOT = Path(__file__).resolve().parents[1]

WANG = "Wang et al. 2025"
ONION = "onion-transplanter paper"
RICE = "rice-transplanter paper"
REVERSE = "reverse-gear-design paper"
CUSP = "cusp-pitch-curve paper"
TABLE4_B, TABLE4_BE, TABLE4_EP = np.array([-78.83, -33.37]), 227.68, 55.01
#: Random five-bars for the eq (10) count: lengths uniform in [0.3, 2], angles uniform in [-pi, pi).
EQ10_SAMPLES, EQ10_SEED = 10_000, 20261123


@dataclass(frozen=True)
class Finding:
    """One row of the table: what the paper prints (or its formula gives, read as printed) and
    what the derivation gives; numbers are shown with ``digits`` decimals and ``unit``."""

    key: str
    paper: str
    quantity: str
    printed: float | str
    derived: float | str
    unit: str = ""
    digits: int = 3

    def shown(self, value) -> str:
        """Text as it is; a number with ``digits`` decimals and the unit."""
        return value if isinstance(value, str) else f"{value:.{self.digits}f} {self.unit}".strip()


def fixed_relative_angle(path: Path = ROOT / "examples/published/relative_angle_wang2025.toml") -> RelativeAngle:
    """The committed relative angle rho(c) (radians inside)."""
    data = tomllib.loads(path.read_text())
    return RelativeAngle(np.radians(data["rho1_deg"]), np.radians(np.array(data["control_values_deg"])))


def printed_eq9(lengths, angles, lib=np):
    """A1, B1, C1 of Wang et al. 2025 eq (9) as printed (lengths (5, n), angles theta1, theta2, theta5 (3, n));
    ``lib`` numpy, or sympy for symbols."""
    l1, l2, l3, l4, l5 = lengths
    t1, t2, t5 = angles
    common = (l1**2 + l2**2 - l3**2 + l4**2 + l5**2 + 2 * l1 * l5 * lib.cos(t1 + t5)
              + 2 * l1 * l2 * lib.cos(t1 - t2) + 2 * l2 * l5 * lib.cos(t2 + t5))
    a1 = common - 2 * l1 * l4 * lib.cos(t1) + 2 * l4 * l5 * lib.cos(t5) - 2 * l2 * l4 * lib.cos(t2)
    b1 = -4 * l4 * l5 * lib.sin(t5) + 4 * l1 * l4 * lib.sin(t1) + 4 * l2 * l4 * lib.sin(t2)
    c1 = common - 2 * l4 * l5 * lib.cos(t5) - 2 * l1 * l4 * lib.cos(t1) - 2 * l2 * l4 * lib.cos(t2)
    return a1, b1, c1


def wang_fivebar_closure(samples: int = EQ10_SAMPLES, seed: int = EQ10_SEED) -> list[Finding]:
    """Eq (9) against the derived quadratic, and eq (10) against whether the chain can close at all
    (E exists iff |F - B| lies between |L3 - L4| and L3 + L4)."""
    rng = np.random.default_rng(seed)
    lengths = rng.uniform(0.3, 2.0, (5, samples))
    angles = rng.uniform(-np.pi, np.pi, (3, samples))
    a, b, c = numpy_twin(fivebar_half_angle_quadratic)(lengths, angles)[0]
    a1, b1, c1 = printed_eq9(lengths, angles)
    l1, l2, l3, l4, l5 = lengths
    t1, t2, t5 = angles
    size = np.abs([a, b, c]).max(axis=0)
    a_gap = np.abs(a - a1 - 4 * l4 * (l1 * np.cos(t1) + l2 * np.cos(t2))).max() / size.max()
    f = np.array([l1 * np.cos(t1) + l2 * np.cos(t2), l1 * np.sin(t1) + l2 * np.sin(t2)])
    distance = np.hypot(f[0] + l5 * np.cos(t5), f[1] - l5 * np.sin(t5))
    closes = (np.abs(l3 - l4) <= distance) & (distance <= l3 + l4)
    clear = np.minimum(np.abs(distance - np.abs(l3 - l4)), np.abs(distance - (l3 + l4))) > 1e-9
    derived_says = numpy_twin(fivebar_discriminant)(lengths, angles)[0][0] >= 0
    printed_says = b1**2 - 4 * a1 * c1 >= 0
    wrong_printed = int((printed_says != closes)[clear].sum())
    wrong_derived = int((derived_says != closes)[clear].sum())
    return [
        Finding("eq9_A1", WANG, "eq (9): (A - A1) - 4 L4 (L1 cos t1 + L2 cos t2), relative", "A1 = A",
                f"{a_gap:.0e}"),
        Finding("eq9_B1", WANG, "eq (9): B1 + B, relative (t = tan(theta4/2) flips sign)", "B1 = B",
                f"{np.abs(b + b1).max() / size.max():.0e}"),
        Finding("eq9_C1", WANG, "eq (9): C1 - C, relative", "C1 = C", f"{np.abs(c - c1).max() / size.max():.0e}"),
        Finding("eq10_wrong_pct", WANG, f"eq (10): misjudged closability, {clear.sum()} random five-bars",
                100 * wrong_printed / clear.sum(), 100 * wrong_derived / clear.sum(), "%", 1),
        Finding("eq10_wrong_count", WANG, "  the same, counted", wrong_printed, wrong_derived, "", 0),
    ]


def wang_gear_train() -> list[Finding]:
    """Eq (12) and eq (13) read as printed, on the fixed relative angle; the stage-one ratio is
    I1 = 1 / (k sqrt(rho')) (sun -> first intermediate gear)."""
    relative = fixed_relative_angle()
    k = correction_factor(relative)
    k_printed, turn_printed = printed_correction(relative)
    def ratio(c):
        return 1 / (k * np.sqrt(relative.evaluate(c, 1)))

    rate = numpy_twin(ratio_pair_pitch)
    rolled = TurnMap(lambda c: rate([1.0], ratio(c)[None])[1][0], relative.knots).total
    eq13_printed = TurnMap(ratio, relative.knots).total
    return [
        Finding("eq12_k", WANG, "eq (12): correction k (fixed relative angle)", k_printed, k, "", 5),
        Finding("eq12_turn", WANG, "  first intermediate gear per sun turn", np.degrees(turn_printed), 360.0,
                "deg", 2),
        Finding("eq13_turn", WANG, "eq (13): first intermediate gear per sun turn", np.degrees(eq13_printed),
                np.degrees(rolled), "deg", 2),
    ]


def wang_table4_design() -> list[Finding]:
    """Table 4 as a whole design against Tables 1-3 (``fivebar.evaluate_design``)."""
    problem = fivebar.load_problem(ROOT / "examples/vegetable_planting.toml")
    evaluation = fivebar.evaluate_design(problem, fivebar.load_design(ROOT / "examples/vegetable_planting_table4.toml"))
    margin = evaluation.candidate.min_margin
    low, high = evaluation.candidate.ratio_range
    rows = [Finding(f"table4_P{j + 1}_mm", WANG, f"Table 4: P to key pose P{j + 1}", 0.0,
                    float(evaluation.position_errors_mm[j]), "mm", 3) for j in (1, 2, 3)]
    rows += [Finding(f"table4_P{j + 1}_deg", WANG, f"Table 4: plate angle off at P{j + 1}", 0.0,
                     float(abs(evaluation.angle_errors_deg[j])), "deg", 3) for j in (1, 2, 3)]
    return rows + [
        Finding("table4_EBF_deg", WANG, "Table 4: smallest angle EBF over a turn", "-",
                float(np.degrees(np.arcsin(np.sqrt(margin)))), "deg", 1),
        Finding("table4_sin2_EBF", WANG, "its sin^2 (closure margin; default required 0.01)", "-", margin, "", 4),
        Finding("table4_ratio_low", WANG, "Table 4: total ratio, lowest", "-", low, "", 2),
        Finding("table4_ratio_high", WANG, "Table 4: total ratio, highest", "-", high, "", 2),
    ]


def wang_table4_hinges() -> list[Finding]:
    """Table 4's hinges against the exact four-pose curves (``burmester.nearest_center``: true minima)."""
    table1 = burmester.synthesize(burmester.load_problem(ROOT / "examples/burmester_4poses.toml"))
    p1 = table1.problem.poses[0, :2]
    nearest = burmester.nearest_center(table1, TABLE4_B)
    same_length = burmester.nearest_center(table1, TABLE4_B, length=TABLE4_BE)
    relative = burmester.synthesize(burmester.load_problem(ROOT / "examples/burmester_relative.toml"))
    a = 47.47 * np.array([np.cos(np.radians(-28.59)), np.sin(np.radians(-28.59))])
    f = a + 275.88 * np.array([np.cos(np.radians(-100.88)), np.sin(np.radians(-100.88))])
    chain = verify_dyad(relative.problem.poses, a, f, relative.problem.link)
    return [
        Finding("B_to_curve_mm", WANG, "Table 4 B to the exact center-point curve", 0.0,
                nearest.distance_mm, "mm", 3),
        Finding("B_to_sample_mm", WANG, "  (to the nearest traced sample, for comparison)", "-",
                nearest.sample_distance_mm, "mm", 2),
        Finding("B_foot_BE", WANG, "  BE of the exact dyad there", TABLE4_BE, nearest.dyad.length, "mm", 2),
        Finding("B_foot_EP", WANG, "  EP of the exact dyad there", TABLE4_EP,
                float(np.linalg.norm(nearest.dyad.circle - p1)), "mm", 2),
        Finding("BE_dyad_shift_mm", WANG, "exact dyad with BE = 227.68: its B from Table 4's", 0.0,
                same_length.distance_mm, "mm", 2),
        Finding("BE_dyad_B", WANG, "  its B", "({:.2f}, {:.2f}) mm".format(*TABLE4_B),
                "({:.2f}, {:.2f}) mm".format(*same_length.dyad.center)),
        Finding("BE_dyad_EP", WANG, "  its EP", TABLE4_EP, float(np.linalg.norm(same_length.dyad.circle - p1)),
                "mm", 2),
        Finding("AF_spread_mm", WANG, "Table 4 A-F length change over the four poses", 0.0,
                chain.max_residual_mm, "mm", 3),
        Finding("A_to_curve_mm", WANG, "Table 4 A to the exact relative center-point curve", 0.0,
                burmester.nearest_center(relative, a).distance_mm, "mm", 3),
    ]


def onion_gear() -> list[Finding]:
    """Eq (19), eq (10) and Table 2 of the onion-transplanter paper (``gears.design_pair``)."""
    m11, m12 = 1.5, denatured_partner(1.5)
    printed = denatured_limacon(53.0, 13.0, m11, 0.375)
    before, after = (printed.evaluate(np.array([2 * np.pi / 3 + s * 1e-12]))[0][0] for s in (-1, 1))
    pair = design_pair(denatured_limacon(53.0, 13.0, m11, m12), 1)
    k, m = 0.5, 2.5
    eq10 = (m**2 + 1) * k**2 + (2 - m**2) * k - m**2 * k**3 + 1
    partner = denatured_partner(m)
    driven = design_pair(denatured_limacon(1.0, k, m, partner), 1)
    convexity = numpy_twin(limacon_driven_convexity)
    cosine = np.linspace(-1, 1, 401)
    derived = min(convexity([k], [order], [driven.center_distance], [cosine])[0][0].min() for order in (m, partner))
    return [
        Finding("onion_m12", ONION, "eq (19): m12 (closure, eq 2: pi/m11 + pi/m12 = 2 pi)", 0.375, m12, "", 3),
        Finding("onion_span", ONION, "  the two halves span", float(np.degrees(np.pi / m11 + np.pi / 0.375)),
                float(np.degrees(np.pi / m11 + np.pi / m12)), "deg", 0),
        Finding("onion_r_jump", ONION, "  r jumps at 120 deg from 40 mm by", after - before, 0.0, "mm", 1),
        Finding("onion_bend_jump", ONION, "  r'' jumps at the joint (m12 = 0.75) by", "-",
                float(pair.joints[0]["bend_jump"]), "mm/rad^2", 2),
        Finding("onion_center_distance", ONION, "Table 2: center distance that closes", 110.0,
                pair.center_distance, "mm", 4),
        Finding("onion_perimeter", ONION, "  driver perimeter", "-", pair.perimeters[0], "mm", 2),
        Finding("onion_teeth", ONION, "  teeth of module 2 on it", 55.0, pair.perimeters[0] / (2 * np.pi), "", 2),
        Finding("onion_eq10", ONION, "eq (10) at k = 0.5, m11 = 2.5 (< 0: driven curve concave)", eq10,
                derived, "", 3),
    ]


def rice_arm_lengths() -> list[Finding]:
    """The rice-transplanter paper's eq (1-2), derived from the reach annulus."""
    l1, l2 = numpy_twin(arm_lengths_from_extremes)([254.3, 69.7])[0]
    return [Finding("rice_L1", RICE, "eq (1-2): L1 from Lmax = 254.3, Lmin = 69.7", 92.3, float(l1), "mm", 1),
            Finding("rice_L2", RICE, "eq (1-2): L2", 162.0, float(l2), "mm", 1)]


def rice_idler_train() -> list[Finding]:
    """The rice-transplanter paper's identical sun and planet (eq 5-12) on the rice path, against four gears."""
    problem = reverse.load_problem(ROOT / "examples/rice_hoe_reverse.toml")
    four = reverse.synthesize(problem)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", TransplanterWarning)
        idler = reverse.synthesize(dataclasses.replace(problem, topology="sun-idler-planet",
                                                       split="identical_sun_planet"))
    closure = max(abs(idler.train.stage_one.closure_error), abs(idler.train.stage_two.closure_error))
    return [
        Finding("rice_residual_pct", RICE, "eq (5) residual where its iteration stalls",
                100 * idler.train.model_residual, "-", "%", 0),
        Finding("rice_iterations", RICE, "  iterations before it gives up", idler.train.iterations, "-", "", 0),
        Finding("rice_closure", RICE, "  closure of the train built from the best iterate", f"{closure:.0e} rad", "-"),
        Finding("rice_miss_mm", RICE, "path missed by the rolled train: eq (8) vs four gears",
                idler.verification.max_error_mm, f"{four.verification.max_error_mm:.0e} mm", "mm", 1),
    ]


def reverse_gear_split() -> list[Finding]:
    """The reverse-gear-design paper's i1 = i25 bs, on the bundled pick-up loop (bs = 0.6)."""
    result = reverse.synthesize(reverse.load_problem(ROOT / "examples/pickup_arm_reverse.toml"))
    turn = np.degrees(printed_peak_to_valley_turn(result.relative, 0.6))
    return [Finding("bs_turn_deg", REVERSE, "split i1 = i25 bs, bs = 0.6: intermediate gear per cycle",
                    float(turn), 360.0, "deg", 1)]


def cusp_eq15(samples: int = 200, seed: int = EQ10_SEED) -> list[Finding]:
    """Eq (15): the tip equals a two-link arm whose carrier angle is phi0 + phi1 (Table 1 calls phi1 the planet's)."""
    rng = np.random.default_rng(seed)
    carrier, bend, planet, mounting = rng.uniform(-3, 3, (4, samples))
    first, second, arm = 90.0, 90.0, 207.81
    tip = numpy_twin(pickup_tip)([first, second, arm], [carrier, bend, planet, mounting])[0]
    def unit(t):
        return np.array([np.cos(t), np.sin(t)])

    arm_tip = first * unit(carrier) + second * unit(carrier + bend) + arm * unit(carrier + bend + planet + mounting)
    return [Finding("cusp_eq15", CUSP, "eq (15): phi0 + phi1 is the carrier's angle (tip vs two-link arm)",
                    "phi1: planet's turn (Table 1)", f"agree to {np.abs(tip - arm_tip).max():.0e} mm")]


SECTIONS = (wang_fivebar_closure, wang_gear_train, wang_table4_design, wang_table4_hinges, onion_gear,
            rice_arm_lengths, rice_idler_train, reverse_gear_split, cusp_eq15)


def findings(sections=SECTIONS) -> list[Finding]:
    """Every finding of ``sections``, recomputed."""
    return [row for section in sections for row in section()]


def main() -> int:
    start = time.perf_counter()
    rows = findings()
    table = [(r.paper, r.quantity, r.shown(r.printed), r.shown(r.derived)) for r in rows]
    widths = [max(len(line[k]) for line in table) for k in range(3)]
    print(f"{'paper':<{widths[0]}}  {'quantity':<{widths[1]}}  {'printed':<{widths[2]}}  derived")
    for paper, quantity, printed, derived in table:
        print(f"{paper:<{widths[0]}}  {quantity:<{widths[1]}}  {printed:<{widths[2]}}  {derived}")
    print(f"\n{len(rows)} findings recomputed in {time.perf_counter() - start:.1f} s")
    return 0


if __name__ == "__main__":
    sys.exit(main())
