"""Plane geometry shared by every mechanism: poses and frames, RR dyads, traced algebraic
curves, pivot pairing, periodic cubic B-splines, closed B-spline paths, monotone turn maps
and quadrature over a turn. Imports no mechanism."""
