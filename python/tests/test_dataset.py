"""Dataset sweeps (issue 31): `mechkin sweep --curves COLS --out DIR` writes every row of
the chosen columns of every variant into HDF5 (read here with h5py); the curves equal
single runs with --set bit for bit; shards merged (virtual datasets) equal the unsharded
file; mechkin.sweep(client=..., out=..., curves=...) on a 2-process LocalCluster writes
the same data, also when a worker dies mid-sweep (its task is retried)."""
import json
import os
import random
import subprocess

import numpy as np
import pytest

import mechkin

h5py = pytest.importorskip("h5py")

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
FOUR_BAR = os.path.join(ROOT, "mechanisms", "parametric-four-bar.json")
BINARY = os.environ.get("MECHKIN_BINARY", os.path.join(ROOT, "build", "mechkin"))
CURVES = ["coupler_point.x", "coupler_point.y"]
# 5 crank lengths x 4 coupler lengths = 20 variants; b = 5 mm cannot close the loop
# (invalid), some of the others stop at a limit of the crank.
GRID = ["--grid", "a=30:60:5", "--grid", "b=5:160:4"]
DATASETS = ("curves", "parameters", "status", "rows", "t_stop", "variant", "t")


def _mechkin(*args, check=True):
    r = subprocess.run([BINARY] + [str(a) for a in args], capture_output=True, text=True)
    if check and r.returncode != 0:
        raise AssertionError("mechkin %s: exit %d\n%s" % (" ".join(map(str, args)), r.returncode, r.stderr))
    return r


@pytest.fixture(scope="module")
def four_bar(tmp_path_factory):
    """The parametric four-bar with 360-row runs."""
    spec = json.load(open(FOUR_BAR))
    spec["analysis"]["steps"] = 359
    path = tmp_path_factory.mktemp("model") / "four-bar-360.json"
    path.write_text(json.dumps(spec))
    return str(path)


@pytest.fixture(scope="module")
def whole(four_bar, tmp_path_factory):
    """The unsharded dataset: (folder, {dataset: array}, attributes)."""
    out = tmp_path_factory.mktemp("whole")
    _mechkin("sweep", four_bar, *GRID, "--curves", ",".join(CURVES), "--out", out, "--threads", 2)
    return out, _read(out / "sweep.h5")


def _read(path):
    with h5py.File(path, "r") as f:
        data = {name: f[name][()] for name in DATASETS}
        attrs = {
            "columns": list(f["curves"].attrs["columns"]), "units": list(f["curves"].attrs["units"]),
            "parameters": list(f["parameters"].attrs["names"]), "statuses": list(f["status"].attrs["names"]),
            "complete": int(f.attrs["complete"]), "total": int(f.attrs["total"]),
        }
    return data, attrs


def _same_bits(a, b):
    a, b = np.ascontiguousarray(a), np.ascontiguousarray(b)
    return a.dtype == b.dtype and a.shape == b.shape and a.tobytes() == b.tobytes()


def test_the_dataset_reads_in_h5py_with_its_names_parameters_and_statuses(whole):
    _, (data, attrs) = whole
    assert data["curves"].shape == (20, 360, 2) and data["curves"].dtype == np.float64
    assert attrs["columns"] == CURVES and attrs["units"] == ["mm", "mm"]
    assert attrs["parameters"] == ["a", "b"] and attrs["complete"] == 1 and attrs["total"] == 20
    assert attrs["statuses"] == list(mechkin._mechkin.sweep_statuses())
    assert attrs["statuses"][:2] == ["complete", "invalid"]
    # The grid, row-major with the last axis fastest, as GridVariants makes it.
    for i in range(20):
        ka, kb = divmod(i, 4)
        assert data["parameters"][i, 0] == 30 + (60 - 30) * ka / 4
        assert data["parameters"][i, 1] == 5 + (160 - 5) * kb / 3
    assert list(data["variant"]) == list(range(20))
    assert data["t"][0] == 0 and data["t"][-1] == 1 and np.allclose(data["t"], np.arange(360) / 359, rtol=0, atol=1e-15)


def test_a_variant_that_cannot_close_is_invalid_with_nan_rows(whole):
    _, (data, attrs) = whole
    invalid = attrs["statuses"].index("invalid")
    bad = [i for i in range(20) if data["parameters"][i, 1] == 5]
    assert len(bad) == 5
    for i in bad:
        assert data["status"][i] == invalid and data["rows"][i] == 0
        assert np.isnan(data["curves"][i]).all()
    others = [i for i in range(20) if i not in bad]
    assert all(attrs["statuses"][data["status"][i]] in ("complete", "limit") for i in others)
    assert any(attrs["statuses"][data["status"][i]] == "complete" for i in others)


