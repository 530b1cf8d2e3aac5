"""Freeform honeycomb structures: hexagonal meshes on a design surface whose walls are planar
and meet at 120 degrees at every node (Jiang, Tang, Wallner, Pottmann et al.)."""

import os
from typing import Any, Callable, Dict, List, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

__version__: str

#: A mesh: a path (OBJ, OFF, PLY), a ``(vertices, faces)`` pair (an (n, 3) array of points
#: and an (m, k) integer array or lists of vertex indices), or a compas ``Mesh``.
MeshLike = Union[
    str,
    "os.PathLike[str]",
    Tuple[npt.ArrayLike, Union[npt.ArrayLike, Sequence[Sequence[int]]]],
    Any,
]

#: What the progress callback gets: ``{"step": "init"}`` while the hexagonal mesh is made,
#: then ``{"step": "iteration", "solve", "solve_number", "iteration", "max_residual",
#: "energy", "eps"}`` at every iteration of every solve. Returning ``False`` stops the work
#: (:class:`Cancelled`); raising stops it with that exception.
ProgressCallback = Callable[[Dict[str, Any]], Optional[bool]]

class Cancelled(Exception):
    """The progress callback returned False: the work stopped before its next iteration."""

class Result:
    """A honeycomb: the mesh M on the surface, its offset M' along the node axes, its walls.

    Its arrays are made once and are read-only: every access returns the same array (copy
    one to change it)."""

    @property
    def vertices(self) -> npt.NDArray[np.float64]:
        """The vertices of M: (n, 3)."""
    @property
    def offset_vertices(self) -> npt.NDArray[np.float64]:
        """The vertices of M' (M moved by the thickness along the node axes): (n, 3)."""
    @property
    def faces(self) -> List[List[int]]:
        """The cells as vertex indices in order (boundary cells may have fewer than six)."""
    @property
    def edges(self) -> npt.NDArray[np.int64]:
        """The edges, one wall each: (m, 2) vertex indices."""
    @property
    def wall_normals(self) -> npt.NDArray[np.float64]:
        """The unit normal of each edge's wall, as seen from its first vertex: (m, 3)."""
    @property
    def node_axes(self) -> npt.NDArray[np.float64]:
        """The unit axis at each vertex, along which its walls meet: (n, 3)."""
    @property
    def thickness(self) -> float:
        """The distance between M and M' along the node axes (model units)."""
    @property
    def measures(self) -> Dict[str, Any]:
        """omega (degrees from 120 at the nodes), delta (wall planarity), closeness to the
        surface, axis to normal, edge lengths, valences."""
    @property
    def report(self) -> Optional[Dict[str, Any]]:
        """The report, with the keys of report.json (None for an edit session's)."""
    @property
    def is_honeycomb(self) -> bool:
        """Every node within the 120-degree tolerance and every wall planar."""
    @property
    def why(self) -> Optional[str]:
        """Why this is not a honeycomb, in a sentence; None for a honeycomb."""
    @property
    def unmet(self) -> Optional[str]:
        """What a honeycomb falls short of that was asked (a shading device's share of the
        light), in a sentence; None when all is met, and for a structure read back (its
        report's ``shading.met`` says) or an edit session's."""
    def export(
        self,
        dir: Union[str, "os.PathLike[str]"],
        format: str = "all",
        *,
        units: str = "m",
        up: str = "z",
        material_thickness: Optional[float] = None,
        sheet: Optional[str] = None,
        label_height: Optional[float] = None,
    ) -> List[str]:
        """Files for fabrication and exchange into ``dir`` (replaced whole), as ``honeycomb
        export`` writes them: glb, obj, dxf, svg, csv or all (several joined by commas).
        Returns the names of the files written; a bad option raises ValueError naming it."""
    def save(self, dir: Union[str, "os.PathLike[str]"]) -> str:
        """Writes structure.json, base.obj, offset.obj, walls.obj, report.json, ... into
        ``dir`` for a honeycomb, else into ``dir.failed``; returns where they went. Only for
        a result of :func:`pipeline` or :func:`optimize` (ValueError otherwise)."""

    def to_compas(self) -> Any:
        """M as a compas ``Mesh`` with the vertex attributes ``node_axis`` and ``offset`` (the
        vertex of M') and the edge attribute ``wall_normal`` (as seen from the edge's first
        vertex in ``edges``). ImportError naming compas when it is not installed."""

    def to_3dm(self, path: Union[str, "os.PathLike[str]"]) -> None:
        """Writes a Rhino 3dm file with the layers "M", "M'" (meshes; cells of more than
        four sides as triangle fans) and "walls" (one quad per wall). ImportError naming
        rhino3dm when it is not installed."""

