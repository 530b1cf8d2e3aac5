"""Tests of `import honeycomb` over the library's front door (issue 25)."""

import json
import os
import pathlib
import signal
import subprocess

import numpy as np
import pytest

import honeycomb

REPO = pathlib.Path(__file__).resolve().parents[2]
CELLS = 150


def height_field(height, n, lo, hi):
    """The height field z = height(x, y) on [lo, hi]^2, n x n points, triangulated:
    (vertices, faces)."""
    x, y = np.meshgrid(np.linspace(lo, hi, n), np.linspace(lo, hi, n))
    vertices = np.stack([x.ravel(), y.ravel(), height(x, y).ravel()], axis=1)
    faces = []
    for i in range(n - 1):
        for j in range(n - 1):
            a = i * n + j
            b, c, d = a + 1, a + n, a + n + 1
            faces += [[a, b, d], [a, d, c]]
    return vertices, np.array(faces, dtype=np.int64)


def saddle(n=25):
    """The height field z = 0.1 (x^2 - y^2) on [-1, 1]^2, triangulated."""
    return height_field(lambda x, y: 0.1 * (x**2 - y**2), n, -1, 1)


def write_obj(path, vertices, faces):
    with open(path, "w") as f:
        for v in vertices:
            f.write("v {:.17g} {:.17g} {:.17g}\n".format(*v))
        for face in faces:
            f.write("f " + " ".join(str(int(i) + 1) for i in face) + "\n")
    return path


@pytest.fixture(scope="module")
def surface():
    return saddle()


@pytest.fixture(scope="module")
def result(surface):
    return honeycomb.pipeline(surface, cells=CELLS)


def test_pipeline_on_arrays_is_a_honeycomb(result):
    assert result.is_honeycomb, result.why
    assert result.why is None
    n = result.vertices.shape[0]
    assert result.vertices.shape == (n, 3) and result.vertices.dtype == np.float64
    assert result.offset_vertices.shape == (n, 3)
    assert result.node_axes.shape == (n, 3)
    m = result.edges.shape[0]
    assert result.edges.shape == (m, 2) and result.edges.dtype == np.int64
    assert result.wall_normals.shape == (m, 3)
    assert result.edges.max() < n
    assert all(3 <= len(f) <= 6 for f in result.faces)
    # M' is M moved along the unit node axes by the thickness.
    assert np.allclose(np.linalg.norm(result.node_axes, axis=1), 1.0)
    assert np.allclose(
        result.offset_vertices,
        result.vertices + result.thickness * result.node_axes,
    )
    assert result.measures["omega_max_deg"] < 0.1
    assert result.report["honeycomb"] is True
    assert result.report["omega_max_deg"] == result.measures["omega_max_deg"]
    assert "honeycomb" in repr(result)

    # The arrays are made once: every access returns the same read-only array.
    assert result.vertices is result.vertices
    with pytest.raises(ValueError):
        result.vertices[0, 0] = 1.0


def test_the_pipeline_takes_the_base_mesh_options_of_the_cli(surface):
    chosen = honeycomb.pipeline(surface, cells=150, flatten="lscm", align="none", seed=1)
    assert chosen.is_honeycomb, chosen.why
    assert abs(len(chosen.faces) / 150 - 1) < 0.25


def test_zigzag_quads_follow_the_principal_directions(surface):
    # The saddle twists least along x and y: the default grid of zigzag quads follows them,
    # and its quads come out far flatter than on the grid along the boundary.
    quads = {"kind": "quads", "pattern": "zigzag"}
    along = honeycomb.pipeline(surface, cells=CELLS, variant=quads)
    boundary = honeycomb.pipeline(surface, cells=CELLS, variant=quads, align="boundary")
    assert along.is_honeycomb and boundary.is_honeycomb
    flat, bent = along.report["delta_face_avg"], boundary.report["delta_face_avg"]
    assert flat < 0.3 * bent, (flat, bent)
    assert along.report["delta_face_max"] <= 0.01


