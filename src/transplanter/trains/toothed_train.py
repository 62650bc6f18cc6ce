"""The planetary train with whole teeth on its four gears, laid out on a bent or a straight carrier.

Sizes. ``design_train`` makes every driver curve r = a / (1 + i) and its mate a - r, so a stage's
pitch curves, perimeter and curvature radii all scale with its centre distance a_j. Both gears of a
stage turn once per cycle in the carrier frame and share the perimeter a_j P_j (P_j: perimeter per
unit centre distance); whole teeth of module m need a_j = pi m Z_j / P_j.

Smallest counts. A rack of module m (addendum one module, pressure angle alpha) undercuts where the
pitch curve's radius of curvature falls below m / sin^2(alpha) (the limit ``gears.teeth`` enforces).
With rho_j the smallest convex radius per unit centre distance of either gear of stage j,
a_j rho_j >= m / sin^2(alpha) reads Z_j >= P_j / (pi rho_j sin^2(alpha)), whatever the module (a circle
gives the familiar 2 / sin^2(alpha), 17.1 at 20 deg). Where a curve has a concave stretch a rack cannot
cut it: the stage goes to the shaper path (``generate_teeth``: the shaper cuts the driver, whose teeth
sweep the driven gear), and the shaper's pitch circle, radius m N / 2 for N cutter teeth, must also fit
the driver's tightest hollow, kappa_j per unit centre distance: Z_j > N P_j / (2 pi kappa_j).

Layout. The planet's turn against the carrier does not depend on where the intermediate shaft sits,
so a1 and a2 are free within |a1 - a2| <= |OA| <= a1 + a2 (``layout = "bent"``): among whole counts
at or above their minimum the search takes the least largest centre distance (the gears' reach on the
carrier), then the least a1 + a2, then the least Z1. The shaft sits on the counterclockwise side of
O->A in the carrier frame, at the bend angle delta0 = angle(O->A, O->shaft) of the cosine rule.
``layout = "straight"`` keeps the shaft on O-A, a1 + a2 = |OA|: whole counts then exist only at the
modules |OA| / (pi (Z1 / P1 + Z2 / P2)). A cutter of a made-up module does not exist, so the asked
module is never changed: it must be one of these (to 1e-9), or it is refused with the nearest ones
(the most even pair of counts for each). Centre distances given in the problem fix a1,
a2, and must give whole counts (to 1e-9), clear the undercut and fit the layout, or are refused with
what would.

Placement. In the carrier frame (O at the origin, A on +x, counterclockwise positive) the sun turns by
+c as the carrier turns clockwise by c, the intermediate gears by -psi(c), the planet by rho(c) - rho1.
``design_pair`` turns its driver clockwise, so stage 1 is the mirror image (y -> -y) of its pair design
and stage 2 is its pair design. Outlines are given in each gear's own frame in that handedness, with
the gear's angle at carrier turn 0 (``gear_angles`` at any turn).
"""
from __future__ import annotations

import math
import time
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass

import numpy as np

from transplanter.errors import InfeasibleError, ProblemError
from transplanter.gears.mesh_check import MeshCheck, check_mesh
from transplanter.gears.pair import GearPairDesign, driven_angle
from transplanter.gears.problem import MAX_SHAPER_TEETH, MAX_TEETH
from transplanter.gears.rack_teeth import ADDENDUM
from transplanter.gears.swept_teeth import shared_with
from transplanter.gears.teeth import PairTeeth, generate_teeth
from transplanter.side_process import Twin, twinned
from transplanter.toml_fields import ClassFields, is_finite_number
from transplanter.trains.gearing_fields import GearingFields
from transplanter.trains.planetary import PlanetaryTrain, RelativeMotion, design_train

CUTTERS, LAYOUTS = ("rack", "shaper"), ("bent", "straight")
#: Module range (mm): below, the train's gears carry hundreds of teeth; above, tens of mm per tooth.
MODULE_RANGE = (0.2, 10.0)
#: Standard pressure angles span 14.5 (old) to 20 (ISO) to 25-30 (strong teeth); below 14.5 deg the rack's
#: undercut limit 1 / sin^2 grows past 16 modules of curvature radius, above 30 deg the tips turn pointed.
PRESSURE_ANGLE_RANGE_DEG = (14.5, 30.0)
#: Shaper cutter teeth, as the gear command takes them.
SHAPER_TEETH_RANGE = (8, 200)
#: Whole counts and a straight carrier's module hold to this relative tolerance.
WHOLE = 1e-9
GEAR_NAMES = ("sun", "first intermediate", "second intermediate", "planet")


