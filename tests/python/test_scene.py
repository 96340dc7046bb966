"""Scenes from Python: overrides, dicts, and located errors as stagger.SceneError."""

import pytest

import stagger
from conftest import SCENES


def test_overrides_take_python_values():
    scene = stagger.load_scene(SCENES / "sod.toml", {"mesh.refine": 2, "time.end": 0.1})
    assert scene.zones == 200 * 5
    assert scene.t_end == 0.1
    assert scene.reference == "shock_tube"
    assert scene.reference_parameters["left"]["pressure"] == 1.0


def test_a_scene_error_is_an_exception_naming_the_key(tmp_path):
    bad = tmp_path / "bad.toml"
    text = (SCENES / "sod.toml").read_text().replace("cfl = 0.15", "cfl = 7.5")
    bad.write_text(text)
    with pytest.raises(stagger.SceneError) as caught:
        stagger.load_scene(bad)
    error = caught.value
    assert error.key == "numerics.cfl", str(error)
    assert error.file == str(bad)
    line = next(i for i, l in enumerate(text.splitlines(), 1) if l.startswith("cfl"))
    assert error.line == line
    assert isinstance(error, stagger.Error) and isinstance(error, RuntimeError)


def test_an_override_error_names_the_key():
    with pytest.raises(stagger.SceneError) as caught:
        stagger.load_scene(SCENES / "sod.toml", {"numerics.cfl": -1.0})
    assert caught.value.key == "numerics.cfl" and caught.value.line is None
    assert caught.value.file == str(SCENES / "sod.toml")


def test_a_scene_from_dicts_runs(tmp_path):
    scene = stagger.scene_from_dict({
        "scene": {"name": "tube"},
        "time": {"end": 0.01},
        "mesh": {"generator": "rectangle", "x": [0.0, 1.0], "y": [0.0, 0.1], "nx": 20, "ny": 2},
        "material": [{"name": "gas", "eos": "ideal_gas", "gamma": 1.4}],
        "region": [{"name": "domain", "material": "gas", "density": "x < 0.5 ? 1.0 : 0.125",
                    "pressure": "x < 0.5 ? 1.0 : 0.1"}],
        "boundary": [{"tags": ["left", "right", "bottom", "top"], "type": "wall"}],
    })
    assert scene.zones == 40
    sim = stagger.Simulation(scene)
    assert sim.run() == "completed"
    assert sim.time == 0.01
    assert abs(sim.summary()["energy"]["relative_error"]) < 1e-12
