"""Time a cam with 3,600 profile points and all its checks against a plain numpy baseline that takes
the derivatives by finite differences on the same profile.

    python bench/bench_cam.py

The cam: examples/cam_seedling_support.toml (an oscillating roller follower, harmonic rise and return
between dwells; 3,600 cam angles). Ours: ``synthesize`` (the generated laws, roller centre and pitch
functions, then the checks with their polished extremes). The baseline, in the same process: the
displacement from the laws' closed forms, the roller centre from the arm, the pitch curve turned into
the cam frame, then its tangent, normal and curvature by periodic central differences, the profile, the
pressure angle, the undercut and interference checks (the same k-d tree query), all in numpy. Target:
ours under 0.2 s warm. Printed: both times, their ratio, and how far the baseline's pressure angle and
curvature radius are from ours (the price of differences).
"""
from __future__ import annotations

from pathlib import Path

import numpy as np
from best_time import best_time  # bench/ is the script's own folder
from scipy.spatial import cKDTree

from transplanter import cam
from transplanter.cam.kinematics import oscillating_start

ROOT = Path(__file__).resolve().parents[1]



def baseline(problem):
    """Everything the checks need, by finite differences of sampled points (harmonic segments only)."""
    angle = np.linspace(0, 2 * np.pi, problem.samples, endpoint=False)
    swing, start = np.zeros_like(angle), 0.0
    level = 0.0
    for segment in problem.segments:
        into = angle - start
        inside = (into >= 0) & (into < segment.angle)
        swing[inside] = level + segment.lift * (1 - np.cos(np.pi * into[inside] / segment.angle)) / 2
        level += segment.lift
        start += segment.angle
    follower = problem.follower
    pitch_radius = problem.base_radius + follower.roller_radius
    b0, sense = oscillating_start(follower, pitch_radius, problem.direction)
    arm = b0 + sense * swing
    center = follower.pivot + follower.arm_length * np.column_stack([np.cos(arm), np.sin(arm)])
    turn = -problem.direction * angle
    pitch = np.column_stack([np.cos(turn) * center[:, 0] - np.sin(turn) * center[:, 1],
                             np.sin(turn) * center[:, 0] + np.cos(turn) * center[:, 1]])
    step = angle[1] - angle[0]
    tangent = (np.roll(pitch, -1, 0) - np.roll(pitch, 1, 0)) / (2 * step)
    second = (np.roll(pitch, -1, 0) - 2 * pitch + np.roll(pitch, 1, 0)) / step**2
    speed = np.linalg.norm(tangent, axis=1)
    radius = -problem.direction * speed**3 / (tangent[:, 0] * second[:, 1] - tangent[:, 1] * second[:, 0])
    outward = problem.direction * np.column_stack([-tangent[:, 1], tangent[:, 0]]) / speed[:, None]
    profile = pitch - follower.roller_radius * outward
    velocity = (np.roll(center, -1, 0) - np.roll(center, 1, 0)) / (2 * step)
    back = -turn
    ground = np.column_stack([np.cos(back) * tangent[:, 0] - np.sin(back) * tangent[:, 1],
                              np.sin(back) * tangent[:, 0] + np.cos(back) * tangent[:, 1]])
    moving = np.linalg.norm(velocity, axis=1) > 0
    unit = np.zeros_like(velocity)
    unit[moving] = velocity[moving] / np.linalg.norm(velocity[moving], axis=1)[:, None]
    along = np.einsum("ij,ij->i", ground, unit)
    across = np.abs(ground[:, 0] * unit[:, 1] - ground[:, 1] * unit[:, 0])
    pressure = np.where(moving, np.arctan2(np.abs(along), across), 0.0)
    undercut = bool(((radius > 0) & (radius < follower.roller_radius)).any())
    distance, _ = cKDTree(profile).query(pitch)
    interference = bool((distance < follower.roller_radius * (1 - 1e-6)).any())
    return pressure, radius, undercut, interference


def main():
    problem = cam.load_problem(ROOT / "examples/cam_seedling_support.toml")
    cam.synthesize(problem)
    ours, result = best_time(lambda: cam.synthesize(problem), 7)
    theirs, (pressure, radius, undercut, interference) = best_time(lambda: baseline(problem), 7)
    g = result.geometry
    ends = np.zeros(g.angle.size, bool)
    for start in np.cumsum([s.angle for s in problem.segments]):
        ends |= np.abs((g.angle - start + np.pi) % (2 * np.pi) - np.pi) < 2 * (g.angle[1] - g.angle[0])
    exact = np.abs(g.pressure_angle)
    moving = np.array([s.kind != "dwell" for s in problem.segments])[g.segment] & ~ends
    print(f"cam of {g.angle.size} profile points, {len(problem.segments)} segments, all checks")
    print(f"  transplanter.cam.synthesize  {ours * 1e3:7.1f} ms  (target < 200 ms)  "
          f"largest pressure angle {np.degrees(max(e.value for e in result.checks.pressure.values())):.6f} deg")
    print(f"  numpy finite differences     {theirs * 1e3:7.1f} ms  largest pressure angle "
          f"{np.degrees(pressure.max()):.6f} deg  (same undercut: {undercut == bool(result.checks.undercut)}, "
          f"same interference: {interference == bool(result.checks.interference)})")
    print(f"  ratio ours / baseline        {ours / theirs:7.2f}")
    pressure_off = np.degrees(np.abs(pressure - exact)[moving].max())
    curvature_off = np.abs(1 / radius - 1 / g.curvature_radius)
    print(f"  baseline off ours, away from segment ends: pressure angle on rises and returns {pressure_off:.2e} "
          f"deg, curvature {curvature_off[~ends].max():.2e} 1/mm; at segment ends (jumps of "
          f"acceleration) curvature off by up to {curvature_off[ends].max():.2e} 1/mm")


if __name__ == "__main__":
    main()
