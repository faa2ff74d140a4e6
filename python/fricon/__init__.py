"""fricon: 3D elastic contact with friction, from Python.

The same library as the command line (`fricon solve`), with nothing re-implemented here:

    import fricon
    p = fricon.load("examples/paper-brick.toml")
    p.contact.friction.param = 3e4          # read and validated by the library's reader
    r = fricon.solve(p, progress=print)
    r.report["contact"]["outer_iterations"], r.displacement.shape, r.patches["lambda_n"]

A Problem's attributes are the keys of the problem file (docs/problem-file.md). Assigning one
re-reads the problem through the same reader and validation as a file and as `--set`: a wrong
type or value raises fricon.InputError (a ValueError) naming the key, and leaves the problem as
it was.
"""

import json
import os
import re

from ._fricon import InputError, Mesh, NumericalError, OuterIteration, Result, __version__
from . import _fricon

__all__ = ["load", "solve", "Problem", "Mesh", "Result", "FrictionLaw", "OuterIteration",
           "InputError", "NumericalError", "__version__"]

# How messages name a value set from Python: "fricon.Problem material.young=-1: material.young:
# expected a positive number [Pa], got -1.0".
_ORIGIN = "fricon.Problem"
# The smallest problem file: every key takes its default (a 3 m x 1 m x 1 m steel brick).
_EMPTY_PROBLEM = "[mesh]\n[material]\n"
_BARE_KEY = re.compile(r"^[A-Za-z0-9_-]+$")


def _toml_key(key):
    return key if _BARE_KEY.match(key) else json.dumps(key)


def _toml_value(value):
    """A Python value (numbers, strings, sequences, dicts, numpy arrays) as TOML value text."""
    if hasattr(value, "tolist"):  # numpy arrays and scalars
        value = value.tolist()
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, int):
        return str(value)
    if isinstance(value, float):
        return repr(value) if value == value and abs(value) != float("inf") else \
            ("nan" if value != value else ("inf" if value > 0 else "-inf"))
    if isinstance(value, str):
        return json.dumps(value, ensure_ascii=False)
    if isinstance(value, os.PathLike):
        return json.dumps(os.fspath(value), ensure_ascii=False)
    if isinstance(value, dict):
        return "{" + ", ".join(f"{_toml_key(str(k))} = {_toml_value(v)}"
                               for k, v in value.items()) + "}"
    if isinstance(value, (list, tuple)):
        return "[" + ", ".join(_toml_value(v) for v in value) + "]"
    if isinstance(value, (_Section, _TableList)):  # a table of a problem, e.g. p.contact[0]
        return _toml_value(value.to_dict() if isinstance(value, _Section) else value.to_list())
    raise InputError(f"cannot write a {type(value).__name__} as a problem-file value: {value!r}")


class FrictionLaw:
    """A coefficient of friction F(t) of the slip t = ||u_t|| [m], for p.contact.friction.

    FrictionLaw.paper(param), .constant(value), .table(t, f) and .expression(text) are the laws
    of problem files; FrictionLaw.function(F) is any Python callable.
    """

    def __init__(self, spec, function=None, name="function"):
        self.spec = dict(spec)  # the keys of [contact.friction]
        self.function = function
        self.name = name

    @classmethod
    def paper(cls, param=6.0e4):
        return cls({"law": "paper", "param": param})

    @classmethod
    def constant(cls, value):
        return cls({"law": "constant", "value": value})

    @classmethod
    def table(cls, t, f):
        """Piecewise linear through the points (t [m], f), constant beyond them."""
        return cls({"law": "table", "t": list(t), "f": list(f)})

    @classmethod
    def expression(cls, text, kinks=None, quadrature_rtol=None):
        """A formula in t [m] (muparser syntax), e.g. "0.1 + 0.4*exp(-t/5e-5)"."""
        spec = {"law": "expression", "expression": text}
        if kinks is not None:
            spec["kinks"] = list(kinks)
        if quadrature_rtol is not None:
            spec["quadrature_rtol"] = quadrature_rtol
        return cls(spec)

    @classmethod
    def function(cls, F, kinks=None, quadrature_rtol=None, name=None):
        """F: a callable taking a 1-D numpy array of slips t [m] and returning F(t), same length.

        kinks: slips [m] where F is not smooth (the radii's quadrature splits there);
        quadrature_rtol: relative accuracy of the radii (adaptive Gauss-Kronrod between kinks).
        F must be finite and >= 0 at every slip it is called with (checked there).
        """
        if not callable(F):
            raise InputError(f"contact.friction: FrictionLaw.function needs a callable, got {F!r}")
        spec = {"law": "function"}
        if kinks is not None:
            spec["kinks"] = list(kinks)
        if quadrature_rtol is not None:
            spec["quadrature_rtol"] = quadrature_rtol
        return cls(spec, F, name or getattr(F, "__name__", "function"))

    def __repr__(self):
        return f"fricon.FrictionLaw({self.spec})"