def test_flattest_quads_on_a_boundary_grid_beat_the_zigzag_there(surface):
    # On the grid along the boundary the saddle twists along every long diagonal of a zigzag
    # cover; each cell of a flattest cover picks its own diagonal, and its quads end flatter.
    def capped(pattern):
        variant = {"kind": "quads", "pattern": pattern}
        out = honeycomb.pipeline(surface, cells=CELLS, variant=variant, align="boundary")
        assert out.is_honeycomb, out.why
        return out.report

    flattest, zigzag = capped("flattest"), capped("zigzag")
    assert flattest["quad_pattern"] == "flattest"
    assert flattest["delta_face_avg"] < 0.5 * zigzag["delta_face_avg"]
    assert flattest["closeness_max"] <= 0.1


def test_a_quad_pattern_kept_whole_takes_no_cell_off_it(surface):
    # The report counts the cells taken off the pattern; kept whole, there are none.
    variant = {"kind": "quads", "pattern": "zigzag", "quads_whole_pattern": True}
    out = honeycomb.pipeline(surface, cells=CELLS, variant=variant, align="boundary")
    assert out.is_honeycomb, out.why
    assert out.report["capping"]["cells_off_pattern"] == 0
    assert "whole_pattern" not in out.report["capping"]


def test_lists_paths_and_arrays_give_the_same_result(surface, result, tmp_path):
    vertices, faces = surface
    as_lists = honeycomb.pipeline((vertices.tolist(), faces.tolist()), cells=CELLS)
    as_int32 = honeycomb.pipeline((vertices, faces.astype(np.int32)), cells=CELLS)
    obj = write_obj(tmp_path / "saddle.obj", vertices, faces)
    as_path = honeycomb.pipeline(str(obj), cells=CELLS)
    as_pathlike = honeycomb.pipeline(obj, cells=CELLS)
    for other in (as_lists, as_int32, as_path, as_pathlike):
        assert other.faces == result.faces
        assert np.allclose(other.vertices, result.vertices, atol=1e-9)
        assert other.report["iterations"] == result.report["iterations"]


def test_arrays_round_trip_through_optimize(surface, result):
    # The pipeline's honeycomb as a base mesh: the same cells, edges and vertices back.
    again = honeycomb.optimize((result.vertices, result.faces), surface)
    assert again.faces == result.faces
    assert again.vertices.shape == result.vertices.shape
    assert np.array_equal(np.sort(again.edges, axis=1), np.sort(result.edges, axis=1))
    # Already a honeycomb: the solve barely moves it.
    scale = result.measures["mean_edge_length"]
    assert np.abs(again.vertices - result.vertices).max() < 0.25 * scale
    assert again.is_honeycomb, again.why


def test_optimize_on_its_own_base(result):
    again = honeycomb.optimize((result.vertices, [list(f) for f in result.faces]))
    assert again.is_honeycomb, again.why


@pytest.mark.parametrize(
    "option, value, named",
    [
        ("w_fiar", 1.0, "w_fiar"),
        ("w_fair", "much", "w_fair"),
        ("eps", -1.0, "eps"),
        ("iterations", 0, "iterations"),
        ("walls", "sideways", "walls"),
        ("thickness", -0.1, "thickness"),
        ("method", "magic", "method"),
        ("flatten", "origami", "flatten"),
        ("boundary", "fold", "boundary"),
        ("align", "no/such/strokes.txt", "align"),
        ("variant", {"kind": "quads", "pattern": "zigzag", "quads_reshape": -1.0}, "quads.reshape"),
        ("variant", {"kind": "quads", "pattern": "zigzag", "quads_whole_patern": True}, "quads_whole_patern"),
    ],
)
def test_a_bad_option_raises_value_error_naming_it(surface, option, value, named):
    with pytest.raises(ValueError, match=named):
        honeycomb.pipeline(surface, cells=CELLS, **{option: value})


def test_numpy_scalars_and_arrays_as_options(surface, result):
    again = honeycomb.pipeline(surface, cells=CELLS, w_fair=np.float64(3.0), iterations=np.int64(10))
    assert again.report["iterations"] == result.report["iterations"]
    vertical = honeycomb.pipeline(surface, cells=CELLS, walls=np.array([0.0, 0.0, 1.0]))
    assert np.allclose(np.abs(vertical.node_axes[:, 2]), 1.0, atol=1e-6)


