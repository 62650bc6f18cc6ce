"""Mechanisms built here, whose poses the synthesis must recover."""
from __future__ import annotations

import numpy as np


def dyad_poses(rng, count: int, spread: float = 1.0):
    """Poses of a body guided by one random dyad: (poses, center, circle in pose 1)."""
    center = rng.normal(size=2) * spread
    length = rng.uniform(0.5, 2.0) * spread
    pivot_in_body = rng.normal(size=2) * spread
    poses = []
    for _ in range(count):
        crank, turn = rng.uniform(-np.pi, np.pi), rng.uniform(-1.5, 1.5)
        moving = center + length * np.array([np.cos(crank), np.sin(crank)])
        c, s = np.cos(turn), np.sin(turn)
        poses.append([*(moving - np.array([[c, -s], [s, c]]) @ pivot_in_body), turn])
    poses = np.array(poses)
    c, s = np.cos(poses[0, 2]), np.sin(poses[0, 2])
    return poses, center, poses[0, :2] + np.array([[c, -s], [s, c]]) @ pivot_in_body


def fourbar_poses(crank_angles, crank_pivot=(0.0, 0.0), rocker_pivot=(100.0, 0.0), crank=40.0,
                  coupler=90.0, rocker=80.0, point=(30.0, 25.0)):
    """Coupler poses of a crank-rocker at the given crank angles (rad).

    The coupler frame has its origin at the crank's moving pivot A and its x-axis along AB;
    the pose reference point is ``point`` in that frame. Returns (poses, dyads) where dyads
    are the two true (center, circle in pose 1) pairs.
    """
    a0, b0 = np.array(crank_pivot, float), np.array(rocker_pivot, float)
    poses, joints = [], []
    for phi in crank_angles:
        a = a0 + crank * np.array([np.cos(phi), np.sin(phi)])
        gap = b0 - a
        d = np.linalg.norm(gap)
        along = (coupler**2 - rocker**2 + d**2) / (2 * d)
        across = np.sqrt(coupler**2 - along**2)
        b = a + (along * gap + across * np.array([-gap[1], gap[0]])) / d
        angle = np.arctan2(*(b - a)[::-1])
        c, s = np.cos(angle), np.sin(angle)
        poses.append([*(a + np.array([[c, -s], [s, c]]) @ np.array(point)), angle])
        joints.append((a, b))
    return np.array(poses), [(a0, joints[0][0]), (b0, joints[0][1])]
