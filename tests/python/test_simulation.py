"""Simulations from Python: views without copies, callbacks, CLI bits, bitwise restarts."""

import json
import subprocess

import numpy as np
import pytest

import stagger
from conftest import SCENES, SMALL_SOD


def small_sod(**more):
    return stagger.load_scene(SCENES / "sod.toml", {**SMALL_SOD, **more})


def test_a_field_view_shares_memory_with_the_state():
    sim = stagger.Simulation(small_sod())
    for _ in range(3):
        sim.step()
    rho = sim.field("density")
    assert rho.shape == (sim.scene.zones,)
    assert np.shares_memory(rho, sim.field("density"))  # the same memory each time: no copy
    assert rho.base is not None
    assert not rho.flags.writeable
    with pytest.raises(ValueError):
        rho[0] = 1.0
    x, y = sim.points()
    assert x.shape == (sim.scene.points,) and np.shares_memory(x, sim.field("x"))
    # The view holds the state the summary and the library see.
    mass = sim.field("zone_mass")
    assert np.array_equal(rho, mass / sim.field("zone_area"))
    mesh = sim.mesh()
    assert mesh["zone_corner_begin"][-1] == len(mesh["corner_point"])
    assert set(mesh["tags"]) == {"left", "right", "bottom", "top"}


def test_an_unknown_field_names_the_fields():
    sim = stagger.Simulation(small_sod())
    with pytest.raises(KeyError, match="density"):
        sim.field("densty")
    assert "stress_xx" not in sim.field_names()


def test_a_callback_stops_a_run():
    sim = stagger.Simulation(small_sod())
    seen = []
    status = sim.run(callback=lambda s: seen.append(s.cycle) or s.cycle >= 10)
    assert status == "stopped by the callback"
    assert sim.cycle == 10 and seen == list(range(1, 11))
    assert not sim.finished
    assert sim.run() == "completed"


def test_a_callback_stops_a_run_that_writes_files(tmp_path):
    sim = stagger.Simulation(small_sod())
    status = sim.run(out=tmp_path, callback=lambda s: s.cycle >= 7)
    assert "stopped by the callback" in status
    assert sim.cycle == 7
    assert json.loads((tmp_path / "summary.json").read_text())["cycles"] == 7


def test_run_until_lands_on_the_time():
    sim = stagger.Simulation(small_sod())
    sim.run(until=0.02)
    assert sim.time == 0.02
    history = sim.history()
    assert history["cycle"][0] == 0 and history["time"][-1] == 0.02


def summary_numbers(summary):
    wall_clock = {"wall_seconds", "loop_seconds", "zone_cycles_per_second", "threads"}
    return {k: v for k, v in summary.items() if k not in wall_clock}


def test_a_run_from_python_gives_the_bits_of_the_cli(tmp_path, cli):
    sets = [arg for key, value in SMALL_SOD.items() for arg in ("--set", f"{key}={value}")]
    subprocess.run([cli, "run", str(SCENES / "sod.toml"), "--out", str(tmp_path / "cli"), "--quiet", *sets],
                   check=True)
    sim = stagger.Simulation(small_sod())
    assert sim.run(out=tmp_path / "python") == "completed"
    for name in ["history.csv", "sod.pvd", "sod_000000.vtu", "sod_000001.vtu", "sod_000002.vtu"]:
        assert (tmp_path / "python" / name).read_bytes() == (tmp_path / "cli" / name).read_bytes(), name
    cli_summary = json.loads((tmp_path / "cli" / "summary.json").read_text())
    assert summary_numbers(json.loads((tmp_path / "python" / "summary.json").read_text())) == summary_numbers(
        cli_summary)
    assert summary_numbers(sim.summary()) == summary_numbers(cli_summary)
    assert sim.errors()["L1_density"] == cli_summary["errors"]["L1_density"]


def test_an_in_memory_run_gives_the_history_of_the_cli(tmp_path, cli):
    settings = {**SMALL_SOD, "output.dump_interval": 0}  # no dump times to land on
    sets = [arg for key, value in settings.items() for arg in ("--set", f"{key}={value}")]
    subprocess.run([cli, "run", str(SCENES / "sod.toml"), "--out", str(tmp_path), "--quiet", *sets], check=True)
    sim = stagger.Simulation(stagger.load_scene(SCENES / "sod.toml", settings))
    assert sim.run() == "completed"
    assert sim.history_text() == (tmp_path / "history.csv").read_text()


def state_bytes(sim):
    return {name: sim.field(name).tobytes() for name in sim.field_names()}


def test_a_restart_from_python_is_bitwise():
    whole = stagger.Simulation(small_sod())
    whole.run()
    first = stagger.Simulation(small_sod())
    for _ in range(40):
        first.step()
    blob = first.checkpoint()
    second = stagger.Simulation(small_sod())
    second.restore(blob)
    assert second.cycle == 40
    second.run()
    assert second.cycle == whole.cycle and second.time == whole.time
    assert state_bytes(second) == state_bytes(whole)


def test_a_restart_from_a_checkpoint_file_is_bitwise(tmp_path):
    settings = {"output.checkpoint_every_cycles": 100}
    whole = stagger.Simulation(small_sod(**settings))
    whole.run(out=tmp_path / "whole")
    resumed = stagger.Simulation(small_sod(**settings))
    resumed.run(out=tmp_path / "resumed", restart=tmp_path / "whole" / "sod.checkpoint")
    assert (tmp_path / "resumed" / "history.csv").read_bytes() == (tmp_path / "whole" / "history.csv").read_bytes()
    assert state_bytes(resumed) == state_bytes(whole)


def test_a_foreign_checkpoint_is_refused():
    sod = stagger.Simulation(small_sod())
    other = stagger.Simulation(small_sod(**{"mesh.refine": 2}))
    with pytest.raises(stagger.Error, match="checkpoint"):
        other.restore(sod.checkpoint())


def test_dumps_and_exact_solutions(tmp_path):
    sim = stagger.Simulation(small_sod())
    sim.run()
    sim.write_vtu(tmp_path / "state.vtu")
    sim.write_zone_csv(tmp_path / "zones.csv")
    assert (tmp_path / "state.vtu").stat().st_size > 0
    p = sim.scene.reference_parameters
    exact = stagger.ExactRiemann(p["left"], p["right"], p["gamma"], p["x0"])
    zone = sim.zone_points(0)
    assert len(zone) == 4
    x = np.array([0.1, 0.9])
    states = exact.sample(x, sim.time)
    assert np.array_equal(states["density"], [1.0, 0.125])  # outside the waves at t = 0.05


def test_progress_is_a_line_on_stderr(capsys):
    sim = stagger.Simulation(small_sod())
    sim.run(progress=True)
    err = capsys.readouterr().err
    assert err.startswith("\rstagger: cycle 1,") and err.endswith(f"cycle {sim.cycle}, t = 0.05 of 0.05 (100%), dt "
                                                                  f"{sim.dt:.3g}\n")


def test_the_gil_is_released_while_stepping():
    import threading
    import time
    sim = stagger.Simulation(small_sod(**{"mesh.refine": 4}))
    stamps = []
    done = threading.Event()

    def count():  # Python code: it runs only while the other thread does not hold the GIL
        while not done.is_set():
            stamps.append(time.perf_counter())
            time.sleep(0.001)

    counter = threading.Thread(target=count)
    counter.start()
    start = time.perf_counter()
    sim.run()
    end = time.perf_counter()
    done.set()
    counter.join()
    if end - start < 0.1:
        pytest.skip("the run was too short to tell")
    assert any(start + 0.03 < t < end - 0.03 for t in stamps)  # it ran in the middle of the run