def test_a_bad_mesh_raises_value_error(surface):
    vertices, faces = surface
    with pytest.raises(ValueError):
        honeycomb.pipeline((vertices, faces + len(vertices)), cells=CELLS)
    with pytest.raises(ValueError, match="vertices"):
        honeycomb.pipeline((vertices[:, :2], faces), cells=CELLS)
    with pytest.raises(ValueError):
        honeycomb.pipeline(42, cells=CELLS)
    with pytest.raises(FileNotFoundError):
        honeycomb.pipeline("/nonexistent/surface.obj", cells=CELLS)


def test_progress_reports_steps(surface, result):
    steps = []
    honeycomb.pipeline(surface, cells=CELLS, progress=steps.append)
    assert steps[0] == {"step": "init"}
    iterations = [s for s in steps if s["step"] == "iteration"]
    assert iterations and all(s["iteration"] >= 1 for s in iterations)
    assert {"solve", "solve_number", "max_residual", "energy", "eps"} <= set(iterations[0])


def stop_after(k, how):
    """A progress callback that stops at the k-th iteration by `how`, counting its calls."""
    calls = []

    def callback(step):
        calls.append(step)
        if step["step"] == "iteration" and len(calls) > k:
            return how()
        return None

    return callback, calls


def test_a_callback_returning_false_cancels(surface):
    callback, calls = stop_after(2, lambda: False)
    with pytest.raises(honeycomb.Cancelled):
        honeycomb.pipeline(surface, cells=CELLS, progress=callback)
    # Not called again once stopped.
    assert len(calls) == 3


def test_a_callback_raising_cancels_with_its_error(surface):
    class Stop(Exception):
        pass

    def raise_stop():
        raise Stop("enough")

    callback, calls = stop_after(2, raise_stop)
    with pytest.raises(Stop, match="enough"):
        honeycomb.optimize(surface_base(surface), surface, progress=callback)
    assert len(calls) == 3


def test_ctrl_c_raises_keyboard_interrupt(surface):
    # Python leaves Ctrl-C ignored when it starts ignored (under a shell's background job):
    # the test installs the handler a terminal would have.
    previous = signal.signal(signal.SIGINT, signal.default_int_handler)
    try:
        callback, calls = stop_after(1, lambda: signal.raise_signal(signal.SIGINT))
        with pytest.raises(KeyboardInterrupt):
            honeycomb.pipeline(surface, cells=CELLS, progress=callback)
        assert len(calls) == 2
    finally:
        signal.signal(signal.SIGINT, previous)


def surface_base(surface):
    """A base mesh on `surface` (the pipeline's), for optimize."""
    r = honeycomb.pipeline(surface, cells=CELLS)
    return r.vertices, r.faces


def test_save_and_read(result, tmp_path):
    where = result.save(tmp_path / "out")
    assert pathlib.Path(where) == tmp_path / "out"
    for name in ("structure.json", "report.json", "walls.obj", "base.obj", "offset.obj"):
        assert (tmp_path / "out" / name).is_file(), name
    with open(tmp_path / "out" / "report.json") as f:
        report = json.load(f)
    assert set(report) == set(result.report)
    back = honeycomb.read(tmp_path / "out")
    assert back.is_honeycomb
    assert back.faces == result.faces
    assert np.allclose(back.vertices, result.vertices)
    assert np.allclose(back.node_axes, result.node_axes)
    assert np.array_equal(back.edges, result.edges)
    assert back.report["iterations"] == result.report["iterations"]
    assert back.measures["omega_max_deg"] < 0.1
    with pytest.raises(ValueError):
        back.save(tmp_path / "again")


def cli():
    """The CLI's binary: $HONEYCOMB_BIN, else the workspace's release build."""
    path = os.environ.get("HONEYCOMB_BIN") or REPO / "target" / "release" / "honeycomb"
    return pathlib.Path(path)