class _Section:
    """A table of the problem (p.material, p.contact.friction, p.dirichlet[0], ...)."""

    def __init__(self, problem, path):
        object.__setattr__(self, "_problem", problem)
        object.__setattr__(self, "_path", path)

    def __getattr__(self, name):
        if name.startswith("__"):
            raise AttributeError(name)
        return self._problem._view(self._path + [name])

    def __setattr__(self, name, value):
        self._problem._assign(self._path + [name], value)

    def __getitem__(self, name):
        return self.__getattr__(name)

    def __setitem__(self, name, value):
        self.__setattr__(name, value)

    def to_dict(self):
        return self._problem._value(self._path)

    def __repr__(self):
        return f"{'.'.join(map(str, self._path))} = {self.to_dict()!r}"


class _Pair(_Section):
    """The one contact pair of [contact]: a table (p.contact.friction) that is also the list of
    the pairs, [p.contact] (p.contact[0], len(p.contact), iteration), as [[contact]] gives."""

    def __getitem__(self, name):
        if isinstance(name, int):
            if name not in (0, -1):
                raise IndexError(f"contact[{name}]: the problem has 1 contact pair")
            return self
        return super().__getitem__(name)

    def __len__(self):
        return 1

    def __iter__(self):
        return iter([self])


class _TableList:
    """An array of tables of the problem (p.dirichlet, p.traction, p.material per region)."""

    def __init__(self, problem, path):
        self._problem = problem
        self._path = path

    def __len__(self):
        return len(self._problem._value(self._path))

    def __getitem__(self, i):
        n = len(self)
        if not -n <= i < n:
            raise IndexError(f"{'.'.join(map(str, self._path))}[{i}]: it has {n} entries")
        return self._problem._view(self._path + [i % n])

    def __setitem__(self, i, value):
        self._problem._assign(self._path + [i % len(self)], value)

    def __iter__(self):
        return (self[i] for i in range(len(self)))

    def append(self, table):
        self._problem._assign(self._path + [len(self)], table)

    def to_list(self):
        return self._problem._value(self._path)

    def __repr__(self):
        return f"{'.'.join(map(str, self._path))} = {self.to_list()!r}"


