"""Stagger from Python: load scenes, run them, read the state as numpy views (docs/python.md).

    import stagger
    scene = stagger.load_scene("apps/scenes/sod.toml", {"mesh.refine": 2})
    sim = stagger.Simulation(scene)
    sim.run()
    rho = sim.field("density")        # a read-only numpy view of the state, no copy
    print(sim.summary()["energy"]["relative_error"])
"""

import json
import os
import re
import tempfile

import numpy as np

from . import _stagger
from ._stagger import Error, ExactRiemann, NohSolution, SedovSolution, set_threads, threads
from ._toml import document_text, override_text

__all__ = ["Error", "SceneError", "Scene", "Simulation", "load_scene", "scene_from_dict", "read_history",
           "ExactRiemann", "NohSolution", "SedovSolution", "set_threads", "threads"]


class SceneError(Error):
    """A scene the library rejects. `file`, `line` and `key` locate it (None where the message
    has no such part); str(error) is the library's one-line message."""

    def __init__(self, message, file=None, line=None, key=None):
        super().__init__(message)
        self.file, self.line, self.key = file, line, key


# "FILE:LINE[:COLUMN]: key 'KEY': what" (docs/scenes.md), "--set KEY: ..." for an override, or
# "FILE: ..." for a set-up error.
_LOCATION = re.compile(r"^(?P<where>--set [^:]+|[^:]+?)(?::(?P<line>\d+))?(?::\d+)?: (?:key '(?P<key>[^']*)': )?")


def _scene_error(error, path):
    message = str(error)
    match = _LOCATION.match(message)
    if not match:
        return SceneError(message, file=path)
    where, line, key = match.group("where"), match.group("line"), match.group("key")
    if where.startswith("--set "):
        return SceneError(message, file=path, key=key or where[len("--set "):].split("=")[0])
    return SceneError(message, file=where, line=int(line) if line else None, key=key)


class Scene:
    """A scene read, meshed and validated (stagger::Scene): name, t_end, zones, output,
    reference and reference_parameters, notes, warnings, describe()."""

    def __init__(self, handle):
        self._handle = handle

    def __getattr__(self, name):
        return getattr(self._handle, name)

    def __repr__(self):
        return f"<stagger.Scene {self.name!r} from {self.file!r}: {self.zones} zones, t_end {self.t_end}>"


def load_scene(path, overrides=None):
    """Reads a scene file with overrides {"section.key": value} (the CLI's --set). Raises
    SceneError naming the file, line and key."""
    pairs = [(key, override_text(value)) for key, value in (overrides or {}).items()]
    try:
        return Scene(_stagger.load_scene(os.fspath(path), pairs))
    except Error as error:
        raise _scene_error(error, os.fspath(path)) from None


def scene_from_dict(tables, file=None, overrides=None):
    """A scene from dicts, {"time": {"end": 0.2}, "mesh": {...}, "material": [{...}], ...}, the
    sections of docs/scenes.md. It is written as TOML to `file` (kept; relative mesh files are
    found next to it) or to a temporary file, and loaded as load_scene does."""
    text = document_text(tables)
    if file is not None:
        with open(file, "w") as out:
            out.write(text)
        return load_scene(file, overrides)
    with tempfile.TemporaryDirectory(prefix="stagger-scene-") as directory:
        path = os.path.join(directory, "scene.toml")
        with open(path, "w") as out:
            out.write(text)
        return load_scene(path, overrides)


def read_history(text):
    """history.csv's text as {column: numpy array} (time, cycle, dt, energies, momentum, ...)."""
    lines = text.strip().splitlines()
    names = lines[0].split(",")
    rows = np.array([[float(v) for v in line.split(",")] for line in lines[1:]], dtype=float).reshape(-1, len(names))
    columns = {name: rows[:, i].copy() for i, name in enumerate(names)}
    columns["cycle"] = columns["cycle"].astype(np.int64)
    return columns