@dataclass(frozen=True)
class Gearing:
    """How the train's gears are cut and where the intermediate shaft sits (mm, radians).

    Attributes
    ----------
    module : float
        mm, in ``MODULE_RANGE``.
    pressure_angle : float
        rad, in ``PRESSURE_ANGLE_RANGE_DEG``.
    cutter : str
        ``"rack"`` (stages with a concave stretch go to the shaper, with the reason) or ``"shaper"``.
    shaper_teeth : int
        Teeth of the shaper cutter, wherever a stage is shaper-cut.
    layout : str
        ``"bent"`` (shaft off O-A) or ``"straight"`` (a1 + a2 = |OA|).
    center_distances : (float, float) or None
        Fixed a1, a2 (mm); None: chosen by the search of the module docstring.
    max_pressure_angle : float
        rad, above ``pressure_angle`` and below pi / 2: the largest pressure angle a mesh may reach over the
        turn (``trains.pressure_angle``; the push along the motion falls as its cosine).
    fields : GearingFields
        The problem-file names error messages give these fields (the five-bar's by default).
    """

    module: float = 1.5
    pressure_angle: float = math.radians(20.0)
    cutter: str = "rack"
    shaper_teeth: int = 16
    layout: str = "bent"
    center_distances: tuple[float, float] | None = None
    max_pressure_angle: float = math.radians(45.0)
    fields: GearingFields = GearingFields()

    def __post_init__(self):
        check = ClassFields(self)
        if not is_finite_number(self.module) or not MODULE_RANGE[0] <= self.module <= MODULE_RANGE[1]:
            check.fail("module", self.module, f"a module from {MODULE_RANGE[0]:g} to {MODULE_RANGE[1]:g} mm")
        low, high = np.radians(PRESSURE_ANGLE_RANGE_DEG)
        if not is_finite_number(self.pressure_angle) or not low - 1e-12 <= self.pressure_angle <= high + 1e-12:
            check.fail("pressure_angle", self.pressure_angle, "an angle from {:g} to {:g} deg, in radians".format(
                *PRESSURE_ANGLE_RANGE_DEG))
        if self.cutter not in CUTTERS:
            check.fail("cutter", self.cutter, " or ".join(f'"{c}"' for c in CUTTERS))
        if self.layout not in LAYOUTS:
            check.fail("layout", self.layout, " or ".join(f'"{v}"' for v in LAYOUTS))
        low_teeth, high_teeth = SHAPER_TEETH_RANGE
        if isinstance(self.shaper_teeth, bool) or not isinstance(self.shaper_teeth, (int, np.integer)) \
                or not low_teeth <= self.shaper_teeth <= high_teeth:
            check.fail("shaper_teeth", self.shaper_teeth, f"a whole number from {low_teeth} to {high_teeth}")
        centers = self.center_distances
        if centers is not None and (len(centers) != 2 or not all(is_finite_number(v) and v > 0 for v in centers)):
            check.fail("center_distances", self.center_distances, "two positive distances (mm) or None")
        limit = self.max_pressure_angle
        if not is_finite_number(limit) or not self.pressure_angle < limit < np.pi / 2:
            check.fail("max_pressure_angle", limit, f"an angle above pressure_angle ({self.pressure_angle:.6g}) and "
                                                    "below pi / 2, in radians")
        if not isinstance(self.fields, GearingFields):
            check.fail("fields", self.fields, "a trains.gearing_fields.GearingFields")


@dataclass(frozen=True)
class StageShape:
    """One stage at unit centre distance: what fixes its size and its cutter."""

    perimeter: float                        # P_j: pitch perimeter per unit centre distance
    convex_radius: float                    # smallest convex curvature radius of either gear, per unit a
    concave_radius: tuple[float, float]     # smallest |concave radius| of driver, driven per unit a (inf: convex)
    cutter: str
    min_teeth: int


