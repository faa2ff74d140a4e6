"""Render the paper's figures from a fricon results folder.

Usage:
    /usr/bin/python3 scripts/plot_results.py RESULTS_DIR [--out DIR] [--format png]

Reads what `fricon solve` writes (report.json, contact.vtu, solution.vtu) and writes one figure
per file into RESULTS_DIR/plots (or --out):

    convergence            log10 err(k) of the successive approximations        (paper Fig. 6)
    friction_law           the coefficient of friction F(t) of the run           (paper Fig. 3)
    contact_maps           -w_n, ||w_t|| (nodal), lambda_n, ||lambda_t|| (patch) (paper Figs. 8-9)
    friction_coefficient   F(||w_t||) on the contact surface                     (paper Fig. 10)
    friction_circles       lambda_t against the slip bound of each patch         (paper Fig. 11)
    deformed               the deformed body, displacement magnified             (paper Fig. 7)

and, for a run along a loading path ([loading] steps > 1: the folder has steps.csv),

    force_displacement     tangential and normal force against the displacement of the first
                           load with a path, and their ratio
    stick_slip_steps       the state of each patch (stick, slip, separated), one map per step
                           (at most MAX_STEP_MAPS steps, evenly chosen)

The maps of the contact surface are drawn in the obstacle plane's coordinates (t1, t2) =
(x . t1, x . t2), with the basis of report.json's contact_basis (x, y for an older folder without
it), on the surface's own triangles from contact.vtu. They zoom to the contact zone (the patches
with pressure or not separated) with a margin, and then show the whole surface and the zoomed
window in a small inset in a corner; a zone that covers most of the surface is not zoomed
(map_limits).

A run without contact has no contact results: then only the deformed body is drawn. A run that
did not converge (its files named report.not-converged.json, contact.not-converged.vtu, ...) is
drawn from its last iterate, each figure named with ".not-converged" before its extension
(convergence.not-converged.png, ...) and its title saying the status. The figures of an earlier
run in the output folder (the names above, converged or not, in any format) are removed first,
so that none of them is taken for this run's. Every file is
written atomically (temporary name in the same folder, then os.replace) and the list of files
written is printed on stdout, one per line; notes go to stderr. Exit status 0 on success, 1 when
the folder is not a complete results folder or the arguments are wrong.

Needs only matplotlib (Agg backend, no display), numpy and meshio: Debian's python3-matplotlib,
python3-numpy and python3-meshio under /usr/bin/python3.
"""
import argparse
import csv
import json
import os
import pathlib
import sys
import tempfile
import textwrap

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402  (the backend must be chosen first)
import matplotlib.tri as mtri  # noqa: E402
import meshio  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.collections import LineCollection, PatchCollection, PolyCollection  # noqa: E402
from matplotlib.patches import Circle, Rectangle  # noqa: E402
from mpl_toolkits.mplot3d.art3d import Line3DCollection, Poly3DCollection  # noqa: E402

DPI = 150
# The paper's law (docs/theory.md §7.1): F = 0.3 up to t = 1e-5 m, then linear down to 0.2 at 1e-5 + 2/param.
PAPER_PARAMS = (2.0e4, 6.0e4, 3.0e5)
PAPER_T0 = 1.0e-5
STUCK_RTOL = 1.0e-3  # a patch slips when ||lambda_t|| >= (1 - STUCK_RTOL) * radius

# Zoom of the contact-surface maps (map_limits): the window is the contact zone's bounding box
# padded on every side by ZOOM_MARGIN times the zone's larger side, at least one patch size; it
# is used only when its area is below ZOOM_MAX_AREA_FRACTION of the whole surface's bounding box.
ZOOM_MARGIN = 0.15
ZOOM_MAX_AREA_FRACTION = 0.5
INSET_SIZE = 0.25  # the longer side of the overview inset, as a fraction of the panel's
INSET_GAP = 0.02  # between the inset and the panel's border, as a fraction of the panel
# Figure sizes of the maps (map_figsize), inches: the map's width, at most MAP_MAX_HEIGHT high;
# the window's height / width is kept within MAP_ASPECT_RANGE so that a thin strip stays legible.
MAP_MAX_HEIGHT = 3.6
MAP_ASPECT_RANGE = (0.2, 1.5)
TITLE_LINE_HEIGHT = 0.22  # a line of a figure's title (10-11 pt)
# The patch states of contact.vtu ("state") and patches.csv, and their colours on the maps.
STATE_CODES = {"separated": 0, "stick": 1, "slip": 2}
STATE_COLORS = {"stick": "C0", "slip": "C3", "separated": "0.82"}
MAX_STEP_MAPS = 12  # stick_slip_steps draws at most this many steps
STEPS_LEGEND_HEIGHT = 0.45  # inches below the maps of stick_slip_steps for the legend
CIRCLES_PAD = 0.02  # friction_circles, unzoomed: the surface padded by this part of its size
# The cells of a quadratic mesh (docs/theory.md §2.12): meshio's "tetra10" and "triangle6" (VTK's
# 10- and 6-node cells), whose first nodes are the corners. A 6-node triangle (corners 0-2, then
# the nodes of its edges 01, 12, 20) is drawn as four linear ones through its edge nodes, each
# oriented as the triangle is (QUADRATIC_TRIANGLE_SPLIT), so that the maps use every node's
# value; the deformed body is drawn by the tetrahedra's corners.
TETRA_TYPES = ("tetra", "tetra10")
TET_CORNERS = 4
QUADRATIC_TRIANGLE_SPLIT = np.array([[0, 3, 5], [3, 1, 4], [5, 4, 2], [3, 4, 5]])


# ----------------------------------------------------------------------------------------------
# Reading the results folder
# ----------------------------------------------------------------------------------------------

# Before the extension of every file of a run that did not converge.
NOT_CONVERGED = ".not-converged"

# The figures this script writes (each also with "-pairI" and NOT_CONVERGED in its name).
FIGURE_NAMES = ["convergence", "friction_law", "contact_maps", "friction_coefficient",
                "friction_circles", "deformed", "force_displacement", "stick_slip_steps"]
FIGURE_FORMATS = ["png", "pdf", "svg"]


def result_file(results, name):
    """The path of result file `name` ("contact.vtu") in the folder: its converged name, or the
    name of a run that did not converge (contact.not-converged.vtu) when only that exists."""
    path = results / name
    if path.exists():
        return path
    stem, dot, extension = name.rpartition(".")
    marked = results / f"{stem}{NOT_CONVERGED}{dot}{extension}"
    return marked if marked.exists() else path


def read_report(results):
    """The parsed report.json (or report.not-converged.json of a run that did not converge); a
    folder with neither is incomplete (the report is written last)."""
    path = result_file(results, "report.json")
    if not path.is_file():
        raise SystemExit(f"plot_results: {path}: no report.json nor report{NOT_CONVERGED}.json "
                         "(not a complete fricon results folder; the report is written last)")
    try:
        return json.loads(path.read_text())
    except json.JSONDecodeError as e:
        raise SystemExit(f"plot_results: {path}: not valid JSON: {e}")


def cell_field(mesh, name):
    """Cell data `name` of the first cell block, as a 1D array (scalars) or 2D (vectors)."""
    a = np.asarray(mesh.cell_data[name][0])
    return a[:, 0] if a.ndim == 2 and a.shape[1] == 1 else a


def linear_triangles(block):
    """The cells of a contact.vtu cell block as linear triangles (k, 3), and the cell each one
    belongs to: "triangle" cells as they are, "triangle6" cells split in four
    (QUADRATIC_TRIANGLE_SPLIT)."""
    data = np.asarray(block.data)
    if block.type == "triangle6":
        pieces = len(QUADRATIC_TRIANGLE_SPLIT)
        return (data[:, QUADRATIC_TRIANGLE_SPLIT].reshape(-1, 3),
                np.repeat(np.arange(len(data)), pieces))
    return data, np.arange(len(data))


def point_field(mesh, name):
    """Point data `name`, as a 1D array (scalars) or 2D (vectors)."""
    a = np.asarray(mesh.point_data[name])
    return a[:, 0] if a.ndim == 2 and a.shape[1] == 1 else a