class Simulation:
    """A scene being run (stagger::Simulation), set up at t = 0.

    run() steps in memory; run(out=DIR) runs the library's driver (the files and bits of
    `stagger run --out DIR`). field(name) and points() are read-only numpy views of the state
    without copying; they show the state until the next step (take them again after a run)."""

    def __init__(self, scene):
        self.scene = scene
        try:
            self._sim = _stagger.Simulation(scene._handle)
        except Error as error:
            raise _scene_error(error, scene.file) from None

    def __getattr__(self, name):  # time, cycle, dt, dt_limit, finished, t_end, energy(), ...
        return getattr(self._sim, name)

    def run(self, until=None, callback=None, progress=False, out=None, restart=None):
        """Runs to the end time, or to `until` (in memory only). `callback(sim)` is called after
        every cycle; a true result stops the run. With `out` the driver of `stagger run` writes
        dumps, history.csv, checkpoints and summary.json there (`restart`: continue from a
        checkpoint it wrote). The GIL is released while stepping; `progress` prints a line on
        stderr. Returns the status ("completed", "stopped by the callback", ...)."""
        if out is None:
            if restart is not None:
                raise ValueError("restart= resumes a run that writes files: give out= as well")
            return self._sim.advance(until, self._wrap(callback), progress)
        if until is not None:
            raise ValueError("a run with out= goes to the scene's end time; set time.end instead of until=")
        outcome = self._sim.run_with_files(os.fspath(out), os.fspath(restart) if restart else "",
                                           self._wrap(callback), progress)
        if not outcome["completed"]:
            return outcome["message"]
        return "completed"

    def _wrap(self, callback):
        return None if callback is None else (lambda _: callback(self))

    def step(self):
        """One cycle with the controlled dt."""
        self._sim.step()

    def field(self, name):
        """A read-only numpy view of a state array (names: field_names())."""
        return self._sim.field(name)

    def points(self):
        """The current point positions (x, y), read-only views."""
        return self._sim.field("x"), self._sim.field("y")

    def mesh(self):
        """The topology (mesh.hpp) as int32 views: zone_corner_begin, corner_point, ...,
        zone_region, region_names, tags {name: {edges, points}}."""
        return self._sim.mesh()

    def zone_points(self, zone):
        """The point ids of one zone, counter-clockwise."""
        mesh = self._sim.mesh()
        begin, end = mesh["zone_corner_begin"][zone], mesh["zone_corner_begin"][zone + 1]
        return mesh["corner_point"][begin:end]

    def history(self):
        """The history (one row per recorded cycle) as {column: numpy array}: the in-memory
        runs', or history.csv of the last run with out=."""
        if self._sim.history_file:
            with open(self._sim.history_file) as f:
                return read_history(f.read())
        return read_history(self._sim.history_text())

    def history_text(self):
        """The in-memory history as history.csv's text."""
        return self._sim.history_text()

    def summary(self):
        """summary.json of the current state as a dict: energy audit, momentum, errors and
        diagnostics against the scene's reference, timings."""
        return json.loads(self._sim.summary_json())

    def errors(self):
        """The error norms against the scene's exact or analytic reference (L1_density, ...)."""
        return self.summary()["errors"]

    def write_vtu(self, path):
        self._sim.write_vtu(os.fspath(path))

    def write_zone_csv(self, path):
        self._sim.write_zone_csv(os.fspath(path))

    def checkpoint(self):
        """Everything the next cycle reads, as bytes (a bitwise restart)."""
        return self._sim.checkpoint()

    def restore(self, blob, source="checkpoint"):
        """Restores bytes from checkpoint() of a simulation of the same scene."""
        self._sim.restore(blob, source)

    def __repr__(self):
        return f"<stagger.Simulation {self.scene.name!r}: cycle {self.cycle}, t = {self.time:.6g} of {self.t_end:.6g}>"