class Problem:
    """A problem: the keys of a problem file as attributes (docs/problem-file.md).

    Problem() is the default problem (a steel brick, no supports, no contact), to be completed
    by assignments; fricon.load(path) reads a file. Every assignment goes through the library's
    reader and validation; a bad value raises fricon.InputError naming the key and changes
    nothing.
    """

    def __init__(self):
        self._init(_EMPTY_PROBLEM, "fricon.Problem()")

    def _init(self, text, source):
        object.__setattr__(self, "_text", text)
        object.__setattr__(self, "_source", source)
        object.__setattr__(self, "_edits", [])
        object.__setattr__(self, "_mesh", None)
        object.__setattr__(self, "_law", None)
        object.__setattr__(self, "_parsed", self._parse([], None, None))
        object.__setattr__(self, "_dict", None)

    # -- the library's reader -----------------------------------------------------------------
    def _parse(self, edits, mesh, law, origin=_ORIGIN):
        function = law.function if law is not None else None
        name = law.name if law is not None else "function"
        return _fricon._parse(self._text, self._source, edits, origin, mesh, function, name)

    def _edit(self, items, origin=_ORIGIN):
        """Reads the problem with the edits KEY=VALUE of items, (key, value) pairs, all at once
        (so that values that depend on one another, such as loading.steps and a path, may change
        together); commits them only if the problem they give is valid."""
        mesh, law, edits = self._mesh, self._law, list(self._edits)
        for key, value in items:
            if isinstance(value, Mesh):
                if key != "mesh":
                    raise InputError(f"{key}: a fricon.Mesh can only be assigned to p.mesh")
                mesh, value = value, {"kind": "arrays"}
            elif isinstance(value, FrictionLaw):
                if not key.endswith("friction"):
                    raise InputError(f"{key}: a fricon.FrictionLaw belongs in p.contact.friction")
                law, value = value, value.spec
            edits.append(f"{key}={_toml_value(value)}")
        parsed = self._parse(edits, mesh, law, origin)
        object.__setattr__(self, "_edits", edits)
        object.__setattr__(self, "_mesh", mesh)
        object.__setattr__(self, "_law", law)
        object.__setattr__(self, "_parsed", parsed)
        object.__setattr__(self, "_dict", None)

    def _assign(self, path, value):
        if (len(path) > 1 and path[0] == "contact" and not isinstance(path[1], int)
                and self._parsed.contact_key == "contact[0]"):
            # The one pair of a file that writes [[contact]]: p.contact.KEY is contact.0.KEY.
            path = ["contact", 0] + list(path[1:])
        self._edit([(".".join(map(str, path)), value)])

    # -- reading --------------------------------------------------------------------------------
    def to_dict(self):
        """The effective problem (every default filled in), as report.json's "problem"."""
        if self._dict is None:
            object.__setattr__(self, "_dict", self._parsed.to_dict())
        return self._dict

    def _value(self, path):
        v = self.to_dict()
        for i, k in enumerate(path):
            try:
                v = v[k]
            except (KeyError, IndexError, TypeError):
                where = ".".join(map(str, path[:i + 1]))
                raise AttributeError(
                    f"{where}: not in this problem (unknown, or not used by its choices; assign "
                    f"it to add it, e.g. p.contact = {{\"boundary\": \"z0\"}})") from None
        return v

    def _view(self, path):
        v = self._value(path)
        if isinstance(v, dict):
            return _Pair(self, path) if path == ["contact"] else _Section(self, path)
        if isinstance(v, list) and v and all(isinstance(e, dict) for e in v):
            return _TableList(self, path)
        if isinstance(v, list) and path[-1] in ("dirichlet", "traction"):
            return _TableList(self, path)
        return v

    def __getattr__(self, name):
        if name.startswith("_"):
            raise AttributeError(name)
        return self._view([name])

    def __setattr__(self, name, value):
        self._assign([name], value)

    @property
    def source(self):
        return self._source

    def to_toml(self):
        """The effective problem as the text of a problem file (every default written out).

        Raises fricon.InputError for what a file cannot hold: a fricon.Mesh (write it as a Gmsh
        file) or a FrictionLaw.function (write it as an expression or a table).
        """
        return self._parsed.to_toml()

    def save(self, path):
        """Writes to_toml() to path, atomically: `fricon solve path` then solves this problem.

        A relative mesh.file is written as the path the problem opens it by.
        """
        text = self.to_toml()
        path = os.fspath(path)
        partial = f"{path}.partial"
        with open(partial, "w", encoding="utf-8") as out:
            out.write(text)
        os.replace(partial, path)

    def set(self, key, value):
        """p.set("contact.friction.param", 3e4): as the attribute, by the key path of --set."""
        self._assign([key], value)

    def update(self, values):
        """p.update({"loading.steps": 3, "dirichlet.1.path": [0, 1, 2]}): several keys (key
        paths of --set) at once, read and validated together, as several --set are: values that
        must agree (a path's length and loading.steps) change in one step. Nothing changes if
        the result is invalid."""
        self._edit([(str(k), v) for k, v in dict(values).items()])

    def copy(self):
        other = Problem.__new__(Problem)
        for k in ("_text", "_source", "_edits", "_mesh", "_law", "_parsed", "_dict"):
            object.__setattr__(other, k, getattr(self, k))
        object.__setattr__(other, "_edits", list(self._edits))
        return other

    def __repr__(self):
        return f"fricon.Problem({self._source}, {len(self._edits)} edit(s))"


# The meshio cell types fricon takes: tetrahedra and triangles, linear or quadratic (theory.md
# §2.12). meshio lists a 10-node tetrahedron's nodes in VTK's order, whose edge nodes 8 and 9
# (edges 13 and 23) are Gmsh's, and fricon's, 9 and 8 (edges 32 and 31): _FROM_MESHIO_ORDER puts
# them back (the swap is its own inverse). meshio's 6-node triangle is in fricon's order.
_TETRA_TYPES = ("tetra", "tetra10")
_TRIANGLE_TYPES = ("triangle", "triangle6")
_FROM_MESHIO_ORDER = {"tetra10": [0, 1, 2, 3, 4, 5, 6, 7, 9, 8]}
_TRIANGLE_CORNERS = 3