@dataclass(frozen=True)
class TrainSize:
    """Whole-tooth sizes of the train before any tooth is cut (mm): counts Z1, Z2, centre distances
    a1, a2, the module, each stage's cutter and the largest pitch radius of each stage."""

    counts: tuple[int, int]
    center_distances: tuple[float, float]
    module: float
    cutters: tuple[str, str]
    largest_pitch_radius: tuple[float, float]


@dataclass(frozen=True)
class ToothedGear:
    """One of the four gears, cut (mm, radians; carrier-frame handedness)."""

    name: str
    role: str                    # "driver" or "driven"
    teeth: int
    module: float
    center: np.ndarray           # in the carrier frame (O at the origin, A on +x)
    angle_at_turn_zero: float    # the gear's angle in the carrier frame at carrier turn 0
    outline: np.ndarray          # (N, 2) tooth outline in the gear's own frame
    pitch_curve: np.ndarray      # (M, 2) pitch curve in the gear's own frame
    convex: bool
    min_curvature_radius: float  # smallest convex radius of curvature of the pitch curve (mm)
    min_concave_radius: float | None   # smallest |radius| of a concave stretch, None when convex
    cutter: str
    reason: str


@dataclass(frozen=True)
class ToothedTrain:
    """The planetary train with whole teeth, its carrier layout and the mesh check of both stages.

    ``train`` is the ``PlanetaryTrain`` at the chosen a1, a2; ``bend_angle`` is delta0 (rad, 0 on a
    straight carrier) and ``shaft`` the intermediate shaft in the carrier frame (mm).
    """

    train: PlanetaryTrain
    carrier_length: float
    layout: str
    module: float
    pressure_angle: float
    counts: tuple[int, int]
    bend_angle: float
    shaft: np.ndarray
    gears: tuple[ToothedGear, ToothedGear, ToothedGear, ToothedGear]
    teeth: tuple[PairTeeth, PairTeeth]
    mesh: tuple[MeshCheck, MeshCheck]
    timings_s: dict

    @property
    def mesh_failures(self) -> list[str]:
        """What the mesh check of either stage finds wrong."""
        pairs = ("sun -> first intermediate", "second intermediate -> planet")
        return [f"{pair}: {text}" for pair, check in zip(pairs, self.mesh, strict=True) for text in check.failures]

    @property
    def self_intersections(self) -> tuple[int, int, int, int]:
        """Crossings of each gear's tooth outline with itself (sun, first intermediate, second intermediate,
        planet): a cut outline must be a simple closed curve."""
        (sun, first), (second, planet) = (teeth.self_intersections for teeth in self.teeth)
        return sun, first, second, planet

    @property
    def crossing_failures(self) -> list[str]:
        """Each gear whose tooth outline crosses itself."""
        return [f"{name}: its tooth outline crosses itself ({count} crossings)"
                for name, count in zip(GEAR_NAMES, self.self_intersections, strict=True) if count]

    @property
    def failures(self) -> list[str]:
        """The mesh check's failures, then the crossing tooth outlines."""
        return [*self.mesh_failures, *self.crossing_failures]

    @property
    def passed(self) -> bool:
        return not self.failures


def stage_shape(design: GearPairDesign, gearing: Gearing) -> StageShape:
    """Perimeter and curvature per unit centre distance of a stage, its cutter and its smallest whole
    count (module docstring)."""
    a = design.center_distance
    convex = [c > 0 for c in design.convexity]
    rho = min(float(r[c].min()) for c, r in zip(convex, design.curvature_radius, strict=True)) / a
    driver_hollow, driven_hollow = (float(np.abs(r[~c]).min()) / a if (~c).any() else np.inf
                                    for c, r in zip(convex, design.curvature_radius, strict=True))
    concave = (driver_hollow, driven_hollow)
    perimeter = design.perimeters[0] / a
    least = math.ceil(ADDENDUM * perimeter / (np.pi * rho * np.sin(gearing.pressure_angle) ** 2) * (1 + WHOLE))
    cutter = "rack" if gearing.cutter == "rack" and np.isinf(concave).all() else "shaper"
    if cutter == "shaper" and np.isfinite(concave[0]):     # the shaper's pitch circle must fit the driver's hollow
        least = max(least, math.floor(gearing.shaper_teeth * perimeter / (2 * np.pi * concave[0]) * (1 + WHOLE)) + 1)
    return StageShape(perimeter, rho, concave, cutter, least)


