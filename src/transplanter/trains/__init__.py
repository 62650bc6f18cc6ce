"""Planetary trains of non-circular gears: the ratio split over two stages, the four pitch
curves, and the train rolled from its pitch curves alone."""