def plane_basis(report, pair=None):
    """The tangents (t1, t2) of the obstacle plane and their axis names, from the report's
    contact_basis (of pair `pair`'s surface: its basis in report.json's pairs); (e1, e2) named
    x, y for a folder written before the report had it."""
    basis = report["pairs"][pair]["basis"] if pair is not None else report.get("contact_basis")
    if basis is None:
        return np.eye(3)[:2], ["x", "y"]
    return np.array([basis["t1"], basis["t2"]], dtype=float), ["t1", "t2"]


def first_pair(report):
    """The problem's [contact] table, or the first of [[contact]] (all pairs share one law)."""
    contact = report["problem"]["contact"]
    return contact[0] if isinstance(contact, list) else contact


def load_contact(results, report, pair=None):
    """The contact surface of contact.vtu in the plane's coordinates, or None without contact
    results.

    The nodes are placed at (x . t1, x . t2) and connected by the surface's own triangles (those
    of contact.vtu, not a Delaunay triangulation of the points: the surface may be curved or in
    several pieces). With `pair`, only that contact pair's triangles (contact.vtu's "pair"),
    seen along its own normal. Returns a dict with the 2D triangulation `tri`, the names of its
    two axes, the nodal fields and the per-triangle (patch) fields, and the patch table (centroid, radius,
    lambda_t in the plane) computed from the triangles.
    """
    path = result_file(results, "contact.vtu")
    if not path.is_file():
        return None
    mesh = meshio.read(path)
    # Quadratic triangles as four linear ones each, every piece with its cell's values.
    triangles, cell = linear_triangles(mesh.cells[0])
    # With `pair`: that pair's triangles only, each per-triangle field cut alike.
    mine = (cell_field(mesh, "pair").astype(int)[cell] == pair if pair is not None
            else np.ones(len(triangles), dtype=bool))
    triangles = triangles[mine]

    def cells(name):
        return cell_field(mesh, name)[cell][mine]

    tangents, axes = plane_basis(report, pair)
    uv = np.asarray(mesh.points) @ tangents.T
    tri = mtri.Triangulation(uv[:, 0], uv[:, 1], triangles)
    # A curved surface seen along n: draw only the triangles that face the plane, so that its far
    # side (a wheel's top, say) does not hide the part in contact.
    basis = report["pairs"][pair]["basis"] if pair is not None else report.get("contact_basis", {})
    n = np.asarray(basis.get("n", [0.0, 0.0, -1.0]))
    p = np.asarray(mesh.points)[triangles]
    facing = np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0]) @ n > 0
    if facing.any() and not facing.all():
        tri.set_mask(~facing)
    patch = cells("patch").astype(int)
    w_n = point_field(mesh, "w_n")
    gap = point_field(mesh, "gap") if "gap" in mesh.point_data else np.zeros_like(w_n)
    surface = {
        "tri": tri,
        "axes": axes,
        "w_n": w_n,
        "opening": gap - w_n,
        "norm_w_t": point_field(mesh, "norm_w_t"),
        # F's argument (the accumulated slip along a loading path); ||w_t|| in an older folder
        "slip": point_field(mesh, "slip" if "slip" in mesh.point_data else "norm_w_t"),
        "F": point_field(mesh, "F"),
        "lambda_n": cells("lambda_n"),
        "norm_lambda_t": cells("norm_lambda_t"),
        "patch": patch,
    }
    state = cells("state") if "state" in mesh.cell_data else None
    surface["state"] = state  # per triangle (its patch's), None in an older folder
    surface["patches"] = patch_table(tri, patch, cells("radius"),
                                     cells("lambda_t") @ tangents.T, state)
    surface["patch_edges"] = patch_boundary_segments(tri, patch)
    # Against a rigid obstacle: its signed distance at the undeformed nodes, where it is moved
    # (the zero line is its outline on the surface, draw_obstacle_outline).
    surface["obstacle_distance"] = (point_field(mesh, "obstacle_distance")
                                    if "obstacle_distance" in mesh.point_data else None)
    return surface


def patch_table(tri, patch, radius, lambda_t_plane, state=None):
    """Per patch (id >= 0): area-weighted centroid, area, slip bound, lambda_t in the plane and,
    when contact.vtu has it, the state fricon gives it (0 separated, 1 stick, 2 slip)."""
    xy = np.column_stack([tri.x, tri.y])
    corners = xy[tri.triangles]
    e1, e2 = corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0]
    area = 0.5 * np.abs(e1[:, 0] * e2[:, 1] - e1[:, 1] * e2[:, 0])
    centre = corners.mean(axis=1)
    ids = np.unique(patch[patch >= 0])
    table = {"centre": [], "area": [], "radius": [], "lambda_t": [], "state": []}
    for p in ids:
        sel = patch == p
        table["centre"].append((area[sel, None] * centre[sel]).sum(axis=0) / area[sel].sum())
        table["area"].append(area[sel].sum())
        table["radius"].append(radius[sel][0])
        table["lambda_t"].append(lambda_t_plane[sel][0])
        table["state"].append(int(state[sel][0]) if state is not None else -1)
    return {k: np.array(v) for k, v in table.items()}


def patch_boundary_segments(tri, patch):
    """Segments (n, 2, 2) between triangles of different patches and on the surface's border."""
    owners = {}
    for t, (a, b, c) in enumerate(tri.triangles):
        for e in ((a, b), (b, c), (c, a)):
            owners.setdefault(tuple(sorted(e)), []).append(t)
    edges = [e for e, ts in owners.items() if len(ts) == 1 or patch[ts[0]] != patch[ts[1]]]
    xy = np.column_stack([tri.x, tri.y])
    return xy[np.array(edges, dtype=int).reshape(-1, 2)]


# ----------------------------------------------------------------------------------------------
# Zooming the maps to the contact zone
# ----------------------------------------------------------------------------------------------

def visible_triangles(tri):
    """A mask of the triangles drawn (those facing the plane: load_contact masks the others)."""
    return ~tri.mask if tri.mask is not None else np.ones(len(tri.triangles), dtype=bool)


def triangle_areas(tri):
    """The area of each triangle of the (2D) triangulation."""
    xy = np.column_stack([tri.x, tri.y])[tri.triangles]
    e1, e2 = xy[:, 1] - xy[:, 0], xy[:, 2] - xy[:, 0]
    return 0.5 * np.abs(e1[:, 0] * e2[:, 1] - e1[:, 1] * e2[:, 0])


def contact_triangles(surface, state=None, lambda_n=None):
    """A mask of the triangles in contact: their patch has a pressure or is not separated.

    `state` and `lambda_n` are per triangle (default: the surface's own, from contact.vtu); a
    folder without the state uses the pressure alone."""
    state = surface["state"] if state is None else state
    lambda_n = surface["lambda_n"] if lambda_n is None else lambda_n
    touching = np.asarray(lambda_n) > 0
    if state is not None:
        touching |= np.asarray(state) != STATE_CODES["separated"]
    return touching & (surface["patch"] >= 0) & visible_triangles(surface["tri"])


def bounding_box(x, y):
    """((xmin, xmax), (ymin, ymax)) of the points."""
    return (float(np.min(x)), float(np.max(x))), (float(np.min(y)), float(np.max(y)))


def box_area(box):
    """The area of ((xmin, xmax), (ymin, ymax))."""
    return (box[0][1] - box[0][0]) * (box[1][1] - box[1][0])