def _carrier_turn_deg(train: PlanetaryTrain, stage: int, phi1: float) -> float:
    """Carrier turn (deg) at which a stage's driver has turned by phi1 (rad)."""
    c = phi1 if stage == 0 else train.intermediate_turn.inverse(np.array([phi1]))[0]
    return float(np.degrees(c))


def cutting_reasons(train: PlanetaryTrain, stage: int, cutter: str, gearing: Gearing, module: float) -> tuple[str, str]:
    """Why each gear of a stage is cut as it is, with the numbers at the chosen size."""
    design = (train.stage_one, train.stage_two)[stage]
    names = GEAR_NAMES[2 * stage:2 * stage + 2]
    limit = ADDENDUM * module / np.sin(gearing.pressure_angle) ** 2
    convex = [c > 0 for c in design.convexity]
    if cutter == "rack":
        driver_why, driven_why = (f"convex; smallest radius of curvature {float(r[c].min()):.3f} mm >= the rack's "
                                  f"undercut limit m / sin^2(alpha) = {limit:.3f} mm"
                                  for c, r in zip(convex, design.curvature_radius, strict=True))
        return driver_why, driven_why
    fit = (f"{gearing.shaper_teeth}-tooth shaper, pitch radius {module * gearing.shaper_teeth / 2:.3f} mm; convex "
           f"stretches keep radii of curvature >= {limit:.3f} mm")
    if gearing.cutter == "shaper":
        why = f"cutter = \"shaper\" asked ({fit})"
    else:
        g = int(np.argmin([np.abs(r[~c]).min() if (~c).any() else np.inf
                           for c, r in zip(convex, design.curvature_radius, strict=True)]))
        k = int(np.argmin(design.convexity[g]))
        hollow = float(np.abs(design.curvature_radius[g][~convex[g]]).min())
        why = (f"the {names[g]}'s pitch curve is concave: convexity r^2 + 2 r'^2 - r r'' = "
               f"{design.convexity[g][k]:.4g} mm^2 at its lowest, carrier turn "
               f"{_carrier_turn_deg(train, stage, design.phi1[k]):.1f} deg, hollow radius down to {hollow:.3f} mm; a "
               f"rack cannot cut a hollow, so the stage is shaper-cut ({fit})")
    return why, f"{why}; cut as the envelope of the {names[0]}'s teeth in the designed motion"


def _bent_counts(shapes, module: float, length: float) -> tuple[int, int]:
    """Least max(a1, a2), then least a1 + a2, then least Z1, with |a1 - a2| <= |OA| <= a1 + a2."""
    pitch = [np.pi * module / s.perimeter for s in shapes]          # a_j per tooth
    if 2 * length < pitch[1] * (1 - WHOLE):       # then some a1 would leave no whole Z2 within a1 -+ |OA|
        finer = ("use a finer module" if module > MODULE_RANGE[0] else
                 f"{MODULE_RANGE[0]:g} is the finest module taken: the mechanism is too small for cut teeth")
        raise InfeasibleError(f"the carrier |OA| = {length:.4g} mm is shorter than half a tooth step of the second "
                              f"centre distance ({pitch[1]:.4g} mm at module {module:g}): no whole counts fit; {finer}")
    found: list[tuple[float, float, int, int]] = []
    z1 = shapes[0].min_teeth
    while not found or z1 * pitch[0] <= min(found)[0]:
        a1 = z1 * pitch[0]
        # for a given Z1 the smallest Z2 that spans the carrier is best on every key
        least = max(shapes[1].min_teeth, math.ceil(abs(length - a1) / pitch[1] * (1 - WHOLE)))
        if least <= math.floor((a1 + length) / pitch[1] * (1 + WHOLE)):
            a2 = least * pitch[1]
            found.append((max(a1, a2), a1 + a2, z1, least))
        z1 += 1
    return min(found)[2:]


