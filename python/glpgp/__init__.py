"""glpgp: quad-mesh parametrizations of planar domains with the Ginzburg-Landau
periodic global parametrization (GL-PGP), from Python.

The package wraps the C library (the extension ``glpgp._glpgp``) the way the
``glpgp`` command line does: the same options (one table in the library; see
:func:`options`), the same pipeline and the same results bit for bit::

    import glpgp
    mesh = glpgp.shape("disk", 20000)          # or glpgp.read("part.msh"), glpgp.Mesh(xy, tri)
    r = glpgp.solve(mesh, size=0.1)            # the GIL is released while it runs
    print(r.stats["singularities"])            # the --stats JSON as a dict
    q = r.quads()                              # QuadMesh: vertices, faces, report, valid
    q.write("quads.obj")

Progress goes to the ``logging`` logger ``"glpgp"`` (INFO: levels and Newton
steps; enable with ``logging.basicConfig(level=logging.INFO)``); library
warnings are WARNING records. Failures raise :class:`Error` (bad input:
:class:`InputError`, a ValueError; files: :class:`FileError`, an OSError) with
the library's one-line message. Ctrl-C stops a solve at its next Newton step
(KeyboardInterrupt). An unconverged solve issues a :class:`ConvergenceWarning`
(and ``Result.converged`` is False), an invalid quad mesh a
:class:`QualityWarning` (``QuadMesh.valid`` False).
"""

import atexit as _atexit
import textwrap as _textwrap

from . import _glpgp
from ._glpgp import (ConvergenceWarning, Error, FileError, InputError, InvalidQuadMeshError, Mesh, QualityWarning,
                     QuadMesh, Result, __version__)

__all__ = ["Mesh", "Result", "QuadMesh", "read", "shape", "solve", "read_result", "render", "crosscheck", "devices",
           "options", "build_info", "Error", "InputError", "FileError", "InvalidQuadMeshError", "ConvergenceWarning",
           "QualityWarning", "__version__"]

_atexit.register(_glpgp._shutdown)


def options(kind="solve"):
    """The options of :func:`solve` (``kind="solve"``), :meth:`Result.quads` (``"quads"``) or :func:`render`
    (``"render"``), as the library's table defines them for the CLI too: a list of dicts with ``name`` (the
    keyword), ``cli`` (the option without ``--``), ``kind`` (flag, int, float, choice, text), ``default``,
    ``range``, ``choices`` and ``help``."""
    return _glpgp._options(kind)


def _options_doc(kind):
    lines = []
    for o in options(kind):
        what = o["choices"] or o["range"] or o["kind"]
        head = "%s : %s, default %s  (--%s)" % (o["name"], what, o["default"] or "-", o["cli"])
        lines.append(head)
        lines.append(_textwrap.indent(o["help"].replace("\n", " "), "    "))
    return "\n".join(lines)


def read(path, *, mesh_size=None, remesh=False, max_elements=20000000, max_pixels=100000000):
    """Read a domain as the CLI reads an INPUT: a triangle mesh file (.obj, .msh, .stl), ``"shape:NAME[:N]"``,
    or, meshed by Gmsh, a mask image (.png, .tif, ...) or a polygon file (.poly); ``remesh=True`` meshes a
    .obj/.msh/.stl again inside its boundary points. ``mesh_size``: Gmsh's target size (default h / 8 of the
    default h). ``max_elements`` / ``max_pixels``: the CLI's --max-elements / --max-pixels. Returns a
    :class:`Mesh` whose ``source`` is ``path``. Raises :class:`FileError` (missing, unreadable) or
    :class:`InputError` (malformed, rejected, above a limit)."""
    kw = {"remesh": bool(remesh), "max_elements": max_elements, "max_pixels": max_pixels}
    if mesh_size is not None:
        kw["mesh_size"] = float(mesh_size)
    return _glpgp.read(path, **kw)


def shape(name, n=20000, *, max_elements=20000000):
    """A built-in domain (``"square"``, ``"disk"``, ``"annulus"``, ``"lshape"``) with about ``n`` vertices:
    the mesh of ``glpgp solve shape:NAME:N`` (its ``source``)."""
    return _glpgp.shape(name, n, max_elements=max_elements)