def _fricon_order(block):
    """The node indices of a meshio cell block, in fricon's order of the nodes of a cell."""
    import numpy as np

    data = np.asarray(block.data)
    order = _FROM_MESHIO_ORDER.get(block.type)
    return data[:, order] if order is not None else data


def _mesh_from_meshio(mesh):
    """A fricon.Mesh from a meshio.Mesh: its "tetra" (or quadratic "tetra10") cells, and its cell
    sets as boundary tags (the sets' "triangle" or "triangle6" cells) and regions (the sets'
    tetrahedra), e.g. the physical groups of a Gmsh file read by meshio.read."""
    import numpy as np

    blocks = list(mesh.cells)
    tet_blocks = [i for i, b in enumerate(blocks) if b.type in _TETRA_TYPES]
    if not tet_blocks:
        raise InputError("fricon.Mesh.from_meshio: the mesh has no \"tetra\" nor \"tetra10\" "
                         "cells (fricon needs tetrahedra, linear or quadratic)")
    kinds = sorted({blocks[i].type for i in tet_blocks})
    if len(kinds) > 1:
        raise InputError(f"fricon.Mesh.from_meshio: the mesh has cells of the types {kinds}; "
                         "fricon needs tetrahedra of one order, linear or quadratic")
    offset, start = {}, 0
    for i in tet_blocks:
        offset[i] = start
        start += len(blocks[i].data)
    tets = np.concatenate([_fricon_order(blocks[i]) for i in tet_blocks])
    boundary, regions = {}, {}
    for name, per_block in mesh.cell_sets.items():
        if name.startswith("gmsh:"):
            continue
        triangles, members = [], []
        for i, idx in enumerate(per_block):
            if idx is None or len(idx) == 0:
                continue
            if blocks[i].type in _TRIANGLE_TYPES:
                triangles.append(_fricon_order(blocks[i])[idx])
            elif blocks[i].type in _TETRA_TYPES:
                members.append(offset[i] + np.asarray(idx))
        if len({t.shape[1] for t in triangles}) > 1:  # 3- and 6-node triangles: their corners
            triangles = [t[:, :_TRIANGLE_CORNERS] for t in triangles]
        if triangles:
            boundary[name] = np.concatenate(triangles)
        if members:
            regions[name] = np.concatenate(members)
    return Mesh(np.asarray(mesh.points, dtype=float), tets, boundary, regions or None)


Mesh.from_meshio = staticmethod(_mesh_from_meshio)


def load(path):
    """Reads the problem file at path (as `fricon solve path` does) into a Problem."""
    p = Problem.__new__(Problem)
    p._init(_fricon._read_text(os.fspath(path)), os.fspath(path))
    return p


def solve(problem, set=None, progress=None, threads=None, on_step=None):
    """Solves a Problem or the problem file at a path; returns a Result.

    set:      {"KEY": value} overrides spelled as --set keys ("contact.friction.param": 3e4),
              applied to a copy (the problem itself is not changed), all at once as several
              --set are (so {"loading.steps": 3, "dirichlet.1.path": [0, 1, 2]} works)
    progress: called with each outer iteration (an OuterIteration: k, err, qp_iterations,
              qp_products, qp_rel_gp, seconds); an exception it raises stops the run
    threads:  BLAS threads (default: as `fricon solve`, the cores the machine's load leaves);
              one count per process: solves running at once share the first one's
    on_step:  with [loading] steps > 1, called after each step of the path with the step's
              figures as a dict (the entry of report.json's "steps": step, factors,
              normal_force, tangential_force, patch_states, ...), before the next step starts;
              an exception it raises ends the path after that step (the exception's .result
              holds the steps it saw). Result.steps holds the columns of steps.csv

    The GIL is released while the library runs, so solves from several threads run at once
    (docs/python.md, "Threads"); Ctrl-C stops the run at its next QP step and raises
    KeyboardInterrupt, whose .result is the Result reached (along a path: the steps done, the
    last one interrupted unless the stop came between two steps). A run that did not converge
    returns a Result with
    converged == False and the reason in .message (as `fricon solve` exits with code 2); bad
    input raises fricon.InputError, an ill-posed problem fricon.NumericalError.
    """
    if not isinstance(problem, Problem):
        problem = load(problem)
    if set:
        problem = problem.copy()
        problem._edit([(str(k), v) for k, v in dict(set).items()], origin="--set")
    return _fricon._solve(problem._parsed, progress, threads, on_step)
