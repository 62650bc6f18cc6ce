"""STEP solids of the parts (``step``), through build123d: the optional extra ``transplanter[cad]``."""