def _run_table(four_bar, values, tmp_path):
    """`mechkin run --set ... --order 1 --format json`: (rows of the curve columns, exit code)."""
    out = tmp_path / "run.json"
    if out.exists():
        out.unlink()
    sets = []
    for name, value in values.items():
        sets += ["--set", "%s=%r" % (name, float(value))]
    r = _mechkin("run", four_bar, *sets, "--order", 1, "--format", "json", "-o", out, "--quiet", check=False)
    if not out.exists():
        return None, r.returncode
    table = json.load(open(out))
    names = [c["name"] for c in table["columns"]]
    rows = np.array([[np.nan if x is None else x for x in row] for row in table["rows"]], dtype=np.float64)
    return rows[:, [names.index(c) for c in CURVES]].reshape(-1, len(CURVES)), r.returncode


def test_five_random_variants_equal_single_runs_with_set_bit_for_bit(whole, four_bar, tmp_path):
    _, (data, attrs) = whole
    model = mechkin.load(four_bar)
    picks = random.Random(31).sample(range(20), 5)
    # Always one that stops early and the invalid one too, whatever the draw.
    statuses = [attrs["statuses"][s] for s in data["status"]]
    picks += [statuses.index(s) for s in ("limit", "invalid") if s in statuses]
    for i in picks:
        values = dict(zip(attrs["parameters"], data["parameters"][i]))
        rows, code = _run_table(four_bar, values, tmp_path)
        n = int(data["rows"][i])
        if statuses[i] == "invalid":
            assert rows is None and code == 1 and n == 0
            continue
        assert rows.shape[0] == n, (i, statuses[i])
        assert _same_bits(data["curves"][i, :n], rows), i
        assert np.isnan(data["curves"][i, n:]).all()
        assert (code == 0) == (statuses[i] == "complete")
        motion = model.with_parameters(**values).run(order=1)
        assert _same_bits(data["curves"][i, :n], np.stack([motion[c] for c in CURVES], axis=1)), i


def test_shards_merged_equal_the_unsharded_dataset(whole, four_bar, tmp_path):
    _, (data, _) = whole
    for s in (1, 2, 3):
        _mechkin("sweep", four_bar, *GRID, "--curves", ",".join(CURVES), "--out", tmp_path, "--shard", "%d/3" % s)
    parts = sorted(str(p) for p in tmp_path.glob("sweep-shard-*-of-3.h5"))
    assert len(parts) == 3
    r = _mechkin("sweep", "--merge", "--out", tmp_path, *parts[:2], check=False)
    assert r.returncode == 1 and "missing shards: 3/3" in r.stderr
    _mechkin("sweep", "--merge", "--out", tmp_path, *parts)
    merged = tmp_path / "sweep.h5"
    # The merged file holds no curve data of its own: it references the parts.
    assert merged.stat().st_size < 0.5 * min(os.path.getsize(p) for p in parts)
    # Read from another folder: the parts are found beside the merged file.
    moved = tmp_path.parent / (tmp_path.name + "-moved")
    os.rename(tmp_path, moved)
    cwd = os.getcwd()
    try:
        os.chdir("/")
        got, attrs = _read(str(moved / "sweep.h5"))
    finally:
        os.chdir(cwd)
        os.rename(moved, tmp_path)
    for name in DATASETS:
        assert _same_bits(got[name], data[name]), name
    assert attrs["complete"] == 1


def test_a_merge_refuses_parts_of_another_sweep(whole, four_bar, tmp_path):
    other = tmp_path / "other"
    _mechkin("sweep", four_bar, "--grid", "a=30:60:5", "--grid", "b=5:160:4", "--tol", "1e-12", "--curves",
             ",".join(CURVES), "--out", other, "--shard", "2/3")
    for s in (1, 3):
        _mechkin("sweep", four_bar, *GRID, "--curves", ",".join(CURVES), "--out", tmp_path, "--shard", "%d/3" % s)
    parts = [tmp_path / "sweep-shard-1-of-3.h5", other / "sweep-shard-2-of-3.h5", tmp_path / "sweep-shard-3-of-3.h5"]
    r = _mechkin("sweep", "--merge", "--out", tmp_path, *parts, check=False)
    assert r.returncode == 1 and "another sweep" in r.stderr
    r = _mechkin("sweep", "--merge", "--out", tmp_path, tmp_path / "none.h5", check=False)
    assert r.returncode == 1 and "cannot open" in r.stderr
    r = _mechkin("sweep", "--merge", "--out", tmp_path, four_bar, check=False)
    assert r.returncode == 1 and "is not an HDF5 file" in r.stderr


