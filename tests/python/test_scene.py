"""drumlab.Scene: keys by dotted name, the engine's validation, ValueError with the CLI's line."""
import pytest

import drumlab
from conftest import SCENES, run_cli


def test_keys_read_and_written_by_dotted_name(small_scene, tmp_path):
    scene = drumlab.Scene.load(str(small_scene))
    assert scene.name == "py_small"
    assert scene["liquid.surface_tension"] == pytest.approx(0.072)
    assert scene["fill.count"] == 300
    assert scene["gravity"] == [0.0, -9.81, 0.0]
    scene["liquid.surface_tension"] = 0.05
    scene["fill.count"] = 200
    scene["gravity"] = [0.0, -20.0, 0.0]
    assert "liquid.surface_tension" in scene.keys()
    out = tmp_path / "saved.toml"
    scene.save(str(out))
    again = drumlab.Scene.load(str(out))
    assert again["liquid.surface_tension"] == 0.05
    assert again["fill.count"] == 200
    assert again["gravity"] == [0.0, -20.0, 0.0]
    with pytest.raises(KeyError):
        scene["no.such.key"]


def test_a_bad_value_raises_the_clis_line_and_keeps_the_old_value(small_scene, tmp_path):
    scene = drumlab.Scene.load(str(small_scene))
    with pytest.raises(ValueError) as err:
        scene["liquid.surface_tension"] = -1.0
    assert scene["liquid.surface_tension"] == pytest.approx(0.072)  # unchanged
    # The CLI's line for the same scene text, after its "drumlab: error: " prefix.
    bad = tmp_path / "bad.toml"
    bad.write_text(scene.text().replace("surface_tension = 0.072", "surface_tension = -1.0"))
    code, out = run_cli("info", bad)
    assert code == 2
    cli_line = [l for l in out.splitlines() if l.startswith("drumlab: error: ")][0]
    assert str(err.value).replace(str(small_scene), str(bad)) == cli_line[len("drumlab: error: "):]
    with pytest.raises(ValueError, match="is not a number"):
        scene["liquid.surface_tension"] = "wet"
    with pytest.raises(ValueError, match="unknown key"):
        scene["drum.colour"] = "red"


def test_every_shipped_scene_loads():
    for path in sorted(SCENES.glob("*.toml")):
        assert drumlab.Scene.load(str(path)).name == path.stem


def test_a_bad_file_raises_the_clis_line_with_the_files_own_line_number(small_scene, tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text(small_scene.read_text().replace("friction = 0.4", "friction = -0.4"))
    with pytest.raises(ValueError) as err:
        drumlab.Scene.load(str(bad))
    code, out = run_cli("info", bad)
    assert code == 2
    assert "drumlab: error: " + str(err.value) in out.splitlines()
    assert "(line" in str(err.value)


def test_keys_as_attributes(small_scene):
    scene = drumlab.Scene.load(str(small_scene))
    assert scene.liquid.surface_tension == pytest.approx(0.072)
    assert scene.name == "py_small"  # the property, not a key lookup
    scene.liquid.surface_tension = 0.04
    scene.fill.count = 250
    assert scene["liquid.surface_tension"] == 0.04
    assert scene["fill.count"] == 250
    with pytest.raises(ValueError, match="liquid.surface_tension"):
        scene.liquid.surface_tension = -2.0
    assert scene.liquid.surface_tension == 0.04
    with pytest.raises(AttributeError):
        scene.liquid.no_such_key
