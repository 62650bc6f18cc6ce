"""Shafts and the bores that take them: parallel keys to DIN 6885-1 (``keys``), a keyed bore's geometry
(``keyed_bore``), the default diameters by torque or by gear size and the check against each gear's root
(``sizing``)."""