def map_limits(surface, in_contact=None):
    """The axis limits of a map of the contact surface: a dict with "xlim", "ylim" (the window
    drawn), "full" (the whole surface's bounding box, as (xlim, ylim)), "zoomed" and "in_contact"
    (the mask of the triangles in contact the window was made for).

    The window is the bounding box of the triangles in contact (`in_contact`, default
    contact_triangles(surface)) padded on every side by ZOOM_MARGIN times the zone's larger side,
    at least the mean size (sqrt of the area) of its patches, and cut to the surface's box. Without
    contact, or when the window covers ZOOM_MAX_AREA_FRACTION of the surface's box or more, the
    window is the whole surface ("zoomed" False)."""
    tri = surface["tri"]
    visible = visible_triangles(tri)
    nodes = np.unique(tri.triangles[visible]) if visible.any() else np.arange(len(tri.x))
    full = bounding_box(tri.x[nodes], tri.y[nodes])
    in_contact = contact_triangles(surface) if in_contact is None else in_contact
    limits = {"xlim": full[0], "ylim": full[1], "full": full, "zoomed": False,
              "in_contact": in_contact}
    if not in_contact.any() or box_area(full) <= 0:
        return limits
    corners = tri.triangles[in_contact]
    zone = bounding_box(tri.x[corners], tri.y[corners])
    patch_size = np.sqrt(triangle_areas(tri)[in_contact].sum()
                         / len(np.unique(surface["patch"][in_contact])))
    margin = max(ZOOM_MARGIN * max(zone[0][1] - zone[0][0], zone[1][1] - zone[1][0]), patch_size)
    window = tuple((max(lo - margin, f_lo), min(hi + margin, f_hi))
                   for (lo, hi), (f_lo, f_hi) in zip(zone, full))
    if box_area(window) < ZOOM_MAX_AREA_FRACTION * box_area(full):
        limits.update(xlim=window[0], ylim=window[1], zoomed=True)
    return limits


def surface_outline(tri):
    """The border segments (n, 2, 2) of the drawn part of the surface (edges of one triangle)."""
    owners = {}
    for a, b, c in tri.triangles[visible_triangles(tri)]:
        for e in ((a, b), (b, c), (c, a)):
            key = (min(e), max(e))
            owners[key] = owners.get(key, 0) + 1
    edges = np.array([e for e, n in owners.items() if n == 1], dtype=int).reshape(-1, 2)
    return np.column_stack([tri.x, tri.y])[edges]


def inset_bounds(limits, corner):
    """The inset's [x0, y0, width, height] in the panel's axes fraction at `corner` ("upper right",
    ...): its longer side INSET_SIZE, its shape that of the whole surface (the panel has the
    window's shape, equal aspect)."""
    (fx, fy), (wx, wy) = limits["full"], (limits["xlim"], limits["ylim"])
    # The surface's height / width on the page, in the panel's fractions of width and height.
    shape = ((fy[1] - fy[0]) / (fx[1] - fx[0])) * ((wx[1] - wx[0]) / (wy[1] - wy[0]))
    w, h = (INSET_SIZE, INSET_SIZE * shape) if shape <= 1 else (INSET_SIZE / shape, INSET_SIZE)
    x0 = 1.0 - INSET_GAP - w if "right" in corner else INSET_GAP
    y0 = 1.0 - INSET_GAP - h if "upper" in corner else INSET_GAP
    return [x0, y0, w, h]


def inset_corner(surface, limits):
    """The corner of the panel where the inset hides the fewest triangles in contact (upper right
    first when several are equal)."""
    tri = surface["tri"]
    centres = np.column_stack([tri.x, tri.y])[tri.triangles[limits["in_contact"]]].mean(axis=1)
    (x0, x1), (y0, y1) = limits["xlim"], limits["ylim"]
    u, v = (centres[:, 0] - x0) / (x1 - x0), (centres[:, 1] - y0) / (y1 - y0)

    def hidden(corner):
        bx, by, bw, bh = inset_bounds(limits, corner)
        return np.count_nonzero((u >= bx) & (u <= bx + bw) & (v >= by) & (v <= by + bh))

    return min(("upper right", "upper left", "lower right", "lower left"), key=hidden)


def draw_overview_inset(ax, surface, limits):
    """In a corner of a zoomed map: the whole surface (outline, contact zone filled) and the
    window drawn (rectangle)."""
    tri = surface["tri"]
    inset = ax.inset_axes(inset_bounds(limits, inset_corner(surface, limits)))
    inset.set_facecolor("white")
    inset.add_collection(LineCollection(surface_outline(tri), colors="0.2", linewidths=0.6))
    zone = np.column_stack([tri.x, tri.y])[tri.triangles[limits["in_contact"]]]
    inset.add_collection(PolyCollection(zone, facecolors="C1", edgecolors="none"))
    (x0, x1), (y0, y1) = limits["xlim"], limits["ylim"]
    inset.add_patch(Rectangle((x0, y0), x1 - x0, y1 - y0, fill=False, edgecolor="C3",
                              linewidth=1.0))
    (fx0, fx1), (fy0, fy1) = limits["full"]
    inset.set_xlim(fx0, fx1)
    inset.set_ylim(fy0, fy1)
    inset.set_aspect("equal", adjustable="datalim")
    inset.set_xticks([])
    inset.set_yticks([])
    inset.set_title("whole surface", fontsize=6, pad=1.5)
    return inset


def map_figsize(limits, nrows, ncols, map_width, extra_width, extra_height, min_width=0.0,
                title_lines=0):
    """(width, height) in inches of a figure of nrows x ncols maps of the window `limits`: each
    map `map_width` wide (less if it would be over MAP_MAX_HEIGHT high) plus `extra_width` and
    `extra_height` for its colour bar, labels and titles, and room for `title_lines` lines of
    the figure's title."""
    (x0, x1), (y0, y1) = limits["xlim"], limits["ylim"]
    aspect = np.clip((y1 - y0) / (x1 - x0), *MAP_ASPECT_RANGE) if x1 > x0 else 1.0
    width = min(map_width, MAP_MAX_HEIGHT / aspect)
    return (max(ncols * (width + extra_width), min_width),
            nrows * (width * aspect + extra_height) + TITLE_LINE_HEIGHT * title_lines)


def title_lines(report, other_lines):
    """The number of lines of a title made of `other_lines` lines and run_label(report)."""
    return other_lines + run_label(report).count("\n") + 1


def padded_limits(limits, fraction):
    """`limits` widened on every side by `fraction` of the window's larger side."""
    (x0, x1), (y0, y1) = limits["xlim"], limits["ylim"]
    pad = fraction * max(x1 - x0, y1 - y0)
    return dict(limits, xlim=(x0 - pad, x1 + pad), ylim=(y0 - pad, y1 + pad))


def window_range(surface, values, limits):
    """(vmin, vmax) of nodal `values` over the nodes inside the window (all of them when the map
    is not zoomed), for a colour scale that uses its whole range where the map looks."""
    tri = surface["tri"]
    inside = np.ones(len(values), dtype=bool)
    if limits["zoomed"]:
        (x0, x1), (y0, y1) = limits["xlim"], limits["ylim"]
        inside = (tri.x >= x0) & (tri.x <= x1) & (tri.y >= y0) & (tri.y <= y1)
    if not inside.any():
        inside[:] = True
    return float(values[inside].min()), float(values[inside].max())


# ----------------------------------------------------------------------------------------------
# Small helpers
# ----------------------------------------------------------------------------------------------

def save_figure(fig, out_dir, name, fmt, written, mark=""):
    """Save `fig` as out_dir/name<mark>.fmt atomically (temporary file in the same folder,
    os.replace); `mark` is NOT_CONVERGED for the figures of a run that did not converge."""
    name += mark
    final = out_dir / f"{name}.{fmt}"
    fd, tmp = tempfile.mkstemp(dir=out_dir, prefix=f".{name}.", suffix=f".{fmt}.tmp")
    os.close(fd)
    try:
        fig.savefig(tmp, format=fmt, dpi=DPI)
        os.replace(tmp, final)
    finally:
        plt.close(fig)
        if os.path.exists(tmp):
            os.remove(tmp)
    written.append(final)


def run_label(report):
    """A short description of the run for figure titles: title, --set overrides, mesh cells."""
    problem = report.get("problem", {})
    label = problem.get("title") or pathlib.Path(report.get("source", "run")).stem
    cells = problem.get("mesh", {}).get("cells")
    if cells:
        label += f"  (mesh {cells[0]}x{cells[1]}x{cells[2]} cubes)"
    if report.get("status") not in (None, "converged"):
        label += f"  [status: {report['status']}]"
    if report.get("overrides"):
        label += "\n" + textwrap.fill("with --set " + " ".join(report["overrides"]), width=90)
    return label


def sci(x):
    """A number in short notation: 60000 -> '6e4', 0.000219 -> '2.19e-4', 0.3 -> '0.3'."""
    x = float(x)
    if x == 0 or 1e-2 <= abs(x) < 1e4:
        return f"{x:.3g}"
    mantissa, exponent = f"{x:.2e}".split("e")
    mantissa = mantissa.rstrip("0").rstrip(".")
    return f"{mantissa}e{int(exponent)}"