class EditSession:
    """Live editing of a honeycomb (the paper's three modes), with undo and redo. Each edit
    runs its solve to the end without the GIL and returns the honeycomb as it stands (its
    ``report`` is None; ``is_honeycomb`` by the report's tolerances)."""

    def __init__(
        self,
        base: MeshLike,
        surface: Optional[MeshLike] = None,
        *,
        thickness: Optional[float] = None,
    ) -> None:
        """Optimizes ``base`` on ``surface`` (default: itself) into a honeycomb to edit, M' at
        ``thickness`` (model units; default 0.3 mean edge lengths)."""
    @staticmethod
    def read(
        dir: Union[str, "os.PathLike[str]"], surface: Optional[MeshLike] = None
    ) -> "EditSession":
        """A saved structure to go on editing from its walls; ``surface`` as for :func:`read`
        (give it: without it the session edits on M itself)."""
    def move_vertex(self, vertex: int, target: npt.ArrayLike, radius: int = 0) -> Result:
        """Mode (i): ``vertex`` to the surface's point closest to ``target``, the vertices up
        to ``radius`` rings away moving along; re-optimized."""
    def slide_vertex(self, vertex: int, distance: float) -> Result:
        """Mode (ii): ``vertex`` moves ``distance`` along its node axis; nothing is
        optimized. Warns (UserWarning) when that leaves it off the surface."""
    def turn_axis(self, vertex: int, direction: npt.ArrayLike, radius: int = 0) -> Result:
        """Mode (iii): the node axis of ``vertex`` turns to ``direction``, the axes up to
        ``radius`` rings away following; re-optimized with the axes as targets."""
    def undo(self) -> bool:
        """Back to the state before the last edit; False when there is none."""
    def redo(self) -> bool:
        """The edit undone last, again; False when there is none."""
    @property
    def result(self) -> Result:
        """The honeycomb as it stands, measured."""

def pipeline(
    surface: MeshLike,
    cells: int = 1500,
    walls: Union[str, Sequence[float], npt.ArrayLike] = "across",
    *,
    edge_length: Optional[float] = None,
    method: str = "flatten",
    flatten: Optional[str] = None,
    boundary: str = "trim",
    align: Optional[str] = None,
    seed: int = 0,
    even_cells: Optional[bool] = None,
    progress: Optional[ProgressCallback] = None,
    **options: Any,
) -> Result:
    """Makes a honeycomb on a design surface from nothing else.

    ``walls``: "across" (node axes as close to the surface's normals as a honeycomb allows),
    "uniform" (along its mean normal), "free", or one direction (x, y, z) for every axis.
    ``cells``: about this many cells, or ``edge_length`` in model units. ``method``:
    "flatten" or "field". ``align``: "boundary", "curvature" (an edge direction along the
    surface's principal directions where they agree), "none" or a polyline file (default:
    "boundary", "curvature" with zigzag or flattest quads). ``even_cells``: where walls across
    the surface leave cells of uneven size (edge cv 0.12 or more), they are evened afterwards
    unless this is False (``honeycomb pipeline --no-even-cells``); True asks for it and is
    refused with other walls or a shading device. ``options``: the options of ``honeycomb optimize`` by their field
    names (``w_fair=0`` for ``--w-fair 0``): iterations, eps, tolerance, thickness, min_edge,
    w_angle, w_cons, w_norm, w_close, w_boundary, w_fair, w_guide, wall_normals, variant.
    A bad one raises ValueError naming it. Releases the GIL; Ctrl-C raises
    KeyboardInterrupt before the next iteration.
    """

def optimize(
    base: MeshLike,
    surface: Optional[MeshLike] = None,
    *,
    progress: Optional[ProgressCallback] = None,
    **options: Any,
) -> Result:
    """Optimizes a hexagonal (trivalent) base mesh into a honeycomb on ``surface`` (default:
    the base mesh itself). ``options`` as for :func:`pipeline`, and ``variant``, e.g.
    ``variant={"kind": "parallel", "depth": 0.2}`` or ``{"kind": "quads", "pattern":
    "zigzag"}`` (with ``"quads_reshape": 0.3``, the cells may re-shape up to that edge-length
    cv for flatter quads; with ``"quads_whole_pattern": True``, no cell leaves the pattern for
    flatter quads)."""

def read(dir: Union[str, "os.PathLike[str]"], surface: Optional[MeshLike] = None) -> Result:
    """Reads a structure directory (``save``'s, or the CLI's ``optimize`` or ``pipeline``) and
    measures it on ``surface``: the one given, else the directory's surface.obj, else its own
    mesh. The verdict is report.json's; ``save`` is not available on it."""