@pytest.mark.skipif(not cli().is_file(), reason="no CLI binary (cargo build --release -p honeycomb-cli)")
def test_the_same_as_the_cli(surface, result, tmp_path):
    obj = write_obj(tmp_path / "saddle.obj", *surface)
    out = tmp_path / "cli"
    subprocess.run(
        [str(cli()), "pipeline", str(obj), "--cells", str(CELLS), "-o", str(out), "--quiet"],
        check=True,
    )
    with open(out / "report.json") as f:
        report = json.load(f)
    for key in ("iterations", "iterations_total", "vertices", "faces", "edges", "honeycomb", "walls"):
        assert report[key] == result.report[key], key
    for key in ("omega_max_deg", "delta_max", "closeness_max", "mean_edge_length"):
        assert report[key] == pytest.approx(result.report[key], rel=1e-6, abs=1e-12), key
    from_cli = honeycomb.read(out)
    assert from_cli.faces == result.faces
    assert np.allclose(from_cli.vertices, result.vertices, atol=1e-9)


def test_export_writes_the_workshop_files(result, tmp_path):
    out = tmp_path / "export"
    # Model units: the saddle spans 2 units, its edges about 0.1.
    files = result.export(out, "glb,csv", units="m", material_thickness=0.005)
    assert {"structure.glb", "walls.csv", "nodes.csv", "bom.csv"} <= set(files)
    for name in files:
        assert (out / name).stat().st_size > 0, name
    with open(out / "walls.csv") as f:
        rows = f.read().splitlines()
    assert len(rows) == 1 + result.edges.shape[0]
    with pytest.raises(ValueError, match="units furlong"):
        result.export(tmp_path / "bad", units="furlong")
    assert not (tmp_path / "bad").exists()


def test_edit_session_modes_undo_and_redo(result, surface, tmp_path):
    session = honeycomb.EditSession((result.vertices, result.faces), surface)
    start = session.result
    assert start.is_honeycomb, start.why
    assert start.report is None
    inner = int(np.argmin(np.linalg.norm(start.vertices[:, :2], axis=1)))
    # Mode (ii): along the node axis, the walls unchanged.
    with pytest.warns(UserWarning, match="off S"):
        slid = session.slide_vertex(inner, 0.01)
    moved = slid.vertices[inner] - start.vertices[inner]
    assert np.allclose(moved, 0.01 * start.node_axes[inner], atol=1e-6)
    assert slid.is_honeycomb
    # Mode (i): towards a point, re-optimized.
    target = start.vertices[inner] + [0.02, 0.0, 0.0]
    dragged = session.move_vertex(inner, target, radius=1)
    assert dragged.vertices[inner][0] > start.vertices[inner][0] + 0.005
    assert dragged.is_honeycomb, dragged.why
    # Mode (iii): turn an axis.
    axis = start.node_axes[inner] + [0.2, 0.0, 0.0]
    turned = session.turn_axis(inner, axis, radius=2)
    assert turned.measures["omega_max_deg"] < 1.0
    assert not np.allclose(turned.node_axes[inner], dragged.node_axes[inner])
    assert session.undo() and session.undo()
    assert np.allclose(session.result.vertices[inner], slid.vertices[inner], atol=1e-9)
    assert session.redo()
    assert np.allclose(session.result.vertices[inner], dragged.vertices[inner], atol=1e-9)
    with pytest.raises(ValueError):
        session.move_vertex(inner, [1.0, 2.0])
    with pytest.raises(ValueError):
        session.result.save(tmp_path / "edited")


def test_edit_session_from_a_saved_structure(result, surface, tmp_path):
    # save() writes no surface.obj: given, the session edits on S; without it, on M itself.
    result.save(tmp_path / "out")
    on_m = honeycomb.EditSession.read(tmp_path / "out").result
    assert on_m.is_honeycomb, on_m.why
    session = honeycomb.EditSession.read(tmp_path / "out", surface)
    edited = session.result
    assert edited.is_honeycomb, edited.why
    assert edited.faces == result.faces
    # The session's first solve starts from the saved walls: inner vertices barely move,
    # boundary ones go towards S's boundary (the pipeline trimmed its boundary cells).
    scale = result.measures["mean_edge_length"]
    moved = np.linalg.norm(edited.vertices - result.vertices, axis=1)
    assert np.median(moved) < 0.05 * scale
    assert moved.max() < 0.5 * scale