def nice_round_down(x):
    """The largest number 1, 2 or 5 times a power of ten that is <= x (x > 0)."""
    p = 10.0 ** np.floor(np.log10(x))
    for m in (5.0, 2.0, 1.0):
        if m * p <= x * (1 + 1e-12):
            return m * p
    return p


def setup_plane_axes(ax, surface, title, limits=None, fontsize=10):
    """Equal-aspect axes for a map of the contact surface, labelled with the plane's coordinates,
    showing the window `limits` (default map_limits(surface)) and, when it is zoomed, the whole
    surface in an inset."""
    limits = map_limits(surface) if limits is None else limits
    ax.set_aspect("equal")
    ax.set_xlabel(f"{surface['axes'][0]} [m]")
    ax.set_ylabel(f"{surface['axes'][1]} [m]")
    ax.set_title(title, fontsize=fontsize)
    ax.set_xlim(*limits["xlim"])
    ax.set_ylim(*limits["ylim"])
    if limits["zoomed"]:
        draw_overview_inset(ax, surface, limits)


def add_colorbar(fig, mappable, ax, label, extend="neither"):
    """A colour bar beside `ax` with scientific notation for very small or large values."""
    cb = fig.colorbar(mappable, ax=ax, shrink=0.9, pad=0.02, extend=extend)
    cb.set_label(label)
    cb.formatter.set_powerlimits((-2, 3))
    cb.update_ticks()
    return cb


def draw_obstacle_outline(ax, surface, color="c"):
    """The rigid obstacle's outline on the undeformed contact surface: the zero line of its
    signed distance where it is moved (inside it, the obstacle overlaps the undeformed body),
    dashed; nothing where the obstacle does not reach the surface or is a body."""
    distance = surface.get("obstacle_distance")
    if distance is None or not (distance.min() < 0.0 < distance.max()):
        return
    ax.tricontour(surface["tri"], distance, levels=[0.0], colors=color, linewidths=1.2,
                  linestyles="--")


def draw_patch_edges(ax, surface, color="k", lw=0.6, alpha=0.6):
    """The outlines of the multiplier patches."""
    ax.add_collection(LineCollection(surface["patch_edges"], colors=color, linewidths=lw,
                                     alpha=alpha))


# ----------------------------------------------------------------------------------------------
# Friction laws
# ----------------------------------------------------------------------------------------------

def paper_law(t, param):
    """The paper's coefficient: 0.3, linear to 0.2 on (1e-5, 1e-5 + 2/param), then 0.2."""
    return np.clip(0.3 - 0.05 * param * (np.asarray(t) - PAPER_T0), 0.2, 0.3)


def friction_curves(friction):
    """(label, callable F(t), characteristic slip in m) for the run's law and, for the paper's
    law, the paper's other parameters. The first entry is the run's law."""
    law = friction.get("law", "paper")
    if law == "paper":
        param = float(friction.get("param", 6.0e4))
        curves = [(f"param = {sci(param)} 1/m (this run)", lambda t, p=param: paper_law(t, p),
                   PAPER_T0 + 2.0 / param)]
        for p in PAPER_PARAMS:
            if not np.isclose(p, param, rtol=1e-9):
                curves.append((f"param = {sci(p)} 1/m (paper)", lambda t, q=p: paper_law(t, q),
                               PAPER_T0 + 2.0 / p))
        return curves
    if law == "constant":
        value = float(friction.get("value", 0.3))
        return [(f"constant F = {value:g} (this run)",
                 lambda t, v=value: np.full_like(np.asarray(t, dtype=float), v), 0.0)]
    if law == "table":
        ts, fs = np.asarray(friction["t"], float), np.asarray(friction["f"], float)
        return [(f"table, {len(ts)} points (this run)",
                 lambda t, a=ts, b=fs: np.interp(t, a, b), float(ts[-1]))]
    raise ValueError(f"unknown friction law {law!r}")


def law_range(friction):
    """(min F, max F) of the run's law, for colour scales that do not depend on the data."""
    law = friction.get("law", "paper")
    if law == "paper":
        return 0.2, 0.3
    if law == "constant":
        v = float(friction.get("value", 0.3))
        return v, v
    fs = np.asarray(friction["f"], float)
    return float(fs.min()), float(fs.max())


# ----------------------------------------------------------------------------------------------
# The figures
# ----------------------------------------------------------------------------------------------

def plot_convergence(report):
    """Fig. 6: log10 err(k) against the outer iteration k, with the stopping tolerance."""
    err = np.asarray(report["err_history"], dtype=float)
    tol = float(report["problem"].get("solver", {}).get("outer_tol", 1e-4))
    k = np.arange(1, len(err) + 1)
    fig, ax = plt.subplots(figsize=(6.4, 4.6), layout="constrained")
    with np.errstate(divide="ignore"):
        log_err = np.log10(np.maximum(err, np.finfo(float).tiny))
    ax.plot(k, log_err, "o-", color="C0", label="err(k)")
    ax.axhline(np.log10(tol), ls="--", color="C3", label=f"outer_tol = {tol:.0e}")
    ax.set_xlabel("outer iteration k")
    ax.set_ylabel(r"$\log_{10}\,\mathrm{err}(k)$")
    ax.set_xticks(k if len(k) <= 20 else np.unique(np.linspace(1, len(k), 11).astype(int)))
    ax.grid(True, alpha=0.3)
    ax.legend()
    fig.suptitle("Convergence of the successive approximations\n"
                 r"err(k) = $\Vert \varphi^k-\varphi^{k-1}\Vert / \Vert \varphi^k\Vert$",
                 fontsize=11)
    ax.set_title(run_label(report), fontsize=9)
    return fig


def plot_friction_law(report, surface):
    """Fig. 3: F(t) of the run (and the paper's other parameters), with the slips reached."""
    friction = first_pair(report).get("friction", {})
    curves = friction_curves(friction)
    # Along a loading path F takes the accumulated slip s, in a static run ||w_t||.
    path = bool(report.get("steps"))
    phi = surface["slip"] if surface is not None else np.zeros(0)
    phi_max = float(phi.max()) if phi.size else float(report.get("max_wt", 0.0))
    symbol = "s" if path else r"\Vert w_t\Vert"
    what = "accumulated slip" if path else "tangential displacement"
    t_end = max([1.5 * c[2] for c in curves] + [1.15 * phi_max, 1e-5])
    t = np.linspace(0.0, t_end, 2000)
    fig, ax = plt.subplots(figsize=(7.0, 4.6), layout="constrained")
    styles = ["-", "--", "-.", ":"]
    for i, (label, f, _) in enumerate(curves):
        ax.plot(t, f(t), styles[i % 4], lw=2.2 if i == 0 else 1.4,
                color="C0" if i == 0 else "0.45", label=label, zorder=3 if i == 0 else 2)
    if phi.size:
        ax.plot(phi, surface["F"], "o", ms=3, color="C1", alpha=0.6, zorder=4,
                label=f"contact nodes: (${symbol}$, F), {what}")
        ax.axvline(phi_max, ls=":", color="C1")
        ax.annotate(f"max ${symbol}$ = {phi_max:.2e} m", xy=(phi_max, 0.22),
                    xycoords=("data", "axes fraction"), xytext=(-4, 0),
                    textcoords="offset points", rotation=90, ha="right", va="bottom",
                    fontsize=8, color="C1")
    lo, hi = law_range(friction)
    pad = max(0.25 * (hi - lo), 0.05 * hi, 0.02)
    ax.set_ylim(max(0.0, lo - pad), hi + pad)
    ax.set_xlim(0.0, t_end)
    ax.ticklabel_format(axis="x", style="sci", scilimits=(-2, 3))
    ax.set_xlabel("accumulated slip $t = s$ [m]" if path else r"slip $t = \Vert u_t\Vert$ [m]")
    ax.set_ylabel("coefficient of friction F [-]")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8, loc="upper right")
    ax.set_title(f"Coefficient of friction F(t), law \"{friction.get('law', 'paper')}\"\n"
                 f"{run_label(report)}", fontsize=10)
    return fig