def solve(mesh, size=None, field=None, backend="auto", precond="amg", **options):
    """Parametrize a domain: ``glpgp solve`` from Python, the same pipeline and result bit for bit.

    mesh : Mesh, or a path / ``"shape:NAME[:N]"`` (read with :func:`read`)
    size : the target quad size h (None: the bounding-box diagonal / 20, at least 10 mean edges)
    field : ``"boundary"``, ``"radial"``, ``"cross"``, a file of ``ux uy`` lines, or an (n, 2) array of
        the guiding field per vertex of ``mesh``; None: ``"boundary"``, on a 3D surface ``"cross"``
    backend : ``"auto"`` (OpenCL, else the reference backend with a warning), ``"opencl"``,
        ``"reference"``, ``"petsc"``; ``device=N`` picks an OpenCL device (see :func:`devices`)
    precond : ``"amg"`` or ``"jacobi"``
    refine : False solves the input as it is (--no-refine)
    max_elements, max_pixels : the CLI's limits; size_image_box : (x0, y0, x1, y1) of a size image

    The other keywords are the options of the library's table (the CLI's ``--NAME``, ``-`` as ``_``),
    checked there (an out-of-range value raises :class:`InputError`):

    {options}

    The GIL is released while the solve runs (two solves in two threads run at once); Ctrl-C stops it at
    its next Newton step with KeyboardInterrupt. Returns a :class:`Result`; an unconverged solve issues
    a :class:`ConvergenceWarning`.
    """
    return _glpgp.solve(mesh, size=size, field=field, backend=backend, precond=precond, **options)


def read_result(path):
    """A :class:`Result` read back from a result file (.vtu or .vtk, as ``glpgp solve -o`` and
    :meth:`Result.write` write them), with its mesh; its ``stats`` have no options."""
    return _glpgp.read_result(path)


def render(result, path=None, **options):
    """A picture of a result (the CLI's ``glpgp render``): an (h, w, 4) float32 RGBA array, also written to
    ``path`` when given (.png, .exr, .tif, ... through OpenImageIO, atomically). ``boundary`` and
    ``singular`` (bools) draw the domain boundary and mark the singular triangles. Options:

    {options}
    """
    return _glpgp.render(result, path, **options)


def crosscheck(mesh, size=None, *, energy="p1", device=None, tol_scale=1.0, solve=True, seed=12345, precond=None):
    """Compare the OpenCL backend with the reference backend on ``mesh``, stage by stage (``glpgp
    crosscheck``): a dict with ``pass`` (every stage within its tolerance), ``rows`` (stage, max_abs,
    max_rel, tolerance, pass), ``device``, ``vertices``, ``size``. ``solve=False`` skips the whole GL solve
    stage. Raises :class:`Error` without a usable OpenCL device."""
    kw = {"energy": energy, "tol_scale": tol_scale, "solve": bool(solve), "seed": seed}
    if device is not None:
        kw["device"] = device
    if precond is not None:
        kw["precond"] = precond
    return _glpgp.crosscheck(mesh, size, **kw)


def devices():
    """The OpenCL devices as ``glpgp devices`` lists them: a list of dicts (index, name, vendor, version,
    platform, compute_units, global_mem, fp64, type, default); empty without OpenCL."""
    return _glpgp.devices()


def build_info():
    """What this build has: version, opencl, openimageio, gmsh, petsc, zlib."""
    return _glpgp.build_info()


solve.__doc__ = solve.__doc__.replace("{options}", _textwrap.indent(_options_doc("solve"), "    ").lstrip())
render.__doc__ = render.__doc__.replace("{options}", _textwrap.indent(_options_doc("render"), "    ").lstrip())


_c_quads = Result.quads


def _quads(self, **options):
    """Extract the quad mesh (``glpgp solve --quads``): the integer level lines of theta_u and theta_v, the
    polygons around dislocations closed, smoothed, invalid regions repaired, cleaned up. The GIL is released
    meanwhile. Returns a :class:`QuadMesh`; an invalid one issues a :class:`QualityWarning`. Options:

    {options}
    """
    return _c_quads(self, **options)


