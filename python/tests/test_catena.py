"""Tests of the Python package against the command line, which runs the same library: the numbers
must be the same to the bit, and the errors the same messages.

The command line is `CATENA_BIN` (default: `target/release/catena` in this repository, which
`.ci/run` builds); h5py reads its results.h5.
"""

import json
import os
import shutil
import subprocess
from pathlib import Path

import numpy as np
import pytest

import catena

ROOT = Path(__file__).resolve().parents[2]
BIN = Path(os.environ.get("CATENA_BIN", ROOT / "target" / "release" / "catena"))
HEAVE = ROOT / "cases" / "benchmarks" / "scr-heave.toml"


def cli(*args):
    assert BIN.exists(), f"the catena command is needed at {BIN} (set CATENA_BIN)"
    return subprocess.run([str(BIN), *map(str, args)], check=True, capture_output=True, text=True)


@pytest.fixture
def short_heave(tmp_path):
    """The heave benchmark cut to 20 s, as a Scene and as a file."""
    scene = catena.Scene.from_file(HEAVE).edited(
        {"dynamic.duration": 20.0, "dynamic.envelope_start": 10.0, "dynamic.output_interval": 0.5}
    )
    path = tmp_path / "short.toml"
    path.write_text(scene.text)
    return scene, path


def test_run_equals_the_command_lines_results_h5_to_the_bit(short_heave, tmp_path):
    h5py = pytest.importorskip("h5py")
    scene, path = short_heave
    r = catena.run(scene)
    cli("run", path, "--out", tmp_path / "out")
    with h5py.File(tmp_path / "out" / "results.h5", "r") as f:
        d = f["dynamic"]
        assert np.array_equal(r["arc"], d["arc"][...])
        for name in ["time", "top_x", "top_z", "top_tension", "touchdown_arc"]:
            assert np.array_equal(r[name], d[name][...]), name
        for name in ["x", "z", "effective_tension", "bending_moment", "penetration", "seabed_force"]:
            assert r[name].shape == d[name].shape, name
            assert np.array_equal(r[name], d[name][...]), name
        # Self-describing: time and arc are HDF5 dimension scales, attached to every field and
        # series (h5py, netCDF and xarray read them), and the decimated records are compressed.
        assert d["time"].is_scale and d["arc"].is_scale and f["static/arc"].is_scale
        for name in ["x", "z", "effective_tension", "bending_moment", "penetration",
                     "seabed_force", "seabed_mode"]:
            assert d[name].dims[0][0] == d["time"] and d[name].dims[1][0] == d["arc"], name
            assert h5py.h5ds.is_attached(d[name].id, d["arc"].id, 1), name
            assert d[name].compression == "gzip", name
        for name in ["top_x", "top_z", "top_tension", "touchdown_arc"]:
            assert d[name].dims[0][0] == d["time"], name
        assert f["static/bending_moment"].dims[0][0] == f["static/arc"]
        assert f["ranges/bending_moment/max"].dims[0][0] == d["arc"]
        assert d.attrs["bending_moment"] == "negative in a sag bend"
        # Range graphs: the same quantities, to the bit (no section in this scene: no stresses).
        ranges = sorted(f["ranges"].keys())
        assert ranges == sorted(
            ["bending_moment", "effective_tension", "curvature", "penetration", "seabed_force"]
        )
        for q in ranges:
            for what in ["min", "max", "mean"]:
                key = f"ranges/{q}/{what}"
                assert np.array_equal(r[key], f[key][...], equal_nan=True), key
    summary = json.loads((tmp_path / "out" / "summary.json").read_text())
    dyn = summary["dynamic"]
    assert r.summary["completed"] and dyn["completed"]
    assert r.summary["touchdown_arc_min"] == dyn["touchdown_arc_min"]
    assert r.summary["touchdown_arc_max"] == dyn["touchdown_arc_max"]
    # 41 records: t = 0, 0.5, ..., 20 s; 401 nodes of the heave riser.
    assert r["bending_moment"].shape == (41, 401)
    # The range graph: the envelopes from envelope_start, max above min where the line moves.
    rng = r["ranges/bending_moment/max"] - r["ranges/bending_moment/min"]
    assert rng.max() > 1e4 and (rng >= 0).all()


def test_statics_equal_the_command_line(tmp_path):
    st = catena.statics(HEAVE)
    cli("static", HEAVE, "--out", tmp_path / "st")
    summary = json.loads((tmp_path / "st" / "summary.json").read_text())
    s = summary.get("static", summary)
    assert st.summary["top_tension"] == s["top_tension"]
    assert st.summary["touchdown_arc"] == s["touchdown_arc"]
    # Sign conventions: the sag bend's moment is negative, the resting line penetrates (positive).
    assert st["bending_moment"].min() < 0 and st.summary["max_sag_moment"] < 0
    assert st["penetration"].max() > 0
    assert st.at_arc("bending_moment", st.summary["max_sag_moment_arc"]) == st.summary["max_sag_moment"]