def plot_contact_maps(report, surface):
    """Figs. 8-9: -w_n and ||w_t|| (nodal, P1) and lambda_n, ||lambda_t|| (per patch).

    Zoomed to the contact zone (map_limits), the nodal fields are coloured over their range in
    the window (the colour bar extends beyond it); the titles give the whole surface's range."""
    tri = surface["tri"]
    limits = map_limits(surface)
    fig, axs = plt.subplots(2, 2, figsize=map_figsize(limits, 2, 2, 4.8, 1.7, 1.2,
                                                      title_lines=title_lines(report, 1)),
                            layout="compressed")
    panels = [
        (axs[0, 0], surface["opening"], "nodal",
         "a) opening gap $- w_n$ (> 0: open, < 0: penetration)", (r"gap $- w_n$", "m"), "viridis"),
        (axs[0, 1], surface["lambda_n"], "patch", r"b) contact pressure $\lambda_n$ per patch",
         (r"$\lambda_n$", "Pa"), "magma"),
        (axs[1, 0], surface["norm_w_t"], "nodal", r"c) tangential displacement $\Vert w_t\Vert$",
         (r"$\Vert w_t\Vert$", "m"), "viridis"),
        (axs[1, 1], surface["norm_lambda_t"], "patch",
         r"d) friction multiplier $\Vert \lambda_t\Vert$ per patch",
         (r"$\Vert \lambda_t\Vert$", "Pa"), "magma"),
    ]
    for ax, values, kind, title, (symbol, unit), cmap in panels:
        extend, note = "neither", ""
        if kind == "nodal":
            vmin, vmax = window_range(surface, values, limits)
            if vmin > values.min() or vmax < values.max():
                extend = {(True, True): "both", (True, False): "min",
                          (False, True): "max"}[(vmin > values.min(), vmax < values.max())]
                note = "\n(colours: range in the window)"
            m = ax.tripcolor(tri, values, shading="gouraud", cmap=cmap, vmin=vmin,
                             vmax=vmax if vmax > vmin else None)
        else:
            m = ax.tripcolor(tri, facecolors=values, cmap=cmap, edgecolors="none")
        draw_patch_edges(ax, surface, color="w" if kind == "patch" else "k", lw=0.5,
                         alpha=0.5 if kind == "patch" else 0.25)
        draw_obstacle_outline(ax, surface)
        setup_plane_axes(ax, surface, f"{title}\nmin {sci(values.min())} {unit}, "
                                      f"max {sci(values.max())} {unit}", limits)
        add_colorbar(fig, m, ax, f"{symbol} [{unit}]{note}", extend=extend)
    outline = ""
    if surface.get("obstacle_distance") is not None:
        kind = report.get("obstacle", {}).get("kind", "obstacle")
        outline = f"\ndashed: the {kind}'s outline on the undeformed surface"
    fig.suptitle(f"Contact surface: displacements (nodal) and multipliers (piecewise constant on "
                 f"patches)\n{run_label(report)}{outline}", fontsize=11)
    return fig


def plot_friction_coefficient(report, surface):
    """Fig. 10: the coefficient F(||w_t||) on the contact surface."""
    tri = surface["tri"]
    friction = first_pair(report).get("friction", {})
    lo, hi = law_range(friction)
    if hi - lo < 1e-12:
        lo, hi = lo - 0.05, hi + 0.05
    limits = map_limits(surface)
    fig, ax = plt.subplots(figsize=map_figsize(limits, 1, 1, 7.5, 1.5, 0.8, min_width=8.0,
                                               title_lines=title_lines(report, 1)),
                           layout="compressed")
    m = ax.tripcolor(tri, surface["F"], shading="gouraud", cmap="coolwarm", vmin=lo, vmax=hi)
    draw_patch_edges(ax, surface, color="k", lw=0.5, alpha=0.25)
    F = surface["F"]
    setup_plane_axes(ax, surface, r"Coefficient of friction F($\Vert w_t\Vert$) on the contact "
                     "surface "
                     f"(nodal values; min {F.min():.3f}, max {F.max():.3f})\n{run_label(report)}",
                     limits)
    cb = fig.colorbar(m, ax=ax, shrink=0.9, pad=0.02)
    cb.set_label("F [-]")
    return fig


def plot_friction_circles(report, surface):
    """Fig. 11: per patch, a circle of radius = slip bound and the arrow lambda_t, same scale."""
    P = surface["patches"]
    radius, lt, centre = P["radius"], P["lambda_t"], P["centre"]
    norm_lt = np.hypot(lt[:, 0], lt[:, 1])
    if (P["state"] >= 0).all():  # the states fricon wrote (contact.vtu "state")
        slipping, separated = P["state"] == 2, P["state"] == 0
    else:
        slipping = norm_lt >= (1.0 - STUCK_RTOL) * radius
        separated = np.zeros_like(slipping)
    side = np.sqrt(P["area"].min())
    scale = 0.45 * side / radius.max() if radius.max() > 0 else 0.0  # m on the plot per Pa
    limits = map_limits(surface)
    if not limits["zoomed"]:  # room for the circles of the patches on the border
        limits = padded_limits(limits, CIRCLES_PAD)
    x0, x1 = limits["xlim"]
    fig, ax = plt.subplots(figsize=map_figsize(limits, 1, 1, 10.0, 1.0, 1.7, min_width=9.0,
                                               title_lines=title_lines(report, 2)),
                           layout="compressed")
    draw_patch_edges(ax, surface, color="0.6", lw=0.6, alpha=1.0)
    colors = np.where(separated, "0.5", np.where(slipping, "C3", "C0"))
    ax.add_collection(PatchCollection([Circle(c, r * scale) for c, r in zip(centre, radius)],
                                      facecolors="none", edgecolors=colors, linewidths=1.2))
    q = ax.quiver(centre[:, 0], centre[:, 1], lt[:, 0] * scale, lt[:, 1] * scale, color=colors,
                  angles="xy", scale_units="xy", scale=1.0, units="xy",
                  width=min(0.045 * side, 0.0035 * (x1 - x0)),
                  headwidth=3.5, headlength=4, headaxislength=3.6, zorder=3)
    ax.plot(centre[:, 0], centre[:, 1], ".", color="k", ms=1.5)
    setup_plane_axes(ax, surface, "", limits)
    rtol = 1e-6 if (P["state"] >= 0).all() else STUCK_RTOL  # fricon's test, or this script's
    ax.plot([], [], "-", color="C3", label=f"slipping: $\\Vert \\lambda_t\\Vert$ = radius "
            f"(within {rtol:g} rel.), {slipping.sum()} patches")
    ax.plot([], [], "-", color="C0", label=f"sticking: $\\Vert \\lambda_t\\Vert$ < radius, "
            f"{(~slipping & ~separated).sum()} patches")
    if separated.any():
        ax.plot([], [], "-", color="0.5", label=f"separated: $\\lambda_n$ = 0, "
                f"{separated.sum()} patches")
    ax.legend(loc="upper left", bbox_to_anchor=(0.0, -0.14), ncol=2, fontsize=9, frameon=False)
    if radius.max() > 0:
        ref = nice_round_down(radius.max())
        ax.quiverkey(q, X=0.86, Y=-0.2, U=ref * scale, label=f"scale: {sci(ref)} Pa",
                     labelpos="E", coordinates="axes", color="k")
        scale_note = (f"same scale for circles and arrows: {sci(ref)} Pa is drawn as "
                      f"{ref * scale:.3g} m")
    else:
        scale_note = "the slip bound is 0 on every patch (no friction): nothing to draw"
        ax.text(0.5, 0.5, "slip bound 0 on every patch:\nno friction, $\\lambda_t$ = 0",
                transform=ax.transAxes, ha="center", va="center", fontsize=12, color="0.3")
    coulomb = report.get("model") == "coulomb"
    bound = (r"$\lambda_n(R)\,\frac{1}{|R|}\int_R F(\Vert w_t\Vert)\,dS$" if coulomb
             else r"$\frac{1}{|R|}\int_R F(\Vert w_t\Vert)\,g\,dS$")
    ax.set_title(r"Friction multiplier $\lambda_t$ (arrows) against the slip bound "
                 + bound + r" (circle radius) per patch R"
                 f"\n{scale_note}; max radius {sci(radius.max())} Pa, "
                 f"max $\\Vert \\lambda_t\\Vert$ {sci(norm_lt.max())} Pa"
                 f"\n{run_label(report)}", fontsize=9)
    return fig


