"""Every DXF of every command that draws (gear, cam, parallelogram, fivebar) has the convention's layers, each
with its colour, in millimetres, and its entities on them alone."""
from pathlib import Path

import ezdxf
import pytest

from transplanter.cli import main
from transplanter.drawing.sheet import LAYERS

ROOT = Path(__file__).resolve().parents[2]
#: Layers every DXF file has besides the convention's: AutoCAD's own "0" and "Defpoints" (dimensions' points).
STANDARD = {"0", "Defpoints"}
COMMANDS = {"gear": ["gear", str(ROOT / "examples/gear_ellipse.toml"), "--no-step"],
            "cam": ["cam", str(ROOT / "examples/cam_flat_faced.toml"), "--no-step"],
            "parallelogram": ["parallelogram", str(ROOT / "examples/onion_transplanter.toml"), "--no-animation",
                              "--no-tolerance", "--no-step"]}


@pytest.fixture(scope="module")
def folders(example_result_drawings, tmp_path_factory) -> dict[str, Path]:
    out = {}
    for name, arguments in COMMANDS.items():
        out[name] = tmp_path_factory.mktemp(name) / "out"
        assert main([*arguments, "--out", str(out[name])]) in (0, 1)
    out["fivebar"] = example_result_drawings[0].parent
    return out


def test_every_dxf_of_every_command_has_the_same_layers(folders):
    counts = {}
    for command, folder in folders.items():
        files = sorted(folder.glob("*.dxf"))
        counts[command] = len(files)
        for path in files:
            document = ezdxf.readfile(path)
            assert document.header["$INSUNITS"] == 4, path.name       # millimetres
            layers = {layer.dxf.name: layer.color for layer in document.layers}
            assert set(layers) == STANDARD | set(LAYERS), path.name
            assert {name: layers[name] for name in LAYERS} == LAYERS, path.name
            assert {entity.dxf.layer for entity in document.modelspace()} <= set(LAYERS), path.name
            assert len(document.modelspace().query("TEXT[layer=='TEXT']")) >= 5, path.name    # the title block
    assert counts == {"gear": 2, "cam": 1, "parallelogram": 2, "fivebar": 1 + 4 + 4}