def _straight_module(shapes, module: float, length: float, source: str, fields: GearingFields
                     ) -> tuple[int, int, float]:
    """Whole counts for a1 + a2 = |OA| at the asked module, the most even pair; else refuse with the nearest."""
    p1, p2 = (s.perimeter for s in shapes)
    z1_min, z2_min = (s.min_teeth for s in shapes)
    target = length / (np.pi * module)                 # Z1 / P1 + Z2 / P2 must equal this
    found = []
    for z1 in range(z1_min, max(z1_min, int((target - z2_min / p2) * p1) + 1) + 1):
        rest = (target - z1 / p1) * p2
        for z2 in {max(z2_min, math.floor(rest)), max(z2_min, math.ceil(rest))}:
            exact = length / (np.pi * (z1 / p1 + z2 / p2))
            found.append((abs(exact - module), z1, z2, exact))

    def evenness(f):
        return abs(f[1] / p1 - f[2] / p2), f[1]

    exact = [f for f in found if f[0] <= WHOLE * module]
    if exact:
        _, z1, z2, m = min(exact, key=evenness)
        return z1, z2, m
    below = min((f for f in found if f[3] < module), key=lambda f: (-f[3], *evenness(f)), default=None)
    above = min((f for f in found if f[3] > module), key=lambda f: (f[3], *evenness(f)), default=None)
    offers = "; ".join(f"module = {f[3]:.12g} (Z = {f[1]}, {f[2]})" for f in (below, above) if f)
    raise ProblemError(f"{source}: {fields.module} = {module:g} with {fields.straight}: no whole tooth counts "
                       f"without undercut (Z1 >= {z1_min}, Z2 >= {z2_min}) make a1 + a2 = |OA| = {length:.6g} mm; "
                       f"expected one of the modules that do, nearest: {offers}; or {fields.bent}")


def _given_counts(shapes, gearing: Gearing, distances: tuple[float, float], length: float,
                  source: str) -> tuple[int, int]:
    """Whole counts of the given centre ``distances`` (gearing.center_distances), or refuse them."""
    m, fields = gearing.module, gearing.fields
    counts = []
    for j, (a, shape, key) in enumerate(zip(distances, shapes, fields.center_distances, strict=True)):
        z = a * shape.perimeter / (np.pi * m)
        step = np.pi * m / shape.perimeter
        if abs(z - round(z)) > WHOLE * z:
            lower, upper = max(math.floor(z), shape.min_teeth), max(math.ceil(z), shape.min_teeth + 1)
            raise ProblemError(f"{source}: {key} = {a:g}: gives {z:.4f} teeth at module {m:g}; expected whole "
                               f"teeth: {lower} at {lower * step:.12g} mm or {upper} at {upper * step:.12g} mm")
        if round(z) < shape.min_teeth:
            raise ProblemError(f"{source}: {key} = {a:g}: {round(z)} teeth of module {m:g} are undercut by the "
                               f"{shape.cutter} (stage {j + 1} needs at least {shape.min_teeth}); expected at least "
                               f"{shape.min_teeth * step:.12g} mm")
        counts.append(int(round(z)))
    a1, a2 = distances
    if gearing.layout == "straight" and abs(a1 + a2 - length) > WHOLE * length:
        raise ProblemError(f"{source}: {' + '.join(fields.center_distances)} = {a1 + a2:g}: expected "
                           f"|OA| = {length:.12g} mm on a straight carrier (or {fields.bent})")
    if not abs(a1 - a2) <= length * (1 + WHOLE) or not length <= (a1 + a2) * (1 + WHOLE):
        raise ProblemError(f"{source}: {fields.both_distances} [{a1:g}, {a2:g}] mm: expected |a1 - a2| <= |OA| = "
                           f"{length:.6g} mm <= a1 + a2, so that the shaft can be placed")
    return counts[0], counts[1]


def bend_angle(a1: float, a2: float, length: float) -> float:
    """delta0: the angle at O between O->A and O->shaft, by the cosine rule (0 when a1 + a2 = |OA|)."""
    return float(np.arccos(np.clip((a1**2 + length**2 - a2**2) / (2 * a1 * length), -1.0, 1.0)))