# ----------------------------------------------------------------------------------------------
# Loading paths: steps.csv and steps/patches-NNNN.csv
# ----------------------------------------------------------------------------------------------

def read_steps(results):
    """steps.csv of a loading path as a dict of columns (numbers as float arrays, text such as
    "status" as arrays of str), its column names in order under "columns"; None without it."""
    path = result_file(results, "steps.csv")
    if not path.is_file():
        return None
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    if not rows:
        return None
    header, body = rows[0], rows[1:]
    steps = {"columns": header}
    for j, name in enumerate(header):
        values = [row[j] for row in body]
        try:
            steps[name] = np.array(values, dtype=float)
        except ValueError:
            steps[name] = np.array(values, dtype=str)
    return steps


def path_loads(steps):
    """The keys of the loads with a path ("traction[0]", ...), in steps.csv's order."""
    return [c[len("factor."):] for c in steps["columns"] if c.startswith("factor.")]


def step_converged(steps):
    """Per step, whether it converged (steps.csv "status"; every step for a file without it)."""
    status = steps.get("status")
    return (status == "converged") if status is not None else np.ones(len(steps["step"]), bool)


def path_abscissa(steps):
    """(x, label) for the figures along the path: the component with the largest range of the
    mean displacement of the first load with one (displacement.KEY_x, _y, _z), else of a moving
    rigid obstacle's displacement, else the step."""
    for key in path_loads(steps):
        names = [f"displacement.{key}_{c}" for c in "xyz"]
        if all(n in steps for n in names):
            d = np.column_stack([steps[n] for n in names])
            c = int(np.argmax(np.ptp(d, axis=0)))
            return d[:, c], f"mean displacement of {key}, {'xyz'[c]} component [m]"
    # A rigid obstacle moved along the path (steps.csv's obstacle.KEY_x, _y, _z): its displacement
    # component with the largest range.
    for name in steps:
        if name.startswith("obstacle.") and name.endswith("_x"):
            key = name[len("obstacle."):-2]
            d = np.column_stack([steps[f"obstacle.{key}_{c}"] for c in "xyz"])
            c = int(np.argmax(np.ptp(d, axis=0)))
            if np.ptp(d[:, c]) > 0.0:
                return d[:, c], f"displacement of the obstacle ({key}), {'xyz'[c]} component [m]"
    return steps["step"], "step"


def signed_tangential_force(steps):
    """(values, direction): the tangential force of each step along the direction of the largest
    one over the path (unit vector, global x y z; zeros and None when there is none)."""
    T = np.column_stack([steps[f"tangential_force_{c}"] for c in "xyz"])
    norms = np.linalg.norm(T, axis=1)
    if not norms.size or norms.max() <= 0:
        return np.zeros(len(T)), None
    direction = T[np.argmax(norms)] / norms.max()
    return T @ direction, direction


def factor_label(steps, i, sep=", "):
    """The factors of step row `i`: "traction[0] x0.5, dirichlet[1] x1"."""
    return sep.join(f"{key} \u00d7{sci(steps['factor.' + key][i])}" for key in path_loads(steps))


def steps_label(report, steps):
    """"N steps", or "N of M steps" when the run stopped before the end of its path."""
    n = len(steps["step"])
    planned = report.get("problem", {}).get("loading", {}).get("steps")
    return f"{n} of {planned} steps" if planned and planned != n else f"{n} steps"


def annotate_ends(ax, x, y, steps, color, above=True):
    """Labels "start (step a)" and "end (step b)" at the first and last points of a curve, above
    or below it, towards the middle of the x range (inside the axes)."""
    first, last = int(steps["step"][0]), int(steps["step"][-1])
    middle = 0.5 * (np.min(x) + np.max(x))
    for i, text in ((0, f"start (step {first})"), (-1, f"end (step {last})")):
        right = x[i] > middle
        ax.annotate(text, xy=(x[i], y[i]), xytext=(-5 if right else 5, 5 if above else -5),
                    textcoords="offset points", ha="right" if right else "left",
                    va="bottom" if above else "top", fontsize=8, color=color)


def plot_force_displacement(report, steps):
    """The tangential force (signed along its largest direction) and the normal force of each
    step against the displacement of the first load with a path (else the step), and below their
    ratio with the coefficient of a constant friction law."""
    x, xlabel = path_abscissa(steps)
    tangential, direction = signed_tangential_force(steps)
    normal = steps["normal_force"]
    converged = step_converged(steps)
    fig, (ax, ax2) = plt.subplots(2, 1, sharex=True, figsize=(8.0, 7.5), layout="constrained",
                                  height_ratios=(3, 2))
    along = ("along (" + ", ".join(f"{c:.2f}" for c in direction) + ")" if direction is not None
             else "(zero)")
    for y, color, marker, above, label in (
            (tangential, "C3", "o", False, f"tangential force {along}"),
            (normal, "C0", "s", True, "normal force")):
        ax.plot(x, y, "-", color=color, lw=1.2, label=label)
        ax.plot(x[converged], y[converged], marker, color=color, ms=4, ls="none")
        annotate_ends(ax, x, y, steps, color, above)
    if not converged.all():
        for y in (tangential, normal):
            ax.plot(x[~converged], y[~converged], "x", color="k", ms=6, ls="none")
        ax.plot([], [], "x", color="k", label="step not converged")
    ax.axhline(0.0, color="0.6", lw=0.6)
    ax.set_ylabel("force [N]")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8, loc="best")
    ax.ticklabel_format(axis="y", style="sci", scilimits=(-3, 4))

    with np.errstate(divide="ignore", invalid="ignore"):
        ratio = np.where(normal > 0, tangential / normal, np.nan)
    ax2.plot(x, ratio, "o-", color="C2", ms=4, lw=1.2, label="tangential / normal force")
    finite = np.isfinite(ratio)
    if finite.any():
        annotate_ends(ax2, x[finite], ratio[finite], {"step": steps["step"][finite]}, "C2",
                      above=False)
    friction = first_pair(report).get("friction", {}) if "contact" in report.get(
        "problem", {}) else {}
    if friction.get("law") == "constant":
        value = float(friction.get("value", 0.0))
        ax2.axhline(value, ls="--", color="k", lw=1.0, label=f"coefficient of friction {value:g}")
        if finite.any() and np.nanmin(ratio) < 0:
            ax2.axhline(-value, ls="--", color="k", lw=1.0)
    ax2.axhline(0.0, color="0.6", lw=0.6)
    ax2.set_xlabel(xlabel)
    ax2.set_ylabel("tangential / normal [-]")
    ax2.grid(True, alpha=0.3)
    ax2.legend(fontsize=8, loc="best")
    if xlabel == "step":
        ax2.xaxis.set_major_locator(matplotlib.ticker.MaxNLocator(integer=True))
    else:
        ax2.ticklabel_format(axis="x", style="sci", scilimits=(-3, 4))
    fig.suptitle(f"Forces of the obstacle on the contact surface along the loading path "
                 f"({steps_label(report, steps)})\n{run_label(report)}", fontsize=10)
    return fig


def chosen_steps(n, limit=MAX_STEP_MAPS):
    """Indices of at most `limit` of n steps, evenly spread, the first and the last included."""
    return np.unique(np.round(np.linspace(0, n - 1, min(n, limit))).astype(int))


def step_files(results, base, extension):
    """{step number: path} of the per-step files steps/BASE-NNNN.EXT of a loading path."""
    files = {}
    for path in (results / "steps").glob(f"{base}-*{extension}"):
        number = path.name[len(base) + 1:-len(extension)]
        if number.isdigit():
            files[int(number)] = path
    return files


def read_step_patches(path):
    """The state codes (STATE_CODES) and lambda_n of each patch of a steps/patches-NNNN.csv."""
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    states = np.array([STATE_CODES.get(r["state"], STATE_CODES["separated"]) for r in rows])
    return states, np.array([float(r["lambda_n"]) for r in rows])