def test_edits_set_and_remove_keys_and_are_checked():
    base = catena.Scene.from_file(HEAVE)
    stiffer = base.edited({"seabed.stiffness": 1.0e6})
    assert "1000000" in stiffer.text
    with pytest.raises(catena.CatenaError, match=r"line\.od"):
        base.edited({"line.od": -1.0})
    with pytest.raises(catena.CatenaError, match=r"scr-heave\.toml"):
        base.edited({"line.od": "thick"})
    with pytest.raises(catena.CatenaError, match="<text>"):
        catena.Scene.from_text("[line]\nlength = ")
    with pytest.raises(catena.CatenaError, match="nope.toml"):
        catena.Scene.from_file("nope.toml")
    # Removing the motion leaves a scene that still reads (statics only).
    assert catena.statics(base.edited({"motion": None})).summary["top_tension"] > 1e6


def test_progress_is_reported_and_its_errors_propagate(short_heave):
    scene, _ = short_heave
    seen = []
    catena.run(scene, progress=lambda t, d: seen.append((t, d)), every=100)
    assert seen[0] == (0.0, 20.0) and seen[-1] == (20.0, 20.0) and len(seen) == 5

    def boom(t, d):
        if t > 2:
            raise ValueError("stop here")

    with pytest.raises(ValueError, match="stop here"):
        catena.run(scene, progress=boom, every=10)


def small_study(d):
    for f in ["fatigue/scr1000-linear-k100.toml", "semi-rao.csv"]:
        shutil.copy(ROOT / "cases" / "scr1000" / f, d / Path(f).name)
    (d / "storms.toml").write_text(
        "[[storm]]\nid = 22\nhs = 5.0\ntp = 8.4\nprobability = 0.002\n\n"
        "[[storm]]\nid = 23\nhs = 5.0\ntp = 9.9\nprobability = 0.004\n"
    )
    (d / "study.toml").write_text(
        '[study]\nscene = "scr1000-linear-k100.toml"\nstorms = "storms.toml"\nrecord = 20.0\n'
        'transient = 10.0\n\n[fatigue]\nsn_curve = "dnv-e-seawater-cp"\nscf = 1.2\nfibres = ["outer"]\n'
    )
    (d / "plan.toml").write_text(
        '[sweep]\nbase = "study.toml"\ncombine = "product"\n[[sweep.parameter]]\n'
        'key = "seabed.stiffness"\nvalues = [100e3, 1000e3]\n'
    )
    return d / "study.toml", d / "plan.toml"


def test_fatigue_study_and_sweep_equal_the_command_line(tmp_path):
    study, plan = small_study(tmp_path)
    f = catena.fatigue_study(study, jobs=2)
    cli("fatigue", study, "--out", tmp_path / "fo")
    s = json.loads((tmp_path / "fo" / "summary.json").read_text())
    life = f.summary["lives"]["outer"]
    assert life["min_life_years"] == s["min_life_years"]
    assert life["arc"] == s["min_life_arc"]
    assert np.array_equal(f["life_outer"], 1.0 / f["damage_outer"])
    assert f["life_outer"].min() == s["min_life_years"]

    rows = catena.sweep(plan, jobs=2)
    cli("sweep", plan, "--out", tmp_path / "so")
    points = json.loads((tmp_path / "so" / "sweep.json").read_text())["points"]
    assert len(rows) == len(points) == 2
    for a, b in zip(rows, points):
        for k in ["min_life_years", "min_life_arc", "tdz_moment_range", "max_penetration"]:
            assert a[k] == b[k], k
    # A stiffer seabed shortens the life (Figure 9's trend).
    assert rows[1]["min_life_years"] < rows[0]["min_life_years"]


def test_sequence_equals_the_command_line(tmp_path):
    """Two short visits in sequence on the R–Q seabed: the Python sequence gives the command
    line's lives and trench to the bit; the second visit starts from the first one's trench."""
    for f in ["fatigue/scr1000-rq-fsuc0.2.toml", "fatigue/gom-30-storms.toml", "semi-rao.csv"]:
        shutil.copy(ROOT / "cases" / "scr1000" / f, tmp_path / Path(f).name)
    seq = tmp_path / "sequence.toml"
    seq.write_text(
        '[sequence]\nscene = "scr1000-rq-fsuc0.2.toml"\nstorms = "gom-30-storms.toml"\n'
        "order = [23, 23]\nrecord = 20.0\ntransient = 20.0\ncalm = 0.0\nsettle = 20.0\n\n"
        '[fatigue]\nsn_curve = "dnv-e-seawater-cp"\nscf = 1.2\nfibres = ["outer"]\n'
    )
    r = catena.sequence(seq, jobs=2)
    cli("sequence", seq, "--out", tmp_path / "out")
    s = json.loads((tmp_path / "out" / "summary.json").read_text())
    assert r["life_memory"].min() == s["memory"]["minimum_life_years"]
    assert r["life_as_laid"].min() == s["as_laid"]["minimum_life_years"]
    trench = np.loadtxt(tmp_path / "out" / "trench.csv", delimiter=",", skiprows=1)
    assert np.array_equal(trench[:, 2:].T, r["trench"])
    assert r["trench"].shape == (2, r["arc"].size)
    assert r["trench"][1].max() > r["as_laid_penetration"].max()