def test_an_unknown_curve_column_is_refused_with_the_columns_there_are(four_bar, tmp_path):
    r = _mechkin("sweep", four_bar, *GRID, "--curves", "coupler_point.w", "--out", tmp_path, check=False)
    assert r.returncode == 2 and "no column 'coupler_point.w'" in r.stderr and "coupler_point.y" in r.stderr
    assert not list(tmp_path.iterdir())


def _variants(data, attrs):
    return [dict(zip(attrs["parameters"], map(float, p))) for p in data["parameters"]]


def test_python_local_threads_write_the_cli_dataset(whole, four_bar, tmp_path):
    _, (data, attrs) = whole
    path = mechkin.sweep(mechkin.load(four_bar), _variants(data, attrs), out=tmp_path, curves=CURVES, threads=2)
    got, _ = _read(path)
    for name in DATASETS:
        assert _same_bits(got[name], data[name]), name


def _cluster():
    distributed = pytest.importorskip("distributed")
    return distributed, distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                                 dashboard_address=None)


def test_dask_local_cluster_writes_the_cli_dataset(whole, four_bar, tmp_path):
    _, (data, attrs) = whole
    distributed, cluster = _cluster()
    with cluster, distributed.Client(cluster) as client:
        path = mechkin.sweep(mechkin.load(four_bar), _variants(data, attrs), client=client, out=tmp_path,
                             curves=CURVES, chunk=3)
    assert sorted(p.name for p in tmp_path.glob("part-*.h5")) == ["part-%05d.h5" % k for k in range(7)]
    got, got_attrs = _read(path)
    for name in DATASETS:
        assert _same_bits(got[name], data[name]), name
    assert got_attrs["complete"] == 1


def test_a_worker_killed_mid_sweep_loses_no_variant(whole, four_bar, tmp_path):
    _, (data, attrs) = whole
    distributed, cluster = _cluster()
    marker = str(tmp_path / "killed")

    class ExitOnce(distributed.WorkerPlugin):
        """Ends its worker's process (os._exit) as the sweep's first task starts there."""

        def transition(self, key, start, finish, **kwargs):
            if finish != "executing" or "mechkin-dataset-part" not in str(key):
                return
            try:  # created exclusively: one worker of the two dies, once
                fd = os.open(marker, os.O_CREAT | os.O_EXCL | os.O_WRONLY)
            except FileExistsError:
                return
            os.write(fd, str(key).encode())
            os.close(fd)
            os._exit(1)

    out = tmp_path / "data"
    with cluster, distributed.Client(cluster) as client:
        client.register_worker_plugin(ExitOnce(), name="exit-once")
        path = mechkin.sweep(mechkin.load(four_bar), _variants(data, attrs), client=client, out=out,
                             curves=CURVES, chunk=2)
    assert os.path.exists(marker)  # a worker died running a part
    got, _ = _read(path)
    for name in DATASETS:
        assert _same_bits(got[name], data[name]), name


def _stderr_on_a_terminal(args):
    """What a command writes to its stderr when that is a terminal (a pty)."""
    import pty
    master, slave = pty.openpty()
    proc = subprocess.Popen(args, stdout=subprocess.DEVNULL, stderr=slave)
    os.close(slave)
    seen = b""
    while True:
        try:
            chunk = os.read(master, 4096)
        except OSError:  # EIO: the child closed the terminal
            break
        if not chunk:
            break
        seen += chunk
    os.close(master)
    assert proc.wait() == 0
    return seen


def test_progress_on_a_terminal_and_none_on_a_pipe(four_bar, tmp_path):
    dataset = [BINARY, "sweep", four_bar, *GRID, "--curves", ",".join(CURVES), "--out", str(tmp_path / "d")]
    summary = [BINARY, "sweep", four_bar, *GRID, "-o", str(tmp_path / "s.csv")]
    for args, last in ((dataset, b"mechkin sweep: 20 variants in "), (summary, b"")):
        seen = _stderr_on_a_terminal(args)
        assert b"\r\x1b[K" in seen and b"20/20 variants, " in seen and b" variants/s" in seen, seen[:300]
        assert last in seen
        piped = subprocess.run(args, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
        assert piped.returncode == 0 and b"\r" not in piped.stderr and b"20/20" not in piped.stderr
        assert piped.stderr.startswith(last) and (last or not piped.stderr)