_quads.__doc__ = _quads.__doc__.replace("{options}", _textwrap.indent(_options_doc("quads"), "    ").lstrip())
_quads.__name__ = _quads.__qualname__ = "quads"
Result.quads = _quads


# ---- meshio ------------------------------------------------------------------------------

def _from_meshio(m, name=None):
    """Mesh.from_meshio(m, name=None): the triangles of a ``meshio.Mesh`` (its "triangle" cell blocks; quads
    are split in two along a diagonal) as a :class:`Mesh`; points (n, 2) or (n, 3)."""
    import numpy as np
    tris = []
    for block in m.cells:
        data = np.asarray(block.data)
        if block.type == "triangle":
            tris.append(data)
        elif block.type == "quad":
            tris.append(data[:, [0, 1, 2]])
            tris.append(data[:, [0, 2, 3]])
    if not tris:
        raise InputError("meshio mesh: no triangle or quad cells")
    return Mesh(np.asarray(m.points, dtype=float), np.concatenate(tris), name=name)


def _mesh_to_meshio(self):
    """The triangles as a ``meshio.Mesh`` (points (n, 3) with z = 0)."""
    import meshio
    import numpy as np
    v = self.vertices
    pts = v if v.shape[1] == 3 else np.column_stack([v, np.zeros(len(v))])
    return meshio.Mesh(pts, [("triangle", np.array(self.triangles))])


def _result_to_meshio(self):
    """The result as a ``meshio.Mesh`` with the arrays of the .vtu file: point data z_u, z_v (Re, Im),
    theta_u, theta_v, zabs_u, zabs_v, dirichlet_u, dirichlet_v, field_u, field_v; cell data singular_u,
    singular_v (windings); write it with ``meshio.write``."""
    import meshio
    import numpy as np
    m = self.mesh
    v = m.vertices
    pts = v if v.shape[1] == 3 else np.column_stack([v, np.zeros(len(v))])
    pd = {}
    for k in ("u", "v"):
        z = getattr(self, "z_" + k)
        pd["z_" + k] = np.column_stack([z.real, z.imag])
        pd["theta_" + k] = np.array(getattr(self, "theta_" + k))
        pd["zabs_" + k] = np.abs(z)
        pd["dirichlet_" + k] = getattr(self, "dirichlet_" + k).astype(np.int8)
    f = self.field
    pd["field_u"] = np.column_stack([f, np.zeros(len(f))])
    pd["field_v"] = np.column_stack([-f[:, 1], f[:, 0], np.zeros(len(f))])
    cd = {"singular_" + k: [np.array(getattr(self, "winding_" + k))] for k in ("u", "v")}
    return meshio.Mesh(pts, [("triangle", np.array(m.triangles))], point_data=pd, cell_data=cd)


def _quadmesh_to_meshio(self):
    """The quad mesh as a ``meshio.Mesh``: a "quad" cell block (faces of other sizes: "triangle" and
    "polygon" blocks, one per corner count), cell data scaled_jacobian is not included (see report)."""
    import meshio
    import numpy as np
    v = self.vertices
    pts = v if v.shape[1] == 3 else np.column_stack([v, np.zeros(len(v))])
    off = np.asarray(self.face_offsets)
    fv = np.asarray(self.face_vertices)
    sizes = np.diff(off)
    cells = []
    for n in sorted(set(sizes.tolist())):
        idx = np.nonzero(sizes == n)[0]
        data = np.stack([fv[off[i]:off[i] + n] for i in idx]) if len(idx) else np.zeros((0, n), int)
        kind = {3: "triangle", 4: "quad"}.get(n, "polygon")
        cells.append((kind, data))
    return meshio.Mesh(pts, cells)


Mesh.from_meshio = staticmethod(_from_meshio)
Mesh.to_meshio = _mesh_to_meshio
Result.to_meshio = _result_to_meshio
QuadMesh.to_meshio = _quadmesh_to_meshio