def test_to_compas_and_back(surface, result):
    compas = pytest.importorskip("compas.datastructures")
    mesh = result.to_compas()
    assert isinstance(mesh, compas.Mesh)
    assert mesh.number_of_vertices() == len(result.vertices)
    assert mesh.number_of_faces() == len(result.faces)
    assert mesh.number_of_edges() == len(result.edges)
    assert np.allclose(mesh.vertex_attribute(7, "node_axis"), result.node_axes[7])
    assert np.allclose(mesh.vertex_attribute(7, "offset"), result.offset_vertices[7])
    a, b = (int(i) for i in result.edges[11])
    assert np.allclose(mesh.edge_attribute((a, b), "wall_normal"), result.wall_normals[11])
    # A compas Mesh is a base mesh (or a surface) as it is.
    again = honeycomb.optimize(mesh, surface)
    assert again.faces == result.faces
    assert again.is_honeycomb, again.why


def test_to_3dm(result, tmp_path):
    rhino3dm = pytest.importorskip("rhino3dm")
    result.to_3dm(tmp_path / "honeycomb.3dm")
    model = rhino3dm.File3dm.Read(str(tmp_path / "honeycomb.3dm"))
    assert [layer.Name for layer in model.Layers] == ["M", "M'", "walls"]
    meshes = {model.Layers[o.Attributes.LayerIndex].Name: o.Geometry for o in model.Objects}
    assert len(meshes["M"].Vertices) == len(result.vertices)
    assert len(meshes["M'"].Vertices) == len(result.vertices)
    assert len(meshes["walls"].Faces) == len(result.edges)


@pytest.mark.parametrize("method, package", [("to_3dm", "rhino3dm"), ("to_compas", "compas.datastructures")])
def test_a_missing_package_is_named(result, tmp_path, monkeypatch, method, package):
    import sys

    monkeypatch.setitem(sys.modules, package, None)
    args = (tmp_path / "x.3dm",) if method == "to_3dm" else ()
    with pytest.raises(ImportError, match=package.split(".")[0]):
        getattr(result, method)(*args)


def bowl(n=61):
    """The steep bowl z = 1.5 r^2 over [0, 1]^2 (r from its centre), triangulated."""
    return height_field(lambda x, y: 1.5 * ((x - 0.5) ** 2 + (y - 0.5) ** 2), n, 0, 1)


def test_uneven_cells_are_evened_by_default():
    surface = bowl()
    fitted = honeycomb.pipeline(surface, cells=750, even_cells=False)
    evened = honeycomb.pipeline(surface, cells=750)
    assert evened.is_honeycomb, evened.why
    assert fitted.measures["edge_length_cv"] > 0.12
    assert evened.measures["edge_length_cv"] <= 0.1
    assert any("the cells were evened" in n for n in evened.report["notes"])


def sun(elevation, azimuth):
    """The direction sunlight travels from a sun this high (degrees) in this azimuth."""
    e, a = np.radians(elevation), np.radians(azimuth)
    return [-np.cos(e) * np.cos(a), -np.cos(e) * np.sin(a), -np.sin(e)]


def test_a_shading_device_lets_through_at_most_half_the_light(surface):
    light = sun(45, 200)
    out = honeycomb.pipeline(
        surface, cells=300, variant={"kind": "shading", "light": light}
    )
    assert out.is_honeycomb, out.why
    assert out.unmet is None
    shading = out.report["shading"]
    assert shading["met"]
    assert shading["light"]["after"] <= 0.5 * shading["light"]["before"]
    assert shading["light"]["before"] > 0.05


def test_a_shading_device_that_falls_short_says_so(surface):
    # Walls a small fraction of an edge deep block almost nothing, turned or not.
    out = honeycomb.pipeline(
        surface,
        cells=300,
        thickness=0.005,
        variant={"kind": "shading", "light": sun(45, 200)},
    )
    assert out.is_honeycomb, out.why
    assert not out.report["shading"]["met"]
    assert "the cells let through" in out.unmet and "light" in out.unmet