def plot_stick_slip_steps(report, surface, steps, patch_files):
    """One small map of the contact surface per step (at most MAX_STEP_MAPS, chosen_steps), each
    patch coloured by its state in that step (steps/patches-NNNN.csv), all zoomed to the union
    of the steps' contact zones; None when no chosen step has its patches file."""
    rows = chosen_steps(len(steps["step"]))
    patch = surface["patch"]
    ids = np.unique(patch[patch >= 0])  # the patches of this view
    safe = np.maximum(patch, 0)
    per_step, in_contact = [], np.zeros(len(patch), dtype=bool)
    for i in rows:
        path = patch_files.get(int(steps["step"][i]))
        codes = None
        if path is not None:
            codes, lambda_n = read_step_patches(path)
            if len(codes) <= patch.max():  # not the patches of contact.vtu
                print(f"plot_results: {path}: {len(codes)} patches, contact.vtu has more; "
                      "step skipped", file=sys.stderr)
                codes = None
            else:
                in_contact |= contact_triangles(surface, codes[safe],
                                                np.where(patch >= 0, lambda_n[safe], 0.0))
        per_step.append((i, codes))
    if all(codes is None for _, codes in per_step):
        return None
    limits = map_limits(surface, in_contact)
    (x0, x1), (y0, y1) = limits["xlim"], limits["ylim"]
    ncols = min(len(rows), 4 if (y1 - y0) >= 0.5 * (x1 - x0) else 3)
    nrows = -(-len(rows) // ncols)
    width, height = map_figsize(limits, nrows, ncols, 2.7, 0.5, 1.0, min_width=7.0,
                                title_lines=title_lines(report, 1))
    fig, axs = plt.subplots(nrows, ncols, figsize=(width, height + STEPS_LEGEND_HEIGHT),
                            layout="compressed", squeeze=False)
    legend = STEPS_LEGEND_HEIGHT / (height + STEPS_LEGEND_HEIGHT)  # as a part of the figure
    fig.get_layout_engine().set(rect=(0.0, legend, 1.0, 1.0 - legend))
    order = sorted(STATE_CODES, key=STATE_CODES.get)
    cmap = matplotlib.colors.ListedColormap([STATE_COLORS[name] for name in order])
    converged = step_converged(steps)
    for n, ax in enumerate(axs.flat):
        if n >= len(per_step):
            ax.set_axis_off()
            continue
        i, codes = per_step[n]
        title = f"step {int(steps['step'][i])}" + ("" if converged[i] else " (not converged)")
        if path_loads(steps):
            title += "\n" + textwrap.fill(factor_label(steps, i), width=44)
        if codes is None:
            ax.text(0.5, 0.5, "no patches file\nfor this step", transform=ax.transAxes,
                    ha="center", va="center", fontsize=8, color="0.3")
        else:
            states = np.where(patch >= 0, codes[safe], STATE_CODES["separated"])
            ax.tripcolor(surface["tri"], facecolors=states.astype(float), cmap=cmap, vmin=-0.5,
                         vmax=len(order) - 0.5, edgecolors="none")
            draw_patch_edges(ax, surface, color="w", lw=0.4, alpha=0.8)
            title += "\n" + ", ".join(f"{np.count_nonzero(codes[ids] == STATE_CODES[name])} "
                                      f"{name}" for name in ("stick", "slip"))
        setup_plane_axes(ax, surface, title, dict(limits, zoomed=limits["zoomed"] and n == 0),
                         fontsize=8)
        ax.tick_params(labelsize=7)
        if n % ncols:
            ax.set_ylabel("")
        if n < len(per_step) - ncols:
            ax.set_xlabel("")
    fig.legend([Rectangle((0, 0), 1, 1, facecolor=STATE_COLORS[name], edgecolor="0.3")
                for name in ("stick", "slip", "separated")], ["stick", "slip", "separated"],
               loc="lower center", bbox_to_anchor=(0.5, 0.0), ncol=3, fontsize=9, frameon=False)
    shown = "" if len(rows) == len(steps["step"]) else f", {len(rows)} of them shown"
    fig.suptitle(f"Patch states along the loading path ({steps_label(report, steps)}{shown})"
                 f"\n{run_label(report)}", fontsize=10)
    return fig


def boundary_faces(tets):
    """The triangles that belong to exactly one tetrahedron, with that tetrahedron's index."""
    local = np.array([[0, 1, 2], [0, 1, 3], [0, 2, 3], [1, 2, 3]])
    faces = tets[:, local].reshape(-1, 3)
    owner = np.repeat(np.arange(len(tets)), 4)
    _, first, count = np.unique(np.sort(faces, axis=1), axis=0, return_index=True,
                                return_counts=True)
    keep = first[count == 1]
    return faces[keep], owner[keep]


def box_edges(lo, hi):
    """The 12 edges (12, 2, 3) of the axis-aligned box [lo, hi]."""
    corners = np.array([[x, y, z] for x in (lo[0], hi[0]) for y in (lo[1], hi[1])
                        for z in (lo[2], hi[2])])
    pairs = [(i, j) for i in range(8) for j in range(i + 1, 8)
             if np.count_nonzero(corners[i] != corners[j]) == 1]
    return corners[np.array(pairs)]


def shade(rgba, normals, light=(-0.4, -0.6, 0.7)):
    """Lambert shading of face colours by their unit normals (matplotlib 3.6 has no built-in)."""
    light = np.asarray(light) / np.linalg.norm(light)
    k = 0.55 + 0.45 * np.abs(normals @ light)
    out = rgba.copy()
    out[:, :3] *= k[:, None]
    return out


def foundation_height(report, z_min):
    """The height z of the obstacle plane when it is horizontal (it is then a line in the side
    view), else None. Without the report's obstacle (an older folder): the brick's bottom z_min
    when it is the contact boundary."""
    obstacle = report.get("obstacle")
    if obstacle is not None and obstacle.get("kind", "plane") != "plane":
        return None  # another body: it is in the view itself
    if obstacle is None:
        boundary = report.get("problem", {}).get("contact", {}).get("boundary")
        return z_min if boundary == "z0" else None
    normal = np.asarray(obstacle["normal"], dtype=float)
    if abs(abs(normal[2]) - 1.0) > 1e-12:
        return None
    return float(obstacle["point"][2])


def plot_deformed(report, results):
    """Fig. 7: the boundary of the deformed body, coloured by von Mises, magnified displacement.

    Top: a 3D view of the boundary triangles; bottom: the side view (x-z) of the face y = min,
    with the undeformed outline dashed in both.
    """
    mesh = meshio.read(result_file(results, "solution.vtu"))
    pts = np.asarray(mesh.points)
    u = point_field(mesh, "displacement")
    tets = next(c.data for c in mesh.cells if c.type in TETRA_TYPES)
    faces, owner = boundary_faces(np.asarray(tets)[:, :TET_CORNERS])
    lo, hi = pts.min(axis=0), pts.max(axis=0)
    size = float((hi - lo).max())
    umax = float(np.linalg.norm(u, axis=1).max())
    factor = nice_round_down(0.1 * size / umax) if umax > 0 else 1.0
    X = pts + factor * u
    if "von_mises" in mesh.cell_data:
        values, label = cell_field(mesh, "von_mises")[owner], "von Mises stress [Pa]"
    else:
        values, label = np.linalg.norm(u, axis=1)[faces].mean(axis=1), "|u| [m]"
    # A stress singularity (e.g. at a clamped edge) would wash out the colours: clip it.
    vmax, extend = float(values.max()), "neither"
    p99 = float(np.percentile(values, 99))
    if vmax > 1.25 * p99 > 0:
        vmax, extend = p99, "max"
        label += f"\n(scale clipped at the 99th percentile; max {sci(values.max())})"
    norm = matplotlib.colors.Normalize(values.min(), vmax)
    cmap = matplotlib.colormaps["turbo"]
    blo, bhi = np.minimum(lo, X.min(axis=0)), np.maximum(hi, X.max(axis=0))

    fig = plt.figure(figsize=(10.0, 8.0))
    ax3 = fig.add_axes([0.0, 0.35, 0.84, 0.58], projection="3d")
    verts = X[faces]
    normals = np.cross(verts[:, 1] - verts[:, 0], verts[:, 2] - verts[:, 0])
    normals /= np.maximum(np.linalg.norm(normals, axis=1, keepdims=True), 1e-300)
    ax3.add_collection3d(Poly3DCollection(verts, facecolors=shade(cmap(norm(values)), normals),
                                          edgecolors=(0, 0, 0, 0.08), linewidths=0.2))
    ax3.add_collection3d(Line3DCollection(box_edges(lo, hi), colors="0.3", linewidths=0.8,
                                          linestyles="--"))
    ax3.set_xlim(blo[0], bhi[0])
    ax3.set_ylim(blo[1], bhi[1])
    ax3.set_zlim(blo[2], bhi[2])
    ax3.set_box_aspect(bhi - blo, zoom=1.15)
    ax3.view_init(elev=22, azim=-62)
    for name, axis in zip("xyz", (ax3.xaxis, ax3.yaxis, ax3.zaxis)):
        axis.set_label_text(f"{name} [m]")

    # Side view: the boundary faces lying on y = min, drawn at their deformed x and z; a body
    # without such a flat face (a sphere, a wheel) shows the faces that look towards -y.
    ax2 = fig.add_axes([0.08, 0.06, 0.66, 0.28])
    front = np.all(np.isclose(pts[faces][:, :, 1], lo[1]), axis=1)
    view = f"the face y = {lo[1]:g} m"
    if not front.any():
        p = pts[faces]
        front = np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0])[:, 1] < 0
        view = "the body seen from -y"
    side = mtri.Triangulation(X[:, 0], X[:, 2], faces[front])
    ax2.tripcolor(side, facecolors=values[front], cmap=cmap, norm=norm, edgecolors="none")
    ax2.triplot(side, color="k", alpha=0.15, lw=0.3)
    ax2.plot([lo[0], hi[0], hi[0], lo[0], lo[0]], [lo[2], lo[2], hi[2], hi[2], lo[2]], "--",
             color="0.3", lw=0.9, label="undeformed")
    foundation = foundation_height(report, lo[2])
    if foundation is not None:
        ax2.axhline(foundation, color="k", lw=1.6, label="rigid foundation")
    ax2.set_aspect("equal")
    ax2.set_xlim(blo[0] - 0.02 * size, bhi[0] + 0.02 * size)
    ax2.set_ylim(blo[2] - 0.05 * size, bhi[2] + 0.03 * size)
    ax2.set_xlabel("x [m]")
    ax2.set_ylabel("z [m]")
    ax2.set_title(f"side view of {view} (deformed, {factor:g}x)", fontsize=9)
    ax2.legend(loc="upper left", bbox_to_anchor=(1.0, 1.0), fontsize=8, frameon=False)

    cax = fig.add_axes([0.86, 0.4, 0.018, 0.45])
    cb = fig.colorbar(matplotlib.cm.ScalarMappable(norm=norm, cmap=cmap), cax=cax,
                      extend=extend)
    cb.set_label(label)
    cb.formatter.set_powerlimits((-2, 3))
    cb.update_ticks()
    fig.suptitle(f"Deformed body, displacement magnified {factor:g}x "
                 f"(max |u| = {sci(umax)} m); dashed: undeformed\n{run_label(report)}",
                 fontsize=11)
    return fig