def gear_angles(toothed: ToothedTrain, carrier_turn) -> np.ndarray:
    """Angles (rad, carrier frame) of sun, first and second intermediate and planet at carrier turns c: (..., 4).

    In the world, with the carrier O->A at angle theta1(0) in pose 1 and turning clockwise, a gear's angle is
    theta1(0) - c plus this, and its centre is its carrier-frame centre turned by theta1(0) - c about O."""
    c = np.asarray(carrier_turn, float)
    laps = np.floor(c / (2 * np.pi))
    psi = toothed.train.intermediate_turn(c - 2 * np.pi * laps) + 2 * np.pi * laps
    planet = driven_angle(toothed.train.stage_two, psi)
    start = np.array([g.angle_at_turn_zero for g in toothed.gears])
    return start + np.stack([c, -psi, -psi, planet], -1)


def _mirror(points: np.ndarray) -> np.ndarray:
    return points * [1.0, -1.0]


def _gear(name, role, stage_design: GearPairDesign, side: int, count, module, center, angle, outline, mirrored,
          cutter: str, reason: str) -> ToothedGear:
    convex = stage_design.convexity[side] > 0
    rho = stage_design.curvature_radius[side]
    flip = _mirror if mirrored else (lambda p: p)
    return ToothedGear(name, role, count, module, center, angle, flip(outline), flip(stage_design.points[side]),
                       bool(convex.all()), float(rho[convex].min()),
                       None if convex.all() else float(np.abs(rho[~convex]).min()), cutter, reason)


def _sizes(relative: RelativeMotion, carrier_length: float, gearing: Gearing, source: str, exponent: float = 0.5):
    """Stage shapes, whole counts, centre distances and module of the layout (module docstring)."""
    unit = design_train(relative, (1.0, 1.0), source, exponent)
    shapes = (stage_shape(unit.stage_one, gearing), stage_shape(unit.stage_two, gearing))
    module = gearing.module
    if gearing.center_distances is not None:
        counts = _given_counts(shapes, gearing, gearing.center_distances, carrier_length, source)
    elif gearing.layout == "straight":
        z1, z2, module = _straight_module(shapes, module, carrier_length, source, gearing.fields)
        counts = (z1, z2)
    else:
        try:
            counts = _bent_counts(shapes, module, carrier_length)
        except InfeasibleError as error:
            raise InfeasibleError(f"{source}: {error}") from None
    for stage, (count, shape) in enumerate(zip(counts, shapes, strict=True)):
        most = MAX_SHAPER_TEETH if shape.cutter == "shaper" else MAX_TEETH
        if count > most:
            coarser = ("a coarser module" if module < MODULE_RANGE[1] else
                       f"{MODULE_RANGE[1]:g} is the coarsest module taken: the mechanism is too large for it")
            raise ProblemError(f"{source}: {gearing.fields.module} = {module:g}: gives {count} teeth on the "
                               f"{GEAR_NAMES[2 * stage]} ({shape.cutter}-cut); expected at most {most} (every tooth "
                               f"is cut and checked, in time and memory growing with the count); {coarser}")
    a1, a2 = (z * np.pi * module / s.perimeter for z, s in zip(counts, shapes, strict=True))
    if gearing.layout == "straight":
        a2 = carrier_length - a1
    return shapes, counts, (a1, a2), module, unit


def train_size(relative: RelativeMotion, carrier_length: float, gearing: Gearing = Gearing(),
               source: str = "<train>") -> TrainSize:
    """The sizes ``design_toothed_train`` would give, without cutting teeth (for comparing designs);
    raises as it does."""
    shapes, counts, distances, module, unit = _sizes(relative, carrier_length, gearing, source)
    largest_one, largest_two = (a * max(float(np.max(r)) for r in stage.radius)
                                for a, stage in zip(distances, (unit.stage_one, unit.stage_two), strict=True))
    return TrainSize((int(counts[0]), int(counts[1])), (float(distances[0]), float(distances[1])), float(module),
                     (shapes[0].cutter, shapes[1].cutter), (largest_one, largest_two))