# ----------------------------------------------------------------------------------------------
# Driver
# ----------------------------------------------------------------------------------------------

def parse_args(argv):
    """The command line."""
    ap = argparse.ArgumentParser(
        description="Render the paper's figures (PNG) from a fricon results folder.")
    ap.add_argument("results", type=pathlib.Path, help="results folder written by `fricon solve`")
    ap.add_argument("--out", type=pathlib.Path, default=None,
                    help="where to write the figures (default: RESULTS/plots)")
    ap.add_argument("--format", default="png", choices=["png", "pdf", "svg"],
                    help="image format (default: png)")
    return ap.parse_args(argv)


def plot_steps(results, report, views, out_dir, fmt, written, mark=""):
    """The figures of a loading path (a folder with steps.csv): force_displacement and, per view
    (surface, file-name suffix) of the contact surface, stick_slip_steps."""
    steps = read_steps(results)
    if steps is None:
        return
    if "step" not in steps or not len(steps["step"]):
        print(f"plot_results: {results}: steps.csv has no step; the loading path is not plotted",
              file=sys.stderr)
        return
    save_figure(plot_force_displacement(report, steps), out_dir, "force_displacement", fmt,
                written, mark)
    patch_files = step_files(results, "patches", ".csv")
    for view, suffix in views:
        fig = plot_stick_slip_steps(report, view, steps, patch_files)
        if fig is None:
            print(f"plot_results: {results}: no steps/patches-NNNN.csv of the steps; "
                  f"stick_slip_steps{suffix} is skipped", file=sys.stderr)
        else:
            save_figure(fig, out_dir, "stick_slip_steps" + suffix, fmt, written, mark)


def remove_earlier_figures(out_dir):
    """Removes the figures of an earlier run from out_dir (FIGURE_NAMES in FIGURE_FORMATS, with
    any pair suffix, converged or not): a figure this run does not draw must not stay beside
    its own (a loading path's force_displacement beside a static run's figures)."""
    for name in FIGURE_NAMES:
        for fmt in FIGURE_FORMATS:
            for path in out_dir.glob(f"{name}*.{fmt}"):
                rest = path.name[len(name):-len(fmt) - 1]
                rest = rest[:-len(NOT_CONVERGED)] if rest.endswith(NOT_CONVERGED) else rest
                if rest == "" or (rest.startswith("-pair") and rest[5:].isdigit()):
                    path.unlink()


def make_plots(results, out_dir, fmt):
    """Draw every figure the folder has data for; return the list of files written."""
    report = read_report(results)
    out_dir.mkdir(parents=True, exist_ok=True)
    remove_earlier_figures(out_dir)
    written = []
    mark = "" if report.get("status", "converged") == "converged" else NOT_CONVERGED
    if mark:
        print(f"plot_results: {results}: the run did not converge ({report.get('status')}); "
              f"its last iterate is plotted, the figures named *{NOT_CONVERGED}.*",
              file=sys.stderr)
    has_contact = "contact" in report.get("problem", {})
    surface = load_contact(results, report) if has_contact else None
    if not has_contact:
        print(f"plot_results: {results}: a run without contact; only the deformed body is "
              "plotted", file=sys.stderr)
    else:
        if report.get("err_history"):
            save_figure(plot_convergence(report), out_dir, "convergence", fmt, written, mark)
        save_figure(plot_friction_law(report, surface), out_dir, "friction_law", fmt, written,
                    mark)
        views = []  # (surface, file-name suffix) of each map of the contact surface
        if surface is None:
            print(f"plot_results: {results}: no contact.vtu; the contact-surface figures are "
                  "skipped", file=sys.stderr)
        else:
            # Several pairs: the maps of each, seen along its own normal (name-pairI).
            pairs = report.get("pairs", [])
            views = [(surface, "")] if len(pairs) <= 1 else [
                (load_contact(results, report, i), f"-pair{i}") for i in range(len(pairs))]
            for view, suffix in views:
                save_figure(plot_contact_maps(report, view), out_dir, "contact_maps" + suffix,
                            fmt, written, mark)
                save_figure(plot_friction_coefficient(report, view), out_dir,
                            "friction_coefficient" + suffix, fmt, written, mark)
                save_figure(plot_friction_circles(report, view), out_dir,
                            "friction_circles" + suffix, fmt, written, mark)
        plot_steps(results, report, views, out_dir, fmt, written, mark)
    if result_file(results, "solution.vtu").is_file():
        save_figure(plot_deformed(report, results), out_dir, "deformed", fmt, written, mark)
    else:
        print(f"plot_results: {results}: no solution.vtu; the deformed body is skipped",
              file=sys.stderr)
    return written


def main(argv=None):
    """Entry point: parse, plot, print the files written."""
    args = parse_args(argv)
    if not args.results.is_dir():
        raise SystemExit(f"plot_results: {args.results}: no such folder")
    out_dir = args.out if args.out is not None else args.results / "plots"
    for path in make_plots(args.results, out_dir, args.format):
        print(path)
    return 0


if __name__ == "__main__":
    sys.exit(main())