def cut_stages(stages: tuple[GearPairDesign, GearPairDesign], module: float, pressure_angle: float,
               cutters: tuple[str, str], shaper_teeth: int, source: str) -> tuple[PairTeeth, PairTeeth]:
    """Both stages' teeth (``generate_teeth``), cut here and in a side process at once (``side_process.twinned``),
    each cutting every envelope half (``swept_teeth.shared_with``): both cores stay busy to the end, whatever the
    stages' sizes (all here where no side process may run). Processes, not threads: the cut is many small numpy
    operations, and between them two threads wait for the interpreter lock (on the main job's stages two threads
    took longer than one after the other, 1.95 s against 1.47). A stage to each process left one core idle while
    the larger stage (77 teeth against 57 on the main job) was cut: 0.92-1.10 s in quiet moments, where the
    envelopes shared take 0.79-0.92 s."""

    def cut_both(twin: Twin | None) -> tuple[PairTeeth, PairTeeth]:
        with shared_with(twin):
            one, two = (generate_teeth(stage, module, pressure_angle, source, cutter, shaper_teeth)
                        for stage, cutter in zip(stages, cutters, strict=True))
        return one, two

    return twinned(cut_both)


def design_toothed_train(relative: RelativeMotion, carrier_length: float, gearing: Gearing = Gearing(),
                         source: str = "<train>", exponent: float = 0.5) -> ToothedTrain:
    """The planetary train realising ``relative`` with whole teeth on all four gears, cut and mesh-checked.

    Parameters
    ----------
    relative : RelativeMotion
        rho(c), the planet's turn against the carrier (``fivebar.relative_angle.RelativeAngle``).
    carrier_length : float
        |OA| (mm).
    gearing : Gearing
        Module, pressure angle, cutter, layout and optional fixed centre distances.
    source : str
        Named in error messages.
    exponent : float
        Stage one carries i0^exponent of the total ratio (``trains.planetary.design_train``; 1/2: Wang et al.
        2025 eq 11-12).

    Raises
    ------
    ProblemError
        Centre distances or a straight carrier's module that give no whole counts (with the nearest that do).
    InfeasibleError
        A carrier too short for one tooth step; a cutter that cannot cut (from ``generate_teeth``).
    """
    timings = {}
    start = time.perf_counter()
    shapes, counts, (a1, a2), module, _ = _sizes(relative, carrier_length, gearing, source, exponent)
    train = design_train(relative, (a1, a2), source, exponent)
    delta = bend_angle(a1, a2, carrier_length)
    shaft = a1 * np.array([np.cos(delta), np.sin(delta)])
    timings["layout"] = time.perf_counter() - start

    start = time.perf_counter()
    stages = (train.stage_one, train.stage_two)
    teeth = cut_stages(stages, module, gearing.pressure_angle, (shapes[0].cutter, shapes[1].cutter),
                       gearing.shaper_teeth, source)
    timings["teeth"] = time.perf_counter() - start
    start = time.perf_counter()
    with ThreadPoolExecutor(2) as stage_pool:       # numpy and cKDTree release the GIL
        mesh_one, mesh_two = stage_pool.map(lambda design, cut: check_mesh(design, cut.outlines, module), stages, teeth)
    timings["mesh_check"] = time.perf_counter() - start

    line_one = delta                                                         # O -> shaft
    line_two = float(np.arctan2(-shaft[1], carrier_length - shaft[0]))      # shaft -> A
    centers = (np.zeros(2), shaft, shaft, np.array([carrier_length, 0.0]))
    reasons = [cutting_reasons(train, stage, shape.cutter, gearing, module) for stage, shape in enumerate(shapes)]

    def gear(k: int) -> ToothedGear:
        stage, side = divmod(k, 2)
        return _gear(GEAR_NAMES[k], ("driver", "driven")[side], stages[stage], side, counts[stage], module,
                     centers[k], (line_one, line_two)[stage], teeth[stage].outlines[side], stage == 0,
                     shapes[stage].cutter, reasons[stage][side])

    return ToothedTrain(train, float(carrier_length), gearing.layout, float(module), gearing.pressure_angle,
                        (int(counts[0]), int(counts[1])), delta, shaft, (gear(0), gear(1), gear(2), gear(3)), teeth,
                        (mesh_one, mesh_two), timings)
